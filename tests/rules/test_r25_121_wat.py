"""§25.121 over weight–altitude–temperature (the baseline's takeoff_landing_envelope: −1,000…8,400 ft, −40…50 °C,
ISA+40 line; GE90 flat rating 30 °C), checked by hand where the path is independent of certkit:

* hot-day thrust: Mattingly (*Aircraft Engine Design*, 2nd ed., §2.3) high-bypass lapse written out below, the
  break moved to the flat rating (throttle ratio 303.15/288.15) for the temperature change, the standard day's
  thrust from the parametric engine (throttle ratio 1);
* the energy relation sin γ = (T − D)/W (Anderson, *Aircraft Performance and Design*, eq. 5.12): at one pressure
  altitude and CAS the drag is the same on every day, so the gradient falls by the thrust lost over W
  (tolerance 0.001: the trims are at slightly different γ);
* the WAT limit weight (§25.1533(a)(1): the maximum takeoff weight for an altitude and temperature is the weight at
  which §25.121 is met) is checked by an own trim at the reported weight, at the flight-path angle of the minimum
  gradient: the thrust it needs against the hand (Mattingly) thrust of that day, through sin γ = (T − D)/W
  (tolerance 1e-4 in gradient, the search's);
* a corner where even the lightest declared weight (the CG envelope's 310,000 lb) misses the minimum fails.
"""

import math

import pytest

from certkit.units import KN, LB, LBF

from ..conftest import BASELINE
from .helpers import own, run_rule

FT = 0.3048
G = 9.80665
ENVELOPE = ("  pressure_altitude_min: -1000 ft", "  pressure_altitude_max: 8400 ft", "  temperature_max: 50 degC")


def isa(h):
    t = 288.15 - 0.0065 * h
    return t, 101_325.0 * (t / 288.15) ** 5.25588


def mattingly(h, mach, t_amb, tr):
    """Installed-thrust lapse of a high-bypass turbofan (Mattingly §2.3) at ambient temperature t_amb."""
    k = 1 + 0.2 * mach * mach
    d0, t0 = isa(h)[1] / 101_325.0 * k**3.5, t_amb / 288.15 * k
    base = 1 - 0.49 * math.sqrt(mach)
    return d0 * (base if t0 <= tr else base - 3 * (t0 - tr) / (1.5 + mach))


@pytest.fixture(scope="module")
def base_b():
    return run_rule("25.121(b)")


def gradients(result, airport_prefix=None):
    return [
        f
        for f in own(result)
        if f.unit == "gradient"
        and (f.condition.get("airport") or "").startswith(airport_prefix or "")
        and (airport_prefix is not None or f.condition.get("airport") is None)
    ]


def limitation(result, airport_prefix):
    (f,) = [f for f in own(result) if f.unit == "kg" and f.condition.get("airport", "").startswith(airport_prefix)]
    return f


def mach_of(cas, h):
    """Mach number of a CAS (m/s) at pressure altitude h: subsonic pitot relation, ISA pressures."""
    qc = 101_325.0 * ((1 + 0.2 * (cas / 340.294) ** 2) ** 3.5 - 1)
    return math.sqrt(5 * ((qc / isa(h)[1] + 1) ** (2 / 7) - 1))


def hot_thrust(h, cas, delta_isa, static=97_300 * LBF):
    """One engine's full thrust (N) at pressure altitude h, CAS (m/s) on the day ISA + delta_isa, by hand: Mattingly's
    standard-day lapse (break at throttle ratio 1) times the flat-rated temperature ratio (break at 303.15/288.15)."""
    mach, t, tr = mach_of(cas, h), isa(h)[0], 303.15 / 288.15
    return static * mattingly(h, mach, t, 1.0) * mattingly(h, mach, t + delta_isa, tr) / mattingly(h, mach, t, tr)


