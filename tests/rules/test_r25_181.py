"""§25.181 dynamic stability and the MIL-F-8785C levels.

Hand calculation: the short-period approximation (Nelson, Flight Stability and Automatic Control, 2nd ed.,
§4.4, eq. 4.85–4.86): ω_sp² = Z_α M_q / u0 − M_α, 2 ζ ω_sp = −(M_q + M_α̇ + Z_α / u0), with
Z_α = −(CL_α + CD0) q S / m, M_α = Cm_α,cg q S c / Iyy, M_q = Cm_q (c / 2u0) q S c / Iyy,
M_α̇ = Cm_α̇ (c / 2u0) q S c / Iyy, and Cm_α moved to the CG by CL_α (x_cg − x_ref)/c.
Tolerance: 10 % on ω_sp, 15 % on ζ_sp (the approximation drops the speed and pitch-attitude coupling,
CL_q and the thrust terms).
"""

import math

import pytest

from certkit.atmosphere import density
from certkit.engine.conditions import speed_as
from certkit.models.dynamics.modes import Mode
from certkit_rules.part25.support import handling_levels as hq

from .helpers import own, run_rule

RULE = "25.181"


@pytest.fixture(scope="module")
def result():
    return run_rule(RULE)


def _sp(result, loading, configuration, point, altitude=0.0):
    return next(f for f in own(result) if f.condition.loading == loading and f.condition.configuration == configuration
                and f.condition.get("speed_point") == point and f.condition.altitude == altitude
                and f.check.startswith("(a) short"))


def test_short_period_hand_calculation(result, ctx):
    """fwd_mrw (657,000 lb, CG 94.23 ft), takeoff, sea level, mid speed."""
    f = _sp(result, "fwd_mrw", "takeoff", "mid")
    c = f.condition
    m = ctx.aero("takeoff").model
    ref = m.reference
    u0 = speed_as(c, "TAS")
    mach = speed_as(c, "MACH")
    d = lambda name: float(m.derivative(name, mach))  # noqa: E731
    qbar = 0.5 * float(density(0.0)) * u0**2
    S, cbar = ref.area, ref.chord
    iyy = ctx.loading(c.mass, c.x_cg).properties.inertia[1][1]
    cm_alpha = d("Cm_alpha") + d("CL_alpha") * (c.x_cg - ref.x_ref) / cbar
    z_a = -(d("CL_alpha") + d("CD0")) * qbar * S / c.mass
    m_a = cm_alpha * qbar * S * cbar / iyy
    m_q = d("Cm_q") * cbar / (2 * u0) * qbar * S * cbar / iyy
    m_ad = d("Cm_alphadot") * cbar / (2 * u0) * qbar * S * cbar / iyy
    wn = math.sqrt(z_a * m_q / u0 - m_a)
    zeta = -(m_q + m_ad + z_a / u0) / (2 * wn)
    assert f.details["natural_frequency_rad_s"] == pytest.approx(wn, rel=0.10)
    assert f.value == pytest.approx(zeta, rel=0.15)
    assert f.limit == 0.35  # takeoff: category C


def test_short_period_minimum_follows_the_flight_phase_category(result):
    """MIL-F-8785C Table IV, Level 1 (the values the issue states): category B (en route, the clean configuration)
    ζ_sp ≥ 0.30, category C (terminal: takeoff, approach, landing) ζ_sp ≥ 0.35; every finding states its reading."""
    sp = [f for f in own(result) if f.check.startswith("(a) short") and f.limit is not None]
    assert {f.condition.configuration for f in sp} >= {"clean", "takeoff", "landing"}
    for f in sp:
        clean = f.condition.configuration == "clean"
        assert f.limit == (0.30 if clean else 0.35)
        assert f.details["category"].startswith("B (en route" if clean else "C (terminal")


