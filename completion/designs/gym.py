"""Gyms: home gyms in a spare room, a garage or a basement (9 to 27 square metres) and
a few studio and club rooms (32 to 40). The cardio machines (treadmills, exercise
bikes, rowing machines) face a window or a television with their console or flywheel
to it, a treadmill keeping a metre free behind its belt; dumbbell racks stand against
a wall with room before them to take the weights; a weight bench stands free with
half a metre either side for the arms and the dumbbells; mats lie where one stretches."""

from scenewright.completion.authoring import Design
from scenewright.completion.designs import (
    DUMBBELL_RACK,
    EXERCISE_BIKE,
    EXERCISE_MAT,
    PLANT,
    ROWING_MACHINE,
    SMALL_TV,
    SMALL_TV_STAND,
    TREADMILL,
    WEIGHT_BENCH,
    television,
)

#: A tall machine facing a window keeps this far (metres) from its wall, clear of the glass.
BY_THE_WINDOW = 0.4


def spare_room():
    d = Design(
        "gym_01",
        "gym",
        "Spare-room gym: a treadmill facing the window, a mat before the dumbbell rack",
        3.4,
        3.0,
    )
    d.door("S", 2.8, 0.8)
    d.window("W", 0.9, 1.0)
    d.against("W", "treadmill", 0.9, TREADMILL, gap=BY_THE_WINDOW)
    d.against("S", "dumbbell_rack", 1.0, DUMBBELL_RACK)
    d.place("exercise_mat", 1.3, 2.05, EXERCISE_MAT, "south")
    d.against("N", "plant", 3.1, PLANT, gap=0.05)
    return d


def bike_and_rower():
    d = Design(
        "gym_02",
        "gym",
        "Bike facing the window, a rower along the west wall, a rack and a mat",
        4.0,
        3.2,
    )
    d.door("E", 2.7, 0.8)
    d.window("N", 2.0, 1.6)
    d.against("N", "exercise_bike", 1.2, EXERCISE_BIKE, gap=BY_THE_WINDOW)
    d.place("rowing_machine", 1.1, 2.6, ROWING_MACHINE, "east")
    d.against("E", "dumbbell_rack", 1.0, DUMBBELL_RACK)
    d.place("exercise_mat", 2.8, 1.0, EXERCISE_MAT, "south")
    return d


def garage_gym():
    d = Design(
        "gym_03",
        "gym",
        "Garage-size gym: two treadmills facing the television, a rack and a bench",
        5.0,
        4.0,
    )
    d.door("S", 4.5)
    d.window("W", 2.0, 1.4)
    television(d, "E", 1.6, SMALL_TV_STAND, SMALL_TV)
    d.against("E", "treadmill", 1.1, TREADMILL, gap=1.2)
    d.against("E", "treadmill", 2.1, TREADMILL, gap=1.2)
    d.against("N", "dumbbell_rack", 1.0, DUMBBELL_RACK)
    d.place("weight_bench", 0.8, 3.2, WEIGHT_BENCH, "north")
    d.place("exercise_mat", 3.0, 3.3, EXERCISE_MAT, "south")
    d.against("N", "plant", 4.7, PLANT, gap=0.05)
    return d


def narrow_cardio_row():
    d = Design(
        "gym_04",
        "gym",
        "Narrow gym: a bike facing the window, a treadmill, a rower along the west wall",
        3.0,
        5.2,
    )
    d.door("N", 2.5, 0.8)
    d.window("E", 2.8, 1.6)
    d.against("E", "exercise_bike", 2.8, EXERCISE_BIKE, gap=BY_THE_WINDOW)
    d.against("E", "treadmill", 4.3, TREADMILL, gap=0.05)
    d.place("rowing_machine", 0.45, 2.5, ROWING_MACHINE, "south")
    d.against("W", "dumbbell_rack", 0.7, DUMBBELL_RACK)
    d.place("exercise_mat", 1.7, 1.2, EXERCISE_MAT, "south")
    return d


def cardio_studio():
    d = Design(
        "gym_05",
        "gym",
        "Studio: four treadmills and four bikes facing the windows, free weights behind",
        8.0,
        5.0,
    )
    d.door("S", 7.3, 1.0)
    d.window("N", 2.5, 2.0)
    d.window("N", 5.5, 2.0)
    for at in (1.0, 2.0, 3.0, 4.0):
        d.against("N", "treadmill", at, TREADMILL, gap=BY_THE_WINDOW)
    for at in (5.0, 5.75, 6.5, 7.25):
        d.against("N", "exercise_bike", at, EXERCISE_BIKE, gap=BY_THE_WINDOW)
    d.against("W", "dumbbell_rack", 3.9, DUMBBELL_RACK)
    d.place("weight_bench", 2.4, 4.2, WEIGHT_BENCH, "north")
    d.place("weight_bench", 4.0, 4.2, WEIGHT_BENCH, "north")
    d.place("exercise_mat", 5.6, 4.3, EXERCISE_MAT, "south")
    d.against("E", "rowing_machine", 3.0, ROWING_MACHINE)
    d.against("N", "plant", 0.3, PLANT, gap=0.05)
    return d


