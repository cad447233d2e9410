"""Draw evidence data (:mod:`certkit.engine.evidence`) as inline SVG (:mod:`certkit.report.svg`), every figure with the
same
conventions:

- colours from the Okabe–Ito palette (distinguishable with the common colour-vision deficiencies); failing bars and
  cells in vermillion and hatched, passing ones in blue; the critical series drawn thicker;
- limits (black dashed), allowables (vermillion dash-dot), events (grey dotted) and references (grey dashed) drawn
  and labelled outside the axes (right of the plot, or above it for vertical lines), labels pushed apart where they
  would overlap; the axes' range includes every limit, so the allowables are always in view;
- the critical point marked with a star and named in the legend;
- legends below the figure, outside the data; heatmaps with a colour bar;
- values converted to aviation units (:mod:`certkit.report.display`); series decimated to the figure's resolution
  keeping each bucket's minimum and maximum (the drawn line is the same to the eye); text at least 8 pt;
- deterministic SVG: no date, no random ids, every id prefixed by the figure's own prefix (unique across a page).
"""

from __future__ import annotations

import math
import re
import textwrap

import numpy as np

from certkit.engine.evidence import Axis, Bars, Chart, Heatmap, Limit, Panel, Series
from certkit.report.display import axis_label, format_value, unit_and_factor
from certkit.report.svg import Canvas, Frame, data_range, log_ticks, nice_ticks, text_width, tick_label

PALETTE = ("#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#000000", "#999933")
FAIL, PASS, NOT_EVALUATED = "#D55E00", "#0072B2", "#e8e8e8"
#: (colour, width pt, SVG dash pattern) of each kind of reference line
LINE_STYLE = {
    "limit": ("#000000", 0.9, "5,3"),
    "allowable": ("#D55E00", 1.2, "7,2.5,1.5,2.5"),
    "event": ("#777777", 0.8, "1.5,2"),
    "reference": ("#777777", 0.7, "4,3"),
}
DASH = {"-": "", "--": "5,3", ":": "1.5,2", "-.": "7,2.5,1.5,2.5"}
#: points per series kept at most: two per bucket, about one bucket per pixel column of the widest axes
MAX_POINTS = 1000
WIDTH = 504.0  # pt (7 in)
FONT = 8.0  # smallest text in a figure (points); figures are shown at least at their size
GRID = "#dcdcdc"


def figure_prefix(rule_id: str) -> str:
    """The id prefix of a rule's figures: ``ev-`` and the rule id's letters and digits (``ev-25-331-b``)."""
    return "ev-" + re.sub(r"[^0-9a-z]+", "-", rule_id.lower()).strip("-")


def render_result(result) -> None:
    """Draw the figures of a :class:`~certkit.engine.results.RuleResult`'s evidence (in the process that evaluated it:
    see
    :func:`certkit.engine.scheduler.run`); a figure that cannot be drawn is dropped with a note, never fails the run."""
    try:
        render_evidence(result.evidence, figure_prefix(result.id))
    except Exception as exc:  # a drawing error must not lose the rule's findings
        result.notes.append(f"evidence could not be drawn: {exc.__class__.__name__}: {exc}")
        for ev in result.evidence:
            if not ev.svg:
                ev.figure = None


def render_evidence(evidence: list, prefix: str) -> None:
    """Draw the figure of each evidence item into its ``svg`` (ids prefixed ``prefix-<k>-``), in place."""
    for k, ev in enumerate(evidence):
        if ev.figure is not None and not ev.svg:
            ev.svg = render(ev.figure, f"{prefix}-{k}")


def render(figure, prefix: str) -> str:
    if isinstance(figure, Chart):
        return chart_svg(figure, prefix)
    if isinstance(figure, Bars):
        return bars_svg(figure, prefix)
    if isinstance(figure, Heatmap):
        return heatmap_svg(figure, prefix)
    raise TypeError(f"no renderer for {type(figure).__name__}")


