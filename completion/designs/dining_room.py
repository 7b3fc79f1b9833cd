"""Dining rooms: the table in the middle of the floor with its chairs round it and room
to pull them out, a sideboard (a chest of drawers) on a wall, a display cabinet, a rug
under the table, plants; a kitchen-diner adds its counter and refrigerator."""

from scenewright.completion.authoring import Design
from scenewright.completion.designs import (
    ARMCHAIR,
    BOOKSHELF,
    DRESSER,
    EIGHT_SEAT_TABLE,
    FLOOR_LAMP,
    FOUR_SEAT_TABLE,
    LARGE_PLANT,
    LARGE_RUG,
    LONG_DRESSER,
    PIANO,
    PIANO_BENCH,
    PLANT,
    REFRIGERATOR,
    RUG,
    SIDEBOARD,
    SIX_SEAT_TABLE,
    SQUARE_TABLE,
    WIDE_BOOKSHELF,
)


def four_seat_window():
    d = Design(
        "dining_room_01",
        "dining_room",
        "Four-seat table under a pendant, sideboard under the window",
        3.4,
        3.6,
    )
    d.door("S", 0.55, 0.8)
    d.window("N", 1.7, 1.4)
    table = d.place("dining_table", 1.7, 1.9, FOUR_SEAT_TABLE, "south")
    d.chairs_around(table, 2)
    d.against("N", "dresser", 1.7, DRESSER)
    d.against("E", "plant", 3.2, PLANT, gap=0.05)
    return d


def six_seat_classic():
    d = Design(
        "dining_room_02",
        "dining_room",
        "Six seats round a long table, sideboard and display cabinet",
        4.6,
        3.8,
    )
    d.door("W", 3.3)
    d.window("E", 1.9, 1.6)
    table = d.place("dining_table", 2.3, 1.9, SIX_SEAT_TABLE, "south")
    d.chairs_around(table, 2, ends=2)
    d.place("rug", 2.3, 1.9, LARGE_RUG, "south")
    d.against("N", "dresser", 2.3, SIDEBOARD)
    d.against("S", "bookshelf", 2.6, WIDE_BOOKSHELF)
    d.free(0.35, 0.6, 0.6, 1, "refrigerator", "plant")
    return d


def banquet_room():
    d = Design(
        "dining_room_03",
        "dining_room",
        "Formal dining room: eight seats, two sideboards, plants in the corners",
        6.0,
        4.6,
    )
    d.door("S", 5.3)
    d.window("N", 2.0, 1.6)
    d.window("N", 4.0, 1.6)
    table = d.place("dining_table", 3.0, 2.3, EIGHT_SEAT_TABLE, "south")
    d.chairs_around(table, 3, ends=2)
    d.place("rug", 3.0, 2.3, (3.2, 2.2), "south")
    d.against("W", "dresser", 2.3, LONG_DRESSER)
    d.against("E", "dresser", 2.0, LONG_DRESSER)
    d.against("N", "plant", 0.4, LARGE_PLANT, gap=0.05)
    d.against("S", "plant", 0.4, LARGE_PLANT, gap=0.05)
    d.free(3, 0.3, 1.6, 0.6, "dresser")
    return d


def kitchen_diner():
    d = Design(
        "dining_room_04",
        "dining_room",
        "Kitchen-diner: counter and refrigerator on the north wall, table for four",
        4.0,
        4.2,
    )
    d.door("S", 3.45)
    d.window("W", 2.4, 1.4)
    d.against("N", "kitchen_counter", 1.6, (2.4, 0.6))
    d.against("N", "refrigerator", 3.35, REFRIGERATOR)
    table = d.place("dining_table", 1.9, 2.7, FOUR_SEAT_TABLE, "south")
    d.chairs_around(table, 2)
    return d


