"""Complete a room from a few objects, from a set of furnished floor plans.

The method is Fu et al., "Adaptive Synthesis of Indoor Scenes via Activity-Associated
Object Relation Graphs" (ACM TOG 36(6), 2017). Its pieces, one module each:

| module | job |
|---|---|
| ``floor_plan`` | the plan format: read a plan (JSON, checked against ``plan.schema.json``) into ``Plan`` |
| ``plan_checks`` | what makes a drawn plan wrong: furniture through walls, overlaps, a blocked door |
| ``activity`` | how each category is used (stay at it, fetch from it), its use pose, touch and visual areas |
| ``features`` | a plan's room feature and its 10 x 10 occupancy mask in the door-aware canonical frame |
| ``model_builder`` | the plan model built from plans: per type P(category), co-occurrence times the activity prior, masks and clusters |
| ``plan_model`` | the plan model's records (``PlanModel``, per type ``RoomTypeModel``, per plan ``PlanEntry``) and its JSON |
| ``accessories`` | what stands on or at what in the plans, and where (relative poses); each accessory's anchor, relations and start in a room |
| ``selection`` | what a room should hold: its type(s) (Equation 2) and categories (Algorithm 1) |
| ``layout_mask`` | where things should go: the mask amalgamated from the most similar plans (Equation 4) |
| ``regions`` | a room of several types split by virtual walls into one region per type |
| ``complete`` | a request (an empty room, a few categories) -> a furnished, laid-out scene (``scenewright complete``) |
| ``request`` | the request: the room, its doors and windows, the categories asked for |
| ``contents`` | what the room holds: its type(s), their categories and the layout mask |
| ``furnishing`` | the scene graph of the room's pieces with the relations a room's rules would state, accessories' from the plans |
| ``starting_poses`` | where the layout starts: the large pieces along the walls, on the mask, accessories by them |
| ``explanation`` | a completed room's summary line and its layout mask drawn for people |
| ``evaluation`` | leave-one-out over a plan set, against simple baselines |
| ``drawing`` | plans (and their layout masks) drawn on one PNG sheet |
| ``stances``, ``neighbours`` | how each category stands to the walls, the windows and the pieces around it, learned from the plans |
| ``authoring``, ``designs/`` | the shipped plans, drawn by hand in a designer's terms |

The shipped plan set is ``completion/plans/<type>/*.json``; ``shipped_plans_dir()``
names the folder.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

#: How ``complete`` chooses the categories beyond the request (``selection.choose_categories``)
#: and the layout mask (``layout_mask.choose_mask``); the first of each is the default. The
#: leave-one-out measured neither paper step better than its baseline by more than its
#: spread (docs/completion.md, "How well it predicts"), so the baselines are the defaults.
CATEGORY_METHODS = ("co-occurrence", "algorithm1")
MASK_METHODS = ("mean", "equation4")


def shipped_plans_dir() -> Path:
    """The folder of the plan set shipped with the package (one sub-folder per room type)."""
    return Path(str(resources.files("scenewright.completion").joinpath("plans")))