# ----------------------------------------------------------------------------------------------------- helpers
def decimate(x: np.ndarray, y: np.ndarray, buckets: int = MAX_POINTS // 2) -> tuple[np.ndarray, np.ndarray]:
    """At most 2 × ``buckets`` points of a series: in each of ``buckets`` runs of consecutive points, the first
    minimum and the first maximum of y (in their order); a run of NaN keeps one NaN (the line stays broken)."""
    n = x.size
    if n <= 2 * buckets:
        return x, y
    size = math.ceil(n / buckets)
    pad = size * buckets - n
    yy = np.concatenate([y, np.full(pad, np.nan)]).reshape(buckets, size)
    nan = np.isnan(yy)
    lo = np.argmin(np.where(nan, np.inf, yy), axis=1)
    hi = np.argmax(np.where(nan, -np.inf, yy), axis=1)
    base = np.arange(buckets) * size
    gap = nan.any(axis=1) & ~nan.all(axis=1)
    first_nan = np.argmax(nan, axis=1)
    idx = np.concatenate([base + lo, base + hi, (base + first_nan)[gap]])
    idx = np.unique(idx[idx < n])
    return x[idx], y[idx]


def _scaled(axis: Axis) -> tuple[str, float]:
    unit, factor = unit_and_factor(axis.unit, axis.display)
    return axis_label(axis.label, unit), factor


def _point_label(pt, panel: Panel, fy: float) -> str:
    return f"{pt.label}: {panel.y.label} {format_value(pt.y / fy)}{_unit_of(panel.y)}"


def _chart_legend(chart: Chart) -> list[str]:
    """The legend's labels in order (known before drawing, so the figure can make room for them)."""
    labels, seen = [], set()
    for panel in chart.panels:
        fy = _scaled(panel.y)[1]
        for s in panel.series:
            if s.label and s.label not in seen:
                seen.add(s.label)
                labels.append(s.label + (" (critical)" if s.critical else ""))
        labels += [_point_label(pt, panel, fy) for pt in panel.points if pt.kind == "critical"]
    return list(dict.fromkeys(labels))


def _unit_of(axis: Axis) -> str:
    unit, _ = unit_and_factor(axis.unit, axis.display)
    return (f" × {unit}" if unit[:1].isdigit() else f" {unit}") if unit else ""


# ----------------------------------------------------------------------------------------------------- charts
def _limit_labels_y(cv: Canvas, frame: Frame, limits, factor: float) -> None:
    """Labels of horizontal lines right of the axes, in order of value, pushed apart by a text height."""
    placed = []
    for lim in sorted((lim for lim in limits if lim.label), key=lambda lim: -lim.value):
        y = float(frame.y(lim.value / factor))
        if placed and y < placed[-1] + FONT + 1.5:
            y = placed[-1] + FONT + 1.5
        placed.append(y)
        cv.text(frame.right + 4, y, lim.label, FONT, colour=LINE_STYLE[lim.kind][0])


def _limit_labels_x(cv: Canvas, frame: Frame, limits, factor: float) -> None:
    """Labels of vertical lines above the axes, turned 90°, pushed apart by a text height."""
    placed = []
    for lim in sorted((lim for lim in limits if lim.label), key=lambda lim: lim.value):
        x = float(frame.x(lim.value / factor))
        if placed and x < placed[-1] + FONT + 1.5:
            x = placed[-1] + FONT + 1.5
        placed.append(x)
        cv.text(
            x + 0.35 * FONT,
            frame.top - 4,
            lim.label,
            FONT,
            colour=LINE_STYLE[lim.kind][0],
            rotate=90.0,
            baseline="alphabetic",
        )


def _lines(cv: Canvas, frame: Frame, limits, fx: float, fy: float) -> None:
    for lim in limits:
        colour, width, dash = LINE_STYLE[lim.kind]
        if lim.axis == "y":
            y = float(frame.y(lim.value / fy))
            cv.line(frame.left, y, frame.right, y, colour, width, dash)
        else:
            x = float(frame.x(lim.value / fx))
            cv.line(x, frame.top, x, frame.bottom, colour, width, dash)


def _ticks(lim, log: bool, target: int) -> list[float]:
    return log_ticks(*lim) if log else nice_ticks(lim[0], lim[1], target)


def _axis_y(cv: Canvas, frame: Frame, ticks, label: str, label_x: float) -> None:
    for v in ticks:
        y = float(frame.y(v))
        cv.line(frame.left, y, frame.right, y, GRID, 0.6)
        cv.line(frame.left - 3, y, frame.left, y, "#333333", 0.6)
        cv.text(frame.left - 5, y, tick_label(v), FONT, anchor="end")
    if frame.ylog:  # minor grid at 2…9 × each decade
        lo, hi = frame.ylim
        for k in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi))):
            for m in range(2, 10):
                v = m * 10.0**k
                if lo < v < hi:
                    y = float(frame.y(v))
                    cv.line(frame.left, y, frame.right, y, GRID, 0.4)
    lines = label.split("\n")
    for k, line in enumerate(lines):
        cv.text(label_x + k * (FONT + 2), frame.top + frame.height / 2, line, FONT + 1, anchor="middle", rotate=90.0)


