"""Bedrooms: a bed with its head against a wall and a night table either side, storage
where its doors can open, and in the larger rooms a desk by the window, a dresser, an
armchair to read in or a television at the foot of the bed."""

from scenewright.completion.authoring import Design
from scenewright.completion.designs import (
    ARMCHAIR,
    BEDSIDE_LAMP,
    BOOKSHELF,
    CHAIR,
    DESK,
    DESK_LAMP,
    DOUBLE_BED,
    DRESSER,
    FLOOR_LAMP,
    KING_BED,
    LONG_DRESSER,
    NARROW_WARDROBE,
    NIGHT_TABLE,
    OFFICE_CHAIR,
    PLANT,
    RUG,
    SINGLE_BED,
    SMALL_DESK,
    SMALL_NIGHT_TABLE,
    SMALL_TV,
    SMALL_TV_STAND,
    WARDROBE,
    WIDE_WARDROBE,
)


def _night_tables(d: Design, bed: str, size=NIGHT_TABLE, lamps: bool = True) -> None:
    for table in d.either_side(bed, "nightstand", size):
        if lamps:
            d.on(table, "lamp", BEDSIDE_LAMP)


def double_by_the_window():
    d = Design(
        "bedroom_01",
        "bedroom",
        "Double bed under the north window, wardrobe by the door, dresser opposite",
        4.0,
        3.6,
    )
    d.door("S", 3.45)
    d.window("N", 2.0, 1.4)
    bed = d.against("N", "bed", 2.0, DOUBLE_BED)
    _night_tables(d, bed)
    d.against("W", "wardrobe", 3.1, NARROW_WARDROBE)
    d.against("E", "dresser", 1.3, DRESSER)
    d.against("S", "plant", 2.4, PLANT, gap=0.05)
    return d


def small_single():
    d = Design(
        "bedroom_02",
        "bedroom",
        "Small single room: bed in the north-west corner, desk under the window",
        2.8,
        3.0,
    )
    d.door("E", 2.45, 0.8)
    d.window("N", 2.1, 1.0)
    bed = d.against("N", "bed", 0.5, SINGLE_BED)
    d.beside(bed, "nightstand", SMALL_NIGHT_TABLE, "left")
    desk = d.against("N", "desk", 2.1, SMALL_DESK)
    d.before(desk, "chair", CHAIR, 0.05)
    d.on(desk, "desk_lamp", DESK_LAMP, across=0.35)
    d.against("S", "wardrobe", 1.45, NARROW_WARDROBE)
    return d


def king_with_tv():
    d = Design(
        "bedroom_03",
        "bedroom",
        "King-size bed against the west wall facing a television, wardrobe and dresser",
        5.0,
        4.2,
    )
    d.door("N", 4.4)
    d.window("S", 2.5, 1.8)
    bed = d.against("W", "bed", 2.2, KING_BED)
    _night_tables(d, bed)
    stand = d.against("E", "tv_stand", 2.1, SMALL_TV_STAND)
    d.on(stand, "tv", SMALL_TV)
    d.against("N", "wardrobe", 3.0, WIDE_WARDROBE)
    d.against("S", "dresser", 3.1, DRESSER)
    d.place("rug", 3.05, 2.2, RUG, "east")
    d.against("S", "armchair", 4.3, ARMCHAIR, gap=0.05)
    d.free(0.35, 3.95, 0.5, 0.5, "plant", "floor_lamp")
    return d


def teen_room_with_desk():
    d = Design(
        "bedroom_04",
        "bedroom",
        "Single bed in the corner, desk under the east window, bookshelf and wardrobe",
        3.2,
        3.4,
    )
    d.door("W", 2.8, 0.8)
    d.window("E", 1.2, 1.2)
    bed = d.against("S", "bed", 2.7, SINGLE_BED)
    d.beside(bed, "nightstand", SMALL_NIGHT_TABLE, "left")
    desk = d.against("E", "desk", 0.8, DESK)
    d.before(desk, "office_chair", OFFICE_CHAIR, 0.05)
    d.on(desk, "desk_lamp", DESK_LAMP, across=0.45)
    d.against("W", "bookshelf", 1.2, BOOKSHELF)
    d.against("N", "wardrobe", 1.05, WARDROBE)
    return d


