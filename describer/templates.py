"""The jinja2 templates that frame each kind of sentence, and a rule set's own templates.

The package's templates live in ``describer/templates/*.j2``. A rule set may bring a
folder of its own: a file there replaces the package's file of the same name, the
others stay. Templates receive plain strings and lists only and are rendered in a
sandboxed environment, so a template from a downloaded rule set cannot reach Python
objects; and a template is read only from a regular file of at most
``MAX_TEMPLATE_BYTES`` that lies in its folder once links are resolved, so a link in a
downloaded folder cannot put another file (/etc/passwd) into a description, nor a
pipe or device stall it. Rendered text has its whitespace normalised, so templates may
be laid out freely.

Rendering is bounded: the loops over ``range`` of one rendering take at most
``MAX_TEMPLATE_STEPS`` steps in all, and ``*``, ``**`` and ``+`` may not make a string,
list or number larger than ``MAX_TEMPLATE_RESULT`` (characters, items or digits). A
rule set's template that fails while rendering (a division by zero, a runaway macro,
a bound above, too little memory) raises ``TemplateError`` naming its file and line;
one of the package's templates that fails is a bug, and its error goes on as it is.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from contextvars import ContextVar
from functools import lru_cache
from pathlib import Path

import jinja2
from jinja2.loaders import split_template_path
from jinja2.sandbox import SandboxedEnvironment

from scenewright.core.files import UnusableFile, read_regular_file
from scenewright.core.limits import forbidden_character

from .english import join_list, with_article
from .errors import TemplateError
from .grounding import split_leading_marks

PACKAGE_TEMPLATES = Path(__file__).parent / "templates"
#: The most a template file may hold (1 MiB); the package's are under 1 KiB each.
MAX_TEMPLATE_BYTES = 1024 * 1024
#: The most steps the ``range`` loops of one rendering may take, all together.
MAX_TEMPLATE_STEPS = 100_000
#: The longest string or list (or the most digits of a number) ``*``, ``**`` or ``+`` may make.
MAX_TEMPLATE_RESULT = 100_000

#: The ``range`` steps the rendering under way may still take.
_steps_left: ContextVar[list[int]] = ContextVar("template_steps_left")


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
    environment = _BoundedSandbox(
        loader=_FolderLoader(folders),
        undefined=jinja2.StrictUndefined,
        autoescape=False,
    )
    environment.filters["join_list"] = join_list
    environment.filters["with_article"] = _with_article_inside_marks
    environment.globals["range"] = _counted_range
    return environment


def _with_article_inside_marks(phrase: str) -> str:
    """``with_article`` for a phrase that may be marked as naming something
    (``grounding``): the article goes inside the marks, so "a desk" is the mention."""
    marks, rest = split_leading_marks(phrase)
    return marks + with_article(rest)


class _FolderLoader(jinja2.BaseLoader):
    """Templates from the first of its folders that has a file of the name, each read
    only from a regular file of at most ``MAX_TEMPLATE_BYTES`` inside that folder once
    links are resolved (``TemplateError`` otherwise)."""

    def __init__(self, folders: tuple[Path, ...]):
        self.folders = tuple(folder.resolve() for folder in folders)

    def get_source(
        self, environment: jinja2.Environment, template: str
    ) -> tuple[str, str, Callable[[], bool]]:
        pieces = split_template_path(template)  # no ".." and no absolute names
        for folder in self.folders:
            path = folder.joinpath(*pieces)
            if os.path.lexists(path):
                return _read_template(folder, path)
        raise jinja2.TemplateNotFound(template)


def _read_template(folder: Path, path: Path) -> tuple[str, str, Callable[[], bool]]:
    """A template file's text, its name for messages, and whether it is unchanged since."""
    real = path.resolve()
    if not real.is_relative_to(folder):
        raise TemplateError(
            f"description template {path}: it leads outside its folder {folder} (to {real})"
        )
    try:
        modified = os.stat(real).st_mtime
        text = read_regular_file(real, MAX_TEMPLATE_BYTES, "a template").decode("utf-8")
    except UnicodeDecodeError:
        raise TemplateError(f"description template {path}: it is not UTF-8 text") from None
    except UnusableFile as problem:
        raise TemplateError(f"description template {path}: it {problem}") from None
    except OSError as error:
        raise TemplateError(
            f"description template {path}: cannot read it ({error.strerror or error})"
        ) from None

    def unchanged() -> bool:
        try:
            return path.resolve() == real and os.stat(real).st_mtime == modified
        except OSError:
            return False

    return text, str(path), unchanged