def _axis_x(cv: Canvas, frame: Frame, ticks, categories=None, labels: bool = True) -> float:
    """Vertical grid at the ticks, tick marks and labels below the axes; returns the labels' depth (pt)."""
    depth = 0.0
    if categories is not None:
        for k, name in enumerate(categories):
            x = float(frame.x(k))
            cv.line(x, frame.top, x, frame.bottom, GRID, 0.6)
            if labels:
                cv.line(x, frame.bottom, x, frame.bottom + 3, "#333333", 0.6)
                cv.text(x + 2, frame.bottom + 6, name, FONT, anchor="end", rotate=40.0, baseline="hanging")
        return 0.643 * max((text_width(c, FONT) for c in categories), default=0.0) + 12
    for v in ticks:
        x = float(frame.x(v))
        cv.line(x, frame.top, x, frame.bottom, GRID, 0.6)
        if labels:
            cv.line(x, frame.bottom, x, frame.bottom + 3, "#333333", 0.6)
            cv.text(x, frame.bottom + 5, tick_label(v), FONT, anchor="middle", baseline="hanging")
            depth = FONT + 8
    return depth


def _panel_range(panel: Panel, fx: float, fy: float, categories=None):
    xs = [s.x / fx for s in panel.series] + [np.array([p.x / fx for p in panel.points])]
    ys = [s.y / fy for s in panel.series] + [np.array([p.y / fy for p in panel.points])]
    ys.append(np.array([lim.value / fy for lim in panel.limits if lim.axis == "y"]))
    xs.append(np.array([lim.value / fx for lim in panel.limits if lim.axis == "x"]))
    xcat = (-0.4, len(categories) - 0.6) if categories else None
    allx = np.concatenate([np.ravel(a) for a in xs]) if xs else np.array([])
    return xcat or data_range(allx, pad=0.03), data_range(np.concatenate([np.ravel(a) for a in ys]), panel.y.log)


def _tick_width(ticks) -> float:
    return max((text_width(tick_label(v), FONT) for v in ticks), default=0.0)


