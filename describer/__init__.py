"""Turns a laid-out scene into grammatical English that is true of it.

``describe(scene, style="full" | "summary" | "short", variant=k, templates=folder, words=n)`` returns a
``Description``: the text, the (subject id, label, object id) facts it states and the
mentions it makes (``grounding``: which characters name which objects). Only
relations the layout satisfied are stated, never ``Implicit*`` ones. The pipeline is
plan (``plan``: what to say, in derivation order, aggregated) -> referring expressions
(``refer``) -> words (``lexicon``, ``english``) -> sentence templates (``templates``).
``view.describe_view`` captions one rendered picture of the scene (only what it shows,
only relations that hold in it), ``refexp`` gives referring expressions for it with
programs that pick out their object and ``questions`` asks CLEVR-style questions about
it with programs that answer them (both run by ``programs``). See docs/describer.md.
"""

from .description import STYLES, Description, describe
from .errors import TemplateError

__all__ = ["Description", "STYLES", "TemplateError", "describe"]