def render(environment: SandboxedEnvironment, name: str, **context: object) -> str:
    """Render ``name`` with ``context`` to one line of text, whitespace normalised."""
    template = None
    budget = _steps_left.set([MAX_TEMPLATE_STEPS])
    try:
        template = environment.get_template(name)
        text = template.render(**context)
    except jinja2.TemplateError as error:
        raise TemplateError(_error_text(_user_frame(error) or name, error)) from None
    except Exception as error:  # MemoryError and RecursionError included: what a template did
        where = _user_frame(error)
        if where is None:
            raise  # one of the package's templates: a bug
        raise TemplateError(f"description template {where}: {_runtime_fault(error)}") from None
    finally:
        _steps_left.reset(budget)
    line = " ".join(text.split())
    if (bad := forbidden_character(line)) is not None:
        raise TemplateError(
            f"description template {template.filename or name}: it writes the character {bad}; "
            "text may not hold control or bidirectional-control characters"
        )
    return line


class _BoundedSandbox(SandboxedEnvironment):
    """The sandbox, with ``*``, ``**`` and ``+`` checked before they build something huge."""

    intercepted_binops = frozenset({"*", "**", "+"})

    def call_binop(
        self, context: jinja2.runtime.Context, operator: str, left: object, right: object
    ) -> object:
        if _result_size(operator, left, right) > MAX_TEMPLATE_RESULT:
            raise jinja2.exceptions.SecurityError(
                f"'{operator}' would make a result larger than {MAX_TEMPLATE_RESULT} (characters, items or digits)"
            )
        return super().call_binop(context, operator, left, right)


def _result_size(operator: str, left: object, right: object) -> float:
    """About how many characters, items or digits ``left operator right`` makes."""
    if operator == "+":
        return (
            len(left) + len(right) if hasattr(left, "__len__") and hasattr(right, "__len__") else 0
        )
    if operator == "*":
        for sequence, count in ((left, right), (right, left)):
            if hasattr(sequence, "__len__") and isinstance(count, int):
                return len(sequence) * count
        return 0
    if isinstance(left, int) and isinstance(right, int) and abs(left) > 1 and right > 0:
        return right * math.log10(abs(left))  # the digits of an integer power
    return 0


def _counted_range(*arguments: int) -> range:
    """``range`` that draws its length from the rendering's step budget."""
    numbers = range(*arguments)
    left = _steps_left.get([MAX_TEMPLATE_STEPS])
    if len(numbers) > left[0]:
        raise jinja2.exceptions.SecurityError(
            f"range({', '.join(map(str, arguments))}) would take the template's loops past "
            f"{MAX_TEMPLATE_STEPS} steps in all"
        )
    left[0] -= len(numbers)
    return numbers


def _user_frame(error: BaseException) -> str | None:
    """``FILE:LINE`` of the innermost line of a rule set's template (not the package's)
    that the error passed through, or None when it passed through none. (jinja2 rewrites
    a rendering's traceback so that each template line is a frame of the template's file,
    marked by ``__jinja_exception__`` in its globals.)"""
    package = str(PACKAGE_TEMPLATES.resolve())
    found = None
    trace = error.__traceback__
    while trace is not None:
        file = trace.tb_frame.f_code.co_filename
        template_line = "__jinja_exception__" in trace.tb_frame.f_globals
        if template_line and not os.path.abspath(file).startswith(package + os.sep):
            found = f"{file}:{trace.tb_lineno}"
        trace = trace.tb_next
    return found


def _runtime_fault(error: Exception) -> str:
    """A template's runtime failure in words, on one line."""
    if isinstance(error, MemoryError):
        return "it ran out of memory"
    if isinstance(error, RecursionError):
        return "it calls itself too deeply (a macro that never stops calling itself?)"
    return " ".join(f"{type(error).__name__}: {error}".split())[:300]


def _error_text(name: str, error: jinja2.TemplateError) -> str:
    """One line naming the template (its file and line for a syntax error) and the fault."""
    where = name
    if isinstance(error, jinja2.TemplateSyntaxError) and error.filename:
        where = f"{error.filename}:{error.lineno}"
    if isinstance(error, jinja2.TemplateNotFound):  # its message is the bare name
        return f"description template {where}: there is no template {error.name!r} (names may not contain '..')"
    return " ".join(f"description template {where}: {error.message or error}".split())
