"""A small SVG writer for the evidence figures: a canvas in points (1/72 in), axes frames mapping data to the page,
nice tick values, text widths estimated from character classes, and the marker shapes. Pure Python: drawing a figure
costs milliseconds, and no plotting library is loaded by a check (matplotlib took ~0.5 s to import in every process
and ~0.1 s a figure).

Deterministic output: numbers written with two decimals, ids made from the figure's prefix and a counter.
"""

from __future__ import annotations

import math
from html import escape

import numpy as np

FONT_FAMILY = "DejaVu Sans, Verdana, Arial, sans-serif"
#: advance widths in em of DejaVu Sans (the widest common sans-serif: layouts sized with it fit the others)
_NARROW = set("il.,:;|!'`ıj()[]{}/\\ ")
_WIDE = set("mwMW%@—")


def text_width(text: str, size: float) -> float:
    """Width (pt) of ``text`` at ``size`` pt, estimated per character class (DejaVu Sans advances)."""
    w = 0.0
    for ch in str(text):
        if ch in _NARROW:
            w += 0.32
        elif ch in _WIDE:
            w += 0.92
        elif ch.isupper() or ch.isdigit() or ch in "·×−+=<>±#&":
            w += 0.68 if ch.isupper() else 0.64
        else:
            w += 0.58
    return w * size


def nice_ticks(lo: float, hi: float, target: int = 5) -> list[float]:
    """Round tick values (1, 2, 2.5, 5 × 10^k steps) inside [lo, hi], about ``target`` of them."""
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
        return [lo] if math.isfinite(lo) else []
    raw = (hi - lo) / max(1, target)
    mag = 10.0 ** math.floor(math.log10(raw))
    step = next(s * mag for s in (1.0, 2.0, 2.5, 5.0, 10.0) if s * mag >= raw * 0.999)
    first = math.ceil(lo / step - 1e-9)
    ticks = []
    k = first
    while k * step <= hi + step * 1e-9:
        v = k * step
        ticks.append(0.0 if abs(v) < step * 1e-9 else round(v, 12))
        k += 1
    return ticks


def log_ticks(lo: float, hi: float) -> list[float]:
    """Decades inside [lo, hi] (lo > 0)."""
    return [
        10.0**k
        for k in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)
        if lo * (1 - 1e-9) <= 10.0**k <= hi * (1 + 1e-9)
    ]


def tick_label(v: float) -> str:
    """Thousands separated, a true minus sign, no ``-0``, at most 6 significant digits."""
    if v == 0:
        return "0"
    text = f"{v:,.0f}" if abs(v) >= 1000 else f"{v:.6g}"
    return text.replace("-", "\u2212")


def f2(v: float) -> str:
    return f"{v:.2f}"