def double_east_wall():
    d = Design(
        "bedroom_05",
        "bedroom",
        "Double bed on the east wall, wardrobe on the window-less west wall",
        3.8,
        3.4,
    )
    d.door("N", 0.6)
    d.window("S", 2.4, 1.2)
    bed = d.against("E", "bed", 1.6, DOUBLE_BED)
    _night_tables(d, bed)
    d.against("W", "wardrobe", 1.55, WARDROBE)
    d.against("S", "dresser", 0.55, DRESSER)
    return d


def reading_corner():
    d = Design(
        "bedroom_06",
        "bedroom",
        "Double bed, an armchair with a floor lamp and a bookshelf for reading",
        4.4,
        3.8,
    )
    d.door("E", 3.2)
    d.window("W", 1.6, 1.4)
    d.window("N", 3.0, 1.0)
    bed = d.against("N", "bed", 1.55, DOUBLE_BED)
    _night_tables(d, bed)
    d.against("S", "wardrobe", 1.3, WIDE_WARDROBE)
    d.place("armchair", 3.75, 1.0, ARMCHAIR, -2.35)
    d.place("floor_lamp", 4.15, 0.3, FLOOR_LAMP, "south")
    d.against("E", "bookshelf", 2.2, BOOKSHELF)
    d.free(2.9, 3.5, 0.8, 0.5, "plant", "dresser")
    return d


def long_narrow():
    d = Design(
        "bedroom_07",
        "bedroom",
        "Long narrow room: bed across the far end, wardrobes along the entrance wall",
        2.9,
        4.6,
    )
    d.door("S", 2.35, 0.8)
    d.window("N", 1.45, 1.2)
    bed = d.against("W", "bed", 1.3, DOUBLE_BED)
    d.beside(bed, "nightstand", SMALL_NIGHT_TABLE, "right")
    d.against("E", "wardrobe", 2.7, WARDROBE)
    d.against("W", "dresser", 3.6, DRESSER)
    return d


def guest_twin():
    d = Design(
        "bedroom_08",
        "bedroom",
        "Twin guest room: two single beds with a shared night table",
        3.8,
        4.0,
    )
    d.door("S", 0.6)
    d.window("N", 1.9, 1.2)
    table = d.against("E", "nightstand", 2.0, NIGHT_TABLE)
    d.on(table, "lamp", BEDSIDE_LAMP)
    d.against("E", "bed", 1.1, SINGLE_BED)
    d.against("E", "bed", 2.9, SINGLE_BED)
    d.against("W", "wardrobe", 2.0, WARDROBE)
    d.against("N", "plant", 0.4, PLANT, gap=0.05)
    return d


def master_suite():
    d = Design(
        "bedroom_09",
        "bedroom",
        "Large master bedroom: king bed, dresser with a television, reading chairs",
        6.0,
        5.0,
    )
    d.door("S", 5.4)
    d.window("N", 1.6, 1.6)
    d.window("W", 2.8, 1.4)
    bed = d.against("N", "bed", 3.5, KING_BED)
    _night_tables(d, bed)
    dresser = d.against("S", "dresser", 3.5, LONG_DRESSER)
    d.on(dresser, "tv", SMALL_TV)
    d.against("E", "wardrobe", 2.6, WIDE_WARDROBE)
    d.place("armchair", 1.0, 1.1, ARMCHAIR, "south")
    d.place("armchair", 1.0, 2.7, ARMCHAIR, "north")
    d.place("floor_lamp", 0.3, 0.3, FLOOR_LAMP, "south")
    d.place("rug", 3.5, 2.8, RUG, "south")
    d.against("S", "plant", 1.0, PLANT, gap=0.05)
    d.free(0.55, 3.9, 1, 0.6, "bookshelf", "dresser")
    return d


def study_bedroom():
    d = Design(
        "bedroom_10",
        "bedroom",
        "Bedroom with a study corner: desk under the east window, shelves beside it",
        4.2,
        3.6,
    )
    d.door("W", 3.05)
    d.window("E", 1.4, 1.2)
    bed = d.against("N", "bed", 1.45, DOUBLE_BED)
    _night_tables(d, bed)
    desk = d.against("E", "desk", 1.4, DESK)
    d.before(desk, "office_chair", OFFICE_CHAIR, 0.05)
    d.on(desk, "desk_lamp", DESK_LAMP, across=-0.45)
    d.against("E", "bookshelf", 2.6, BOOKSHELF)
    d.against("S", "wardrobe", 1.7, WARDROBE)
    return d


