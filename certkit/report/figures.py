"""Draw evidence data (:mod:`certkit.evidence`) as inline SVG, every figure with the same conventions:

- colours from the Okabe–Ito palette (distinguishable with the common colour-vision deficiencies); failing bars and
  cells in vermillion and hatched, passing ones in blue; the critical series drawn thicker;
- limits (black dashed), allowables (vermillion dash-dot), events (grey dotted) and references (grey dashed) drawn
  and labelled outside the axes, labels pushed apart where they would overlap;
- the critical point marked with a star and named in the legend;
- legends below the figure, outside the data; heatmaps with a colour bar;
- values converted to aviation units (:mod:`certkit.report.display`); series decimated to the figure's pixel
  resolution keeping each pixel column's minimum and maximum (the drawn line is the same to the eye);
- deterministic SVG: hashed ids salted with a constant, no date, and every id prefixed by the figure's own prefix so
  ids are unique across a page.
"""

from __future__ import annotations

import math
import re
import textwrap

import numpy as np

from certkit.evidence import Axis, Bars, Chart, Heatmap, Limit, Panel, Series
from certkit.report.display import axis_label, format_value, unit_and_factor
from certkit.report.plots import figure_to_svg, new_figure, text_width
from matplotlib.ticker import MaxNLocator, NullLocator  # noqa: E402 (after plots.py chose the backend)


def _thousands(x, _pos=None) -> str:
    """Tick labels: thousands separated, ``-0`` as 0, at most 6 significant digits."""
    if x == 0:
        return "0"
    return (f"{x:,.0f}" if abs(x) >= 1000 else f"{x:.6g}").replace("-", "\u2212")


PALETTE = ("#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#000000", "#999933")
FAIL, PASS, NOT_EVALUATED = "#D55E00", "#0072B2", "#e8e8e8"
LINE_STYLE = {"limit": dict(color="#000000", ls="--", lw=0.9), "allowable": dict(color="#D55E00", ls="-.", lw=1.1),
              "event": dict(color="#777777", ls=":", lw=0.8), "reference": dict(color="#777777", ls="--", lw=0.7)}
#: points per series kept at most: two per pixel column of the widest axes (min and max of each)
MAX_POINTS = 1200
WIDTH = 7.0
FONT = 8.0  # smallest text in a figure (points); figures are shown at least at their size


def figure_prefix(rule_id: str) -> str:
    """The id prefix of a rule's figures: ``ev-`` and the rule id's letters and digits (``ev-25-331-b``)."""
    return "ev-" + re.sub(r"[^0-9a-z]+", "-", rule_id.lower()).strip("-")


def render_result(result) -> None:
    """Draw the figures of a :class:`~certkit.results.RuleResult`'s evidence (in the process that evaluated it: see
    :func:`certkit.scheduler.run`); a figure that cannot be drawn is dropped with a note, never fails the run."""
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


# ----------------------------------------------------------------------------------------------------- charts
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


