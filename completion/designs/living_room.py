"""Living rooms: a sofa facing the television across a coffee table (the screen on a
wall that does not face a window), armchairs closing the group, a rug under it, and
shelves, lamps, plants and sometimes a piano on the walls left free."""

from scenewright.completion.authoring import Design
from scenewright.completion.designs import (
    ARMCHAIR,
    BOOKSHELF,
    COFFEE_TABLE,
    FLOOR_LAMP,
    LARGE_PLANT,
    LARGE_RUG,
    LOVESEAT,
    PIANO,
    PIANO_BENCH,
    PLANT,
    RUG,
    SMALL_COFFEE_TABLE,
    SMALL_TV,
    SMALL_TV_STAND,
    SOFA,
    WIDE_BOOKSHELF,
    television,
)


def _sofa_group(d: Design, sofa: str, table=COFFEE_TABLE) -> str:
    """The coffee table 0.45 m before the sofa: a knee's room, within reach."""
    return d.before(sofa, "coffee_table", table, 0.45, facing="same")


def east_west_classic():
    d = Design(
        "living_room_01",
        "living_room",
        "Sofa on the east wall facing the television on the west wall",
        5.0,
        4.0,
    )
    d.door("S", 0.6)
    d.window("N", 2.5, 1.8)
    television(d, "W", 2.0)
    sofa = d.against("E", "sofa", 2.0, SOFA)
    _sofa_group(d, sofa)
    d.place("rug", 3.3, 2.0, LARGE_RUG, "east")
    d.place("armchair", 2.4, 0.9, ARMCHAIR, "south")
    d.beside(sofa, "floor_lamp", FLOOR_LAMP, "left")
    d.against("S", "bookshelf", 2.5, BOOKSHELF)
    d.against("N", "plant", 0.4, PLANT, gap=0.05)
    return d


def small_flat():
    d = Design(
        "living_room_02",
        "living_room",
        "Small flat: two-seat sofa facing a small television, one armchair",
        3.4,
        3.8,
    )
    d.door("E", 3.25, 0.8)
    d.window("W", 1.9, 1.4)
    television(d, "N", 1.7, SMALL_TV_STAND, SMALL_TV)
    sofa = d.against("S", "sofa", 1.5, LOVESEAT)
    _sofa_group(d, sofa, SMALL_COFFEE_TABLE)
    d.place("armchair", 0.55, 1.7, ARMCHAIR, "east")
    d.against("W", "plant", 0.35, PLANT, gap=0.05)
    return d


def long_room_with_piano():
    d = Design(
        "living_room_03",
        "living_room",
        "Long living room: sitting group at one end, piano at the other",
        6.0,
        4.0,
    )
    d.door("N", 5.3)
    d.window("S", 1.8, 2.0)
    d.window("W", 2.0, 1.2)
    television(d, "E", 2.0)
    sofa = d.place("sofa", 2.35, 2.0, SOFA, "east")
    _sofa_group(d, sofa)
    d.place("rug", 3.6, 2.0, LARGE_RUG, "east")
    d.place("armchair", 3.6, 0.7, ARMCHAIR, "south")
    d.place("armchair", 3.6, 3.3, ARMCHAIR, "north")
    piano = d.against("N", "piano", 1.0, PIANO)
    d.before(piano, "chair", PIANO_BENCH, 0.15)
    d.against("N", "bookshelf", 2.4, BOOKSHELF)
    return d


def corner_window():
    d = Design(
        "living_room_04",
        "living_room",
        "Square room: sofa with its back to the room's centre line",
        4.5,
        4.5,
    )
    d.door("W", 3.9)
    d.window("N", 2.25, 2.0)
    d.window("E", 1.5, 1.2)
    television(d, "S", 2.6)
    sofa = d.place("sofa", 2.6, 1.3, SOFA, "south")
    _sofa_group(d, sofa)
    d.place("rug", 2.6, 2.3, RUG, "south")
    d.place("armchair", 1.0, 2.4, ARMCHAIR, "east")
    d.beside(sofa, "floor_lamp", FLOOR_LAMP, "right", gap=0.1)
    d.against("W", "bookshelf", 0.6, BOOKSHELF)
    d.against("E", "plant", 3.9, LARGE_PLANT, gap=0.05)
    return d


def two_sofas():
    d = Design(
        "living_room_05",
        "living_room",
        "Conversation room: two sofas facing across a coffee table",
        5.0,
        4.4,
    )
    d.door("S", 4.4)
    d.window("N", 2.5, 2.2)
    d.against("W", "sofa", 2.1, SOFA)
    d.against("E", "sofa", 2.1, SOFA)
    d.place("coffee_table", 2.5, 2.1, (1.2, 0.7), "east")
    d.place("rug", 2.5, 2.1, LARGE_RUG, "east")
    d.against("S", "bookshelf", 1.2, WIDE_BOOKSHELF)
    d.against("S", "bookshelf", 2.5, WIDE_BOOKSHELF)
    d.against("N", "plant", 0.35, PLANT, gap=0.05)
    d.against("N", "plant", 4.65, PLANT, gap=0.05)
    return d