def own_gradient(cond, delta_isa, static=97_300 * LBF, gradient=0.024):
    """The gear-up V2 gradient at ``cond`` by an own trim: the gear-down takeoff configuration trimmed at a fixed
    flight-path angle γ0 = atan ``gradient`` (critical engine left windmilling, zero sideslip, the thrust solved for);
    then sin γ = sin γ0 + (T − T0 + ΔD_gear)/W with T the hand thrust of the day, T0 the trim's and ΔD_gear the rule's
    gear_up_credit ΔCD0 at q̄ = ½ γ p M² (the drag the gear-up segment does not carry). Exact at γ0 (the step from it
    neglects the change of the trim's lift and drag with γ: trimmed at the gradient it checks, none is left)."""
    from certkit_rules.part25.subpart_b.r25_121 import gear_up_credit

    from certkit.aircraft import load_aircraft
    from certkit.engine.context import Context

    ctx = Context(load_aircraft(BASELINE))
    gamma0 = math.atan(gradient)
    r = ctx.trim([cond], kind="sideslip", beta=0.0, gamma=gamma0, inoperative="left").results[0]
    assert r.converged
    w = cond.mass * G
    q = 0.5 * 1.4 * isa(cond.altitude)[1] * mach_of(cond.speed, cond.altitude) ** 2
    gear = gear_up_credit(ctx, "takeoff")[0] * q * ctx.aircraft.reference.area
    t = hot_thrust(cond.altitude, cond.speed, delta_isa, static)
    return math.tan(math.asin(math.sin(gamma0) + (t - r.thrust["right"] + gear) / w))


def test_sea_level_complies_and_hot_and_high_is_weight_limited(base_b):
    """The baseline complies at sea level ISA (gradient 2.78 % ≥ 2.4 %). At 8,400 ft, ISA+40 the gradient at MTOW is
    below 2.4 %: §25.1533(a)(1) makes the corner a takeoff-weight limitation, which complies (it is above the lightest
    declared weight, 310,000 lb); the MTOW gradients there are not applicable."""
    assert all(f.status == "complies" for f in gradients(base_b))
    assert base_b.status != "fails"
    f = limitation(base_b, "8,400 ft, +38.4")
    assert f.status == "complies" and f.limit == pytest.approx(310_000 * LB) and f.margin == f.value - f.limit
    assert 310_000 * LB < f.value < 656_000 * LB and f.value == pytest.approx(f.details["wat_limit_mass_kg"], abs=0.1)
    assert f.condition.mass == f.value and "takeoff weight limited to" in f.reason and "§25.1533(a)" in f.reason
    mtow = [
        g
        for g in own(base_b)
        if g.condition.get("airport", "").startswith("8,400 ft, +38.4")
        and g.check.endswith(", WAT")
        and g.condition.loading.startswith("MTOW")
    ]
    assert len(mtow) == 3 and all(
        g.status == "complies"
        and g.margin is None
        and "not applicable" in g.reason
        and g.details["gradient_at_design_weight"] < 0.024
        for g in mtow
    )


def test_the_limit_weight_gives_the_minimum_gradient_by_an_own_trim(base_b):
    """At the reported WAT limit weight (8,400 ft, ISA+40, V2 scaled as √W from 161 kn at MTOW) an own trim with the
    hand thrust gives 2.4 % within 1e-4; 2 % heavier it is below 2.4 % (the weight is the limit, not any weight)."""
    f = limitation(base_b, "8,400 ft, +38.4")
    c = f.condition
    assert c.speed == pytest.approx(161 * KN * math.sqrt(c.mass / (656_000 * LB)), rel=1e-6)
    assert own_gradient(c, 40.0) == pytest.approx(0.024, abs=1e-4)
    heavier = c.with_(mass=1.02 * c.mass, speed=c.speed * math.sqrt(1.02))
    assert own_gradient(heavier, 40.0) < 0.024 - 5e-4