def chart_svg(chart: Chart, prefix: str) -> str:
    n = len(chart.panels)
    column = chart.arrangement == "column"
    xlabel, fx = _scaled(chart.x)
    cats = chart.x.categories
    scales = []
    for panel in chart.panels:
        pfx = _scaled(panel.x)[1] if panel.x is not None else fx
        ylabel, fy = _scaled(panel.y)
        xlim, ylim = _panel_range(panel, pfx, fy, cats)
        scales.append(
            (pfx, fy, xlim, ylim, _ticks(ylim, panel.y.log, 5), textwrap.fill(ylabel, 26) if column else ylabel)
        )
    if column:  # one x range for the stack
        lo = min(s[2][0] for s in scales)
        hi = max(s[2][1] for s in scales)
        scales = [(a, b, (lo, hi), *rest) for a, b, _, *rest in scales]
    labels = _chart_legend(chart)
    wrapped, ncol, legend_h = _legend_layout(labels)
    title = textwrap.fill(chart.title, 95) if chart.title else ""
    xlines = [lim for panel in chart.panels for lim in panel.limits if lim.axis == "x" and lim.label]
    ylines = [lim for panel in chart.panels for lim in panel.limits if lim.axis == "y" and lim.label]
    right = max([text_width(lim.label, FONT) + 10 for lim in ylines] + [14.0])
    top = (
        8
        + (14 * (title.count("\n") + 1) if title else 0)
        + (max(text_width(lim.label, FONT) for lim in xlines) + 8 if xlines else 0)
    )
    lefts = [s[5].count("\n") * (FONT + 2) + FONT + 10 + _tick_width(s[4]) + 8 for s in scales]
    x_depth = (0.643 * max(text_width(c, FONT) for c in cats) + 12) if cats else FONT + 8
    bottom = x_depth + FONT + 10 + legend_h
    if column:
        left = max(lefts)
        ph, gap = 112.0, 12.0
        height = top + n * ph + (n - 1) * gap + bottom
        frames = [
            Frame(left, top + k * (ph + gap), WIDTH - left - right, ph, s[2], s[3], ylog=chart.panels[k].y.log)
            for k, s in enumerate(scales)
        ]
    else:
        ph, gap = 160.0, 14.0 + (right - 14.0)  # room for the labels right of each panel
        height = top + ph + bottom
        pw = (WIDTH - sum(lefts) - right - gap * (n - 1)) / n
        frames, x = [], 0.0
        for k, s in enumerate(scales):
            x += lefts[k]
            frames.append(Frame(x, top, pw, ph, s[2], s[3], ylog=chart.panels[k].y.log))
            x += pw + gap
        left = lefts[0]
    cv = Canvas(WIDTH, height, prefix)
    if title:
        for k, line in enumerate(title.split("\n")):
            cv.text(WIDTH / 2, 6 + k * 14, line, FONT + 1.5, anchor="middle", baseline="hanging")
    colours: dict[str, int] = {}
    handles: dict[str, tuple] = {}
    for k, (frame, panel, (pfx, fy, xlim, _ylim, yt, ylabel)) in enumerate(zip(frames, chart.panels, scales)):
        _axis_y(cv, frame, yt, ylabel, frame.left - _tick_width(yt) - 8 - FONT - ylabel.count("\n") * (FONT + 2))
        last = not column or k == n - 1
        _axis_x(cv, frame, nice_ticks(xlim[0], xlim[1], 7) if not cats else None, cats, labels=last)
        if last:
            cv.text(
                frame.left + frame.width / 2,
                frame.bottom + x_depth + 2,
                _scaled(panel.x)[0] if panel.x is not None else xlabel,
                FONT + 1,
                anchor="middle",
                baseline="hanging",
            )
        _lines(cv, frame, panel.limits, pfx, fy)
        if panel.band is not None:
            a, b = (panel.series[i] for i in panel.band)
            xa, xb = frame.x(a.x / pfx), frame.x(b.x / pfx)
            c = PALETTE[_colour(a, colours)]
            cv.polygon(list(xa) + list(xb[::-1]), list(frame.y(a.y / fy)) + list(frame.y(b.y / fy)[::-1]), c, 0.15)
        for s in panel.series:  # colours in the data's order, then the critical line drawn on top
            _colour(s, colours)
        for s in sorted(panel.series, key=lambda s: s.critical):
            c = PALETTE[_colour(s, colours)]
            x, y = decimate(s.x / pfx, s.y / fy)
            px, py = frame.x(x), frame.y(y)
            width = 2.2 if s.critical else 1.1
            if s.style != "none":
                cv.polyline(px, py, c, width, DASH.get(s.style, ""))
            if s.marker:
                for u, v in zip(px.tolist(), py.tolist()):
                    cv.marker(u, v, s.marker, 5.0, c, "#333333" if s.style == "none" else c, 0.4)
            if s.label:
                handles.setdefault(
                    s.label + (" (critical)" if s.critical else ""), ("line", c, width, s.style, s.marker)
                )
        for pt in panel.points:
            x, y = float(frame.x(pt.x / pfx)), float(frame.y(pt.y / fy))
            if pt.kind == "corner":
                c = PALETTE[(pt.colour or 0) % len(PALETTE)]
                cv.marker(x, y, "o", 4.0, c)
                cv.text(x + 4, y - 4, pt.label, FONT, colour=c, baseline="alphabetic")
                continue
            cv.marker(x, y, "*", 12.0, "#000000", "#ffffff", 0.8)
            handles.setdefault(_point_label(pt, panel, fy), ("star",))
        cv.rect(frame.left, frame.top, frame.width, frame.height, stroke="#333333", width=0.8)
        _limit_labels_y(cv, frame, [lim for lim in panel.limits if lim.axis == "y"], fy)
        if not column:
            _limit_labels_x(cv, frame, [lim for lim in panel.limits if lim.axis == "x"], pfx)
    if column:
        unique = list({(lim.value, lim.label): lim for lim in xlines}.values())
        _limit_labels_x(cv, frames[0], unique, fx)
    _legend(cv, [(lab, handles[lab]) for lab in labels if lab in handles], wrapped, ncol, left, height - legend_h + 4)
    return cv.svg()


