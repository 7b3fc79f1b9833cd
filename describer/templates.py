"""The jinja2 templates that frame each kind of sentence, and a rule set's own templates.

The package's templates live in ``describer/templates/*.j2``. A rule set may bring a
folder of its own: a file there replaces the package's file of the same name, the
others stay. Templates receive plain strings and lists only and are rendered in a
sandboxed environment, so a template from a downloaded rule set cannot reach Python
objects. Rendered text has its whitespace normalised, so templates may be laid out
freely.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import jinja2
from jinja2.sandbox import SandboxedEnvironment

from scenewright.errors import InputError

from .english import join_list, with_article

PACKAGE_TEMPLATES = Path(__file__).parent / "templates"


class TemplateError(InputError):
    """A description template is missing or does not render."""


def template_environment(user_templates: str | Path | None = None) -> SandboxedEnvironment:
    """A sandboxed environment reading ``user_templates`` first, then the package's templates."""
    folders = [PACKAGE_TEMPLATES]
    if user_templates is not None:
        folder = Path(user_templates)
        if not folder.is_dir():
            raise TemplateError(f"description templates folder {str(folder)!r} does not exist")
        folders.insert(0, folder.resolve())
    return _environment(tuple(folders))


@lru_cache(maxsize=16)
def _environment(folders: tuple[Path, ...]) -> SandboxedEnvironment:
    """One environment per folder list, so compiled templates are reused across scenes.

    jinja2 still notices edited template files (it checks their modification time).
    """
    environment = SandboxedEnvironment(
        loader=jinja2.FileSystemLoader([str(f) for f in folders]),
        undefined=jinja2.StrictUndefined,
        autoescape=False,
    )
    environment.filters["join_list"] = join_list
    environment.filters["with_article"] = with_article
    return environment


def render(environment: SandboxedEnvironment, name: str, **context: object) -> str:
    """Render ``name`` with ``context`` to one line of text, whitespace normalised."""
    try:
        text = environment.get_template(name).render(**context)
    except jinja2.TemplateError as error:
        raise TemplateError(f"description template {name}: {error}") from None
    return " ".join(text.split())
