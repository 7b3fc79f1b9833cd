"""A page to draw a top-down plan on (Pillow, no display): metres in, pixels out.

The page is a framed plot of the ground between ``x_limits`` (east) and ``z_limits``
(south), north (-Z) at the top as on a map, with metre ticks on two sides, axis names
and a title. Shapes are drawn at ``SUPERSAMPLE`` times the page's resolution and
reduced, so their edges are smooth; texts are drawn last, at the page's own resolution,
each with a thin white outline that keeps it readable over shapes and lines.

Sizes follow print conventions: line widths and font sizes in points (``POINT`` pixels
each at ``DPI``), so a plan reads alike at any page size.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from PIL import Image, ImageColor, ImageDraw, ImageFont

#: Pixels per inch of the saved image, and pixels per point.
DPI = 110
POINT = DPI / 72.0
#: Shapes are drawn this many times finer than the page and then reduced (smooth edges),
#: unless the finer picture would exceed ``MAX_FINE_PIXELS`` (a very large town).
SUPERSAMPLE = 2
MAX_FINE_PIXELS = 16_000_000
#: Room around the plot (pixels): tick labels and the z axis's name on the left, the x
#: axis's name below, the title above.
LEFT, RIGHT, TOP, BOTTOM = 64, 18, 30, 50
#: Font sizes (points) of the tick labels, the axis names and the title.
TICK_SIZE, AXIS_SIZE, TITLE_SIZE = 8.0, 8.5, 8.5
#: Dash patterns (on, off) per point of line width, as print graphics draw them.
DASHED = (3.7, 1.6)
DOTTED = (1.0, 1.65)

Colour = str | tuple[float, ...]


@dataclass(frozen=True)
class Box:
    """A box on the page (pixels, y down): ``x0 <= x1``, ``y0 <= y1``."""

    x0: float
    y0: float
    x1: float
    y1: float

    def translated(self, dx: float, dy: float) -> Box:
        return Box(self.x0 + dx, self.y0 + dy, self.x1 + dx, self.y1 + dy)

    def overlaps(self, other: Box) -> bool:
        return (
            self.x0 < other.x1 and other.x0 < self.x1 and self.y0 < other.y1 and other.y0 < self.y1
        )

    def within(self, other: Box) -> bool:
        return (
            other.x0 <= self.x0
            and self.x1 <= other.x1
            and other.y0 <= self.y0
            and self.y1 <= other.y1
        )


@dataclass(frozen=True)
class PlacedText:
    """A text written on the page: its words, colour and box (pixels)."""

    text: str
    colour: str
    box: Box
    size: float


def rgb(colour: Colour) -> tuple[int, int, int]:
    """An (r, g, b) of 0..255 from a CSS name or hex string, or from 0..1 floats."""
    if isinstance(colour, str):
        r, g, b = ImageColor.getrgb(colour)[:3]
        return r, g, b
    r, g, b = (min(255, max(0, round(255 * float(c)))) for c in colour[:3])
    return r, g, b


@functools.cache
def font(size: float) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    """Pillow's own sans-serif face at ``size`` points (it ships with Pillow, so the
    page looks the same on every machine with the same Pillow)."""
    return ImageFont.load_default(size=size * POINT)


def text_box(text: str, size: float) -> Box:
    """The box ``text`` at ``size`` points takes, with its outline, centred on (0, 0)."""
    x0, y0, x1, y1 = font(size).getbbox(text, anchor="mm", stroke_width=1)
    return Box(x0, y0, x1, y1)


class PlanPage:
    """A plot of the ground ``x_limits`` x ``z_limits`` (metres) whose larger side is
    about ``side`` pixels; draw shapes, ``place`` texts, then ``save``."""

    def __init__(self, x_limits: tuple[float, float], z_limits: tuple[float, float], side: float):
        self.x_limits, self.z_limits = x_limits, z_limits
        x_span = max(x_limits[1] - x_limits[0], 1e-6)
        z_span = max(z_limits[1] - z_limits[0], 1e-6)
        #: Pixels per metre on the page.
        self.scale = max(1e-6, min((side - LEFT - RIGHT) / x_span, (side - TOP - BOTTOM) / z_span))
        width, height = round(x_span * self.scale), round(z_span * self.scale)
        #: The plot's frame on the page: texts stay inside it.
        self.plot = Box(LEFT, TOP, LEFT + width, TOP + height)
        self.fine = SUPERSAMPLE if width * height * SUPERSAMPLE**2 <= MAX_FINE_PIXELS else 1
        self._shapes = Image.new("RGB", (width * self.fine, height * self.fine), "white")
        self._draw = ImageDraw.Draw(self._shapes, "RGBA")
        self.texts: list[PlacedText] = []

    # -- shapes, in metres ------------------------------------------------------------

    def _pixels(self, points: Iterable[Sequence[float]]) -> list[tuple[float, float]]:
        k = self.scale * self.fine
        x0, z0 = self.x_limits[0], self.z_limits[0]
        return [((float(x) - x0) * k, (float(z) - z0) * k) for x, z in points]

    def _width(self, points_wide: float) -> int:
        return max(1, round(points_wide * POINT * self.fine))

    def polygon(
        self,
        corners,
        fill: Colour | None,
        outline: Colour | None = None,
        width: float = 0.6,
        alpha: float = 1.0,
    ) -> None:
        """A closed shape; ``width``: its outline's, in points."""
        xy = self._pixels(corners)
        if fill is not None:
            self._draw.polygon(xy, fill=(*rgb(fill), round(255 * alpha)))
        if outline is not None:
            self._draw.line(
                [*xy, xy[0]], fill=rgb(outline), width=self._width(width), joint="curve"
            )

    def line(
        self,
        points,
        colour: Colour,
        width: float = 1.0,
        *,
        style: str = "solid",
        alpha: float = 1.0,
        metres_wide: float | None = None,
    ) -> None:
        """A line through ``points``, ``width`` points wide (or ``metres_wide``, with
        round ends: a road); ``style``: "solid", "dashed" or "dotted"."""
        xy = self._pixels(points)
        if metres_wide is not None:
            # Roads go down first, on the white ground: drawn opaque in the colour they
            # would show there, so a road is not darker where its pieces overlap.
            solid = tuple(round(c * alpha + 255 * (1.0 - alpha)) for c in rgb(colour))
            pixels = max(1, round(metres_wide * self.scale * self.fine))
            self._draw.line(xy, fill=solid, width=pixels, joint="curve")
            for x, y in (xy[0], xy[-1]):
                r = pixels / 2
                self._draw.ellipse((x - r, y - r, x + r, y + r), fill=solid)
            return
        fill = (*rgb(colour), round(255 * alpha))
        pixels = self._width(width)
        if style == "solid":
            self._draw.line(xy, fill=fill, width=pixels, joint="curve")
            return
        on, off = DASHED if style == "dashed" else DOTTED
        step = width * POINT * self.fine
        for piece in _dashes(xy, on * step, off * step):
            self._draw.line(piece, fill=fill, width=pixels)

    def dots(self, points, radius: float, colour: Colour) -> None:
        """A filled dot of ``radius`` points at each point."""
        r = radius * POINT * self.fine
        for x, y in self._pixels(points):
            self._draw.ellipse((x - r, y - r, x + r, y + r), fill=rgb(colour))

    # -- texts, in page pixels ----------------------------------------------------------

    def anchor(self, x: float, z: float) -> tuple[float, float]:
        """The page pixel of the ground point (x, z)."""
        return (
            self.plot.x0 + (x - self.x_limits[0]) * self.scale,
            self.plot.y0 + (z - self.z_limits[0]) * self.scale,
        )

    def place(self, text: str, box: Box, colour: str, size: float) -> None:
        """Write ``text`` (``size`` points) centred in ``box`` when the page is saved."""
        self.texts.append(PlacedText(text, colour, box, size))

    def save(self, path: Path, title: str, x_name: str, z_name: str) -> Path:
        """Write the page as a PNG to ``path``: the shapes, the frame with its ticks and
        names, the placed texts and ``title``."""
        shapes = self._shapes.reduce(self.fine) if self.fine > 1 else self._shapes
        width = self.plot.x1 + RIGHT
        height = self.plot.y1 + BOTTOM
        page = Image.new("RGB", (int(width), int(height)), "white")
        page.paste(shapes, (int(self.plot.x0), int(self.plot.y0)))
        pen = ImageDraw.Draw(page)
        self._frame(pen)
        page.paste(*self._z_name(z_name))
        pen.text(
            ((self.plot.x0 + self.plot.x1) / 2, height - 12),
            x_name,
            fill="black",
            font=font(AXIS_SIZE),
            anchor="ms",
        )
        pen.text((width / 2, TOP / 2), title, fill="black", font=font(TITLE_SIZE), anchor="mm")
        for placed in self.texts:
            box = placed.box
            pen.text(
                ((box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2),
                placed.text,
                fill=rgb(placed.colour),
                font=font(placed.size),
                anchor="mm",
                stroke_width=1,
                stroke_fill="white",
            )
        page.save(path, format="PNG")
        return path

    def _frame(self, pen: ImageDraw.ImageDraw) -> None:
        plot = self.plot
        pen.rectangle((plot.x0 - 1, plot.y0 - 1, plot.x1, plot.y1), outline="black", width=1)
        for value in ticks(*self.x_limits):
            x, _ = self.anchor(value, self.z_limits[0])
            pen.line((x, plot.y1, x, plot.y1 + 4), fill="black")
            pen.text(
                (x, plot.y1 + 6), _number(value), fill="black", font=font(TICK_SIZE), anchor="mt"
            )
        for value in ticks(*self.z_limits):
            _, y = self.anchor(self.x_limits[0], value)
            pen.line((plot.x0 - 5, y, plot.x0 - 1, y), fill="black")
            pen.text(
                (plot.x0 - 7, y), _number(value), fill="black", font=font(TICK_SIZE), anchor="rm"
            )

    def _z_name(self, name: str) -> tuple[Image.Image, tuple[int, int]]:
        """The z axis's name turned to read upwards, and where it goes."""
        box = text_box(name, AXIS_SIZE)
        label = Image.new(
            "RGB", (math.ceil(box.x1 - box.x0) + 2, math.ceil(box.y1 - box.y0) + 2), "white"
        )
        ImageDraw.Draw(label).text(
            (label.width / 2, label.height / 2),
            name,
            fill="black",
            font=font(AXIS_SIZE),
            anchor="mm",
        )
        turned = label.transpose(Image.Transpose.ROTATE_90)
        middle = (self.plot.y0 + self.plot.y1) / 2
        return turned, (4, int(middle - turned.height / 2))


def ticks(low: float, high: float, most: int = 9) -> list[float]:
    """Round values between ``low`` and ``high``, 1, 2 or 5 times a power of ten apart,
    at most ``most`` of them."""
    span = max(high - low, 1e-9)
    power = 10.0 ** math.floor(math.log10(span / most))
    step = next(power * f for f in (1, 2, 5, 10) if span / (power * f) <= most)
    first = math.ceil(low / step - 1e-9)
    return [k * step for k in range(first, math.floor(high / step + 1e-9) + 1)]


def _number(value: float) -> str:
    return f"{value:g}" if abs(value) > 1e-9 else "0"


def _dashes(
    xy: list[tuple[float, float]], on: float, off: float
) -> list[list[tuple[float, float]]]:
    """The drawn pieces of a line through ``xy`` dashed ``on`` pixels on, ``off`` off."""
    pieces: list[list[tuple[float, float]]] = []
    drawing, left = True, on  # what the pattern is in, and how much of it is left
    current = [xy[0]]
    for (ax, ay), (bx, by) in zip(xy[:-1], xy[1:], strict=True):
        length = math.hypot(bx - ax, by - ay)
        done = 0.0
        while length - done > left:
            done += left
            point = (ax + (bx - ax) * done / length, ay + (by - ay) * done / length)
            if drawing:
                current.append(point)
                pieces.append(current)
            else:
                current = [point]
            drawing = not drawing
            left = on if drawing else off
        left -= length - done
        if drawing:
            current.append((bx, by))
    if drawing and len(current) > 1:
        pieces.append(current)
    return pieces