def test_an_airplane_that_cannot_meet_b_at_the_hot_corner_fails(tmp_path):
    """Thrust cut to 55,000 lbf per engine: at 8,400 ft, ISA+40 even the lightest declared weight (310,000 lb, the CG
    envelope's) climbs below 2.4 % (own trim with the hand thrust), so the corner's limitation fails and so does the
    rule."""
    r = run_rule("25.121(b)", tmp_path, [("  static_thrust: 97300 lbf", "  static_thrust: 55000 lbf")])
    f = limitation(r, "8,400 ft, +38.4")
    assert f.status == "fails" and f.value < f.limit == pytest.approx(310_000 * LB) and r.status == "fails"
    assert "no weight meets" in f.reason
    light = f.condition.with_(mass=310_000 * LB, speed=161 * KN * math.sqrt(310 / 656))
    assert light.x_cg is not None and own_gradient(light, 40.0, 55_000 * LBF) < 0.024


def test_hot_day_thrust_and_gradient_by_hand(base_b):
    """8,400 ft, V2 = 161 kn CAS (M from the standard day), MTOW reference CG: the available thrust on the ISA+40
    day by hand, and the gradient loss = thrust loss / W (the MTOW gradients of these weight-limited corners are
    kept in the not-applicable findings' details)."""
    h = 8400 * FT

    def at_mtow(prefix):
        return next(
            f
            for f in own(base_b)
            if f.condition.get("airport", "").startswith(prefix)
            and f.condition.loading == "MTOW reference"
            and f.check.endswith(", WAT")
        )

    std, hot = at_mtow("8,400 ft, -1.6"), at_mtow("8,400 ft, +38.4")
    t_std = std.details["thrust_available_N"]
    assert t_std == pytest.approx(97_300 * LBF * mattingly(h, mach_of(161 * KN, h), isa(h)[0], 1.0), rel=1e-4)
    assert hot.details["thrust_available_N"] == pytest.approx(hot_thrust(h, 161 * KN, 40.0), rel=1e-4)
    w = 656_000 * LB * G
    loss = std.details["gradient_at_design_weight"] - hot.details["gradient_at_design_weight"]
    assert loss == pytest.approx((t_std - hot.details["thrust_available_N"]) / w, abs=0.001)


def test_cold_day_equals_the_standard_day(base_b):
    """Below the flat rating the thrust is the standard day's, and so is the climb (same CAS, same q̄ and Mach): the
    cold corner is reported with the standard day's trim, and says so (at 3,700 ft both are weight-limited: the same
    WAT limit weight)."""
    cold = {
        f.check + f.condition.loading: f
        for f in own(base_b)
        if f.condition.get("airport", "").startswith("3,700 ft, -40")
    }
    std = {
        f.check + f.condition.loading: f
        for f in own(base_b)
        if f.condition.get("airport", "").startswith("3,700 ft, +7.7")
    }
    assert cold.keys() == std.keys() and any(f.unit == "kg" for f in cold.values())
    assert all(cold[k].value == std[k].value and cold[k].status == std[k].status for k in std)
    assert all("the trim of 3,700 ft, +7.7" in f.reason for f in cold.values())
    assert all(f.condition.get("delta_isa_K") < -40 for f in cold.values())


def test_a_low_airport_envelope_complies(tmp_path):
    """−500…500 ft, up to ISA+10 (below the flat rating at V2): the gradient stays above 2.4 % (about 2.6 % at
    500 ft from the 0.35 %/1,000 ft fall of the baseline's corners): every WAT finding complies."""
    edits = [
        (ENVELOPE[0], "  pressure_altitude_min: -500 ft"),
        (ENVELOPE[1], "  pressure_altitude_max: 500 ft"),
        ("  isa_deviation_max: 40 delta_degC", "  isa_deviation_max: 10 delta_degC"),
    ]
    r = run_rule("25.121(b)", tmp_path, edits)
    wat = [f for f in own(r) if f.condition.get("airport")]
    assert wat and all(f.status == "complies" for f in wat)


def test_without_an_envelope_only_sea_level_isa(tmp_path, base_b):
    """No takeoff_landing_envelope: the sea-level ISA findings only, unchanged."""
    src = BASELINE.read_text()
    start = src.index("\ntakeoff_landing_envelope:") + 1
    block = src[start : src.index("\n\n", start) + 2]
    r = run_rule("25.121(b)", tmp_path, [(block, "")])
    mine = [(f.check, f.condition.loading, f.value, f.status) for f in own(r)]
    theirs = [(f.check, f.condition.loading, f.value, f.status) for f in own(base_b) if not f.condition.get("airport")]
    assert mine == theirs


