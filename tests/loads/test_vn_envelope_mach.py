"""The manoeuvring envelope with C_N,max varying with Mach (``configurations.clean.CLmax_by_mach``): the positive
stall line n = ½ ρ₀ V² S C_N,max(M) / W at the Mach number of each speed at the altitude (§25.333(b), §25.337(a)
"except where limited by maximum (static) lift coefficients"), against hand numbers from the ISA closed forms
(ICAO Doc 7488 troposphere: T = 288.15 − 0.0065 h, p = 101,325 (T/288.15)^5.25588; TAS = EAS/√σ, a = √(1.4 R T))
written here, not certkit's atmosphere."""

import math

import numpy as np
import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.models.loads.vn_envelope import envelope

from ..rules.helpers import edited_baseline, run_rule

CLEAN = "  clean:\n    CLmax: 1.4                 # [given]\n"
H = 9829.8  # m: 32,250 ft, the third of the envelope altitudes of the baseline (EnvelopeAltitudes)
TABLE = "[0.2, 0.6, 0.9]", "[1.4, 1.3, 1.0]"


def _with_table(tmp_path, mach, clmax, name="t"):
    table = f"    CLmax_by_mach: {{mach: {mach}, CLmax: {clmax}, source: test}}\n"
    path = edited_baseline(tmp_path, [(CLEAN, CLEAN + table)])
    return path.rename(tmp_path / f"{name}.yaml")


def _isa_mach_of_eas(v_eas, h):
    t = 288.15 - 0.0065 * h
    sigma = (t / 288.15) ** 5.25588 * 288.15 / t
    return v_eas / math.sqrt(sigma) / math.sqrt(1.4 * 287.05287 * t)


