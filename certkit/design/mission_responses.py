"""The mission of a design (:func:`certkit.models.performance.mission.fly_missions`) with its sized OEW, as record
responses: objective.cruise_CD, objective.block_fuel_kg, objective.block_time_s, mission.design_range_m and
constraint.range_margin_m (design range − required range, ≥ 0 feasible)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from certkit.models.performance.mission import fly_missions

if TYPE_CHECKING:
    from certkit.aircraft import Aircraft
    from certkit.engine.context import Context

from certkit.errors import InfeasibleDesign, UserError


def mission_responses(aircraft: Aircraft, ctx: Context, oew_kg: float) -> tuple[dict[str, Any], dict[str, Any]]:
    """(responses, details) of the design's missions. A mission the design cannot fly as declared (the design payload
    above MZFW − the sized OEW, the nominal distance beyond its fuel, no cruise level reachable) is an infeasible
    design with the mission's reason."""
    try:
        result = fly_missions(aircraft, ctx.aero("clean"), oew_kg)
    except InfeasibleDesign:
        raise
    except UserError as exc:
        if aircraft.mission is None:
            raise
        raise InfeasibleDesign(f"mission with the sized OEW {oew_kg:.0f} kg: {exc}") from None
    details = result.as_dict()
    details.pop("timings", None)  # wall times belong to the record's timings (details must be reproducible)
    return result.responses(), details
