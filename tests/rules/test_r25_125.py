"""§25.125 landing (simulated −3° approach at VREF, flare, touchdown) against hand numbers in ft and kn.

Hand references: VREF 136 KCAS is 136 × 1.0022 = 136.3 kn TAS at 150 ft (ISA σ = 0.99561), so the
approach sink rate is 136.3 × 1.68781 × sin 3° = 12.04 ft/s and the flare time constant
τ = (15 m + 1 m)/(3.670 m/s) = 4.36 s (exponential flare, Stevens & Lewis §4.7); the criterion is
6 ft/s (§25.473(a)(2)(ii)); the elevator design limit −21.8°. These run on the baseline without its movable
stabiliser (the elevator trims, as without a movable stabiliser); the last test flies the baseline as declared.
"""

import pytest

from .helpers import NO_STABILIZER, own, run_rule
from .helpers import finding_by as _by


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    return run_rule("25.125", tmp_path_factory.mktemp("plain"), [NO_STABILIZER])


def test_hand_calculation_approach_sink_and_flare_constant(result):
    """Approach sink 12.04 ft/s (±0.05), τ 4.36 s (±0.02), limit 6 ft/s, touchdown well below it (< 3 ft/s)."""
    for loading in ("MLW forward", "MLW reference", "MLW aft"):
        f = _by(result, loading, "touchdown")
        assert f.details["approach_sink_fps"] == pytest.approx(136 * 1.0022 * 1.68781 * 0.0523360, abs=0.05)
        assert f.details["flare_tau_s"] == pytest.approx(16.0 / (12.04 * 0.3048), abs=0.02)
        assert f.limit == 6.0 and f.unit == "ft/s" and 0.0 < f.value < 3.0
        e = _by(result, loading, "elevator")
        assert e.limit == pytest.approx(-21.8) and e.unit == "deg"


@pytest.fixture(scope="module")
def steep(tmp_path_factory):
    block = (
        'criteria:\n  "25.125":\n    justification: a steeper approach\n    values: {glide_slope: -4.5}\n\nsources:\n'
    )
    return run_rule("25.125", tmp_path_factory.mktemp("steep"), [NO_STABILIZER, ("\nsources:\n", "\n" + block)])


def _sinks(result, steep):
    sinks = []
    for loading in ("MLW forward", "MLW reference", "MLW aft"):
        base, f = _by(result, loading, "touchdown"), _by(steep, loading, "touchdown")
        assert f.details["approach_sink_fps"] == pytest.approx(base.details["approach_sink_fps"] * 1.4990, rel=2e-3)
        sinks.append((base.value, f.value))
    return sinks


def test_a_steeper_approach_lands_harder(result, steep):
    """A −4.5° approach (criterion glide_slope) sinks 1.5 × faster on the path (sin 4.5°/sin 3° = 1.50, 18.1 ft/s at
    VREF): the flare, started at the same height, ends with a higher touchdown sink rate at the forward CG, where the
    elevator of this airplane without its movable stabiliser is on its stop through the flare (2.67 against
    1.57 ft/s)."""
    sinks = _sinks(result, steep)
    assert sinks[0][1] > sinks[0][0]


@pytest.mark.xfail(
    strict=True,
    reason="since the tail's ground effect (tail_ground_effect.py) the TECS flare's tracking, "
    "not the approach angle, sets the touchdown sink at the reference and aft CG: the −4.5° flare "
    "over-rotates and floats (aft CG 0.23 against 1.46 ft/s; sum of the three 3.96 against 4.55)",
)
def test_a_steeper_approach_lands_harder_at_the_aft_cg_and_on_average(result, steep):
    """The same at the aft CG and on average over the three CGs (held before the tail's ground effect: at the
    reference CG the 3° run's flare already lagged its law more than the steep one's, 1.42 against 1.18 ft/s, both
    near the exponential flare's own terminal sink 1 m/τ, 0.75 and 1.13 ft/s — a difference of flare tracking, not
    of the approach)."""
    sinks = _sinks(result, steep)
    assert sinks[2][1] > sinks[2][0]
    assert sum(s for _, s in sinks) > sum(b for b, _ in sinks)


