"""Studies and offices: the desk under or beside a window so daylight falls on it (never
with the window behind the screen), its chair pulled up to it, shelves and filing
cabinets within a few steps, and in the larger rooms visitors' chairs, a reading
armchair, a sofa or a whiteboard."""

from scenewright.completion.authoring import Design
from scenewright.completion.designs import (
    ARMCHAIR,
    BOOKSHELF,
    CHAIR,
    DESK,
    DESK_LAMP,
    FILING_CABINET,
    FLOOR_LAMP,
    LAPTOP,
    LARGE_DESK,
    LOVESEAT,
    OFFICE_CHAIR,
    PLANT,
    RUG,
    SMALL_COFFEE_TABLE,
    SMALL_DESK,
    WHITEBOARD,
    WIDE_BOOKSHELF,
)


def _workplace(
    d: Design, wall: str, at: float, desk=DESK, lamp: bool = True, laptop: bool = False
) -> str:
    """A desk against ``wall`` with its office chair before it (and a lamp, a laptop)."""
    desk_id = d.against(wall, "desk", at, desk)
    d.before(desk_id, "office_chair", OFFICE_CHAIR, 0.05)
    if lamp:
        d.on(desk_id, "desk_lamp", DESK_LAMP, across=desk[0] / 2.0 - 0.15)
    if laptop:
        d.on(desk_id, "laptop", LAPTOP)
    return desk_id


def home_office_window():
    d = Design(
        "study_01",
        "study",
        "Home office: desk under the north window, shelves on the side wall",
        3.0,
        3.2,
    )
    d.door("S", 2.45, 0.8)
    d.window("N", 1.4, 1.4)
    _workplace(d, "N", 1.4, laptop=True)
    d.against("W", "bookshelf", 1.5, BOOKSHELF)
    d.against("W", "bookshelf", 2.45, BOOKSHELF)
    d.against("E", "filing_cabinet", 1.3, FILING_CABINET)
    return d


def library_study():
    d = Design(
        "study_02",
        "study",
        "Library study: wall of shelves, large desk facing into the room",
        4.4,
        3.8,
    )
    d.door("S", 0.6)
    d.window("E", 1.6, 1.4)
    for at in (0.7, 1.95, 3.2):
        d.against("N", "bookshelf", at, WIDE_BOOKSHELF)
    d.against("W", "bookshelf", 2.3, WIDE_BOOKSHELF)
    desk = d.place("desk", 2.4, 2.45, LARGE_DESK, "north")
    d.place("office_chair", 2.4, 1.7, OFFICE_CHAIR, "south")
    d.on(desk, "desk_lamp", DESK_LAMP, across=-0.6)
    d.place("armchair", 3.7, 2.7, ARMCHAIR, "west")
    d.place("floor_lamp", 4.15, 3.5, FLOOR_LAMP, "south")
    d.free(4.1, 0.7, 0.55, 0.7, "plant")
    return d


def corner_desk_office():
    d = Design(
        "study_03",
        "study",
        "Small office: desk beside the east window, filing cabinets, visitor's chair",
        3.2,
        3.6,
    )
    d.door("W", 3.0, 0.8)
    d.window("E", 1.2, 1.2)
    _workplace(d, "E", 1.3, laptop=True)
    d.against("N", "filing_cabinet", 0.4, FILING_CABINET)
    d.against("N", "filing_cabinet", 0.9, FILING_CABINET)
    d.against("S", "bookshelf", 2.4, BOOKSHELF)
    d.place("chair", 1.1, 1.65, CHAIR, "east")  # clear of the filing cabinets' drawers
    return d


def writer_room():
    d = Design(
        "study_04",
        "study",
        "Writer's room: desk under the window, a reading armchair by the shelves",
        3.8,
        3.4,
    )
    d.door("E", 2.9)
    d.window("W", 1.5, 1.2)
    _workplace(d, "W", 1.5)
    d.against("N", "bookshelf", 2.0, BOOKSHELF)
    d.against("N", "bookshelf", 2.95, BOOKSHELF)
    d.place("armchair", 2.7, 1.5, ARMCHAIR, -2.4)
    d.place("floor_lamp", 3.55, 1.1, FLOOR_LAMP, "south")
    d.against("S", "plant", 0.35, PLANT, gap=0.05)
    d.free(0.35, 2.5, 0.6, 0.7, "filing_cabinet", "plant")
    return d