def _colour(s: Series, colours: dict) -> int:
    key = s.label or f"#{id(s)}"
    k = s.colour if s.colour is not None else colours.setdefault(key, len(colours))
    return k % len(PALETTE)


#: characters of a legend line (the figure's width at the legend's font); longer labels wrap
_LEGEND_CHARS = 95


def _legend_layout(labels: list[str]) -> tuple[list[str], int, float]:
    """(wrapped labels, columns, height in pt) of a legend of ``labels`` below the axes."""
    if not labels:
        return [], 1, 0.0
    wrapped = [textwrap.fill(s, _LEGEND_CHARS, subsequent_indent="  ") for s in labels]
    ncol = 1 if max(len(s) for s in labels) > 44 else 2
    lines = sum(s.count("\n") + 1 for s in wrapped) if ncol == 1 else math.ceil(len(labels) / 2)
    return wrapped, ncol, 10 + lines * (FONT + 3.5)


def _legend(cv: Canvas, entries: list, wrapped: list[str], ncol: int, left: float, top: float) -> None:
    """Entries (label, handle) below the axes: a line sample (with its marker) or a star, then the label."""
    col_w = (WIDTH - left) / ncol
    y_next = [top] * ncol
    for k, ((_, handle), text) in enumerate(zip(entries, wrapped)):
        col = k % ncol
        x, y = left + col * col_w, y_next[col] + FONT / 2
        if handle[0] == "star":
            cv.marker(x + 11, y, "*", 11.0, "#000000", "#ffffff", 0.8)
        elif handle[0] == "patch":  # ("patch", colour, hatch pattern id or "")
            cv.rect(x + 3, y - 4, 16, 8, fill=handle[1])
            if handle[2]:
                cv.rect(x + 3, y - 4, 16, 8, fill=f"url(#{handle[2]})")
        else:
            _, c, width, style, marker = handle
            if style != "none":
                cv.line(x, y, x + 22, y, c, width, DASH.get(style, ""))
            if marker:
                cv.marker(x + 11, y, marker, 5.0, c, "#333333" if style == "none" else c, 0.4)
        for j, line in enumerate(text.split("\n")):
            cv.text(x + 28, y + j * (FONT + 3.5), line, FONT)
        y_next[col] += (text.count("\n") + 1) * (FONT + 3.5)


