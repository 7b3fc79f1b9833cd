"""The describer's errors: a description template that is missing, does not compile or
does not render (``TemplateError``, an input error), and a question program that cannot
be answered on a picture (``ProgramError``, a generation error). It is a leaf, so the
templates and the grounding marks, which both raise ``TemplateError``, need not import
each other.
"""

from __future__ import annotations

from scenewright.core.errors import GenerationError, InputError


class TemplateError(InputError):
    """A description template is missing or does not render."""


class ProgramError(GenerationError):
    """A step that cannot give what it must (``unique`` of none or several, an order
    that is not clear, a colour with no clear name)."""