def two_person_office():
    d = Design(
        "study_05",
        "study",
        "Shared office: two desks along the window wall, shared filing and shelves",
        4.8,
        3.6,
    )
    d.door("S", 4.2)
    d.window("N", 1.3, 1.4)
    d.window("N", 3.5, 1.4)
    _workplace(d, "N", 1.3, LARGE_DESK, laptop=True)
    _workplace(d, "N", 3.5, LARGE_DESK, laptop=True)
    d.against("W", "filing_cabinet", 2.4, FILING_CABINET)
    d.against("W", "filing_cabinet", 2.9, FILING_CABINET)
    d.against("S", "bookshelf", 2.4, WIDE_BOOKSHELF)
    d.against("E", "plant", 2.3, PLANT, gap=0.05)
    return d


def managers_office():
    d = Design(
        "study_06",
        "study",
        "Manager's office: desk facing the door, visitors' chairs, a whiteboard",
        5.0,
        4.2,
    )
    d.door("S", 0.6)
    d.window("N", 2.6, 2.0)
    desk = d.place("desk", 2.6, 1.45, LARGE_DESK, "south")
    d.place("office_chair", 2.6, 0.65, OFFICE_CHAIR, "south")
    d.on(desk, "desk_lamp", DESK_LAMP, across=0.6)
    d.on(desk, "laptop", LAPTOP)
    d.place("chair", 2.2, 2.45, CHAIR, "north")
    d.place("chair", 3.0, 2.45, CHAIR, "north")
    d.against("E", "whiteboard", 2.4, WHITEBOARD)
    d.against("W", "bookshelf", 1.2, WIDE_BOOKSHELF)
    d.against("W", "filing_cabinet", 2.3, FILING_CABINET)
    d.against("S", "plant", 4.6, PLANT, gap=0.05)
    d.free(4.65, 0.6, 0.6, 1, "filing_cabinet", "plant")
    return d


def study_with_sofa():
    d = Design(
        "study_07",
        "study",
        "Study with a sofa for reading: desk by the window, sofa facing the shelves",
        4.6,
        4.0,
    )
    d.door("N", 4.0)
    d.window("W", 1.3, 1.4)
    _workplace(d, "W", 1.3)
    d.against("E", "bookshelf", 1.95, WIDE_BOOKSHELF)
    d.against("E", "bookshelf", 3.2, WIDE_BOOKSHELF)
    sofa = d.against("S", "sofa", 2.3, LOVESEAT)
    d.before(sofa, "coffee_table", SMALL_COFFEE_TABLE, 0.4, facing="same")
    d.place("rug", 2.3, 2.9, RUG, "south")
    return d


def tiny_box_room():
    d = Design(
        "study_08", "study", "Box room office: small desk under the window, one shelf", 2.8, 3.0
    )
    d.door("S", 0.5, 0.8)
    d.window("N", 1.4, 1.0)
    _workplace(d, "N", 1.4, SMALL_DESK, laptop=True, lamp=False)
    d.against("E", "bookshelf", 2.0, BOOKSHELF)
    return d


def architect_office():
    d = Design(
        "study_09",
        "study",
        "Drawing office: two large desks facing the long window wall, plan cabinets",
        5.6,
        4.0,
    )
    d.door("W", 3.4)
    d.window("E", 2.0, 2.4)
    d.window("N", 2.8, 1.6)
    _workplace(d, "E", 1.2, LARGE_DESK)
    _workplace(d, "E", 2.9, LARGE_DESK)
    d.against("S", "filing_cabinet", 1.5, FILING_CABINET)
    d.against("S", "filing_cabinet", 2.0, FILING_CABINET)
    d.against("S", "filing_cabinet", 2.5, FILING_CABINET)
    d.against("W", "whiteboard", 1.5, WHITEBOARD)
    d.against("N", "bookshelf", 1.0, BOOKSHELF)
    return d


def student_study():
    d = Design(
        "study_10",
        "study",
        "Student's study: desk on the side wall, the window to its left, shelves above",
        3.4,
        3.0,
    )
    d.door("N", 2.9, 0.8)
    d.window("W", 1.5, 1.2)
    _workplace(d, "S", 1.0, laptop=True)
    d.against("E", "bookshelf", 1.6, BOOKSHELF)
    d.against("N", "armchair", 0.6, ARMCHAIR, gap=0.05)
    return d