def tv_on_the_long_wall():
    d = Design(
        "living_room_06",
        "living_room",
        "Television on the long north wall, sofa and armchairs facing it",
        5.6,
        3.8,
    )
    d.door("W", 3.2)
    d.window("S", 2.8, 2.4)
    television(d, "N", 2.8)
    sofa = d.place("sofa", 2.8, 2.75, SOFA, "north")
    _sofa_group(d, sofa)
    d.place("rug", 2.8, 1.9, LARGE_RUG, "south")
    d.place("armchair", 1.2, 1.6, ARMCHAIR, 2.2)
    d.place("armchair", 4.4, 1.6, ARMCHAIR, -2.2)
    d.against("E", "bookshelf", 2.6, BOOKSHELF)
    d.against("E", "floor_lamp", 0.4, FLOOR_LAMP, gap=0.05)
    d.free(0.3, 0.6, 0.5, 0.5, "plant", "floor_lamp")
    return d


def reading_room():
    d = Design(
        "living_room_07",
        "living_room",
        "Quiet sitting room without a television: books, armchairs, a sofa",
        4.2,
        3.6,
    )
    d.door("E", 0.6)
    d.window("S", 2.1, 1.6)
    d.against("N", "bookshelf", 1.1, WIDE_BOOKSHELF)
    d.against("N", "bookshelf", 2.35, WIDE_BOOKSHELF)
    sofa = d.against("W", "sofa", 1.9, LOVESEAT)
    _sofa_group(d, sofa, SMALL_COFFEE_TABLE)
    d.place("armchair", 3.0, 1.9, ARMCHAIR, "west")
    d.place("floor_lamp", 3.7, 2.9, FLOOR_LAMP, "south")
    d.place("rug", 1.65, 1.9, RUG, "east")
    return d


def open_door_north():
    d = Design(
        "living_room_08",
        "living_room",
        "Sofa on the south wall under no window, television opposite",
        4.8,
        4.2,
    )
    d.door("N", 0.6)
    d.window("E", 2.1, 1.8)
    television(d, "N", 2.8)
    sofa = d.against("S", "sofa", 2.8, SOFA)
    _sofa_group(d, sofa)
    d.place("rug", 2.8, 2.1, LARGE_RUG, "south")
    d.place("armchair", 0.9, 2.3, ARMCHAIR, "east")
    d.against("W", "bookshelf", 3.5, BOOKSHELF)
    d.against("S", "plant", 4.45, PLANT, gap=0.05)
    d.free(4.3, 0.6, 0.8, 0.6, "plant", "floor_lamp")
    return d


def large_family_room():
    d = Design(
        "living_room_09",
        "living_room",
        "Large family room: sofa and loveseat round a television, a piano",
        6.0,
        5.0,
    )
    d.door("S", 5.4)
    d.window("N", 3.0, 2.4)
    d.window("W", 2.5, 1.6)
    television(d, "E", 2.0)
    sofa = d.place("sofa", 2.75, 2.0, SOFA, "east")
    _sofa_group(d, sofa)
    d.place("sofa", 4.1, 3.55, LOVESEAT, "north")
    d.place("rug", 4.0, 2.1, LARGE_RUG, "east")
    d.place("armchair", 4.1, 0.75, ARMCHAIR, "south")
    piano = d.against("S", "piano", 1.3, PIANO)
    d.before(piano, "chair", PIANO_BENCH, 0.15)
    d.against("S", "bookshelf", 3.0, WIDE_BOOKSHELF)
    d.against("N", "plant", 0.4, LARGE_PLANT, gap=0.05)
    d.against("N", "floor_lamp", 5.6, FLOOR_LAMP, gap=0.05)
    d.free(0.4, 1.1, 0.7, 1, "bookshelf", "floor_lamp")
    return d


def narrow_living():
    d = Design(
        "living_room_10",
        "living_room",
        "Narrow room: sofa along the long wall, television opposite it",
        3.6,
        5.0,
    )
    d.door("S", 3.0, 0.8)
    d.window("N", 1.8, 1.6)
    television(d, "W", 2.5)
    sofa = d.against("E", "sofa", 2.5, SOFA)
    _sofa_group(d, sofa, SMALL_COFFEE_TABLE)
    d.place("rug", 1.9, 2.5, RUG, "east")
    d.against("N", "armchair", 0.6, ARMCHAIR, gap=0.1)
    d.against("S", "bookshelf", 1.0, BOOKSHELF)
    d.free(0.3, 3.85, 0.5, 0.9, "plant", "floor_lamp")
    return d


