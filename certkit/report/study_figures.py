"""Figures of the study report, inline SVG in the house style of :mod:`certkit.report.plots` (fixed margins,
one draw). Dense point clouds are rasterised inside the SVG (an embedded PNG), so that a plot of thousands of
points stays small; lines, axes and text remain vector."""

from __future__ import annotations

import itertools
import re

import numpy as np

from certkit.report.plots import figure_to_svg, subplots
from certkit.study.analysis.labels import response_axis, response_label
from certkit.study.analysis.montecarlo import ConstraintOutcome, MonteCarloResult
from certkit.study.analysis.planform import Planform
from certkit.study.analysis.surrogates import Surrogate
from certkit.units import FT

STAGE_COLOURS = ("#b8bec7", "#2f6db5", "#2e9d4a")
STAGE_LABELS = ("unconstrained", "constrained", "Level-1 preferred")
#: most points of each stage drawn in a scatter panel
SCATTER_POINTS = 4000
_FIGURE_NUMBERS = itertools.count(1)


def inline_svg(svg: str) -> str:
    """An SVG fragment for HTML: without namespace declarations and metadata (HTML5 parses inline SVG
    without them), so the page carries no URL at all; its element ids (matplotlib numbers them per figure:
    ``figure_1``, ``patch_1``...) and the references to them get a prefix of their own, unique in the page."""
    svg = re.sub(r"<metadata>.*?</metadata>", "", svg, flags=re.S)
    svg = re.sub(r'\s+xmlns(:\w+)?="[^"]*"', "", svg)
    prefix = f"s{next(_FIGURE_NUMBERS)}-"
    return re.sub(r'(\bid="|href="#|url\(#)', lambda m: m.group(1) + prefix, svg)


def _svg(fig) -> str:
    return inline_svg(figure_to_svg(fig))


def fit_svg(s: Surrogate) -> str:
    """Actual vs predicted and residual vs predicted, training and validation cases, in the response's words and
    aviation unit (:func:`~certkit.study.analysis.labels.response_label`)."""
    words, unit, k = response_label(s.response)
    shown = f" ({unit})" if unit else ""
    fig, (a1, a2) = subplots(1, 2, figsize=(7.2, 3.0), left=0.75, wspace=0.45, top=0.3)
    data = {
        label: (np.asarray(a, dtype=float) / k, np.asarray(p, dtype=float) / k) for label, (a, p) in s.plot_data.items()
    }
    for (label, (actual, pred)), colour, marker in zip(data.items(), ("0.55", "#c0392b"), ("o", "^")):
        if len(actual) == 0:
            continue
        a1.scatter(pred, actual, s=7, c=colour, marker=marker, label=f"{label} ({len(actual)})", rasterized=True, lw=0)
        a2.scatter(pred, actual - pred, s=7, c=colour, marker=marker, rasterized=True, lw=0)
    both = np.concatenate([np.concatenate(v) for v in data.values()])
    both = both[np.isfinite(both)]
    if both.size:
        lo, hi = float(both.min()), float(both.max())
        a1.plot([lo, hi], [lo, hi], color="0.2", lw=0.8)
    a2.axhline(0.0, color="0.2", lw=0.8)
    a1.set_xlabel(f"predicted{shown}")
    a1.set_ylabel(f"actual{shown}")
    a2.set_xlabel(f"predicted{shown}")
    a2.set_ylabel(f"actual − predicted{shown}")
    for a in (a1, a2):
        a.grid(True, alpha=0.3)
        a.ticklabel_format(axis="both", style="sci", scilimits=(-3, 4))
    a1.legend(loc="upper left", fontsize=7)
    fig.suptitle(f"{words}: {s.kept.label}", fontsize=9, y=0.98)
    return _svg(fig)


