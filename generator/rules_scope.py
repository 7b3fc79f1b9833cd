"""Where a rule set may read files: its own folder, and what the user allows besides.

Includes, meshes and the templates folder are read only inside a rule set's
``ReadScope``, so a rule set from elsewhere cannot make the program read (or quote)
files outside the folder the user named.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

#: The environment variable that lets rule sets read more than their own folder:
#: paths separated by ``os.pathsep`` (":"), each a folder (with all below it) or a file.
ALLOW_VARIABLE = "SCENEWRIGHT_ALLOW_OUTSIDE"


@dataclass(frozen=True)
class ReadScope:
    """Where a rule set may read files (includes, meshes, templates): inside its root,
    the folder of the rules file the user named, and inside what the user allows
    besides. Paths are compared with their links resolved, so a link in the rule set's
    folder to a file elsewhere is outside."""

    root: Path
    allowed: tuple[Path, ...] = ()

    @classmethod
    def of(
        cls, path: str | os.PathLike[str], allow: Iterable[str | os.PathLike[str]] = ()
    ) -> ReadScope:
        """The scope of the rule set whose top file is ``path``, with the paths of
        ``allow`` and of the ``ALLOW_VARIABLE`` environment variable allowed besides."""
        from_environment = [
            item for item in os.environ.get(ALLOW_VARIABLE, "").split(os.pathsep) if item
        ]
        allowed = tuple(Path(item).resolve() for item in [*allow, *from_environment])
        return cls(Path(path).parent.resolve(), allowed)

    def outside(self, path: str | os.PathLike[str]) -> str | None:
        """None when ``path`` is in the scope; else why not, completing "file 'F' ..."."""
        real = Path(path).resolve()
        if any(real.is_relative_to(place) for place in (self.root, *self.allowed)):
            return None
        link = f" (it leads to {real})" if real != Path(os.path.abspath(path)) else ""
        return (
            f"is outside the rule set's folder {self.root}{link}; a rule set reads only its own folder "
            f"unless the user allows more (--allow-outside PATH or {ALLOW_VARIABLE}, see docs/security.md)"
        )