def lounge_with_corner_seats():
    d = Design(
        "living_room_11",
        "living_room",
        "Sofa and two armchairs in a U round the coffee table",
        4.6,
        4.0,
    )
    d.door("W", 0.6)
    d.window("E", 2.0, 1.6)
    television(d, "N", 2.6, SMALL_TV_STAND, SMALL_TV)
    sofa = d.against("S", "sofa", 2.6, SOFA)
    _sofa_group(d, sofa)
    d.place("armchair", 1.1, 2.3, ARMCHAIR, "east")
    d.place("armchair", 4.0, 2.3, ARMCHAIR, "west")
    d.place("rug", 2.6, 2.3, RUG, "south")
    d.against("W", "floor_lamp", 3.7, FLOOR_LAMP, gap=0.05)
    return d


def bay_window_room():
    d = Design(
        "living_room_12",
        "living_room",
        "Armchairs in the window, sofa facing the television on the side wall",
        5.2,
        4.2,
    )
    d.door("N", 4.6)
    d.window("S", 2.0, 2.2)
    d.against("S", "armchair", 1.4, ARMCHAIR, gap=0.1)
    d.against("S", "armchair", 2.6, ARMCHAIR, gap=0.1)
    d.place("coffee_table", 2.0, 2.95, SMALL_COFFEE_TABLE, "south")
    television(d, "E", 2.0)
    sofa = d.against("W", "sofa", 1.8, SOFA)
    _sofa_group(d, sofa)
    d.place("rug", 2.3, 1.8, RUG, "east")
    d.against("N", "bookshelf", 2.2, WIDE_BOOKSHELF)
    return d


def studio_sitting():
    d = Design(
        "living_room_13",
        "living_room",
        "Small sitting room: loveseat and armchair, television in the corner",
        3.6,
        3.4,
    )
    d.door("N", 0.55, 0.8)
    d.window("S", 1.8, 1.2)
    television(d, "E", 1.7, SMALL_TV_STAND, SMALL_TV)
    sofa = d.against("W", "sofa", 1.8, LOVESEAT)
    _sofa_group(d, sofa, SMALL_COFFEE_TABLE)
    d.against("N", "plant", 3.2, PLANT, gap=0.05)
    return d


def music_room():
    d = Design(
        "living_room_14",
        "living_room",
        "Living room for music, no television: piano on the inner wall, sofa facing the window",
        4.8,
        4.4,
    )
    d.door("W", 3.8)
    d.window("N", 2.4, 2.0)
    piano = d.against("E", "piano", 2.0, PIANO)
    d.before(piano, "chair", PIANO_BENCH, 0.15)
    sofa = d.place("sofa", 2.4, 3.45, SOFA, "north")
    _sofa_group(d, sofa)
    d.place("armchair", 1.15, 2.2, ARMCHAIR, "east")  # a way behind it from the door
    d.against("S", "bookshelf", 4.2, BOOKSHELF)
    return d


def tv_wall_between_windows():
    d = Design(
        "living_room_15",
        "living_room",
        "Windows north and south, so the television is on the blind west wall",
        5.4,
        4.6,
    )
    d.door("E", 4.0)
    d.window("N", 2.7, 1.6)
    d.window("S", 2.0, 1.6)
    television(d, "W", 2.3)
    sofa = d.place("sofa", 3.75, 2.3, SOFA, "west")
    _sofa_group(d, sofa)
    d.place("rug", 2.6, 2.3, LARGE_RUG, "east")
    d.place("armchair", 2.4, 0.95, ARMCHAIR, "south")
    d.place("armchair", 2.4, 3.65, ARMCHAIR, "north")
    d.against("E", "bookshelf", 1.0, BOOKSHELF)
    d.against("E", "plant", 2.3, LARGE_PLANT, gap=0.05)
    return d


def den():
    d = Design(
        "living_room_16",
        "living_room",
        "Den: deep sofa, television, a wall of books and a reading lamp",
        4.0,
        3.6,
    )
    d.door("S", 0.55, 0.8)
    d.window("E", 1.8, 1.2)
    television(d, "W", 1.6, SMALL_TV_STAND, SMALL_TV)
    sofa = d.against("E", "sofa", 1.8, SOFA)
    _sofa_group(d, sofa)
    d.against("N", "bookshelf", 1.4, BOOKSHELF)
    d.against("N", "bookshelf", 2.35, BOOKSHELF)
    d.against("S", "floor_lamp", 3.7, FLOOR_LAMP, gap=0.05)
    return d


DESIGNS = (
    east_west_classic,
    small_flat,
    long_room_with_piano,
    corner_window,
    two_sofas,
    tv_on_the_long_wall,
    reading_room,
    open_door_north,
    large_family_room,
    narrow_living,
    lounge_with_corner_seats,
    bay_window_room,
    studio_sitting,
    music_room,
    tv_wall_between_windows,
    den,
)
