"""The payload–range diagram of a mission result (inline SVG drawn by :mod:`certkit.report.figures`)."""

from __future__ import annotations

from certkit.engine.evidence import Axis, Chart, Limit, Panel, Point, Series
from certkit.report.figures import render


def payload_range_outline(points) -> tuple[list[float], list[float]]:
    """(range m, payload kg) of the diagram's outline: zero range at maximum payload, then the maximum-payload,
    maximum-fuel and ferry points (those present), in order of range."""
    corners = sorted((p for p in points if p.name != "design payload"), key=lambda p: p.range_m)
    top = max(p.payload_kg for p in points)
    return [0.0] + [p.range_m for p in corners], [top] + [p.payload_kg for p in corners]


def payload_range_chart(points, requirement_m: float | None = None) -> Chart:
    """Payload (1,000 lb) against still-air range (nmi) with reserves: the outline, the design point (starred) and
    the required design range."""
    x, y = payload_range_outline(points)
    marks = [
        Point(p.range_m, p.payload_kg, f"design point at {p.range_m / 1852:,.0f} nmi")
        for p in points
        if p.name == "design payload"
    ]
    limits = [Limit(requirement_m, f"required {requirement_m / 1852:,.0f} nmi", axis="x")] if requirement_m else []
    outline = Series("payload–range outline", x, y, marker="o", colour=0)
    return Chart(
        Axis("range, still air, reserves on landing", "m", "nmi"),
        [Panel(Axis("payload", "kg", "1,000 lb"), [outline], limits, marks)],
    )


def payload_range_svg(points, requirement_m: float | None = None) -> str:
    return render(payload_range_chart(points, requirement_m), "mission")