def square_table_nook():
    d = Design(
        "dining_room_05",
        "dining_room",
        "Small dining room: square table for four, cabinet on the side wall",
        3.0,
        3.2,
    )
    d.door("E", 2.7, 0.8)
    d.window("N", 1.5, 1.2)
    table = d.place("dining_table", 1.45, 1.6, SQUARE_TABLE, "south")
    d.chairs_around(table, 1, ends=2)
    d.against("W", "bookshelf", 1.6, BOOKSHELF)
    return d


def long_table_long_room():
    d = Design(
        "dining_room_06",
        "dining_room",
        "Long room: six-seat table along it, sideboard on the long wall",
        3.4,
        5.2,
    )
    d.door("N", 2.85, 0.8)
    d.window("S", 1.7, 1.6)
    table = d.place("dining_table", 1.75, 2.7, SIX_SEAT_TABLE, "east")
    d.chairs_around(table, 3)
    d.against("E", "dresser", 4.2, DRESSER)
    d.against("W", "bookshelf", 0.7, BOOKSHELF)
    d.against("S", "plant", 0.35, PLANT, gap=0.05)
    return d


def family_dining():
    d = Design(
        "dining_room_07",
        "dining_room",
        "Family dining room: six seats, a dresser, an armchair by the window",
        4.8,
        4.2,
    )
    d.door("N", 0.6)
    d.window("E", 2.1, 1.8)
    table = d.place("dining_table", 2.2, 2.3, SIX_SEAT_TABLE, "south")
    d.chairs_around(table, 3)
    d.against("W", "dresser", 2.5, SIDEBOARD)
    d.place("armchair", 4.2, 3.6, ARMCHAIR, -2.4)
    d.against("N", "bookshelf", 3.0, BOOKSHELF)
    d.free(4.4, 0.5, 0.7, 0.7, "refrigerator", "plant")
    return d


def dining_with_piano():
    d = Design(
        "dining_room_08",
        "dining_room",
        "Dining room with a piano: table for six, the piano on the south wall",
        5.0,
        4.4,
    )
    d.door("E", 3.8)
    d.window("N", 2.2, 2.0)
    table = d.place("dining_table", 2.8, 2.2, SIX_SEAT_TABLE, "south")
    d.chairs_around(table, 2, ends=2)
    piano = d.against("S", "piano", 1.0, PIANO)
    d.before(piano, "chair", PIANO_BENCH, 0.15)
    d.against("W", "dresser", 2.2, DRESSER)
    d.against("E", "plant", 0.4, PLANT, gap=0.05)
    return d


def round_the_corner():
    d = Design(
        "dining_room_09",
        "dining_room",
        "Table for four turned across the room, cabinets either side of the door",
        3.8,
        3.4,
    )
    d.door("E", 1.7)
    d.window("W", 1.7, 1.4)
    table = d.place("dining_table", 1.85, 1.7, FOUR_SEAT_TABLE, "east")
    d.chairs_around(table, 2)
    d.against("E", "bookshelf", 0.55, BOOKSHELF)
    d.against("E", "bookshelf", 2.85, BOOKSHELF)
    return d


def open_plan_dining():
    d = Design(
        "dining_room_10",
        "dining_room",
        "Open dining area: six seats, a sideboard, a floor lamp and a plant",
        5.2,
        4.0,
    )
    d.door("W", 0.6)
    d.window("S", 2.6, 2.4)
    table = d.place("dining_table", 2.9, 1.95, SIX_SEAT_TABLE, "south")
    d.chairs_around(table, 2, ends=2)
    d.place("rug", 2.9, 1.95, LARGE_RUG, "south")
    d.against("N", "dresser", 3.3, LONG_DRESSER)
    d.against("E", "floor_lamp", 0.3, FLOOR_LAMP, gap=0.05)
    d.against("E", "plant", 3.6, LARGE_PLANT, gap=0.05)
    d.free(0.5, 2.6, 0.6, 1.2, "bookshelf", "refrigerator")
    return d


