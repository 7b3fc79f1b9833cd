"""Static checks of a rule set's scene block, and the room it declares.

There is one scene block, with a start symbol; each setting is checked against its
bounds, the templates folder must lie in the rule set's ``ReadScope``, and a room
(``build_room``) must have a valid floor and openings on walls it has.
"""

from __future__ import annotations

from pathlib import Path

from scenewright.core.errors import RoomError
from scenewright.core.limits import MAX_EXTENT, MAX_NODES, MIN_LENGTH
from scenewright.core.room import DEFAULT_WALL_HEIGHT, Room

from . import rules_ast as ast
from .catalog import SourceLocation
from .rules_check_state import CheckState
from .rules_check_values import UPPER_LIMITS, is_whole, number_text, too_large, too_small

#: Type names a room's parts take: a catalog entry may not use them in a room.
ROOM_TYPES = ("wall", "door", "window")


def build_room(decl: ast.RoomDecl) -> tuple[Room | None, list[tuple[SourceLocation, str]]]:
    """The room a ``room`` setting declares, or None and what is wrong, where."""
    try:
        height = decl.height if decl.height is not None else DEFAULT_WALL_HEIGHT
        if decl.size is not None:
            if min(decl.size) < MIN_LENGTH or max(decl.size) > MAX_EXTENT:
                return None, [
                    (
                        decl.location,
                        f"each side of the room must lie between {MIN_LENGTH:g} and {MAX_EXTENT:g} m",
                    )
                ]
            room = Room.rectangle(*decl.size, height)
        else:
            assert decl.corners is not None  # a room block has a size or corners
            if any(abs(v) > MAX_EXTENT for corner in decl.corners for v in corner):
                return None, [
                    (decl.location, f"a room corner lies further than {MAX_EXTENT:g} m out")
                ]
            room = Room.polygon(decl.corners, height)
    except RoomError as problem:
        return None, [
            (
                decl.height_location
                if "height" in str(problem) and decl.height_location
                else decl.location,
                f"bad room: {problem}",
            )
        ]
    problems = []
    for opening in decl.openings:
        numbers = opening.numbers
        opening_height: float | None
        if opening.kind == "door":
            offset, width, *rest = numbers
            opening_height, sill = (rest[0] if rest else None), 0.0
        else:
            offset, width, sill, opening_height = numbers
        if room.wall(opening.wall) is None:
            problems.append(
                (
                    opening.wall_location,
                    f"the room has no wall '{opening.wall}'; name a wall by its "
                    f"side ({', '.join(dict.fromkeys(w.side for w in room.walls))}) or its number "
                    f"(1 to {len(room.walls)}, in the order of the corners)",
                )
            )
            continue
        try:
            room = room.with_opening(
                opening.kind,
                opening.wall,
                offset=offset,
                width=width,
                height=opening_height,
                sill=sill,
            )
        except RoomError as problem:
            problems.append((opening.location, str(problem)))
    return (None if problems else room), problems


class SceneChecks(CheckState):
    """The checks of the scene block."""

    def check_scenes(self, files: list[ast.RulesFile]) -> tuple[str, SourceLocation] | None:
        """Check the one scene block; return its start symbol and where it is named."""
        scenes = [scene for file in files for scene in file.scenes]
        if not scenes:
            root = files[-1].path
            self.error(
                SourceLocation(root, 1, 1),
                "no scene block; add one, e.g. scene village { extent 40 x 40  start Village }",
            )
            return None
        for extra in scenes[1:]:
            self.error(
                extra.location, f"a second scene block (the first is at {scenes[0].location})"
            )
        scene = scenes[0]
        settings: dict[str, ast.Setting] = {}
        for setting in scene.settings:
            if setting.name in settings:
                self.error(setting.location, f"duplicate scene setting '{setting.name}'")
                continue
            settings[setting.name] = setting
            value, at = setting.value, setting.value_location
            if isinstance(value, str) and self.check_text(setting.name, value, at):
                continue
            if setting.name == "extent" and any(v <= 0 for v in setting.numbers()):
                self.error(at, "the extent must be positive")
            elif setting.name == "extent" and min(setting.numbers()) < MIN_LENGTH:
                self.error(at, too_small("each side of the extent", min(setting.numbers())))
            elif setting.name == "extent" and max(setting.numbers()) > MAX_EXTENT:
                self.error(
                    at,
                    too_large("each side of the extent", max(setting.numbers()), MAX_EXTENT, " m"),
                )
            elif setting.name in ("max_depth", "max_nodes") and (
                setting.number() < 1 or not is_whole(setting.number())
            ):
                self.error(
                    at,
                    f"'{setting.name}' must be a whole number of at least 1, "
                    f"not {number_text(setting.number())}",
                )
            elif setting.name in UPPER_LIMITS and setting.number() > UPPER_LIMITS[setting.name]:
                self.error(
                    at,
                    too_large(
                        f"'{setting.name}'", setting.number(), UPPER_LIMITS[setting.name], ""
                    ),
                )
            elif setting.name == "templates":
                self.check_templates(setting.text(), setting)
            elif setting.name in ("square", "line_of_sight") and value not in ("on", "off"):
                self.error(at, f"'{setting.name}' is 'on' or 'off', not '{value}'")
            elif setting.name == "room":
                self.check_room(setting.room(), settings)
        if "room" in settings:
            for other in ("extent", "walls"):
                if other in settings:
                    self.error(
                        settings[other].location,
                        f"'{other}' and 'room' both set the scene's floor; "
                        f"keep the room (its walls give the extent)",
                    )
        self.has_room = "room" in settings or "walls" in settings
        max_nodes = settings.get("max_nodes")
        if (
            max_nodes is not None
            and is_whole(max_nodes.number())
            and 1 <= max_nodes.number() <= MAX_NODES
        ):
            self.max_nodes = int(max_nodes.number())
        if "start" not in settings:
            self.error(
                scene.location, "the scene block has no start symbol (add: start NONTERMINAL)"
            )
            return None
        return settings["start"].text(), settings["start"].value_location

    def check_room(self, decl: ast.RoomDecl, settings: dict[str, ast.Setting]) -> None:
        self.room, problems = build_room(decl)
        for location, message in problems:
            self.error(location, message)

    def check_templates(self, folder_name: str, setting: ast.Setting) -> None:
        """The description templates folder, like a mesh, is found relative to its file
        and must lie in the rule set's scope (its files are checked when read)."""
        folder = self.folder_of(setting)
        if (outside := self.scope.outside(folder / folder_name)) is not None:
            self.error(setting.value_location, f"templates folder '{folder_name}' {outside}")
        elif not (folder / folder_name).is_dir():
            self.error(
                setting.value_location,
                f"templates folder '{folder_name}' not found (looked in {folder.resolve()})",
            )
        else:
            self.check_template_files(folder / folder_name, setting)

    def check_template_files(self, folder: Path, setting: ast.Setting) -> None:
        """Each ``*.j2`` file of a templates folder must be a regular file in it once its
        links are resolved: the describer reads no other."""
        real_folder = folder.resolve()
        for path in sorted(folder.glob("*.j2")):
            real = path.resolve()
            if not real.is_relative_to(real_folder):
                problem = f"leads outside that folder (to {real})"
            elif not real.is_file():
                problem = "is not a regular file"
            else:
                continue
            self.error(
                setting.value_location,
                f"template '{path.name}' of templates folder '{setting.value}' {problem}",
            )