def chart_svg(chart: Chart, prefix: str) -> str:
    n = len(chart.panels)
    column = chart.arrangement == "column"
    xlabel, fx = _scaled(chart.x)
    cats = chart.x.categories
    labels = _chart_legend(chart)
    legend = _legend_layout(labels)
    bottom = 0.5 + (0.643 * text_width(cats, FONT) if cats else 0.0) + legend[2]
    title = textwrap.fill(chart.title, 105) if chart.title else ""
    # x lines of a stacked chart are labelled once, above the top panel (each panel draws its own lines)
    above_top = list({(lim.value, lim.label): lim for panel in chart.panels for lim in panel.limits
                      if lim.axis == "x" and lim.label}.values()) if column else []
    above = [lim.label for lim in above_top] if column else [
        lim.label for panel in chart.panels for lim in panel.limits if lim.axis == "x" and lim.label]
    top = 0.15 + (0.2 * (title.count("\n") + 1) if title else 0.0) + (text_width(above, FONT) + 0.08 if above else 0.0)
    if column:
        size = (WIDTH, top + 1.6 * n + bottom)
        fig, axes = new_figure(n, 1, size, left=1.0, right=1.1, bottom=bottom, top=top, hspace=0.18)
    else:
        size = (WIDTH + 0.4 * (n - 1), top + 2.3 + bottom)
        fig, axes = new_figure(1, n, size, left=0.7, right=0.3, bottom=bottom, top=top, wspace=0.45)
    handles: dict[str, object] = {}
    colours: dict[str, int] = {}
    for p, (ax, panel) in enumerate(zip(axes, chart.panels)):
        pfx = fx
        if panel.x is not None:
            pfx = _scaled(panel.x)[1]
        ylabel, fy = _scaled(panel.y)
        drawn = []
        for s in panel.series:
            key = s.label or f"#{len(colours)}"
            c = PALETTE[(s.colour if s.colour is not None else colours.setdefault(key, len(colours))) % len(PALETTE)]
            x, y = decimate(s.x / pfx, s.y / fy)
            scatter = s.style == "none"
            line, = ax.plot(x, y, color=c, ls="none" if scatter else s.style, marker=s.marker or None,
                            ms=(5 if scatter else 4) if s.marker else None, lw=2.2 if s.critical else 1.1,
                            zorder=3 if s.critical else 2, mec="#333333" if scatter else c, mew=0.4)
            drawn.append(line)
            handles.setdefault(s.label + (" (critical)" if s.critical else ""), line)
        if panel.band is not None:
            a, b = (panel.series[i] for i in panel.band)
            ax.fill_between(a.x / pfx, a.y / fy, b.y / fy, color=drawn[panel.band[0]].get_color(), alpha=0.15, lw=0)
        for pt in panel.points:
            if pt.kind == "corner":
                c = PALETTE[(pt.colour or 0) % len(PALETTE)]
                ax.plot([pt.x / pfx], [pt.y / fy], marker="o", ms=3.5, color=c, ls="none", zorder=4)
                ax.annotate(pt.label, (pt.x / pfx, pt.y / fy), textcoords="offset points", xytext=(4, 3), color=c,
                            fontsize=FONT)
                continue
            mk, = ax.plot([pt.x / pfx], [pt.y / fy], marker="*", ms=12, color="#000000", mec="#ffffff", mew=0.8,
                          ls="none", zorder=5)
            handles.setdefault(_point_label(pt, panel, fy), mk)
        ax.set_ylabel(textwrap.fill(ylabel, 26) if column else ylabel, fontsize=FONT + 1)
        if panel.y.log:
            ax.set_yscale("log")
        else:  # few ticks: each tick is several artists, the largest part of a figure's cost
            ax.yaxis.set_major_locator(MaxNLocator(nbins=5, steps=[1, 2, 2.5, 5, 10]))
            ax.yaxis.set_major_formatter(_thousands)
        if panel.title:
            ax.set_title(panel.title, fontsize=FONT + 1)
        ax.grid(True, alpha=0.3, which="both" if panel.y.log else "major")
        ax.tick_params(labelsize=FONT)
        _limits(ax, [lim for lim in panel.limits if lim.axis == "y"], fy, "y")
        _limits(ax, [lim for lim in panel.limits if lim.axis == "x"], pfx, "x", label=not column)
        if not column or p == n - 1:
            if cats:
                ax.set_xticks(range(len(cats)), cats, rotation=40, ha="right", rotation_mode="anchor", fontsize=FONT)
            else:
                ax.xaxis.set_major_locator(MaxNLocator(nbins=8, steps=[1, 2, 2.5, 5, 10]))
                ax.xaxis.set_major_formatter(_thousands)
            ax.set_xlabel(_scaled(panel.x)[0] if panel.x is not None else xlabel, fontsize=FONT + 1)
    if column:
        _shared_time_axis(axes)
        if above_top:
            _limits(axes[0], above_top, fx, "x", lines=False)
    if title:
        fig.suptitle(title, fontsize=FONT + 1.5, y=1.0 - 0.06 / size[1], va="top")
    _legend(fig, [(lab, handles[lab]) for lab in labels if lab in handles], legend, size, left=1.0 if column else 0.7)
    return figure_to_svg(fig, prefix)