class Canvas:
    """SVG elements of one figure, ``width`` × ``height`` pt; ``prefix`` starts every id."""

    def __init__(self, width: float, height: float, prefix: str):
        self.width, self.height, self.prefix = width, height, prefix
        self.parts: list[str] = []
        self.defs: list[str] = []
        self._ids = 0

    def new_id(self, kind: str) -> str:
        self._ids += 1
        return f"{self.prefix}-{kind}{self._ids}"

    def add(self, element: str) -> None:
        self.parts.append(element)

    def line(self, x0, y0, x1, y1, colour="#000000", width=1.0, dash: str = "", opacity: float = 1.0, clip: str = ""):
        extra = (f' stroke-dasharray="{dash}"' if dash else "") + (
            f' stroke-opacity="{opacity}"' if opacity < 1 else ""
        )
        extra += f' clip-path="url(#{clip})"' if clip else ""
        self.add(
            f'<line x1="{f2(x0)}" y1="{f2(y0)}" x2="{f2(x1)}" y2="{f2(y1)}" stroke="{colour}" '
            f'stroke-width="{width}"{extra}/>'
        )

    def polyline(self, xs, ys, colour, width=1.0, dash: str = "", clip: str = "") -> None:
        """A line through the points, broken at non-finite values."""
        xs, ys = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)
        ok = np.isfinite(xs) & np.isfinite(ys)
        runs, cur = [], []
        for x, y, good in zip(xs.tolist(), ys.tolist(), ok.tolist()):
            if good:
                cur.append(f"{x:.2f},{y:.2f}")
            elif cur:
                runs.append(cur)
                cur = []
        if cur:
            runs.append(cur)
        d = " ".join("M" + " L".join(run) for run in runs if len(run) > 1)
        if not d:
            return
        extra = (f' stroke-dasharray="{dash}"' if dash else "") + (f' clip-path="url(#{clip})"' if clip else "")
        self.add(
            f'<path d="{d}" fill="none" stroke="{colour}" stroke-width="{width}" stroke-linejoin="round"'
            f' stroke-linecap="round"{extra}/>'
        )

    def polygon(self, xs, ys, colour, opacity=1.0, clip: str = "") -> None:
        pts = " ".join(f"{x:.2f},{y:.2f}" for x, y in zip(xs, ys) if math.isfinite(x) and math.isfinite(y))
        if pts:
            extra = f' clip-path="url(#{clip})"' if clip else ""
            self.add(f'<polygon points="{pts}" fill="{colour}" fill-opacity="{opacity}" stroke="none"{extra}/>')

    def rect(self, x, y, w, h, fill="none", stroke="none", width=1.0, extra: str = "") -> None:
        self.add(
            f'<rect x="{f2(x)}" y="{f2(y)}" width="{f2(w)}" height="{f2(h)}" fill="{fill}" stroke="{stroke}" '
            f'stroke-width="{width}"{extra}/>'
        )

    def text(
        self,
        x,
        y,
        text: str,
        size: float,
        anchor: str = "start",
        colour: str = "#000000",
        rotate: float = 0.0,
        baseline: str = "middle",
        weight: str = "normal",
    ) -> None:
        """Text at (x, y): ``anchor`` start/middle/end, ``baseline`` middle (centred), hanging (top) or
        alphabetic (bottom); rotated by ``rotate`` degrees counter-clockwise about the anchor."""
        dy = {"middle": 0.35 * size, "hanging": 0.8 * size, "alphabetic": 0.0}[baseline]
        transform = f' transform="rotate({f2(-rotate)} {f2(x)} {f2(y)})"' if rotate else ""
        bold = ' font-weight="bold"' if weight == "bold" else ""
        self.add(
            f'<text x="{f2(x)}" y="{f2(y + dy)}" font-size="{size:g}" text-anchor="{anchor}" fill="{colour}"'
            f"{bold}{transform}>{escape(str(text), quote=False)}</text>"
        )

    def marker(self, x, y, shape: str, size: float, fill: str, edge: str = "none", edge_width: float = 0.5) -> None:
        """A marker centred on (x, y), ``size`` pt across: o circle, s square, ^ v triangles, D diamond, * star."""
        if not (math.isfinite(x) and math.isfinite(y)):
            return
        r = size / 2.0
        style = f'fill="{fill}" stroke="{edge}" stroke-width="{edge_width}"'
        if shape == "o":
            self.add(f'<circle cx="{f2(x)}" cy="{f2(y)}" r="{f2(r)}" {style}/>')
            return
        if shape == "s":
            pts = [(-r, -r), (r, -r), (r, r), (-r, r)]
        elif shape == "^":
            pts = [(0, -r), (r, r * 0.8), (-r, r * 0.8)]
        elif shape == "v":
            pts = [(0, r), (r, -r * 0.8), (-r, -r * 0.8)]
        elif shape == "D":
            pts = [(0, -r), (r, 0), (0, r), (-r, 0)]
        else:  # five-pointed star
            pts = [
                (
                    (r if k % 2 == 0 else r * 0.45) * math.sin(k * math.pi / 5),
                    -(r if k % 2 == 0 else r * 0.45) * math.cos(k * math.pi / 5),
                )
                for k in range(10)
            ]
        d = "M" + " L".join(f"{x + px:.2f},{y + py:.2f}" for px, py in pts) + " Z"
        self.add(f'<path d="{d}" {style}/>')

    def clip(self, x, y, w, h) -> str:
        cid = self.new_id("clip")
        self.defs.append(
            f'<clipPath id="{cid}"><rect x="{f2(x)}" y="{f2(y)}" width="{f2(w)}" height="{f2(h)}"/></clipPath>'
        )
        return cid

    def hatch(self, colour: str = "#ffffff") -> str:
        """A diagonal hatch pattern (for failing cells and bars, legible without colour)."""
        pid = self.new_id("hatch")
        self.defs.append(
            f'<pattern id="{pid}" patternUnits="userSpaceOnUse" width="6" height="6" '
            f'patternTransform="rotate(45)"><line x1="0" y1="0" x2="0" y2="6" stroke="{colour}" '
            f'stroke-width="1.6"/></pattern>'
        )
        return pid

    def svg(self) -> str:
        defs = f"<defs>{''.join(self.defs)}</defs>" if self.defs else ""
        return (
            f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {f2(self.width)} {f2(self.height)}" '
            f'font-family="{FONT_FAMILY}">{defs}' + "\n".join(self.parts) + "</svg>\n"
        )


class Frame:
    """An axes box (pt, y down) and its data ranges; ``x``/``y`` map data to the page."""

    def __init__(self, left, top, width, height, xlim, ylim, xlog=False, ylog=False):
        self.left, self.top, self.width, self.height = left, top, width, height
        self.xlim, self.ylim, self.xlog, self.ylog = xlim, ylim, xlog, ylog

    def _frac(self, v, lim, log):
        v = np.asarray(v, dtype=float)
        lo, hi = lim
        if log:
            with np.errstate(divide="ignore", invalid="ignore"):
                return (np.log10(v) - math.log10(lo)) / (math.log10(hi) - math.log10(lo))
        return (v - lo) / (hi - lo)

    def x(self, v):
        return self.left + self._frac(v, self.xlim, self.xlog) * self.width

    def y(self, v):
        return self.top + (1.0 - self._frac(v, self.ylim, self.ylog)) * self.height

    @property
    def right(self):
        return self.left + self.width

    @property
    def bottom(self):
        return self.top + self.height


def data_range(values, log: bool = False, pad: float = 0.05) -> tuple[float, float]:
    """The padded range of the finite values (positive ones on a log scale); (0, 1) without any."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)] if log else v[np.isfinite(v)]
    if not v.size:
        return (0.1, 10.0) if log else (0.0, 1.0)
    lo, hi = float(v.min()), float(v.max())
    if log:
        a, b = math.log10(lo), math.log10(hi)
        span = max(b - a, 0.2)
        return 10 ** (a - pad * span), 10 ** (b + pad * span)
    span = hi - lo if hi > lo else max(abs(hi), 1.0) * 0.1
    return lo - pad * span, hi + pad * span