def consulting_room():
    d = Design(
        "study_11",
        "study",
        "Consulting room: desk with two visitors' chairs, shelves, a plant",
        4.0,
        4.0,
    )
    d.door("E", 3.45)
    d.window("W", 2.0, 1.6)
    desk = d.place("desk", 1.45, 2.0, DESK, "east")
    d.place("office_chair", 0.7, 2.0, OFFICE_CHAIR, "east")
    d.on(desk, "desk_lamp", DESK_LAMP, across=-0.45)
    d.place("chair", 2.4, 1.6, CHAIR, "west")
    d.place("chair", 2.4, 2.4, CHAIR, "west")
    d.against("N", "bookshelf", 2.0, WIDE_BOOKSHELF)
    d.against("N", "filing_cabinet", 3.5, FILING_CABINET)
    d.against("S", "plant", 1.0, PLANT, gap=0.05)
    return d


def long_study():
    d = Design(
        "study_12",
        "study",
        "Long study: desk at the window end, shelves down one long wall",
        2.9,
        4.8,
    )
    d.door("S", 2.35, 0.8)
    d.window("N", 1.45, 1.2)
    _workplace(d, "N", 1.45)
    for at in (1.6, 2.55, 3.5):
        d.against("W", "bookshelf", at, BOOKSHELF)
    d.against("E", "armchair", 2.6, ARMCHAIR, gap=0.05)
    return d


def home_office_with_guest_sofa():
    d = Design(
        "study_13",
        "study",
        "Home office that doubles as a sitting room: desk at the window, sofa opposite",
        4.2,
        4.2,
    )
    d.door("W", 3.6)
    d.window("N", 2.1, 1.6)
    _workplace(d, "N", 2.1, LARGE_DESK, laptop=True)
    d.against("S", "sofa", 2.4, LOVESEAT)
    d.against("E", "bookshelf", 2.8, BOOKSHELF)
    d.against("E", "filing_cabinet", 1.6, FILING_CABINET)
    d.against("W", "plant", 0.4, PLANT, gap=0.05)
    return d


def team_room():
    d = Design(
        "study_14",
        "study",
        "Team room: four desks in two facing pairs, whiteboard on the end wall",
        6.0,
        4.6,
    )
    d.door("S", 5.4)
    d.window("N", 3.0, 3.0)
    for x in (2.2, 3.6):  # desks back to back, each chair facing its desk
        d.place("desk", x, 1.9, (1.4, 0.7), "north")
        d.place("office_chair", x, 1.15, OFFICE_CHAIR, "south")
        d.place("desk", x, 2.6, (1.4, 0.7), "south")
        d.place("office_chair", x, 3.35, OFFICE_CHAIR, "north")
    d.against("W", "whiteboard", 2.2, WHITEBOARD)
    d.against("E", "filing_cabinet", 1.2, FILING_CABINET)
    d.against("E", "filing_cabinet", 1.7, FILING_CABINET)
    d.against("E", "bookshelf", 2.6, BOOKSHELF)
    return d


def attic_study():
    d = Design(
        "study_15",
        "study",
        "Attic study: desk under the gable window, low shelves, a reading chair",
        3.6,
        3.2,
    )
    d.door("S", 0.55, 0.8)
    d.window("E", 1.6, 1.0)
    _workplace(d, "E", 1.6)
    d.against("W", "bookshelf", 0.8, BOOKSHELF)
    d.against("N", "armchair", 1.5, ARMCHAIR, gap=0.05)
    d.free(1.6, 2.9, 1.0, 0.5, "bookshelf", "plant")
    return d


def desk_facing_window_side():
    d = Design(
        "study_16",
        "study",
        "Study with the desk side-on to the south window, filing cabinet and shelves on the other walls",
        3.6,
        3.8,
    )
    d.door("N", 0.55, 0.8)
    d.window("S", 1.8, 1.4)
    _workplace(d, "E", 2.6, laptop=True)
    d.against("N", "filing_cabinet", 2.6, FILING_CABINET)
    d.against("W", "bookshelf", 1.6, WIDE_BOOKSHELF)
    d.against("W", "bookshelf", 2.85, BOOKSHELF)
    return d


DESIGNS = (
    home_office_window,
    library_study,
    corner_desk_office,
    writer_room,
    two_person_office,
    managers_office,
    study_with_sofa,
    tiny_box_room,
    architect_office,
    student_study,
    consulting_room,
    long_study,
    home_office_with_guest_sofa,
    team_room,
    attic_study,
    desk_facing_window_side,
)