def test_sign_forward_cg_needs_more_elevator_and_a_larger_limit_helps(result, tmp_path):
    """The forward CG needs the most nose-up elevator (smallest margin; at MLW it trims on the path at −19.5° —
    −22.6° before the tail-on flap moment was modelled, the flap's downwash at the tail pitching nose-up — and the
    flare takes it past the −21.8° design limit: fails); a −30° design limit raises every elevator margin by
    exactly 8.2°."""
    m = [_by(result, c, "elevator").margin for c in ("MLW forward", "MLW reference", "MLW aft")]
    assert m[0] < m[1] < m[2]
    fwd = _by(result, "MLW forward", "elevator")
    assert fwd.status == "fails" and fwd.value < -21.8 < fwd.details["trim_elevator_deg"]
    wider = run_rule(
        "25.125",
        tmp_path,
        [
            NO_STABILIZER,
            ("design_limits: {min: -21.8 deg, max: 16.8 deg}", "design_limits: {min: -30 deg, max: 16.8 deg}"),
        ],
    )
    assert _by(wider, "MLW forward", "elevator").margin == pytest.approx(fwd.margin + 8.2, abs=1e-6)


def test_not_evaluated_without_vref(tmp_path):
    r = run_rule("25.125", tmp_path, [("  VREF: 136 kn CAS ", "  # VREF removed ")])
    assert r.status == "not_evaluated"
    assert all(f.status == "not_evaluated" and "VREF" in f.reason for f in own(r))


VSR0_KN = 110.707  # MLW 460,000 lb, landing CLmax 2.25, S 4927.3 ft², ρ₀: VS = √(2W/(ρ₀ S CLmax)) (Anderson eq. 6.47)


def test_vref_over_vsr0_by_hand_a_finding_on_the_baseline(result, tmp_path):
    """§25.125(b)(2)(i)(A): VREF ≥ 1.23 VSR0. The baseline declares VREF 136 kn CAS while its landing CLmax gives
    1.23 × 110.707 = 136.17 kn: ratio 1.2285, fails by 0.17 kn (a finding about the declared data, the CLmax having
    been rounded when it was calibrated on VREF). VREF 137 kn complies (137/110.707 = 1.2375)."""
    for loading in ("MLW forward", "MLW reference", "MLW aft"):
        f = _by(result, loading, "(b)(2)(i)(A)")
        assert f.value == pytest.approx(136 / VSR0_KN, abs=1e-4) and f.limit == 1.23
        assert f.status == "fails"
    ok = run_rule("25.125", tmp_path, [("  VREF: 136 kn CAS ", "  VREF: 137 kn CAS ")])
    f = _by(ok, "MLW reference", "(b)(2)(i)(A)")
    assert f.value == pytest.approx(137 / VSR0_KN, abs=1e-4) and f.status == "complies"


def test_movable_stabiliser_relieves_the_flare_elevator(result):
    """The baseline as declared: trimmed on the path at VREF the stabiliser is at its −10.25° nose-up trim limit at
    the forward CG (the elevator holding the rest, a few degrees) and within it elsewhere (elevator at its 0° trim
    setting); the flare moves only the elevator, which now stays within its design limit at every CG where the
    elevator-trimmed airplane needed −22.6° at the forward CG just to trim."""
    declared = run_rule("25.125")
    for loading in ("MLW forward", "MLW reference", "MLW aft"):
        e = _by(declared, loading, "elevator")
        assert e.status == "complies" and e.margin > 0.0
    for loading in ("MLW forward", "MLW reference"):  # where the elevator-trimmed airplane trims trailing edge up
        assert _by(declared, loading, "elevator").margin > _by(result, loading, "elevator").margin + 5.0
    fwd = _by(declared, "MLW forward", "touchdown").details
    assert -10.0 < fwd["trim_elevator_deg"] < 0.0
    assert _by(declared, "MLW reference", "touchdown").details["trim_elevator_deg"] == 0.0