def _shared_time_axis(axes) -> None:
    """Stacked panels on one x range: the bottom panel's ticks and labels, the others only its vertical grid lines
    (no tick artists: cheaper than shared axes, which create every tick on every panel)."""
    lo = min(ax.get_xlim()[0] for ax in axes)
    hi = max(ax.get_xlim()[1] for ax in axes)
    bottom = axes[-1]
    bottom.set_xlim(lo, hi)
    ticks = [v for v in bottom.xaxis.get_major_locator().tick_values(lo, hi) if lo <= v <= hi]
    for ax in axes[:-1]:
        ax.set_xlim(lo, hi)
        ax.xaxis.set_major_locator(NullLocator())
        ax.grid(False, axis="x")
        ax.vlines(ticks, 0.0, 1.0, transform=ax.get_xaxis_transform(), colors="#b0b0b0", linewidths=0.8, alpha=0.3,
                  zorder=0.5)


def _unit_of(axis: Axis) -> str:
    unit, _ = unit_and_factor(axis.unit, axis.display)
    return f" {unit}" if unit else ""


def _limits(ax, limits: list[Limit], factor: float, which: str, label: bool = True, lines: bool = True) -> None:
    """Lines at the limits, labelled outside the axes (right of y lines, above x lines), labels pushed apart by at
    least a text height where they would overlap."""
    if not limits:
        return
    for lim in limits if lines else ():
        style = LINE_STYLE[lim.kind]
        (ax.axhline if which == "y" else ax.axvline)(lim.value / factor, zorder=1.5, **style)
    if not label:
        return
    lo, hi = ax.get_ylim() if which == "y" else ax.get_xlim()
    # the axes' extent in points along the labelled direction
    bbox = ax.get_position()
    fw, fh = ax.figure.get_size_inches()
    span_pt = (bbox.height * fh if which == "y" else bbox.width * fw) * 72.0
    gap = (FONT + 1.5) / span_pt * (hi - lo)  # a label's height in data units
    order = sorted((lim for lim in limits if lim.label), key=lambda lim: lim.value)
    last = -math.inf
    for lim in order:
        v = lim.value / factor
        pos = max(v, last + gap)
        last = pos
        colour = LINE_STYLE[lim.kind]["color"]
        if which == "y":
            ax.annotate(lim.label, xy=(1.0, v), xycoords=("axes fraction", "data"), xytext=(1.01, pos),
                        textcoords=("axes fraction", "data"), fontsize=FONT, va="center", ha="left", color=colour,
                        annotation_clip=False)
        else:
            ax.annotate(lim.label, xy=(v, 1.0), xycoords=("data", "axes fraction"), xytext=(pos, 1.02),
                        textcoords=("data", "axes fraction"), fontsize=FONT, va="bottom", ha="center", color=colour,
                        rotation=90, annotation_clip=False)


#: characters of a legend line (the figure's width at the legend's font); longer labels wrap
_LEGEND_CHARS = 100


def _legend_layout(labels: list[str]) -> tuple[list[str], int, float]:
    """(wrapped labels, columns, height in inches) of a legend of ``labels`` below the axes."""
    if not labels:
        return [], 1, 0.0
    wrapped = [textwrap.fill(s, _LEGEND_CHARS, subsequent_indent="  ") for s in labels]
    ncol = 1 if max(len(s) for s in labels) > 44 else 2
    lines = sum(s.count("\n") + 1 for s in wrapped) if ncol == 1 else math.ceil(len(labels) / 2)
    return wrapped, ncol, 0.15 + lines * FONT * 1.45 / 72.0