def test_a_poorly_damped_airplane_fails(result, tmp_path):
    """A deficient airplane: pitch damping Cm_q −2 and no downwash lag in every configuration (table: −22 to −29)
    leaves the short period below its category minimum at some condition: §25.181(a) fails there."""
    block = ("aerodynamics:\n  overrides_source: test\n  overrides:\n"
             + "".join(f"    {c}: {{Cm_q: -2.0, Cm_alphadot: 0.0}}\n" for c in ("clean", "takeoff", "approach", "landing"))
             + "sources:")
    r = run_rule(RULE, tmp_path, edits=[("\nsources:", "\n" + block)])
    sp = [f for f in own(r) if f.check.startswith("(a) short") and f.value is not None]
    assert any(f.status == "fails" and f.value < f.limit for f in sp)
    assert r.status == "fails"


def test_sign_more_pitch_damping_raises_short_period_margin(result, tmp_path):
    """A pitch-damping derivative Cm_q of −40 (table: −22 to −29) in every configuration raises ζ_sp."""
    base = _sp(result, "fwd_mrw", "takeoff", "mid").margin
    block = ("aerodynamics:\n  overrides_source: test\n  overrides:\n"
             + "".join(f"    {c}: {{Cm_q: -40.0}}\n" for c in ("clean", "takeoff", "approach", "landing")) + "sources:")
    r = run_rule(RULE, tmp_path, edits=[("\nsources:", "\n" + block)])
    assert _sp(r, "fwd_mrw", "takeoff", "mid").margin > base + 0.02


def test_not_evaluated_without_vmo(tmp_path):
    r = run_rule(RULE, tmp_path, edits=[("  VMO: 272 kn EAS              # = VC, see above\n", "")])
    assert r.status == "not_evaluated" and own(r)[0].reason == "needs speeds.VMO"


def test_trim_impossible_is_not_evaluated_with_the_reason(result):
    """MRW at 37,000 ft cannot hold level flight at full thrust: not evaluated, never a pass."""
    bad = [f for f in own(result) if f.status == "not_evaluated"]
    assert bad and all("did not converge" in f.reason for f in bad)


def test_baseline_dutch_roll_is_weakest_at_aft_corners(result):
    """The Dutch roll of the estimated aerodynamics is least damped at an aft corner (smaller Cn_β about the CG);
    whatever its sign, it is reported with its MIL-F-8785C level, never hidden."""
    dr = [f for f in own(result) if f.check.startswith("(b)") and f.margin is not None]
    assert len(dr) == len([f for f in own(result) if f.check.startswith("(a)") and f.margin is not None])
    worst = min(dr, key=lambda f: f.margin)
    assert worst.condition.loading.startswith("aft")
    row = worst.details["modes"]["dutch_roll"]
    lam = complex(*row["eigenvalue"])  # ζ = −Re λ / |λ| of the reported eigenvalue (an independent reading)
    assert worst.value == pytest.approx(-lam.real / abs(lam), abs=2e-5)
    key = next(k for k in row if k.startswith("level_") and not k.endswith("_by"))
    assert row[key] in (1, 2, 3, 4) and (row[key] == 1 or "Table VI" in row[key + "_limited_by"])


def test_level_table_boundaries():
    """Levels from the table: Dutch roll ζ 0.1, ωn 2 rad/s (ζωn 0.2) is Level 1 in category C (0.08, 0.15, 0.4)
    but Level 2 in category A (ζ ≥ 0.19); roll τ = 2 s is Level 2 (Table VII 1.4 / 3.0)."""
    dr = Mode("dutch_roll", complex(-0.2, 2 * math.sqrt(1 - 0.01)), 2.0, 0.1, None, None, None, None)
    assert hq.level_of("dutch_roll", Mode("dutch_roll", complex(-0.1, 1.0), 1.0, 0.1, None, None, None, None), "C")[0] == 2
    assert hq.level_of("dutch_roll", dr, "C")[0] == 1
    assert hq.level_of("dutch_roll", dr, "A")[0] == 2
    roll = Mode("roll", complex(-0.5, 0.0), 0.5, 1.0, None, math.log(2) / 0.5, None, None)
    assert hq.level_of("roll", roll, "B")[0] == 2
    assert all(not lim.verified and lim.paragraph for lim in hq.LIMITS)