def tv_home_gym():
    d = Design(
        "gym_06",
        "gym",
        "Home gym: a treadmill facing the television, a bench across from the rack",
        4.5,
        4.0,
    )
    d.door("W", 3.4)
    d.window("E", 2.0, 1.4)
    television(d, "S", 2.5, SMALL_TV_STAND, SMALL_TV)
    d.against("S", "treadmill", 1.4, TREADMILL, gap=0.95)
    d.against("N", "dumbbell_rack", 3.5, DUMBBELL_RACK)
    d.place("weight_bench", 3.6, 1.6, WEIGHT_BENCH, "east")
    d.place("exercise_mat", 0.45, 1.6, EXERCISE_MAT, "east")
    d.against("N", "plant", 0.3, PLANT, gap=0.05)
    return d


def rowing_room():
    d = Design(
        "gym_07", "gym", "Two rowers side by side under the window, a rack and a mat", 4.2, 3.6
    )
    d.door("S", 3.6, 0.8)
    d.window("N", 1.5, 2.0)
    d.against("N", "rowing_machine", 1.0, ROWING_MACHINE)
    d.against("N", "rowing_machine", 2.0, ROWING_MACHINE)
    d.against("E", "dumbbell_rack", 1.0, DUMBBELL_RACK)
    d.place("exercise_mat", 1.5, 3.0, EXERCISE_MAT, "south")
    return d


def strength_corner():
    d = Design(
        "gym_08",
        "gym",
        "Weight bench before two dumbbell racks, a treadmill facing the window, a bike",
        4.8,
        4.2,
    )
    d.door("N", 4.2)
    d.window("W", 2.1, 1.6)
    d.against("W", "treadmill", 2.1, TREADMILL, gap=BY_THE_WINDOW)
    d.against("E", "dumbbell_rack", 2.2, DUMBBELL_RACK)
    d.against("E", "dumbbell_rack", 3.5, DUMBBELL_RACK)
    d.place("weight_bench", 3.0, 3.4, WEIGHT_BENCH, "north")
    d.place("exercise_mat", 1.3, 3.6, EXERCISE_MAT, "south")
    d.against("N", "exercise_bike", 2.0, EXERCISE_BIKE)
    d.against("N", "plant", 0.3, PLANT, gap=0.05)
    return d


def box_room():
    d = Design(
        "gym_09",
        "gym",
        "Box room: an exercise bike facing the window, a mat and a small rack",
        3.0,
        3.0,
    )
    d.door("E", 2.5, 0.8)
    d.window("N", 1.5, 1.2)
    d.against("N", "exercise_bike", 1.5, EXERCISE_BIKE, gap=BY_THE_WINDOW)
    d.against("W", "dumbbell_rack", 2.2, DUMBBELL_RACK)
    d.place("exercise_mat", 1.6, 2.55, EXERCISE_MAT, "south")
    return d


def club_room():
    d = Design(
        "gym_10",
        "gym",
        "Club room: three treadmills facing the television, two bikes, a rower, free weights",
        7.0,
        5.5,
    )
    d.door("W", 4.8, 1.0)
    d.window("S", 2.0, 2.0)
    d.window("S", 5.0, 2.0)
    television(d, "N", 3.0)
    for at in (2.0, 3.0, 4.0):
        d.against("N", "treadmill", at, TREADMILL, gap=1.3)
    d.against("N", "exercise_bike", 5.5, EXERCISE_BIKE, gap=0.5)
    d.against("N", "exercise_bike", 6.3, EXERCISE_BIKE, gap=0.5)
    d.against("E", "rowing_machine", 2.9, ROWING_MACHINE)
    d.against("E", "dumbbell_rack", 4.2, DUMBBELL_RACK)
    d.place("weight_bench", 5.0, 4.6, WEIGHT_BENCH, "north")
    d.place("exercise_mat", 1.8, 4.8, EXERCISE_MAT, "south")
    d.place("exercise_mat", 3.5, 4.8, EXERCISE_MAT, "south")
    d.against("N", "plant", 0.3, PLANT, gap=0.05)
    return d


