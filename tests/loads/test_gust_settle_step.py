"""The free response after a gust is integrated at a coarser step than the gust itself
(certkit.models.loads.gust_response.simulate_gust, ``settle_step``). Convergence check against a step 8× finer:
the wing and horizontal-tail load peaks of the baseline's heaviest forward corner in a 350 ft and a 100 ft up-gust
at VC, sea level and 32,250 ft, agree within 0.1 % of each station's largest load (RK4 on the short-period motion,
ω ≈ 1–3 rad/s: the peak sampling error (ω Δt)²/8 is below 0.2 % at 0.04 s)."""

import numpy as np
import pytest
from certkit_rules.part25.support.loads_conditions import trimmed_batch

from certkit.engine.conditions import CgCorners, ConditionSpace
from certkit.engine.context import Context
from certkit.models.loads.gust_response import gust_batch, simulate_gust
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope
from certkit.units import FT


@pytest.fixture(scope="module")
def runs(baseline):
    ctx = Context(baseline)
    corners = ConditionSpace(loading=CgCorners(), configurations=("clean",), altitudes=None).expand(baseline.model)
    heavy = max(corners, key=lambda c: (c.mass, -c.x_cg))
    vc = baseline.model.speeds.VC
    conds = [
        heavy.with_(altitude=h * FT, speed=float(ctx.design_speed_eas("VC", h * FT)[0]), speed_kind="EAS")
        for h in (0.0, 32_250.0)
    ]
    batch = trimmed_batch(ctx, conds)
    assert not batch.failed and vc
    loads = airplane_loads(ctx)
    gb = gust_batch(loads, batch.model, batch.x, batch.u)
    out = {}
    for H_ft in (350.0, 100.0):
        alpha = 15.0 / np.array([c.speed for c in batch.conditions])  # 15 m/s EAS peak gust, up
        for step in (0.005, 0.04):
            run = simulate_gust(loads, gb, H_ft * FT, alpha, 20.0, 1.5, settle_step=step)
            out[H_ft, step] = LoadEnvelope.from_histories(loads, run.loads, run.sim.t, ["sl", "alt"])
    return out


@pytest.mark.parametrize("H_ft", [350.0, 100.0])
@pytest.mark.parametrize("surface", ["wing", "horizontal_tail"])
def test_settle_step_converged(runs, H_ft, surface):
    fine, coarse = runs[H_ft, 0.005].peaks[surface], runs[H_ft, 0.04].peaks[surface]
    scale = np.max(np.abs(fine), axis=(0, 1), keepdims=True)  # each quantity's largest at each station
    assert np.max(np.abs(coarse - fine) / scale) < 1e-3
