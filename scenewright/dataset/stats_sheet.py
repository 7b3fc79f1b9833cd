"""stats.png: a dataset's statistics on one sheet of six panels (Pillow, no display).

Top row: object frequencies, relations held, scenes by size with their retries; bottom
row: text lengths, seconds per stage, and the most frequent errors of scenes the rules
could not make. Bars are horizontal with their names on the left; counts get ticks at
whole numbers only (no "1.5 scenes"). The page is drawn with Pillow's own font, so it
looks the same on every machine with the same Pillow.
"""

from __future__ import annotations

import io
import math
import textwrap
from collections.abc import Sequence
from dataclasses import dataclass

from PIL import Image, ImageDraw

from scenewright.render.plan_page import font

#: The sheet (pixels) and its grid of panels.
WIDTH, HEIGHT = 1360, 720
COLUMNS, ROWS = 3, 2
#: The sheet's own title above the cells, and each cell's size (pixels).
SHEET_TITLE_HEIGHT = 20
CELL_WIDTH, CELL_HEIGHT = WIDTH / COLUMNS, (HEIGHT - SHEET_TITLE_HEIGHT) / ROWS
#: Inside each cell: room for the names on the left, the title above, the ticks below.
NAMES_WIDTH, TITLE_HEIGHT, TICKS_HEIGHT, MARGIN = 150, 22, 34, 12
#: Font sizes (points) of the sheet's title, the panels' titles and the labels.
SHEET_SIZE, TITLE_SIZE, LABEL_SIZE = 8.0, 7.5, 6.0
BLUE, RED, GREY = (31, 119, 180), (214, 39, 40), (60, 60, 60)
#: The colours of the histogram's series, in order (the usual ten-colour cycle).
SERIES = ((31, 119, 180), (255, 127, 14), (44, 160, 44), (214, 39, 40), (148, 103, 189))


@dataclass(frozen=True)
class Panel:
    """A panel's plot area on the sheet (pixels, y down)."""

    x0: int
    y0: int
    x1: int
    y1: int


def stats_sheet(stats: dict) -> bytes:
    """The PNG of ``stats`` (as written to stats.json)."""
    image = Image.new("RGB", (WIDTH, HEIGHT), "white")
    draw = ImageDraw.Draw(image, "RGBA")
    errored = stats["failed"] - stats["failed_layouts"]
    title = (
        f"{stats['scenes']} scenes, {stats['written']} written, {stats['failed_layouts']} failed "
        f"layouts, {errored} not made (rules errors), {stats['retries']['scenes_retried']} retried"
    )
    draw.text((WIDTH / 2, 4), title, fill="black", font=font(SHEET_SIZE), anchor="mt")

    top_objects = list(stats["objects"].items())[:20]
    objects = _panel(draw, 0, 0, "objects (top 20 types)")
    _bars(draw, objects, [name for name, _ in top_objects], [[n for _, n in top_objects]])

    labels = list(stats["relations"])
    relations = _panel(draw, 1, 0, "relations: total (light) and satisfied (dark)")
    _bars(
        draw,
        relations,
        labels,
        [
            [stats["relations"][label]["total"] for label in labels],
            [stats["relations"][label]["satisfied"] for label in labels],
        ],
    )

    rows = stats["retries"]["by_objects"]
    retries = _panel(draw, 2, 0, "scenes by objects: retried (dark), failed (red)")
    _bars(
        draw,
        retries,
        [f"{row['objects']} objects" for row in rows],
        [
            [row["scenes"] for row in rows],
            [row["retried"] for row in rows],
            [row["failed_after_retries"] for row in rows],
        ],
    )

    _lengths(draw, _panel(draw, 0, 1, "length in words (full text, short captions)"), stats)

    stages = stats["seconds_per_stage"]
    seconds = _panel(draw, 1, 1, "mean seconds per scene and stage")
    _bars(draw, seconds, list(stages), [[stages[s]["mean"] for s in stages]], whole=False)

    _errors(draw, 2, 1, stats["errors"])
    buffer = io.BytesIO()
    image.save(buffer, format="PNG", optimize=False)
    return buffer.getvalue()