@pytest.fixture(scope="module")
def contexts(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("vn")
    base = Context(load_aircraft(edited_baseline(tmp, [])))
    flat = Context(load_aircraft(_with_table(tmp, "[0.2, 0.9]", "[1.4, 1.4]", "flat")))
    falling = Context(load_aircraft(_with_table(tmp, *TABLE, "falling")))
    return base, flat, falling


def test_a_table_constant_in_mach_is_the_envelope_of_the_constant_cn_max(contexts):
    base, flat, _ = contexts
    mass = base.aircraft.mass.MTOW
    for h in (0.0, H):
        a, b = envelope(base, mass, h, 1.0), envelope(flat, mass, h, 1.0)
        for name, (v, n) in a.corners().items():
            assert b.corners()[name] == pytest.approx((v, n), rel=1e-7)
        assert b.vs1_pos == pytest.approx(a.vs1_pos, rel=1e-7)


def test_the_stall_line_at_altitude_follows_cn_max_of_its_mach(contexts):
    """At 32,250 ft and MRW the stall line's n at VC is ½ ρ₀ VC² S C_N,max(M_VC) / W by hand (C_N,max linear in the
    table between M 0.6 and 0.9), and point A is where that line reaches n₊ — above the constant-C_N,max A, which
    lies at VS1 √n₊ whatever the altitude (EAS)."""
    base, _, falling = contexts
    ac = falling.aircraft
    mass = ac.mass.MRW
    env, const = envelope(falling, mass, H, 1.0), envelope(base, mass, H, 1.0)
    mach_vc = _isa_mach_of_eas(env.v_c, H)
    cn = float(np.interp(mach_vc, [0.2, 0.6, 0.9], [1.4, 1.3, 1.0]))
    hand = 0.5 * 1.225 * env.v_c**2 * ac.reference.area * cn / (mass * 9.80665)
    assert float(env.n_stall_pos(env.v_c)) == pytest.approx(hand, rel=2e-3)
    assert float(env.n_stall_pos(env.v_a)) == pytest.approx(ac.envelope.limit_load_factors.positive, rel=1e-6)
    assert env.v_a > const.v_a * 1.05
    assert env.vs1_pos > const.vs1_pos


def test_the_balanced_point_at_vc_is_held_to_the_stall_line_where_cn_max_falls(tmp_path):
    """§25.331(b) at VC and n₊ at 32,250 ft, MRW: with C_N,max falling to 1.0 at M 0.9 the point is on the stall line
    at VC — n = ½ ρ₀ VC² S C_N,max(M_VC) / W by hand, below n₊, the note says so; with the constant C_N,max 1.4 it is
    at n₊."""

    def vc_point(result):
        return next(
            f.details
            for f in result.findings
            if f.condition.get("point") == "VC at n+"
            and f.condition.altitude == pytest.approx(H, abs=1.0)
            and f.condition.loading == "fwd_mrw"
            and "n" in f.details
        )

    falling = vc_point(run_rule("25.331(b)", tmp_path, edits=[(CLEAN, CLEAN + _table_line(*TABLE))]))
    constant = vc_point(run_rule("25.331(b)"))
    ac = load_aircraft(edited_baseline(tmp_path, [])).model
    mass = ac.mass.MRW
    v_c = falling["V_kn_EAS"] * 1852 / 3600
    cn = float(np.interp(_isa_mach_of_eas(v_c, H), [0.2, 0.6, 0.9], [1.4, 1.3, 1.0]))
    hand = 0.5 * 1.225 * v_c**2 * ac.reference.area * cn / (mass * 9.80665)
    assert constant["n"] == pytest.approx(ac.envelope.limit_load_factors.positive)
    assert falling["n"] == pytest.approx(hand, rel=3e-3) and falling["n"] < constant["n"] - 0.1
    assert "C_N,max line" in falling["speed_note"]


def _table_line(mach, clmax):
    return f"    CLmax_by_mach: {{mach: {mach}, CLmax: {clmax}, source: test}}\n"


def test_the_airplane_model_stalls_at_the_table_s_cn_max(contexts):
    """The airplane model's stall follows the table: its declared C_Lmax at M 0.9 is the table's 1.0 and at M 0.2
    the low-speed 1.4."""
    _, _, falling = contexts
    m = falling.aero("clean").model
    assert float(m.clmax(np.array([0.9]))[0]) == pytest.approx(1.0, rel=1e-9)
    assert float(m.clmax(np.array([0.2]))[0]) == pytest.approx(1.4, rel=1e-9)


@pytest.mark.parametrize(
    "mach, clmax, fragment",
    [
        ("[0.2, 0.9]", "[1.5, 1.2]", "within 2 % of CLmax"),
        ("[0.5, 0.9]", "[1.4, 1.2]", "at most 0.3"),
        ("[0.2, 0.2]", "[1.4, 1.2]", "increase strictly"),
        ("[0.2, 0.6, 0.9]", "[1.4, 1.2]", "one per Mach number"),
    ],
)
def test_a_table_that_contradicts_clmax_is_an_input_error(cli, tmp_path, mach, clmax, fragment):
    path = _with_table(tmp_path, mach, clmax)
    out = cli("check", path, "--select", "25.337", "--out", tmp_path / "rep")
    assert out.exit_code == 2 and "Traceback" not in out.output
    assert "configurations.clean" in out.output and fragment in out.output


def _hand_stall_speed(ac, mass, n, h):
    """EAS (m/s) where ½ ρ₀ V² S C_N,max(M(V)) / W reaches ``n`` with the falling table, by bisection on the ISA
    closed forms of this module (independent of certkit's atmosphere and root finder)."""
    lo, hi = 50.0, 400.0
    for _ in range(80):
        v = 0.5 * (lo + hi)
        cn = float(np.interp(_isa_mach_of_eas(v, h), [0.2, 0.6, 0.9], [1.4, 1.3, 1.0]))
        if 0.5 * 1.225 * v * v * ac.reference.area * cn / (mass * 9.80665) < n:
            lo = v
        else:
            hi = v
    return 0.5 * (lo + hi)


def test_va_required_at_altitude_follows_the_mach_stall_line(tmp_path):
    """§25.335(c): VA ≥ the speed where the stall line reaches n₊ at the altitude (§25.335(c)(2): VA and VS at the
    weight and altitude), at most VC; with C_N,max falling with Mach that speed is the hand one (bisection above), and
    above the constant-C_N,max VS1·√n₊. §25.333 and §25.335(c) agree on it."""
    edits = [(CLEAN, CLEAN + _table_line(*TABLE))]
    result = run_rule("25.335(c)", tmp_path, edits=edits)
    ac = load_aircraft(edited_baseline(tmp_path, edits)).model
    rows = [f for f in result.findings if f.condition.altitude == pytest.approx(H, abs=1.0)]
    assert rows
    below_vc = 0
    for f in rows:
        hand = _hand_stall_speed(ac, f.condition.mass, ac.envelope.limit_load_factors.positive, H)
        assert f.limit == pytest.approx(min(hand, f.details["VC"]), rel=1e-3)
        assert hand > f.details["VS1"] * math.sqrt(ac.envelope.limit_load_factors.positive) * 1.02
        below_vc += hand < f.details["VC"]
    assert below_vc  # the stall line's speed decides at some weight, not only the VC cap


def test_the_checked_pull_s_wing_loads_stop_at_the_table_s_lift(tmp_path):
    """§25.331(c)(2) nose-up from VD at 43,000 ft, fwd_mrw (the heaviest forward corner): the wing's loads count while
    the airplane's linear lift is below C_Lmax at the run's Mach (the strips are linear in α). With the constant
    C_Lmax 1.4 the wing fails there (by about 2 %: lift the airplane cannot make at M 0.89); with C_Lmax falling to 1.0
    at M 0.9 its loads stop at the table's lift and comply — the loads follow the declared C_Lmax(M)."""
    h = 13106.4  # m, 43,000 ft: the envelope's ceiling

    def wing_pulls(result):
        return [
            f
            for f in result.findings
            if f.condition.loading == "fwd_mrw"
            and f.condition.altitude == pytest.approx(h, abs=1.0)
            and f.condition.get("entry_speed") == "VD"
            and f.condition.get("direction") == "nose up"
            and f.condition.get("trim") is None
            and f.check.split(":")[0].endswith("wing")
        ]

    constant = wing_pulls(run_rule("25.331(c)(2)"))
    falling = wing_pulls(run_rule("25.331(c)(2)", tmp_path, edits=[(CLEAN, CLEAN + _table_line(*TABLE))]))
    assert constant and falling
    assert any(f.status == "fails" for f in constant)
    assert all(f.status == "complies" for f in falling)
    assert min(f.normalized_margin for f in falling) > max(f.normalized_margin for f in constant) + 0.1
