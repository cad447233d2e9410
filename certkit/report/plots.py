"""matplotlib figures rendered as inline SVG strings (Agg backend, no files), for the study report (the check's evidence
figures are written directly: :mod:`certkit.report.svg`).

Layout: figures are made by :func:`subplots`, which places the axes with fixed margins in inches, and are
serialised by :func:`figure_to_svg` in one draw. (``bbox_inches="tight"`` drew every figure twice, the first
time only to measure it: about 60 % of a figure's cost.) Texts whose length depends on the data — legends,
titles, annotations — are measured before the draw (text metrics only), and the SVG's view box is widened
over any that reach beyond the figure, so nothing is cut off; tick labels and axis labels lie within the
margins the figure asked for (:func:`text_width` sizes them for string tick labels, which are measured too).
"""

from __future__ import annotations

import io
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.font_manager import FontProperties  # noqa: E402
from matplotlib.legend import Legend  # noqa: E402
from matplotlib.text import Text  # noqa: E402
from matplotlib.textpath import TextToPath  # noqa: E402
from matplotlib.ticker import FixedLocator  # noqa: E402

# legend.loc "best" searches every plotted vertex for the emptiest corner: seconds on long time histories
# svg.hashsalt: matplotlib's SVG ids are hashes of their content salted with this (else a random salt per figure)
plt.rcParams.update(
    {"svg.fonttype": "none", "font.size": 9, "figure.dpi": 100, "legend.loc": "upper right", "svg.hashsalt": "certkit"}
)

_TEXT = TextToPath()
#: white space kept around texts that reach beyond the figure (inches)
PAD = 0.1


def subplots(
    nrows: int = 1,
    ncols: int = 1,
    *,
    figsize: tuple[float, float],
    left: float = 0.8,
    bottom: float = 0.5,
    right: float = 0.2,
    top: float = 0.15,
    hspace: float | None = None,
    wspace: float | None = None,
    **kw,
):
    """``plt.subplots`` with the axes placed by fixed margins (inches from each figure edge); the defaults
    leave room for numeric tick labels, an axis label on the left and below, and no title (give ``top`` about
    0.4 for one). ``hspace``/``wspace`` as in ``subplots_adjust`` (fractions of an axes)."""
    fig, axes = plt.subplots(nrows, ncols, figsize=figsize, **kw)
    w, h = figsize
    fig.subplots_adjust(
        left=left / w, right=1.0 - right / w, bottom=bottom / h, top=1.0 - top / h, hspace=hspace, wspace=wspace
    )
    return fig, axes


def text_width(labels, fontsize: float) -> float:
    """Width (inches) of the widest of ``labels`` at ``fontsize`` points, as the SVG renderer measures it."""
    prop = FontProperties(size=fontsize)
    return max((_TEXT.get_text_width_height_descent(str(s), prop, ismath=False)[0] for s in labels), default=0.0) / 72.0


def _reach(fig) -> tuple[float, float, float, float]:
    """(x0, y0, x1, y1) inches from the figure's lower left corner: the figure united with every legend, title,
    annotation and explicitly set tick label (the texts whose length is the data's) of the figure and its axes."""
    renderer = (fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)).get_renderer()
    w, h = fig.get_size_inches()
    x0, y0, x1, y1 = 0.0, 0.0, w, h
    artists = [a for parent in (fig, *fig.axes) for a in parent.get_children() if isinstance(a, (Text, Legend))]
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if isinstance(axis.get_major_locator(), FixedLocator):  # ticks set by the figure: string labels
                artists += axis.get_ticklabels()
    for artist in artists:
        if not artist.get_visible() or (isinstance(artist, Text) and not artist.get_text()):
            continue
        bb = artist.get_window_extent(renderer).transformed(fig.dpi_scale_trans.inverted())
        x0, y0, x1, y1 = min(x0, bb.x0 - PAD), min(y0, bb.y0 - PAD), max(x1, bb.x1 + PAD), max(y1, bb.y1 + PAD)
    return x0, y0, x1, y1


_ID = re.compile(r'(\bid="|url\(#|href="#)([^"\)]+)')


def figure_to_svg(fig, prefix: str = "") -> str:
    """Serialize a figure to an SVG fragment suitable for inline HTML (no XML prolog, no fixed size, no date); the
    view box covers the figure and any legend, title or annotation reaching beyond it. With ``prefix``, every id
    (and every reference to one) starts with it, so figures on one page never share an id."""
    w, h = fig.get_size_inches()
    x0, y0, x1, y1 = _reach(fig)
    buf = io.StringIO()
    fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    svg = buf.getvalue()
    svg = svg[svg.index("<svg") :]
    svg = re.sub(r'(<svg[^>]*?) width="[^"]*" height="[^"]*"', r"\1", svg, count=1)
    if (x0, y0, x1, y1) != (0.0, 0.0, w, h):  # SVG user units are points, y down from the top
        box = f"{x0 * 72:.2f} {(h - y1) * 72:.2f} {(x1 - x0) * 72:.2f} {(y1 - y0) * 72:.2f}"
        svg = re.sub(r'(<svg[^>]*?) viewBox="[^"]*"', rf'\1 viewBox="{box}"', svg, count=1)
    if prefix:
        svg = _ID.sub(lambda m: f"{m[1]}{prefix}-{m[2]}", svg)
    return svg
