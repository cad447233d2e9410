"""The minimum unstick speeds of the takeoff loadings, all engines and at the one-engine-inoperative thrust-to-weight
ratio (§25.107(d), (e)(1)(iv)), from :func:`certkit.models.dynamics.unstick.minimum_unstick_speed`.

Each loading is taken at sea level ISA in the takeoff configuration with its takeoff trim (the movable stabiliser
at its V2-trim setting, as the simulated takeoff holds it), takeoff thrust on every engine, and again with the
critical engine windmilling (the one-engine-inoperative thrust-to-weight ratio of §25.107(e)(1)(iv)); the attitudes
searched reach the declared tail-strike attitude, the lift coefficient at most the takeoff configuration's declared
trimmed C_Lmax.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from certkit_rules.part25.support.thrust_trims import critical_engine, takeoff_trim

from certkit.atmosphere import convert_speed
from certkit.models.dynamics.unstick import Unstick, minimum_unstick_speed
from certkit.models.flight import control_limits, flight_model, ground_model


@dataclass(frozen=True)
class UnstickSpeeds:
    all_engines: Unstick
    engine_out: Unstick
    engine: str  # the windmilling engine of the engine-out rows

    def vmu_cas(self, engine_out: bool) -> np.ndarray:
        """VMU (m/s CAS, sea level) per loading."""
        u = self.engine_out if engine_out else self.all_engines
        return np.array([float(convert_speed(v, "TAS", "CAS", 0.0)) for v in u.speed])


def unstick_speeds(ctx, conditions) -> UnstickSpeeds:
    """The memoised minimum unstick speeds of ``conditions`` (module docstring); needs the landing gear with its
    tail-strike attitude."""

    def compute():
        ac = ctx.aircraft
        n = len(conditions)
        _, held = takeoff_trim(ctx, conditions)
        loadings = [ctx.loading(c.mass, c.x_cg, c.loading or "") for c in conditions]
        model = flight_model(ac, ctx.aero("takeoff").model, loadings + loadings, ground=ground_model(ac))
        engine = critical_engine(ctx)
        operative = np.ones((2 * n, len(model.engines)), dtype=bool)
        operative[n:, [e.name for e in model.engines].index(engine)] = False
        model.set_operative(operative)
        u = np.zeros((2 * n, len(model.control_names)))
        for e in model.engines:
            u[:, model.control_index(f"throttle:{e.name}")] = 1.0
        for name, values in held.items():
            u[:, model.control_index(name)] = np.tile(values, 2)
        limits = control_limits(ac, design=False)["elevator"]
        cl_max = ctx.clmax("takeoff")
        result = minimum_unstick_speed(
            model, u, ac.geometry.landing_gear.tail_strike_attitude, limits, np.inf if cl_max is None else cl_max
        )
        return UnstickSpeeds(result.take(slice(0, n)), result.take(slice(n, 2 * n)), engine)

    return ctx.memo(("unstick speeds", tuple((c.mass, c.x_cg) for c in conditions)), compute)