def _legend(fig, entries: list, layout, size: tuple[float, float], left: float) -> None:
    """The legend below the axes, inside the room :func:`_legend_layout` measured (a line drawn outside the figure
    would be clipped)."""
    wrapped, ncol, height = layout
    if not entries:
        return
    fig.legend([h for _, h in entries], wrapped[:len(entries)], loc="upper left",
               bbox_to_anchor=(left / size[0] - 0.02, (height - 0.05) / size[1]), ncol=ncol, fontsize=FONT,
               frameon=False, borderaxespad=0.0, handlelength=2.4, labelspacing=0.45)


# ----------------------------------------------------------------------------------------------------- bars
def bars_svg(bars: Bars, prefix: str) -> str:
    label, factor = _scaled(bars.axis)
    names = [s if len(s) <= 70 else s[:69] + "…" for s in bars.labels]
    values = np.asarray(bars.values, dtype=float) / factor
    colours = [FAIL if f else PASS for f in bars.failing]
    hatches = ["///" if f else "" for f in bars.failing]
    n = len(names)
    legend = _legend_layout([s for s, on in (("fails", any(bars.failing)), ("complies", not all(bars.failing))) if on])
    if bars.horizontal:
        size = (WIDTH, 0.26 * n + 1.0 + (0.3 if bars.title else 0.0) + legend[2])
        fig, (ax,) = new_figure(1, 1, size, left=text_width(names, FONT) + 0.2, right=1.0, bottom=0.5 + legend[2],
                                top=0.35 if bars.title else 0.15)
        y = np.arange(n)[::-1]
        for yy, v, c, h in zip(y, values, colours, hatches):
            ax.barh(yy, v, color=c, hatch=h, edgecolor="#ffffff" if h else c, lw=0)
        ax.set_yticks(y, names, fontsize=FONT)
        ax.set_ylim(-0.6, n - 0.4)
        ax.set_xlabel(label, fontsize=FONT + 1)
        ax.grid(True, axis="x", alpha=0.3)
        which = "x"
    else:
        bottom = 0.4 + 0.342 * text_width(names, FONT) + legend[2]
        size = (WIDTH, 2.6 + bottom)
        fig, (ax,) = new_figure(1, 1, size, left=0.8, right=1.1, bottom=bottom, top=0.35 if bars.title else 0.15)
        x = np.arange(n)
        for xx, v, c, h in zip(x, values, colours, hatches):
            ax.bar(xx, v, color=c, hatch=h, edgecolor="#ffffff" if h else c, lw=0)
        ax.set_xticks(x, names, rotation=20, ha="right", rotation_mode="anchor", fontsize=FONT)
        ax.set_ylabel(label, fontsize=FONT + 1)
        ax.grid(True, axis="y", alpha=0.3)
        which = "y"
    ax.tick_params(labelsize=FONT)
    if bars.limit is not None:
        _limits(ax, [Limit(bars.limit.value, bars.limit.label, which, bars.limit.kind)], factor, which)
    if bars.title:
        ax.set_title(bars.title, fontsize=FONT + 1)
    from matplotlib.patches import Patch

    handles = []
    if any(bars.failing):
        handles.append(("fails", Patch(facecolor=FAIL, hatch="///", edgecolor="#ffffff")))
    if not all(bars.failing):
        handles.append(("complies", Patch(facecolor=PASS)))
    _legend(fig, handles, legend, size, left=0.3)
    return figure_to_svg(fig, prefix)