# ----------------------------------------------------------------------------------------------------- bars
def bars_svg(bars: Bars, prefix: str) -> str:
    label, factor = _scaled(bars.axis)
    names = [s if len(s) <= 70 else s[:69] + "…" for s in bars.labels]
    values = np.asarray(bars.values, dtype=float) / factor
    n = len(names)
    present = [name for name, on in (("fails", any(bars.failing)), ("complies", not all(bars.failing))) if on]
    wrapped, ncol, legend_h = _legend_layout(present)
    lim_v = bars.limit.value / factor if bars.limit is not None else None
    vlim = data_range(np.concatenate([values, [0.0] + ([lim_v] if lim_v is not None else [])]))
    ticks = nice_ticks(vlim[0], vlim[1], 6)
    title_h = 18.0 if bars.title else 6.0
    lim_label = bars.limit.label if bars.limit is not None else ""
    if bars.horizontal:
        left = max(text_width(s, FONT) for s in names) + 12
        ph = 16.0 * n + 6
        top = title_h + (FONT + 8 if lim_label else 0)
        height = top + ph + FONT + 8 + FONT + 10 + legend_h
        frame = Frame(left, top, WIDTH - left - 16, ph, vlim, (-0.6, n - 0.4))
    else:
        depth = 0.5 * max(text_width(s, FONT) for s in names) + 12
        left = _tick_width(ticks) + FONT + 22
        right = text_width(lim_label, FONT) + 10 if lim_label else 14.0
        ph = 170.0
        height = title_h + ph + depth + FONT + 10 + legend_h
        frame = Frame(left, title_h, WIDTH - left - right, ph, (-0.6, n - 0.4), vlim)
    cv = Canvas(WIDTH, height, prefix)
    hatch = cv.hatch()
    if bars.title:
        cv.text(WIDTH / 2, 4, bars.title, FONT + 1, anchor="middle", baseline="hanging")
    if bars.horizontal:
        _axis_x(cv, frame, ticks)
        cv.text(
            frame.left + frame.width / 2, frame.bottom + FONT + 9, label, FONT + 1, anchor="middle", baseline="hanging"
        )
        for k, (name, v, fails) in enumerate(zip(names, values, bars.failing)):
            y = float(frame.y(n - 1 - k))
            x0, x1 = sorted((float(frame.x(0.0)), float(frame.x(v))))
            cv.rect(x0, y - 6, x1 - x0, 12, fill=FAIL if fails else PASS)
            if fails:
                cv.rect(x0, y - 6, x1 - x0, 12, fill=f"url(#{hatch})")
            cv.text(frame.left - 5, y, name, FONT, anchor="end")
    else:
        _axis_y(cv, frame, ticks, label, 8)
        for k, (name, v, fails) in enumerate(zip(names, values, bars.failing)):
            x = float(frame.x(k))
            y0, y1 = sorted((float(frame.y(0.0)), float(frame.y(v))))
            cv.rect(x - 10, y0, 20, y1 - y0, fill=FAIL if fails else PASS)
            if fails:
                cv.rect(x - 10, y0, 20, y1 - y0, fill=f"url(#{hatch})")
            cv.text(x + 2, frame.bottom + 6, name, FONT, anchor="end", rotate=30.0, baseline="hanging")
    if bars.limit is not None:
        which = "x" if bars.horizontal else "y"
        lim = Limit(bars.limit.value, bars.limit.label, which, bars.limit.kind)
        _lines(cv, frame, [lim], factor, factor)
        if bars.horizontal:  # one label, written level above its line
            colour = LINE_STYLE[lim.kind][0]
            cv.text(
                float(frame.x(lim.value / factor)),
                frame.top - 4,
                lim.label,
                FONT,
                anchor="middle",
                colour=colour,
                baseline="alphabetic",
            )
        else:
            _limit_labels_y(cv, frame, [lim], factor)
    cv.rect(frame.left, frame.top, frame.width, frame.height, stroke="#333333", width=0.8)
    handles = {"fails": ("patch", FAIL, hatch), "complies": ("patch", PASS, "")}
    _legend(cv, [(name, handles[name]) for name in present], wrapped, ncol, 20.0, height - legend_h + 4)
    return cv.svg()


# ----------------------------------------------------------------------------------------------------- heatmaps
_STOPS = ((0.0, (0x7A, 0x1C, 0x00)), (0.4999, (0xD5, 0x5E, 0x00)), (0.5, (0xC6, 0xDB, 0xEF)), (1.0, (0x08, 0x30, 0x6B)))


def _cmap(t: float) -> str:
    """The margin colour map at ``t`` in [0, 1] (0.5 the threshold): vermillion to dark red below, blues above."""
    t = min(1.0, max(0.0, t))
    for (a, ca), (b, cb) in zip(_STOPS, _STOPS[1:]):
        if t <= b:
            w = 0.0 if b == a else (t - a) / (b - a)
            return "#" + "".join(f"{round(x + w * (y - x)):02x}" for x, y in zip(ca, cb))
    return "#08306b"