def cdf_svg(o: ConstraintOutcome) -> str:
    """Empirical CDF of a constraint response over the Monte Carlo samples; thresholds marked, the infeasible
    side shaded."""
    c = o.constraint
    fig, ax = subplots(figsize=(4.6, 2.6), left=0.7, top=0.3)
    x, f = o.histogram.cdf()
    k = response_label(c.response)[2]  # SI per shown unit: the axis in the response's aviation unit
    ax.step(x / k, f, where="post", color="#2f6db5", lw=1.2)
    lo, hi = float(o.histogram.edges[0]) / k, float(o.histogram.edges[-1]) / k
    shift = 0.5 if c.is_level else 0.0
    if c.min is not None:
        ax.axvspan(lo, c.min / k - shift, color="#c0392b", alpha=0.15, lw=0)
        ax.axvline(c.min / k - shift, color="#c0392b", lw=1.0)
    if c.max is not None:
        ax.axvspan(c.max / k + shift, hi, color="#c0392b", alpha=0.15, lw=0)
        ax.axvline(c.max / k + shift, color="#c0392b", lw=1.0)
    if o.relaxed_max is not None:
        ax.axvline(o.relaxed_max / k + shift, color="#8a6100", lw=1.0, ls="--")
    ax.set_xlim(lo, hi)
    ax.set_ylim(0, 1)
    ax.set_xlabel(response_axis(c.response))
    ax.set_ylabel("fraction ≤ value")
    ax.grid(True, alpha=0.3)
    ax.set_title(f"{c.name}: P(success) = {o.p:.4f} ± {o.se:.4f}", fontsize=9)
    return _svg(fig)


def scatter_matrix_svg(mc: MonteCarloResult, labels: list[str]) -> str:
    """Objectives against each other over the Monte Carlo cloud, coloured by stage; the constrained stage's
    Pareto front of each pair drawn as a line, the histogram of each objective on the diagonal."""
    k = len(labels)
    size = 2.3 * k
    fig, axes = subplots(
        k, k, figsize=(size + 0.6, size + 0.5), left=0.8, bottom=0.6, top=0.45, wspace=0.35, hspace=0.35, squeeze=False
    )
    rng = np.random.default_rng(0)
    for i in range(k):
        for j in range(k):
            ax = axes[i, j]
            ax.tick_params(labelsize=7)
            if i == j:
                for stage in range(3):
                    vals = mc.cloud_f[mc.cloud_stage >= stage, i]
                    if vals.size:
                        ax.hist(vals, bins=40, color=STAGE_COLOURS[stage], alpha=0.9)
            else:
                for stage in range(3):
                    idx = np.flatnonzero(mc.cloud_stage == stage)
                    if idx.size > SCATTER_POINTS:
                        idx = rng.choice(idx, SCATTER_POINTS, replace=False)
                    ax.scatter(
                        mc.cloud_f[idx, j],
                        mc.cloud_f[idx, i],
                        s=2,
                        c=STAGE_COLOURS[stage],
                        lw=0,
                        rasterized=True,
                        label=STAGE_LABELS[stage] if (i, j) == (0, 1) else None,
                    )
                acc = mc.fronts.get(("constrained", (min(i, j), max(i, j))))
                if acc is not None and len(acc.f):
                    f, _ = acc.front()
                    a, b = (f[:, 1], f[:, 0]) if i < j else (f[:, 0], f[:, 1])
                    order = np.argsort(a)
                    ax.plot(a[order], b[order], color="#111", lw=1.0, marker="o", ms=2)
            if i == k - 1:
                ax.set_xlabel(labels[j], fontsize=8)
            if j == 0:
                ax.set_ylabel(labels[i], fontsize=8)
    if k > 1:
        handles = [axes[0, 1].scatter([], [], s=12, c=c, label=lab) for c, lab in zip(STAGE_COLOURS, STAGE_LABELS)]
        fig.legend(handles=handles, loc="upper center", ncol=3, fontsize=8, frameon=False)
    return _svg(fig)


def planforms_svg(items: list[tuple[str, Planform]]) -> str:
    """Horizontal-tail planforms (and elevators) drawn to the same scale in feet, aligned at the aerodynamic
    centre."""
    fig, ax = subplots(figsize=(6.8, 3.6), left=0.7, bottom=0.55, top=0.15)
    colours = ["0.35", "#2f6db5", "#2e9d4a", "#c0392b", "#8e44ad", "#d35400", "#16a085", "#7f8c8d"]
    for n, (label, p) in enumerate(items):
        col = colours[n % len(colours)]
        o = p.outline() / FT
        ax.plot(o[:, 1], -o[:, 0], color=col, lw=1.4 if n else 1.0, ls="--" if n == 0 else "-", label=label)
        for e in p.elevator_outlines():
            ax.fill(e[:, 1] / FT, -e[:, 0] / FT, color=col, alpha=0.25, lw=0)
    ax.plot([0], [0], marker="+", color="k", ms=10)
    ax.annotate("aerodynamic centre", (0, 0), textcoords="offset points", xytext=(6, 6), fontsize=7)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("span position y (ft)")
    ax.set_ylabel("aft of the aerodynamic centre (ft, downward)")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower left", fontsize=7, bbox_to_anchor=(1.01, 0.0))
    return _svg(fig)