# ----------------------------------------------------------------------------------------------------- heatmaps
def heatmap_svg(hm: Heatmap, prefix: str) -> str:
    """Cells coloured by value: failing (below the threshold) in reds to vermillion, hatched, passing in blues
    (darker: more margin), not evaluated in light grey with a dash; a colour bar with the threshold marked."""
    from matplotlib.colors import LinearSegmentedColormap, TwoSlopeNorm

    label, factor = _scaled(hm.scale)
    vals = hm.values / factor
    thr = hm.threshold / factor
    finite = vals[np.isfinite(vals)]
    # the colour scale spans at least one unit either side of the threshold (a normalised margin of −1 is the darkest
    # red): a cell failing by a little is vermillion, never a pale colour
    lo = min(float(finite.min()) if finite.size else thr, thr - 1.0)
    hi = max(float(finite.max()) if finite.size else thr, thr + 1.0)
    cmap = LinearSegmentedColormap.from_list("certkit_margin", [(0.0, "#7a1c00"), (0.4999, FAIL), (0.5, "#c6dbef"),
                                                                 (1.0, "#08306b")])
    cmap = cmap.with_extremes(bad=NOT_EVALUATED)
    norm = TwoSlopeNorm(vmin=lo, vcenter=thr, vmax=hi)
    rows, cols = hm.rows, hm.columns
    size = (min(WIDTH, 2.4 + text_width(rows, FONT) + 1.2 * len(cols)), 0.9 + 0.36 * len(rows) + (0.3 if hm.title else 0))
    fig, (ax,) = new_figure(1, 1, size, left=text_width(rows, FONT) + 0.3, right=1.3, bottom=0.55,
                            top=0.35 if hm.title else 0.15)
    # vector cells (pcolormesh), not an embedded bitmap
    image = ax.pcolormesh(np.arange(len(cols) + 1) - 0.5, np.arange(len(rows) + 1) - 0.5, np.ma.masked_invalid(vals),
                          cmap=cmap, norm=norm, edgecolors="#ffffff", linewidth=1.0)
    ax.set_xlim(-0.5, len(cols) - 0.5)
    ax.set_ylim(len(rows) - 0.5, -0.5)
    for i in range(len(rows)):
        for j in range(len(cols)):
            v = vals[i, j]
            if not math.isfinite(v):
                ax.text(j, i, "—", ha="center", va="center", fontsize=FONT, color="#555555")
                continue
            if v < thr:
                ax.add_patch(_cell(j, i))
            dark = v < thr or norm(v) > 0.8
            ax.text(j, i, f"{v:+.2f}".replace("-", "\u2212"), ha="center", va="center", fontsize=FONT,
                    color="#ffffff" if dark else "#000000", fontweight="bold" if v < thr else "normal",
                    bbox=dict(facecolor="#7a1c00", edgecolor="none", pad=1.5) if v < thr else None)
    ax.set_xticks(range(len(cols)), cols, fontsize=FONT)
    ax.set_yticks(range(len(rows)), rows, fontsize=FONT)
    if hm.column_label:
        ax.set_xlabel(hm.column_label, fontsize=FONT + 1)
    if hm.row_label:
        ax.set_ylabel(hm.row_label, fontsize=FONT + 1)
    if hm.title:
        ax.set_title(hm.title, fontsize=FONT + 1)
    bar_ax = fig.add_axes([1.0 - 1.05 / size[0], 0.55 / size[1], 0.15 / size[0], 1.0 - (0.7 + (0.35 if hm.title else 0.15)) / size[1] + 0.15 / size[1]])
    bar = fig.colorbar(image, cax=bar_ax)
    bar.ax.axhline(thr, color="#000000", lw=1.2)
    bar.set_label(label + " (< " + format_value(thr) + " fails)", fontsize=FONT)
    bar.ax.tick_params(labelsize=FONT)
    return figure_to_svg(fig, prefix)


def _cell(j: int, i: int):
    from matplotlib.patches import Rectangle

    return Rectangle((j - 0.5, i - 0.5), 1.0, 1.0, fill=False, hatch="///", edgecolor="#ffffff", lw=0)


__all__ = ["render_result", "figure_prefix", "render_evidence", "render", "decimate", "chart_svg", "bars_svg", "heatmap_svg", "PALETTE"]
