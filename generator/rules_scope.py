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

from scenewright.core.errors import InputError

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
        return cls.of_folder(Path(path).parent, allow)

    @classmethod
    def of_folder(
        cls, folder: str | os.PathLike[str], allow: Iterable[str | os.PathLike[str]] = ()
    ) -> ReadScope:
        """The scope of a folder (a rule set's, a plan set's), with the paths of ``allow``
        and of the ``ALLOW_VARIABLE`` environment variable allowed besides. A path that
        is a loop of symbolic links is an ``InputError``."""
        from_environment = [
            item for item in os.environ.get(ALLOW_VARIABLE, "").split(os.pathsep) if item
        ]
        allowed = tuple(_resolved(item, "allowed") for item in [*allow, *from_environment])
        return cls(_resolved(folder, "folder"), allowed)

    def outside(self, path: str | os.PathLike[str], holder: str = "rule set") -> str | None:
        """None when ``path`` is in the scope; else why not, completing "file 'F' ..."."""
        try:
            real = Path(path).resolve()
        except (RuntimeError, OSError):  # a loop of links
            return "is a loop of symbolic links"
        if any(real.is_relative_to(place) for place in (self.root, *self.allowed)):
            return None
        link = f" (it leads to {real})" if real != Path(os.path.abspath(path)) else ""
        return (
            f"is outside the {holder}'s folder {self.root}{link}; a {holder} reads only its own folder "
            f"unless the user allows more (--allow-outside PATH or {ALLOW_VARIABLE}, see docs/security.md)"
        )


def _resolved(path: str | os.PathLike[str], what: str) -> Path:
    """``path`` with its links resolved; ``InputError`` for a loop of links."""
    try:
        return Path(path).resolve()
    except (RuntimeError, OSError):
        shown = ascii(os.fspath(path))
        shown = shown if len(shown) <= 60 else shown[:56] + "...'"
        raise InputError(
            f"the {what} path {shown} is a loop of symbolic links; name a real file or folder"
        ) from None
