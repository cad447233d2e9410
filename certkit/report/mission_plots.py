"""The payload–range diagram of a mission result (inline SVG, the style of :mod:`certkit.report.plots`)."""

from __future__ import annotations

from certkit.report.plots import figure_to_svg, subplots
from certkit.units import LB

NMI = 1852.0


def payload_range_outline(points) -> tuple[list[float], list[float]]:
    """(range m, payload kg) of the diagram's outline: zero range at maximum payload, then the maximum-payload,
    maximum-fuel and ferry points (those present), in order of range."""
    corners = sorted((p for p in points if p.name != "design payload"), key=lambda p: p.range_m)
    top = max(p.payload_kg for p in points)
    return [0.0] + [p.range_m for p in corners], [top] + [p.payload_kg for p in corners]


def payload_range_svg(points, requirement_m: float | None = None) -> str:
    """Payload (1,000 lb) against still-air range (nmi) with reserves: the outline, the design point and the
    required design range."""
    fig, ax = subplots(figsize=(6.4, 3.6), left=0.75)
    x, y = payload_range_outline(points)
    ax.plot([v / NMI for v in x], [v / LB / 1000 for v in y], lw=1.8, color="#1f4e79", marker="o", ms=4)
    for p in points:
        if p.name == "design payload":
            ax.plot(p.range_m / NMI, p.payload_kg / LB / 1000, marker="D", color="#c0392b", ms=6, ls="none")
            ax.annotate(f"design: {p.range_m / NMI:,.0f} nmi", (p.range_m / NMI, p.payload_kg / LB / 1000),
                        textcoords="offset points", xytext=(6, 6), fontsize=8, color="#c0392b")
    if requirement_m:
        ax.axvline(requirement_m / NMI, color="0.45", ls="--", lw=0.9)
        ax.annotate(f"required {requirement_m / NMI:,.0f} nmi", (requirement_m / NMI, 0), textcoords="offset points",
                    xytext=(-4, 4), rotation=90, ha="right", va="bottom", fontsize=8, color="0.35")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_xlabel("range (nmi, still air, reserves on landing)")
    ax.set_ylabel("payload (1,000 lb)")
    ax.grid(True, alpha=0.3)
    return figure_to_svg(fig)