def heatmap_svg(hm: Heatmap, prefix: str) -> str:
    """Cells coloured by value: failing (below the threshold) in vermillion to dark red, hatched, passing in blues
    (darker: more margin), not evaluated in light grey with a dash; a colour bar with the threshold marked. The colour
    scale spans at least one unit either side of the threshold, so a cell failing by a little is vermillion."""
    label, factor = _scaled(hm.scale)
    vals = hm.values / factor
    thr = hm.threshold / factor
    finite = vals[np.isfinite(vals)]
    lo = min(float(finite.min()) if finite.size else thr, thr - 1.0)
    hi = max(float(finite.max()) if finite.size else thr, thr + 1.0)

    def norm(v):
        return 0.5 * (v - lo) / (thr - lo) if v < thr else 0.5 + 0.5 * (v - thr) / (hi - thr)

    rows, cols = hm.rows, hm.columns
    cw = max([text_width(c, FONT) + 12 for c in cols] + [56.0])
    ch = 22.0
    left = max(text_width(r, FONT) for r in rows) + 10 + (FONT + 8 if hm.row_label else 0)
    top = 18.0 if hm.title else 6.0
    bar_label = f"{label} (< {format_value(thr)} fails)"
    width = left + cw * len(cols) + 24 + 10 + 40 + FONT + 10
    height = top + ch * len(rows) + FONT + 8 + (FONT + 12 if hm.column_label else 0) + 6
    cv = Canvas(max(width, 200.0), height, prefix)
    hatch = cv.hatch()
    if hm.title:
        cv.text(cv.width / 2, 4, hm.title, FONT + 1, anchor="middle", baseline="hanging")
    for i, r in enumerate(rows):
        y = top + i * ch
        cv.text(left - 5, y + ch / 2, r, FONT, anchor="end")
        for j in range(len(cols)):
            x, v = left + j * cw, vals[i, j]
            if not math.isfinite(v):
                cv.rect(x, y, cw, ch, fill=NOT_EVALUATED, stroke="#ffffff")
                cv.text(x + cw / 2, y + ch / 2, "—", FONT, anchor="middle", colour="#555555")
                continue
            t = norm(v)
            cv.rect(x, y, cw, ch, fill=_cmap(t), stroke="#ffffff")
            failing = v < thr
            if failing:
                cv.rect(x, y, cw, ch, fill=f"url(#{hatch})")
                tw = text_width(f"{v:+.2f}", FONT)
                cv.rect(x + cw / 2 - tw / 2 - 2, y + ch / 2 - FONT / 2 - 2, tw + 4, FONT + 4, fill="#7a1c00")
            cv.text(
                x + cw / 2,
                y + ch / 2,
                f"{v:+.2f}".replace("-", "\u2212"),
                FONT,
                anchor="middle",
                colour="#ffffff" if failing or t > 0.8 else "#000000",
                weight="bold" if failing else "normal",
            )
    for j, c in enumerate(cols):
        cv.text(left + (j + 0.5) * cw, top + ch * len(rows) + 5, c, FONT, anchor="middle", baseline="hanging")
    if hm.column_label:
        cv.text(
            left + cw * len(cols) / 2,
            top + ch * len(rows) + FONT + 12,
            hm.column_label,
            FONT + 1,
            anchor="middle",
            baseline="hanging",
        )
    if hm.row_label:
        cv.text(8, top + ch * len(rows) / 2, hm.row_label, FONT + 1, anchor="middle", rotate=90.0, baseline="hanging")
    # the colour bar: 64 slices from lo (bottom) to hi (top), the threshold as a black line
    bx, bh = left + cw * len(cols) + 24, ch * len(rows)
    for k in range(64):
        cv.rect(bx, top + bh * (1 - (k + 1) / 64), 10, bh / 64 + 0.3, fill=_cmap((k + 0.5) / 64))
    cv.rect(bx, top, 10, bh, stroke="#333333", width=0.6)
    frame = Frame(bx, top, 10, bh, (0, 1), (0, 1))
    ticks = sorted({lo, thr, hi} | {v for v in nice_ticks(lo, hi, 4)})
    for v in ticks:
        y = float(frame.y(norm(v)))
        cv.line(bx + 10, y, bx + 13, y, "#333333", 0.6)
        cv.text(bx + 15, y, tick_label(round(v, 6)), FONT)
    cv.line(bx - 2, float(frame.y(0.5)), bx + 12, float(frame.y(0.5)), "#000000", 1.4)
    cv.text(bx + 50, top + bh / 2, bar_label, FONT, anchor="middle", rotate=90.0, baseline="hanging")
    return cv.svg()


__all__ = [
    "render_result",
    "figure_prefix",
    "render_evidence",
    "render",
    "decimate",
    "chart_svg",
    "bars_svg",
    "heatmap_svg",
    "PALETTE",
    "FAIL",
]