def compact_double():
    d = Design(
        "bedroom_11",
        "bedroom",
        "Compact double: bed centred on the window wall, wardrobe facing its foot",
        3.6,
        3.4,
    )
    d.door("E", 2.9, 0.8)
    d.window("W", 1.4, 1.0)
    bed = d.against("W", "bed", 1.55, DOUBLE_BED)
    _night_tables(d, bed, SMALL_NIGHT_TABLE)
    d.against("E", "wardrobe", 1.2, WARDROBE)
    return d


def kids_room():
    d = Design(
        "bedroom_12",
        "bedroom",
        "Child's room: single bed, small desk, bookshelf and a play rug",
        3.4,
        3.2,
    )
    d.door("N", 2.9, 0.8)
    d.window("W", 1.3, 1.2)
    bed = d.against("E", "bed", 2.45, SINGLE_BED)
    d.beside(bed, "nightstand", SMALL_NIGHT_TABLE, "right")
    desk = d.against("W", "desk", 1.1, SMALL_DESK)
    d.before(desk, "chair", CHAIR, 0.05)
    d.against("N", "bookshelf", 1.2, BOOKSHELF)
    d.against("S", "wardrobe", 0.95, NARROW_WARDROBE)
    d.place("rug", 1.75, 1.3, (1.2, 0.8), "south")
    return d


def double_door_west():
    d = Design(
        "bedroom_13",
        "bedroom",
        "Double bed facing the window, wardrobe and dresser on the door wall",
        4.6,
        3.8,
    )
    d.door("W", 0.6)
    d.window("E", 1.9, 1.6)
    bed = d.against("N", "bed", 2.6, DOUBLE_BED)
    _night_tables(d, bed)
    d.against("W", "wardrobe", 2.6, WIDE_WARDROBE)
    d.against("S", "dresser", 2.5, DRESSER)
    d.against("S", "armchair", 3.9, ARMCHAIR, gap=0.05)
    d.free(4.3, 0.5, 0.5, 0.8, "plant", "floor_lamp")
    return d


def loft_style():
    d = Design(
        "bedroom_14",
        "bedroom",
        "Wide room with a king bed on the east wall and a desk on the north window",
        5.2,
        4.0,
    )
    d.door("S", 0.7)
    d.window("N", 1.6, 1.4)
    d.window("E", 0.6, 0.8)
    bed = d.against("E", "bed", 2.2, KING_BED)
    _night_tables(d, bed)
    desk = d.against("N", "desk", 1.6, DESK)
    d.before(desk, "office_chair", OFFICE_CHAIR, 0.05)
    d.on(desk, "desk_lamp", DESK_LAMP, across=0.45)
    d.against("W", "wardrobe", 1.8, WIDE_WARDROBE)
    d.against("S", "dresser", 1.9, DRESSER)
    d.place("rug", 2.55, 2.3, RUG, "east")
    return d


def attic_single():
    d = Design(
        "bedroom_15",
        "bedroom",
        "Narrow single room: bed in the far corner, dresser and wardrobe on the long walls",
        2.8,
        3.6,
    )
    d.door("S", 0.5, 0.8)
    d.window("N", 1.4, 0.9)
    bed = d.against("N", "bed", 2.3, SINGLE_BED)
    d.beside(bed, "nightstand", SMALL_NIGHT_TABLE, "right")
    d.against("W", "dresser", 1.2, DRESSER)
    d.against("E", "wardrobe", 3.0, NARROW_WARDROBE)
    return d


def double_with_bookshelves():
    d = Design(
        "bedroom_16",
        "bedroom",
        "Double bed between two windows, bookshelves and a wardrobe opposite",
        4.0,
        4.0,
    )
    d.door("E", 3.45)
    d.window("N", 0.6, 0.8)
    d.window("N", 3.4, 0.8)
    bed = d.against("N", "bed", 2.1, DOUBLE_BED)
    _night_tables(d, bed)
    d.against("S", "bookshelf", 1.6, BOOKSHELF)
    d.against("S", "bookshelf", 2.55, BOOKSHELF)
    d.against("W", "wardrobe", 3.05, WARDROBE)
    d.place("rug", 2.1, 2.6, (1.6, 1.0), "south")
    return d


DESIGNS = (
    double_by_the_window,
    small_single,
    king_with_tv,
    teen_room_with_desk,
    double_east_wall,
    reading_corner,
    long_narrow,
    guest_twin,
    master_suite,
    study_bedroom,
    compact_double,
    kids_room,
    double_door_west,
    loft_style,
    attic_single,
    double_with_bookshelves,
)