def _panel(draw: ImageDraw.ImageDraw, column: int, row: int, title: str) -> Panel:
    """The framed plot area of the panel at (``column``, ``row``), titled."""
    x, y = _cell(column, row)
    panel = Panel(
        round(x + NAMES_WIDTH),
        round(y + TITLE_HEIGHT),
        round(x + CELL_WIDTH - MARGIN),
        round(y + CELL_HEIGHT - TICKS_HEIGHT),
    )
    centre = (panel.x0 + panel.x1) / 2
    draw.text((centre, y + 4), title, fill="black", font=font(TITLE_SIZE), anchor="mt")
    return panel


def _cell(column: int, row: int) -> tuple[float, float]:
    """The top left corner of the sheet's cell at (``column``, ``row``), below its title."""
    return column * CELL_WIDTH, SHEET_TITLE_HEIGHT + row * CELL_HEIGHT


def _frame(draw: ImageDraw.ImageDraw, panel: Panel) -> None:
    draw.rectangle((panel.x0, panel.y0, panel.x1, panel.y1), outline="black", width=1)


def nice_ticks(top: float, whole: bool, most: int = 7) -> list[float]:
    """Tick values from 0 to at least ``top`` at a step of 1, 2 or 5 times a power of
    ten, at most ``most`` of them; whole numbers only when ``whole``."""
    top = max(top, 1.0 if whole else 1e-9)
    rough = top / (most - 1)
    power = 10 ** math.floor(math.log10(rough))
    step = next(m * power for m in (1, 2, 5, 10) if m * power >= rough)
    if whole:
        step = max(1.0, float(math.ceil(step)))
    count = math.ceil(top / step - 1e-9)
    return [k * step for k in range(count + 1)]


def _tick_text(value: float, whole: bool) -> str:
    return f"{value:.0f}" if whole else f"{value:g}"


def _bars(
    draw: ImageDraw.ImageDraw,
    panel: Panel,
    names: Sequence[str],
    layers: Sequence[Sequence[float]],
    whole: bool = True,
) -> None:
    """Horizontal bars, the first name at the top. With one layer the bars are dark; with
    two or three the first is light, the second dark over it and the third a thin red
    bar over both (scenes, retried, failed)."""
    _frame(draw, panel)
    ticks = nice_ticks(max((v for layer in layers for v in layer), default=0.0), whole)
    scale = (panel.x1 - panel.x0) / (ticks[-1] * 1.05 or 1.0)
    labels = font(LABEL_SIZE)
    for value in ticks:
        x = panel.x0 + value * scale
        draw.line((x, panel.y1, x, panel.y1 + 4), fill="black")
        draw.text(
            (x, panel.y1 + 6), _tick_text(value, whole), fill="black", font=labels, anchor="mt"
        )
    if not names:
        return
    pitch = (panel.y1 - panel.y0) / len(names)
    styles = (
        [(BLUE, 255, 0.8)]
        if len(layers) == 1
        else [(BLUE, 90, 0.8), (BLUE, 255, 0.8), (RED, 255, 0.4)][: len(layers)]
    )
    for k, name in enumerate(names):
        centre = panel.y0 + (k + 0.5) * pitch
        for layer, (colour, alpha, height) in zip(layers, styles, strict=True):
            length = layer[k] * scale
            if length > 0:
                half = pitch * height / 2
                draw.rectangle(
                    (panel.x0 + 1, centre - half, panel.x0 + max(1.0, length), centre + half),
                    fill=(*colour, alpha),
                )
        draw.text(
            (panel.x0 - 6, centre),
            _fitted(name, NAMES_WIDTH - 10),
            fill="black",
            font=labels,
            anchor="rm",
        )


def _fitted(text: str, width: float) -> str:
    """``text`` cut short with an ellipsis to fit ``width`` pixels at the label size."""
    labels = font(LABEL_SIZE)
    if labels.getlength(text) <= width:
        return text
    while text and labels.getlength(text + "...") > width:
        text = text[:-1]
    return text + "..."


