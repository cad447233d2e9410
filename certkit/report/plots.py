"""Evidence plots rendered as inline SVG strings (matplotlib, Agg backend, no files)."""

from __future__ import annotations

import io
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from certkit.units import KN  # noqa: E402

# legend.loc "best" searches every plotted vertex for the emptiest corner: seconds on long time histories
plt.rcParams.update({"svg.fonttype": "none", "font.size": 9, "figure.dpi": 100, "legend.loc": "upper right"})


def figure_to_svg(fig) -> str:
    """Serialize a figure to an SVG fragment suitable for inline HTML (no XML prolog, no fixed size)."""
    buf = io.StringIO()
    fig.savefig(buf, format="svg", bbox_inches="tight", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    svg = buf.getvalue()
    svg = svg[svg.index("<svg"):]
    svg = re.sub(r'(<svg[^>]*?) width="[^"]*" height="[^"]*"', r"\1", svg, count=1)
    return svg


def vn_diagram_svg(envelopes: list, speeds: dict[str, float]) -> str:
    """V–n diagrams (speeds in kn EAS) of several weights with the declared speeds marked."""
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    for label, env in envelopes:
        v, n = env.outline()
        line, = ax.plot(v / KN, n, lw=1.6, label=label)
        for name, (vc, nc) in env.corners().items():
            ax.annotate(name, (vc / KN, nc), textcoords="offset points", xytext=(4, 3), color=line.get_color(), fontsize=8)
    for name, value in speeds.items():
        ax.axvline(value / KN, color="0.5", ls="--", lw=0.8)
        ax.annotate(name, (value / KN, ax.get_ylim()[0]), textcoords="offset points", xytext=(2, 4), color="0.35", fontsize=8)
    ax.axhline(0, color="0.2", lw=0.6)
    ax.set_xlabel("equivalent airspeed (kn EAS)")
    ax.set_ylabel("load factor n")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower left", fontsize=8)
    return figure_to_svg(fig)


def margin_bars_svg(labels: list[str], margins: list[float], unit: str, title: str = "") -> str:
    """Horizontal bars of normalised margins per condition; failures in red."""
    height = max(1.6, 0.22 * len(labels) + 0.8)
    fig, ax = plt.subplots(figsize=(6.4, height))
    colors = ["#c0392b" if m < 0 else "#2e7d32" for m in margins]
    ax.barh(range(len(labels)), margins, color=colors)
    ax.set_yticks(range(len(labels)), labels, fontsize=7)
    ax.axvline(0, color="0.2", lw=0.8)
    ax.invert_yaxis()
    ax.set_xlabel(f"normalised margin ({unit})" if unit else "normalised margin")
    if title:
        ax.set_title(title, fontsize=9)
    ax.grid(True, axis="x", alpha=0.3)
    return figure_to_svg(fig)
