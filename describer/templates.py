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

from scenewright.core.errors import InputError

from .english import join_list, with_article

PACKAGE_TEMPLATES = Path(__file__).parent / "templates"


class TemplateError(InputError):
    """A description template is missing or does not render."""


def template_environment(user_templates: str | Path | None = None) -> SandboxedEnvironment:
    """A sandboxed environment reading ``user_templates`` first, then the package's templates."""
    folders = [PACKAGE_TEMPLATES]
    if user_templates is not None:
        folders.insert(0, _existing_folder(user_templates))
    return _environment(tuple(folders))


def check_templates(user_templates: str | Path) -> str:
    """The absolute path of a templates folder whose every ``*.j2`` file compiles.

    Raises ``TemplateError`` for a missing folder or a template with a syntax error, so
    a command can refuse bad templates before it spends time on layout. (Errors that
    show only when rendering, such as a misspelt variable, are raised then.)
    """
    folder = _existing_folder(user_templates)
    environment = template_environment(folder)
    for path in sorted(folder.glob("*.j2")):
        try:
            environment.get_template(path.name)
        except jinja2.TemplateError as error:
            raise TemplateError(_error_text(path.name, error)) from None
    return str(folder)


def _existing_folder(user_templates: str | Path) -> Path:
    folder = Path(user_templates)
    if not folder.is_dir():
        raise TemplateError(f"description templates folder {str(folder)!r} does not exist")
    return folder.resolve()


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
        raise TemplateError(_error_text(name, error)) from None
    return " ".join(text.split())


def _error_text(name: str, error: jinja2.TemplateError) -> str:
    """One line naming the template (its file and line for a syntax error) and the fault."""
    where = name
    if isinstance(error, jinja2.TemplateSyntaxError) and error.filename:
        where = f"{error.filename}:{error.lineno}"
    return " ".join(f"description template {where}: {error.message or error}".split())
