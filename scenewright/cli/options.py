"""The parser's parts every command family shares: one-line parse errors, the option
types (checked values with one-line messages), ``--debug``/``--quiet``, and the option
groups several commands take (style, templates, views, contexts, --allow-outside)."""

from __future__ import annotations

import argparse
import re
from collections.abc import Callable

from scenewright.api import STYLES, VIEWS
from scenewright.core.errors import InputError


class CommandLineParser(argparse.ArgumentParser):
    """argparse with one-line errors that exit 2 through ``main``'s error handling."""

    def error(self, message: str):  # type: ignore[override]
        raise InputError(f"{message} (see '{self.prog} --help')")


# -- option types ---------------------------------------------------------------------


def image_size(text: str) -> tuple[int, int]:
    """``WxH`` in pixels, e.g. ``640x480`` (ASCII digits only)."""
    match = re.fullmatch(r"([0-9]{1,9})[xX]([0-9]{1,9})", text)
    if match is None:
        raise argparse.ArgumentTypeError(
            f"expected WIDTHxHEIGHT such as 640x480, not {_clipped(text)}"
        )
    size = (int(match[1]), int(match[2]))
    if not all(8 <= side <= 8192 for side in size):
        raise argparse.ArgumentTypeError(f"each side must be 8..8192 pixels, not {_clipped(text)}")
    return size


#: The bounds of the count options (docs/limits.md).
MAX_DATASET_SCENES = (
    1_000_000_000_000  # far more than can be made: a run starts at once whatever N (datasets.md)
)
MAX_WORKERS = 1024
MAX_CAPTIONS = 100
MAX_VIEWS = 100
MAX_VIEW_TRIES = 1000
MAX_RETRIES = 100
MAX_WORDS = 10_000
MAX_VARIANT = 1000
MAX_VARIANTS = 10_000
MAX_OPERATIONS = 100
MAX_ROUNDS = 100
MAX_LAYOUTS = 10_000
MAX_CHECK_SCENES = 10_000


def whole_number(text: str) -> int:
    """An optionally negative whole number in ASCII digits (``int`` would also take
    full-width digits, underscores and spaces)."""
    if re.fullmatch(r"-?[0-9]{1,30}", text) is None:
        raise argparse.ArgumentTypeError(f"expected a whole number, not {_clipped(text)}")
    return int(text)


def _clipped(text: str, limit: int = 40) -> str:
    """An argument as it may be shown in an error: quoted, escaped, and not too long."""
    shown = ascii(text)
    return shown if len(shown) <= limit else shown[: limit - 4] + "...'"


def count_at_least(minimum: int, maximum: int) -> Callable[[str], int]:
    """A whole number from ``minimum`` to ``maximum``: every count sizes work, so each has
    a bound (docs/limits.md), named in the error."""

    def parse(text: str) -> int:
        value = whole_number(text)
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be at least {minimum}, not {value}")
        if value > maximum:
            raise argparse.ArgumentTypeError(
                f"must be at most {maximum}, not {value} (the bounds: docs/limits.md)"
            )
        return value

    parse.__name__ = "number"
    return parse


def camera_range(name: str) -> Callable[[str], tuple[float, float]]:
    """An option's ``A`` or ``LOW:HIGH`` (``render.views.parse_range`` for ``name``)."""

    def parse(text: str) -> tuple[float, float]:
        from scenewright.render.views import parse_range

        try:
            return parse_range(text, name)
        except InputError as error:
            raise argparse.ArgumentTypeError(str(error)) from None

    parse.__name__ = f"{name} range"
    return parse


def camera_settings(text: str):
    """``generate --camera``'s ``KEY=VALUE,...`` (``render.views.parse_camera``)."""
    from scenewright.render.views import parse_camera

    try:
        return parse_camera(text)
    except InputError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def seed_value(text: str) -> int:
    value = whole_number(text)
    if not 0 <= value < 2**63:
        raise argparse.ArgumentTypeError(f"must be between 0 and 2**63-1, not {value}")
    return value


def prior_value(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, not {_clipped(text)}") from None
    if not 0 < value <= 1000:
        raise argparse.ArgumentTypeError(f"must be above 0 and at most 1000, not {value:g}")
    return value


def seconds_value(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds, not {text!r}") from None
    if not 0 < value < float("inf"):
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, not {text!r}")
    return value


def scheduler_address(text: str) -> str:
    if not text.strip():
        raise argparse.ArgumentTypeError(
            "expected a scheduler address such as tcp://host:8786, not an empty string"
        )
    return text.strip()


def fraction(text: str) -> float:
    """A number from 0 to 1."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected a number from 0 to 1, not {_clipped(text)}"
        ) from None
    if not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"must be from 0 to 1, not {_clipped(text)}")
    return value


def common_options(suppress: bool) -> argparse.ArgumentParser:
    """--debug and --quiet, accepted before or after the subcommand."""
    default = argparse.SUPPRESS if suppress else False
    options = argparse.ArgumentParser(add_help=False)
    options.add_argument(
        "--debug", action="store_true", default=default, help="show tracebacks of errors"
    )
    options.add_argument(
        "-q", "--quiet", action="store_true", default=default, help="print only errors"
    )
    return options


def add_command(
    commands, helps: dict[str, str], name: str, summary: str, handler
) -> CommandLineParser:
    """Add the subcommand ``name`` to ``commands`` (argparse's subparsers), with its
    ``summary``, its help text ``helps[name]`` below its options and its ``handler``."""
    sub = commands.add_parser(
        name,
        help=summary,
        description=summary,
        epilog=helps[name],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        parents=[common_options(suppress=True)],
    )
    sub.set_defaults(handler=handler)
    return sub


# -- option groups several commands take ------------------------------------------------


def style_options(sub: argparse.ArgumentParser) -> None:
    """--style, --words, --variant and --templates: how the description is written."""
    sub.add_argument("--style", choices=STYLES, default="full", help="description style")
    sub.add_argument(
        "--words",
        type=count_at_least(1, MAX_WORDS),
        default=None,
        metavar="N",
        help="a word budget: the most detailed style (full, summary, short) whose text has at most N "
        "words (short when none has), instead of --style",
    )
    sub.add_argument(
        "--variant",
        type=count_at_least(0, MAX_VARIANT),
        default=0,
        help="paraphrase variant (0 canonical)",
    )
    templates_option(sub)


def templates_option(sub: argparse.ArgumentParser) -> None:
    sub.add_argument(
        "--templates",
        metavar="DIR",
        help="folder of description templates (*.j2) to use instead of the rule set's own",
    )


def allow_option(sub: argparse.ArgumentParser) -> None:
    sub.add_argument(
        "--allow-outside",
        action="append",
        default=[],
        metavar="PATH",
        help="let the rule set also read PATH (a folder, with all below it, or a file) outside its own "
        "folder (repeatable; see docs/security.md)",
    )


def context_options(sub: argparse.ArgumentParser) -> None:
    sub.add_argument(
        "--context",
        metavar="JSON",
        help="a learned context (scenewright fit --what context); by default NAME.context.json beside a "
        "NAME.rules file is used when it exists",
    )
    sub.add_argument(
        "--no-context", action="store_true", help="ignore NAME.context.json beside the rules"
    )


def view_options(sub: argparse.ArgumentParser, size: str) -> None:
    """--size (default ``size``) and --view of the images."""
    sub.add_argument(
        "--size",
        type=image_size,
        default=image_size(size),
        metavar="WxH",
        help=f"image size ({size})",
    )
    sub.add_argument("--view", choices=VIEWS, default="perspective", help="camera")
