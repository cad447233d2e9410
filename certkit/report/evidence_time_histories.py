"""Time-history evidence plots (takeoff, approach and landing): stacked panels sharing the time axis,
one line per condition, the critical condition drawn bold, limits as dashed lines."""

from __future__ import annotations

import numpy as np

from certkit.report.plots import figure_to_svg, subplots


def time_histories_svg(t, panels, labels, critical: int = 0, title: str = "") -> str:
    """``t`` (nt,) or (nt, n); ``panels`` a list of (ylabel, values (nt, n), limits dict label → value);
    ``labels`` one per condition."""
    fig, axes = subplots(len(panels), 1, figsize=(7.0, 1.7 * len(panels)), sharex=True, top=0.4 if title else 0.15)
    axes = np.atleast_1d(axes)
    t = np.asarray(t, dtype=float)
    for ax, (ylabel, values, limits) in zip(axes, panels):
        values = np.asarray(values, dtype=float)
        for i, lab in enumerate(labels):
            ti = t if t.ndim == 1 else t[:, i]
            ax.plot(ti, values[:, i], lw=2.0 if i == critical else 1.0, label=lab + (" (critical)" if i == critical else ""))
        for name, value in (limits or {}).items():
            ax.axhline(value, ls="--", lw=0.8, color="k")
            ax.annotate(name, (ax.get_xlim()[0], value), fontsize=7, va="bottom")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("time (s)")
    if title:
        axes[0].set_title(title)
    return figure_to_svg(fig)