def test_the_study_record_carries_the_lowest_wat_limit_weight(base_b):
    """A design study reads the lowest WAT limit weight of (b) as a named sub-check value (certkit/design/record.py),
    and the report has the per-corner table: 8 weight-limited corners, the lowest at 8,400 ft, ISA+40."""
    from certkit.design.record import rule_responses

    responses, statuses = rule_responses([base_b], {})
    key = "subcheck.25.121(b).b_gradient_at_v2_gear_up_wat_limit_weight"
    assert responses[key + ".value"] == limitation(base_b, "8,400 ft, +38.4").value and statuses[key] == "complies"
    (table,) = [e.table for e in base_b.evidence if e.title.endswith("WAT limit weights")]
    assert len(table) == 8 and min(row[1] for row in table.rows) == responses[key + ".value"]


SOURCE_LINE = '  source: "altitude [b777-fcom]; temperatures estimated'


def declared_rows(*rows):
    return (SOURCE_LINE, "  wat_limits:\n" + "".join(f"    - {{{r}}}\n" for r in rows) + SOURCE_LINE)


def test_a_declared_wat_limit_is_checked_at_its_weight(tmp_path):
    """Declared flight-manual takeoff limits: 475,000 lb at 8,400 ft, 38.4 °C is above the weight where the own trim
    gives 2.4 % (460,789 lb; 3 % heavier loses about 0.35 %) and fails; 495,000 lb at 3,700 ft, 47.7 °C is below that
    corner's (508,400 lb) and complies. A landing-only row does not enter (b)."""
    rows = (
        "pressure_altitude: 8400 ft, temperature: 38.4 degC, takeoff_weight: 475000 lb, source: AFM test",
        "pressure_altitude: 3700 ft, temperature: 47.7 degC, takeoff_weight: 495000 lb",
        "pressure_altitude: 0 ft, temperature: 50 degC, landing_weight: 400000 lb",
    )
    r = run_rule("25.121(b)", tmp_path, [declared_rows(*rows)])
    declared = [f for f in own(r) if f.check.endswith("declared WAT limit") and f.unit == "gradient"]
    hot = [f for f in declared if f.condition.get("airport").startswith("8,400 ft")]
    warm = [f for f in declared if f.condition.get("airport").startswith("3,700 ft")]
    assert len(declared) == 6 and len(hot) == 3 and len(warm) == 3
    assert all(f.condition.mass == pytest.approx(475_000 * LB) for f in hot)
    assert min(f.value for f in hot) < 0.024 and any(f.status == "fails" for f in hot) and r.status == "fails"
    assert all(f.status == "complies" and f.value > 0.024 for f in warm) and "AFM test" in hot[0].reason
    worst = min(hot, key=lambda f: f.value)
    delta_isa = 38.4 + 273.15 - isa(8400 * FT)[0]
    assert own_gradient(worst.condition, delta_isa, gradient=worst.value) == pytest.approx(worst.value, abs=1e-4)


def test_a_declared_wat_limit_outside_the_envelope_is_an_input_error(tmp_path):
    """A declared point above the envelope's highest airport, and one with no weight: both reported with their paths."""
    from certkit.aircraft import load_aircraft
    from certkit.errors import InputError

    from .helpers import edited_baseline

    path = edited_baseline(
        tmp_path,
        [
            declared_rows(
                "pressure_altitude: 9000 ft, temperature: 20 degC, takeoff_weight: 1 lb",
                "pressure_altitude: 0 ft, temperature: 20 degC",
            )
        ],
    )
    with pytest.raises(InputError) as err:
        load_aircraft(path)
    message = str(err.value)
    assert "takeoff_landing_envelope.wat_limits.0.pressure_altitude" in message
    assert "takeoff_landing_envelope.wat_limits.1" in message and "neither takeoff_weight nor landing_weight" in message
