"""The describer's error a user can cause: a description template that is missing, does
not compile or does not render (``TemplateError``, an input error). It is a leaf, so
the templates and the grounding marks, which both raise it, need not import each other.
"""

from __future__ import annotations

from scenewright.core.errors import InputError


class TemplateError(InputError):
    """A description template is missing or does not render."""