def breakfast_room():
    d = Design(
        "dining_room_11",
        "dining_room",
        "Breakfast room: square table for four, refrigerator in the corner",
        3.2,
        3.0,
    )
    d.door("S", 2.6, 0.8)
    d.window("W", 1.3, 1.2)
    table = d.place("dining_table", 1.6, 1.2, SQUARE_TABLE, "south")
    d.chairs_around(table, 1, ends=2)
    d.against("W", "refrigerator", 2.55, REFRIGERATOR)  # opens to the way from the door
    return d


def eight_in_a_square_room():
    d = Design(
        "dining_room_12",
        "dining_room",
        "Square room: eight seats, sideboard and display cabinet facing",
        5.0,
        5.0,
    )
    d.door("S", 0.6)
    d.window("E", 2.5, 2.0)
    table = d.place("dining_table", 2.5, 2.4, EIGHT_SEAT_TABLE, "south")
    d.chairs_around(table, 3, ends=2)
    d.against("N", "dresser", 2.5, SIDEBOARD)
    d.against("W", "bookshelf", 2.4, WIDE_BOOKSHELF)
    d.against("S", "plant", 4.5, PLANT, gap=0.05)
    d.free(4.6, 4, 0.7, 0.8, "refrigerator", "plant")
    return d


def cottage_dining():
    d = Design(
        "dining_room_13",
        "dining_room",
        "Cottage dining room: table for four, dresser and shelves on one wall",
        3.6,
        3.8,
    )
    d.door("N", 3.0, 0.8)
    d.window("S", 1.8, 1.2)
    table = d.place("dining_table", 1.8, 2.0, FOUR_SEAT_TABLE, "east")
    d.chairs_around(table, 2)
    d.against("W", "dresser", 0.9, DRESSER)
    d.against("S", "bookshelf", 0.6, BOOKSHELF)  # beside the window, clear of the chairs' backs
    return d


def dining_by_the_garden():
    d = Design(
        "dining_room_14",
        "dining_room",
        "Dining room on the garden side: six seats facing the windows",
        4.4,
        4.0,
    )
    d.door("N", 3.9)
    d.window("S", 1.3, 1.4)
    d.window("S", 3.1, 1.4)
    table = d.place("dining_table", 2.2, 2.05, SIX_SEAT_TABLE, "south")
    d.chairs_around(table, 3)
    d.against("W", "dresser", 2.0, DRESSER)
    d.against("N", "plant", 0.4, PLANT, gap=0.05)
    return d


def dining_with_counter():
    d = Design(
        "dining_room_15",
        "dining_room",
        "Dining room with a serving counter and refrigerator along one wall",
        4.6,
        4.4,
    )
    d.door("W", 3.8)
    d.window("N", 2.3, 1.6)
    d.against("E", "kitchen_counter", 2.2, (1.8, 0.6))
    d.against("E", "refrigerator", 3.6, REFRIGERATOR)
    table = d.place("dining_table", 2.0, 2.2, SIX_SEAT_TABLE, "east")
    d.chairs_around(table, 2, ends=2)
    return d


def compact_six():
    d = Design(
        "dining_room_16",
        "dining_room",
        "Compact six-seat dining room, sideboard on the end wall",
        3.8,
        4.0,
    )
    d.door("S", 3.3, 0.8)
    d.window("W", 2.0, 1.4)
    table = d.place("dining_table", 1.9, 2.0, (1.6, 0.9), "east")
    d.chairs_around(table, 2, ends=2)
    d.against("E", "dresser", 1.2, DRESSER)
    d.place("rug", 1.9, 2.0, RUG, "east")
    return d


DESIGNS = (
    four_seat_window,
    six_seat_classic,
    banquet_room,
    kitchen_diner,
    square_table_nook,
    long_table_long_room,
    family_dining,
    dining_with_piano,
    round_the_corner,
    open_plan_dining,
    breakfast_room,
    eight_in_a_square_room,
    cottage_dining,
    dining_by_the_garden,
    dining_with_counter,
    compact_six,
)
