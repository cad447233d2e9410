"""A weight–CG envelope that follows the design (``sizing.cg_envelope: loading`` in the aircraft file).

By default a design is evaluated at the declared envelope's corners whatever its tail weighs. With the option, each
corner keeps its name and weight and moves to the CG the design's own loading reaches at that weight
(:func:`certkit.models.mass.loading.reachable_cg_range`: the operating empty airplane with the sized tail group and
its CG, payload zones filled forward- or aft-first, fuel in the tanks' order): a forward corner to the most forward
CG reachable, an aft corner to the most aft one, each bounded by the declared envelope (never forward of the
declared forward limit or aft of the declared aft limit at that weight). A corner whose weight no loading reaches
(below the empty weight, beyond the tanks and zones) stays where it is declared. A corner is forward when it lies
nearer the declared forward limit at its weight than the aft one.
"""

from __future__ import annotations

from typing import Any

from certkit.aircraft import Aircraft
from certkit.engine.conditions import cg_limits_at
from certkit.models.mass.loading import reachable_cg_range

FOLLOW_LOADING = "loading"


def follows_loading(aircraft: Aircraft) -> bool:
    """Does the aircraft file ask for corners that follow the design's loading?"""
    sizing = getattr(aircraft, "sizing", None)
    return sizing is not None and sizing.cg_envelope == FOLLOW_LOADING


def loading_corners(design: Aircraft, declared: Aircraft) -> list[dict[str, Any]]:
    """The corners (name, mass kg, x m, declared x m, reachable range m) of ``design`` (the airplane with its sized
    tail group) within the declared envelope of ``declared`` (module doc)."""
    out: list[dict[str, Any]] = []
    if declared.cg_envelope is None:
        return out
    for i, v in enumerate(declared.cg_envelope.vertices):
        fwd, aft = cg_limits_at(declared, v.mass)
        reach = reachable_cg_range(design, v.mass)
        x = v.x
        if reach is not None:
            x = min(max(v.x, reach[0]), aft) if abs(v.x - fwd) <= abs(v.x - aft) else max(min(v.x, reach[1]), fwd)
        out.append(
            {
                "name": v.name or f"corner {i + 1}",
                "mass": float(v.mass),
                "x": float(x),
                "declared_x": float(v.x),
                "reachable_x": None if reach is None else [reach[0], reach[1]],
            }
        )
    return out


def with_loading_corners(data: dict[str, Any], corners: list[dict[str, Any]]) -> dict[str, Any]:
    """A copy of the aircraft data whose envelope vertices are ``corners`` (SI numbers; the rest shared)."""
    envelope = dict(data["cg_envelope"])
    envelope["vertices"] = [{"name": c["name"], "mass": c["mass"], "x": c["x"]} for c in corners]
    return {**data, "cg_envelope": envelope}
