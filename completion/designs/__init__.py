"""The hand-drawn designs of the shipped plan set, one module per room type (see
``completion.authoring``), and the furniture sizes they draw with.

Sizes are (width, depth) in metres, as sold: a double bed's frame is 1.6 x 2.1, a
king-size 1.8 x 2.1, a single 0.95 x 2.0; a night table 0.5 x 0.4; a wardrobe 1.2 (two
doors) or 1.8 (three) by 0.6; a desk 1.2-1.6 by 0.6-0.7; a three-seat sofa 2.2 x 0.9;
a treadmill 0.8 x 1.9, an exercise bike 0.55 x 1.1, a rowing machine 0.6 x 2.2, a
flat weight bench 0.6 x 1.3 with its feet, a two-tier dumbbell rack 1.2 x 0.5, an
exercise mat 1.8 x 0.6.
"""

SINGLE_BED = (0.95, 2.0)
DOUBLE_BED = (1.6, 2.1)
KING_BED = (1.8, 2.1)
NIGHT_TABLE = (0.5, 0.4)
SMALL_NIGHT_TABLE = (0.4, 0.35)
BEDSIDE_LAMP = (0.25, 0.25)
WARDROBE = (1.2, 0.6)
WIDE_WARDROBE = (1.8, 0.6)
NARROW_WARDROBE = (0.9, 0.6)
DRESSER = (1.0, 0.5)
LONG_DRESSER = (1.4, 0.5)
DESK = (1.2, 0.6)
LARGE_DESK = (1.6, 0.75)
SMALL_DESK = (1.0, 0.55)
DESK_LAMP = (0.2, 0.2)
LAPTOP = (0.34, 0.24)
OFFICE_CHAIR = (0.6, 0.6)
CHAIR = (0.45, 0.5)
BOOKSHELF = (0.9, 0.32)
WIDE_BOOKSHELF = (1.2, 0.35)
FILING_CABINET = (0.45, 0.6)
ARMCHAIR = (0.8, 0.8)
SOFA = (2.2, 0.9)
LOVESEAT = (1.6, 0.85)
COFFEE_TABLE = (1.1, 0.6)
SMALL_COFFEE_TABLE = (0.8, 0.5)
TV_STAND = (1.6, 0.45)
SMALL_TV_STAND = (1.2, 0.4)
TV = (1.2, 0.2)
SMALL_TV = (0.9, 0.2)
FLOOR_LAMP = (0.35, 0.35)
PLANT = (0.4, 0.4)
LARGE_PLANT = (0.5, 0.5)
RUG = (2.0, 1.4)
LARGE_RUG = (2.4, 1.7)
PIANO = (1.5, 0.6)
PIANO_BENCH = (0.75, 0.4)
FOUR_SEAT_TABLE = (1.2, 0.8)
SIX_SEAT_TABLE = (1.8, 0.9)
EIGHT_SEAT_TABLE = (2.4, 1.0)
SQUARE_TABLE = (0.9, 0.9)
SIDEBOARD = (1.6, 0.5)
REFRIGERATOR = (0.7, 0.7)
WHITEBOARD = (1.8, 0.1)
TREADMILL = (0.8, 1.9)
EXERCISE_BIKE = (0.55, 1.1)
ROWING_MACHINE = (0.6, 2.2)
WEIGHT_BENCH = (0.6, 1.3)
DUMBBELL_RACK = (1.2, 0.5)
EXERCISE_MAT = (1.8, 0.6)


def television(design, wall: str, at: float, stand=TV_STAND, screen=TV) -> str:
    """A television on its stand with its back to ``wall`` of ``design`` (an
    ``authoring.Design``), centred ``at`` along it; returns the stand's id."""
    stand_id = design.against(wall, "tv_stand", at, stand)
    design.on(stand_id, "tv", screen)
    return stand_id
