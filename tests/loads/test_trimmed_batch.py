"""Set-up of the loads conditions (certkit_rules.part25.support.loads_conditions): a condition short of thrust in level
flight flies
on the full-thrust path (the steady flight nearest to level), and a condition below the 1 g stall speed is not
applicable with the lift coefficient computed by hand."""

import numpy as np
import pytest
from certkit_rules.part25.support.loads_conditions import refusal_findings, trimmed_batch

from certkit.atmosphere import density
from certkit.engine.conditions import CgCorners, ConditionSpace
from certkit.engine.context import Context
from certkit.units import FT, G0, KN


@pytest.fixture(scope="module")
def heavy(baseline):
    """The heaviest forward corner (657,000 lb), clean."""
    ctx = Context(baseline)
    corners = ConditionSpace(loading=CgCorners(), configurations=("clean",), altitudes=None).expand(baseline.model)
    return ctx, max(corners, key=lambda c: (c.mass, -c.x_cg))


def test_short_of_thrust_flies_the_full_thrust_path(heavy):
    """222 kn EAS at 43,000 ft (VB there, M 0.84) at 657,000 lb needs more than full thrust level; the batch flies the
    full-thrust path instead: a shallow descent, throttles at 1; the trim with the throttle free on a path 0.01°
    steeper needs just under full throttle (within 1 %) — the two trim modes agree (on the path itself the free trim
    sits on the throttle stop and reports it)."""
    ctx, corner = heavy
    cond = corner.with_(altitude=43_000 * FT, speed=222 * KN, speed_kind="EAS")
    assert not ctx.trim([cond], gamma=0.0).results[0].ok
    batch = trimmed_batch(ctx, [cond])
    assert batch.n == 1 and not batch.failed
    gamma = float(batch.gamma[0])
    assert np.radians(-3.0) < gamma < 0.0
    assert batch.conditions[0].get("flight_path_deg") == pytest.approx(np.degrees(gamma), abs=0.005)
    throttles = [j for j, name in enumerate(batch.model.control_names) if name.startswith("throttle")]
    np.testing.assert_allclose(batch.u[0, throttles], 1.0)
    free = ctx.trim([cond], gamma=gamma - np.radians(0.01)).results[0]
    assert free.ok
    assert all(0.99 < v <= 1.0 for k, v in free.controls.items() if k.startswith("throttle"))


def test_below_the_stall_speed_is_not_applicable(heavy):
    """150 kn EAS at sea level at 657,000 lb: W/(q̄S) = 2.9225 MN / (½ × 1.225 kg/m³ × (77.167 m/s)² × 457.76 m²)
    = 2.9225 MN / (3,647.3 Pa × 457.76 m²) = 1.7504 by hand, above the clean CLmax at M 0.2268 (77.167 / 340.294 m/s):
    1.40 − 0.03 × 0.0268 / 0.2 = 1.396 on the declared C_Lmax(M) (1.400 at M 0.2, 1.370 at 0.4): no steady flight at
    any thrust — not applicable, with the lift coefficient in the reason."""
    ctx, corner = heavy
    cond = corner.with_(altitude=0.0, speed=150 * KN, speed_kind="EAS")
    batch = trimmed_batch(ctx, [cond])
    assert batch.n == 0
    (refusal,) = batch.refusals([cond])
    cl = corner.mass * G0 / (0.5 * float(density(0.0)) * (150 * KN) ** 2 * ctx.aircraft.reference.area)
    assert cl == pytest.approx(1.7504, rel=1e-3)
    clmax = 1.4 - 0.03 * (150 * KN / 340.294 - 0.2) / 0.2
    assert clmax == pytest.approx(1.396, abs=5e-4)
    assert refusal.outside_envelope and f"W/(q̄S) = {cl:.3f} exceeds CLmax = {clmax:.3f} at M 0.227" in refusal.reason
    (finding,) = refusal_findings([refusal], lambda c: ["check"])
    assert finding.status == "complies" and finding.reason.startswith("not applicable: no steady flight")