def long_attic():
    d = Design(
        "gym_11",
        "gym",
        "Long room: a rower by the door, a bike facing the window, rack and bench at the end",
        5.6,
        3.4,
    )
    d.door("S", 0.6, 0.8)
    d.window("N", 2.8, 1.4)
    d.against("N", "rowing_machine", 1.0, ROWING_MACHINE)
    d.against("N", "exercise_bike", 2.8, EXERCISE_BIKE, gap=BY_THE_WINDOW)
    d.against("E", "dumbbell_rack", 1.6, DUMBBELL_RACK)
    d.place("weight_bench", 3.9, 2.0, WEIGHT_BENCH, "north")
    d.place("exercise_mat", 2.0, 2.8, EXERCISE_MAT, "south")
    return d


def family_gym():
    d = Design(
        "gym_12",
        "gym",
        "Family gym: a treadmill, a bike and a rower in a row facing the television",
        5.4,
        4.4,
    )
    d.door("E", 3.8)
    d.window("S", 2.7, 1.8)
    television(d, "N", 2.7)
    d.against("N", "treadmill", 1.3, TREADMILL, gap=1.0)
    d.against("N", "exercise_bike", 2.7, EXERCISE_BIKE, gap=1.0)
    d.against("N", "rowing_machine", 4.1, ROWING_MACHINE, gap=1.0)
    d.against("W", "dumbbell_rack", 3.6, DUMBBELL_RACK)
    d.place("exercise_mat", 2.7, 3.4, EXERCISE_MAT, "south")
    d.against("E", "plant", 0.3, PLANT, gap=0.05)
    return d


def compact_weights():
    d = Design(
        "gym_13",
        "gym",
        "Compact weights room: a bench before the rack, a bike against the east wall",
        3.6,
        3.4,
    )
    d.door("S", 3.1, 0.8)
    d.window("W", 1.7, 1.2)
    d.against("N", "dumbbell_rack", 1.8, DUMBBELL_RACK)
    d.place("weight_bench", 1.8, 2.0, WEIGHT_BENCH, "north")
    d.against("E", "exercise_bike", 1.0, EXERCISE_BIKE)
    d.place("exercise_mat", 0.7, 1.9, EXERCISE_MAT, "east")
    return d


def basement():
    d = Design(
        "gym_14",
        "gym",
        "Basement gym: two treadmills under the high window, a wall of weights, a bench",
        6.0,
        4.5,
    )
    d.door("N", 5.4)
    d.window("N", 2.0, 1.2, sill=1.7, height=0.5)
    d.against("N", "treadmill", 1.5, TREADMILL, gap=0.1)
    d.against("N", "treadmill", 2.5, TREADMILL, gap=0.1)
    d.against("S", "dumbbell_rack", 3.0, DUMBBELL_RACK)
    d.against("S", "dumbbell_rack", 4.4, DUMBBELL_RACK)
    d.place("weight_bench", 4.0, 2.2, WEIGHT_BENCH, "north")
    d.against("E", "exercise_bike", 2.0, EXERCISE_BIKE)
    d.place("exercise_mat", 1.5, 3.6, EXERCISE_MAT, "south")
    return d


def cycling_studio():
    d = Design(
        "gym_15",
        "gym",
        "Cycling studio: eight bikes in two rows facing the instructor's bike",
        6.5,
        5.0,
    )
    d.door("S", 5.9, 1.0)
    d.window("W", 2.5, 2.0)
    d.window("E", 2.5, 2.0)
    d.place("exercise_bike", 3.25, 0.8, EXERCISE_BIKE, "north")
    for z in (2.0, 3.75):
        for x in (1.75, 2.75, 3.75, 4.75):
            d.place("exercise_bike", x, z, EXERCISE_BIKE, "south")
    d.against("N", "plant", 0.3, PLANT, gap=0.05)
    d.against("N", "plant", 6.2, PLANT, gap=0.05)
    return d


def stretching_room():
    d = Design(
        "gym_16",
        "gym",
        "Stretching and weights room: three mats facing the television, a rack and a bench",
        5.0,
        4.0,
    )
    d.door("W", 0.6)
    d.window("E", 2.0, 1.6)
    d.against("N", "dumbbell_rack", 2.8, DUMBBELL_RACK)
    for z in (1.8, 2.5, 3.2):
        d.place("exercise_mat", 1.6, z, EXERCISE_MAT, "south")
    d.place("weight_bench", 3.8, 2.4, WEIGHT_BENCH, "north")
    television(d, "S", 3.8, SMALL_TV_STAND, SMALL_TV)
    return d


DESIGNS = (
    spare_room,
    bike_and_rower,
    garage_gym,
    narrow_cardio_row,
    cardio_studio,
    tv_home_gym,
    rowing_room,
    strength_corner,
    box_room,
    club_room,
    long_attic,
    family_gym,
    compact_weights,
    basement,
    cycling_studio,
    stretching_room,
)