def _lengths(draw: ImageDraw.ImageDraw, panel: Panel, stats: dict) -> None:
    """Each kind of text's histogram of lengths in words, filled steps, with a legend."""
    _frame(draw, panel)
    described = {name: s for name, s in stats["words"].items() if s["count"]}
    labels = font(LABEL_SIZE)
    edges = [e for s in described.values() for e in s["histogram"]["edges"]]
    left, right = (min(edges), max(edges)) if edges else (0.0, 1.0)
    if right <= left:
        right = left + 1.0
    top = max((c for s in described.values() for c in s["histogram"]["counts"]), default=1)
    counts = nice_ticks(top, whole=True)
    spread = (right - left) * 1.05

    def to_x(words: float) -> float:
        return panel.x0 + (words - left + (right - left) * 0.025) / spread * (panel.x1 - panel.x0)

    def to_y(count: float) -> float:
        return panel.y1 - count / (counts[-1] * 1.05) * (panel.y1 - panel.y0)

    for value in counts:
        y = to_y(value)
        draw.line((panel.x0 - 4, y, panel.x0, y), fill="black")
        draw.text((panel.x0 - 6, y), f"{value:.0f}", fill="black", font=labels, anchor="rm")
    # Ticks at round numbers of words inside the histogram's range.
    step = nice_ticks(right - left, whole=True)[1]
    for k in range(math.ceil(left / step), math.floor(right / step + 1e-9) + 1):
        x = to_x(k * step)
        draw.line((x, panel.y1, x, panel.y1 + 4), fill="black")
        draw.text((x, panel.y1 + 6), f"{k * step:g}", fill="black", font=labels, anchor="mt")
    draw.text(
        ((panel.x0 + panel.x1) / 2, panel.y1 + 20), "words", fill="black", font=labels, anchor="mt"
    )
    draw.text(
        (panel.x0 - 28, (panel.y0 + panel.y1) / 2), "texts", fill="black", font=labels, anchor="mm"
    )
    legend_y = panel.y0 + 8
    for k, (name, summary) in enumerate(described.items()):
        colour = SERIES[k % len(SERIES)]
        histogram = summary["histogram"]
        for (low, high), count in zip(
            zip(histogram["edges"], histogram["edges"][1:], strict=False),
            histogram["counts"],
            strict=False,
        ):
            if count:
                draw.rectangle((to_x(low), to_y(count), to_x(high), panel.y1), fill=(*colour, 150))
        label = f"{name} (median {summary['median']:g})"
        x = panel.x1 - 10 - labels.getlength(label) - 16
        draw.rectangle((x, legend_y - 5, x + 10, legend_y + 5), fill=(*colour, 150))
        draw.text((x + 16, legend_y), label, fill="black", font=labels, anchor="lm")
        legend_y += 16


def _errors(draw: ImageDraw.ImageDraw, column: int, row: int, errors: dict[str, dict]) -> None:
    """The most frequent errors of scenes the rules could not make, as text."""
    lines = [
        f"{n}x  {stage}: {message}"
        for stage, error in errors.items()
        for message, n in error["messages"].items()
    ]
    if not lines:
        return
    x, y = _cell(column, row)
    x += MARGIN
    draw.text(
        (x + CELL_WIDTH / 2, y + 4),
        "scenes the rules could not make",
        fill="black",
        font=font(TITLE_SIZE),
        anchor="mt",
    )
    # Each error on at most three lines of the panel's width, eight errors at most, so
    # the text stays inside the sheet.
    labels = font(LABEL_SIZE)
    wrapped = [textwrap.wrap(line, 70, subsequent_indent="    ")[:3] for line in lines[:8]]
    y += TITLE_HEIGHT + 4
    for part in (part for parts in wrapped for part in parts):
        draw.text((x, y), part, fill=GREY, font=labels)
        y += 13
