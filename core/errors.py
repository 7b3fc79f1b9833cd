"""The two kinds of failure a user can meet, how the CLI tells them apart, and the
core's own errors on the input side of that split.

``InputError``: the user's input is wrong (a rules file, an option, a scene.json); the
CLI prints the message on one line (plus the located excerpt a rules error carries)
and exits 2. ``GenerationError``: the input was fine but the work could not be done
(no OpenGL backend, a layout that could not be found); the CLI exits 1. Every stage
raises a subclass of one of these for anything a user can cause, never a bare
exception.
"""

from __future__ import annotations

import os


class ScenewrightError(Exception):
    """Base of every error scenewright raises on purpose."""

    exit_code = 1


class InputError(ScenewrightError):
    """Bad input from the user: exit code 2."""

    exit_code = 2


class GenerationError(ScenewrightError):
    """Valid input whose generation failed for a reason the user must see: exit code 1."""

    exit_code = 1


class RoomError(InputError, ValueError):
    """A room that cannot be built (``core.room``): the message says what is wrong, in
    the user's words. Also a ``ValueError``: a bad argument to ``Room``'s builders, as
    code that builds rooms catches it."""


class MeshFileError(InputError):
    """A mesh file that cannot be used (``core.shapes``); ``reason`` completes "mesh file
    'F' ..."."""

    def __init__(self, path: str | os.PathLike[str], reason: str):
        self.path = str(path)
        self.reason = reason
        super().__init__(f"mesh file '{self.path}' {reason}")
