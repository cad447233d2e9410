"""Evidence figures with fixed margins (certkit/report/plots.py): drawn once, without bbox_inches="tight", yet
complete — the SVG's view box reaches over a legend, title or string tick label longer than the figure, and is the
figure itself otherwise. Reference: matplotlib's own tight bounding box of the same figure (the content), which
must lie inside the view box."""

import re

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from certkit.report.plots import figure_to_svg, subplots, text_width


def _view_box(svg: str) -> tuple[float, float, float, float]:
    """(x0, y0, x1, y1) of the view box in inches, y up from the figure's bottom edge (as matplotlib's bboxes)."""
    x, y_top, w, h = (float(v) / 72.0 for v in re.search(r'viewBox="([^"]*)"', svg).group(1).split())
    return x, y_top, x + w, y_top + h


def _content_inside(fig, svg: str) -> None:
    height = fig.get_size_inches()[1]
    x0, top, x1, bottom = _view_box(svg)
    bb = fig.get_tightbbox(FigureCanvasAgg(fig).get_renderer())  # inches (the figure is closed: a new canvas)
    assert bb.x0 >= x0 - 0.01 and bb.x1 <= x1 + 0.01
    assert height - bb.y1 >= top - 0.01 and height - bb.y0 <= bottom + 0.01


def test_plain_figure_keeps_its_own_box():
    fig, ax = subplots(figsize=(6.0, 3.0))
    ax.plot(np.arange(10.0), np.arange(10.0) ** 2, label="short")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("n_z")
    ax.legend()
    svg = figure_to_svg(fig)
    assert svg.startswith("<svg") and 'width="' not in svg.split(">", 1)[0]
    assert _view_box(svg) == pytest.approx((0.0, 0.0, 6.0, 3.0))
    _content_inside(fig, svg)


@pytest.mark.parametrize("where", ["legend", "title", "ticks"])
def test_long_texts_widen_the_view_box(where):
    long = "fwd_mrw · 657,000 lb · CG 94.23 ft · clean · 10,750 ft · 340.0 kn EAS · entry_speed VD · direction nose up"
    fig, ax = subplots(figsize=(4.0, 3.0), top=0.4)
    ax.plot([0.0, 1.0], [0.0, 1.0], label=long)
    if where == "legend":
        ax.legend(fontsize=7, loc="upper right")
    elif where == "title":
        ax.set_title(long, fontsize=8)
    else:
        ax.set_xticks([0.0, 1.0], [long[:40], "x"], rotation=20, ha="right")
    svg = figure_to_svg(fig)
    x0, _, x1, _ = _view_box(svg)
    assert x0 < 0.0 or x1 > 4.0  # wider than the 4 in figure
    _content_inside(fig, svg)


def test_text_width_is_the_widest_label():
    assert (
        text_width(["a", "a much longer label"], 9) > text_width(["a much longer label"], 7) > text_width(["a"], 9) > 0
    )
    assert text_width([], 9) == 0.0
