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

from ..rules.helpers import CONSTANT_CN_MAX, edited_baseline, run_rule

CLEAN = "  clean:\n    CLmax: 1.4                 # [given]\n"
H = 9829.8  # m: 32,250 ft, the third of the envelope altitudes of the baseline (EnvelopeAltitudes)
TABLE = "[0.2, 0.6, 0.9]", "[1.4, 1.3, 1.0]"


def _with_table(tmp_path, mach, clmax, name="t"):
    table = f"    CLmax_by_mach: {{mach: {mach}, CLmax: {clmax}, source: test}}\n"
    path = edited_baseline(tmp_path, CONSTANT_CN_MAX + [(CLEAN, CLEAN + table)])
    return path.rename(tmp_path / f"{name}.yaml")


def _isa_mach_of_eas(v_eas, h):
    t = 288.15 - 0.0065 * h
    sigma = (t / 288.15) ** 5.25588 * 288.15 / t
    return v_eas / math.sqrt(sigma) / math.sqrt(1.4 * 287.05287 * t)


@pytest.fixture(scope="module")
def contexts(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("vn")
    base = Context(load_aircraft(edited_baseline(tmp, CONSTANT_CN_MAX)))
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

    falling = vc_point(run_rule("25.331(b)", tmp_path, edits=CONSTANT_CN_MAX + [(CLEAN, CLEAN + _table_line(*TABLE))]))
    constant = vc_point(run_rule("25.331(b)", tmp_path, edits=CONSTANT_CN_MAX))
    ac = load_aircraft(edited_baseline(tmp_path, CONSTANT_CN_MAX)).model
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


def _hand_stall_speed(ac, mass, n, h, table=([0.2, 0.6, 0.9], [1.4, 1.3, 1.0])):
    """EAS (m/s) where ½ ρ₀ V² S C_N,max(M(V)) / W reaches ``n`` with the C_N,max ``table`` (the falling test table by
    default), by bisection on the ISA closed forms of this module (troposphere; independent of certkit's atmosphere
    and root finder)."""
    lo, hi = 50.0, 400.0
    for _ in range(80):
        v = 0.5 * (lo + hi)
        cn = float(np.interp(_isa_mach_of_eas(v, h), *table))
        if 0.5 * 1.225 * v * v * ac.reference.area * cn / (mass * 9.80665) < n:
            lo = v
        else:
            hi = v
    return 0.5 * (lo + hi)


def test_va_required_at_altitude_follows_the_mach_stall_line(tmp_path):
    """§25.335(c): VA ≥ the speed where the stall line reaches n₊ at the altitude (§25.335(c)(2): VA and VS at the
    weight and altitude), at most VC; with C_N,max falling with Mach that speed is the hand one (bisection above), and
    above the constant-C_N,max VS1·√n₊. §25.333 and §25.335(c) agree on it."""
    edits = CONSTANT_CN_MAX + [(CLEAN, CLEAN + _table_line(*TABLE))]
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


def test_the_baseline_va_schedule_is_the_minimum_of_its_declared_cn_max(tmp_path):
    """The baseline's VA schedule (269 KEAS at sea level, 272 from 10,750 ft) is §25.335(c)'s minimum at MRW on the
    stall line of its declared C_Lmax(M) (docs/baseline-sources.md §6a, Q11), the next knot up: at 0 and 10,750 ft the
    hand speed where ½ρ₀V²S C_N,max(M)/W reaches 2.5 (ISA closed forms, the table typed here from the aircraft file's
    comment-free values) lies within 1 kn below it; at 21,500 ft VC (272 KEAS) is below the stall line's speed and VA
    equals it. A table changed without its VA fails here."""
    table = ([0.20, 0.40, 0.60, 0.75, 0.84, 0.90, 0.94], [1.400, 1.370, 1.303, 1.231, 1.138, 1.014, 0.901])
    ac = load_aircraft(edited_baseline(tmp_path, [])).model
    clean = ac.configurations["clean"].CLmax_by_mach
    assert list(clean.mach) == table[0] and list(clean.CLmax) == table[1]
    result = run_rule("25.335(c)")
    kn = 1852.0 / 3600.0
    for h, declared in ((0.0, 269.0), (3276.6, 272.0)):
        hand = _hand_stall_speed(ac, ac.mass.MRW, 2.5, h, table) / kn
        assert 0.0 < declared - hand < 1.0
        f = next(
            f
            for f in result.findings
            if f.condition.mass == pytest.approx(ac.mass.MRW) and f.condition.altitude == pytest.approx(h, abs=0.5)
        )
        assert f.value / kn == pytest.approx(declared, abs=1e-3) and f.limit / kn == pytest.approx(hand, abs=0.05)
    assert _hand_stall_speed(ac, ac.mass.MRW, 2.5, 6553.2, table) / kn > 272.0
    assert result.status == "complies"
    for rule in ("25.335(a)", "25.335(d)", "25.333"):
        assert run_rule(rule).status in ("complies", "complies_partial"), rule


def test_the_checked_pull_stops_at_the_stall_line_of_its_mach(tmp_path):
    """§25.331(c)(2) nose-up from VD at 43,000 ft, fwd_mrw (the heaviest forward corner): the entry speed lies below
    the stall line's speed at n₊ there, so the pull is flown to the stall line's load factor, ½ ρ₀ VD² S C_N,max / W by
    hand (VD the MD-limited EAS at the ISA altitude), not to 2.5 g: 2.20 g with the constant C_Lmax 1.4, and with a
    C_Lmax falling to 1.0 beyond M 0.9 (the entry Mach 0.94) 1.57 g — the peak within the search tolerance of each, and
    the wing's loads lower by the lift the table takes away (margins by more than 0.1 of the allowable higher)."""
    h = 13106.4  # m, 43,000 ft: the envelope's ceiling
    t = 288.15 - 0.0065 * 11000.0
    p11 = 101325.0 * (t / 288.15) ** 5.25588
    p = p11 * math.exp(-9.80665 * (h - 11000.0) / (287.05287 * t))  # isothermal above 11 km
    vd_eas = 0.94 * math.sqrt(1.4 * p / 1.225)  # EAS of M 0.94 at pressure p: √(γ p M² / ρ₀)
    assert vd_eas / 0.514444 == pytest.approx(249.0, abs=1.0)  # kn: below VD 340 KEAS, MD-limited
    s_ref = 4927.3 * 0.3048**2

    mrw = 657000.0 * 0.45359237  # kg, aircraft/lta.yaml

    def stall_n(clmax):
        return 0.5 * 1.225 * vd_eas**2 * s_ref * clmax / (mrw * 9.80665)

    def pulls(result):
        return [
            f
            for f in result.findings
            if f.condition.loading == "fwd_mrw"
            and f.condition.altitude == pytest.approx(h, abs=1.0)
            and f.condition.get("entry_speed") == "VD"
            and f.condition.get("direction") == "nose up"
            and f.condition.get("trim") is None
        ]

    constant = pulls(run_rule("25.331(c)(2)", tmp_path, edits=CONSTANT_CN_MAX))
    falling = pulls(run_rule("25.331(c)(2)", tmp_path, edits=CONSTANT_CN_MAX + [(CLEAN, CLEAN + _table_line(*TABLE))]))
    for found, clmax in ((constant, 1.4), (falling, 1.0)):
        tail = [f for f in found if not f.check.split(":")[0].endswith("wing")]
        assert len(tail) == 1 and tail[0].condition.mass == pytest.approx(mrw, rel=1e-6)
        d = tail[0].all_details()
        assert d["stall_line_load_factor"] == pytest.approx(stall_n(clmax), abs=0.01)
        assert d["peak_n_z"] == pytest.approx(stall_n(clmax), abs=0.02)
    assert stall_n(1.4) == pytest.approx(2.20, abs=0.02) and stall_n(1.0) == pytest.approx(1.57, abs=0.02)
    wing = [[f for f in found if f.check.split(":")[0].endswith("wing")] for found in (constant, falling)]
    assert all(f.status == "complies" for f in wing[1])
    assert min(f.normalized_margin for f in wing[1]) > max(f.normalized_margin for f in wing[0]) + 0.1
