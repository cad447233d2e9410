"""§25.121 over weight–altitude–temperature (the baseline's takeoff_landing_envelope: −1,000…8,400 ft, −40…50 °C,
ISA+40 line; GE90 flat rating 30 °C), checked by hand where the path is independent of certkit:

* hot-day thrust: Mattingly (*Aircraft Engine Design*, 2nd ed., §2.3) high-bypass lapse written out below, the
  break moved to the flat rating (throttle ratio 303.15/288.15) for the temperature change, the standard day's
  thrust from the parametric engine (throttle ratio 1);
* the energy relation sin γ = (T − D)/W (Anderson, *Aircraft Performance and Design*, eq. 5.12): at one pressure
  altitude and CAS the drag is the same on every day, so the gradient falls by the thrust lost over W
  (tolerance 0.001: the trims are at slightly different γ);
* the WAT limit weight is the one where a climb gives the minimum gradient (checked by the gradient reported there).
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
    return [f for f in own(result) if f.unit == "gradient"
            and (f.condition.get("airport") or "").startswith(airport_prefix or "")
            and (airport_prefix is not None or f.condition.get("airport") is None)]


def test_sea_level_isa_passes_and_hot_and_high_fails_with_a_wat_weight(base_b):
    """The baseline complies at sea level ISA (gradient 2.78 % ≥ 2.4 %) but not at 8,400 ft, ISA+40 at MTOW: there
    it is weight-limited; at the reported WAT weight a climb gives 2.4 % (±0.01 %), and the weight is below MTOW."""
    assert all(f.status == "complies" for f in gradients(base_b))
    hot = gradients(base_b, "8,400 ft, +38.4")
    assert len(hot) == 3 and all(f.status == "fails" for f in hot)
    worst = min(hot, key=lambda f: f.value)
    w_lim = worst.details["wat_limit_mass_kg"]
    assert w_lim < 656_000 * LB
    assert worst.details["wat_limit_gradient"] == pytest.approx(0.024, abs=1e-4)
    assert "WAT limit" in worst.reason
    assert base_b.status == "fails"


def test_hot_day_thrust_and_gradient_by_hand(base_b):
    """8,400 ft, V2 = 161 kn CAS (M from the standard day), MTOW reference CG: the available thrust on the ISA+40
    day by hand, and the gradient loss = thrust loss / W."""
    h = 8400 * FT
    std = next(f for f in gradients(base_b, "8,400 ft, -1.6") if f.condition.loading == "MTOW reference")
    hot = next(f for f in gradients(base_b, "8,400 ft, +38.4") if f.condition.loading == "MTOW reference")
    t_std = std.details["thrust_available_N"]
    # Mach of 161 kn CAS at 8,400 ft (subsonic pitot relation, ISA pressure)
    qc = 101_325.0 * ((1 + 0.2 * (161 * KN / 340.294) ** 2) ** 3.5 - 1)
    mach = math.sqrt(5 * ((qc / isa(h)[1] + 1) ** (2 / 7) - 1))
    assert t_std == pytest.approx(97_300 * LBF * mattingly(h, mach, isa(h)[0], 1.0), rel=1e-4)
    tr = 303.15 / 288.15
    ratio = mattingly(h, mach, isa(h)[0] + 40.0, tr) / mattingly(h, mach, isa(h)[0], tr)
    assert hot.details["thrust_available_N"] == pytest.approx(t_std * ratio, rel=1e-4)
    w = 656_000 * LB * G
    assert std.value - hot.value == pytest.approx((t_std - hot.details["thrust_available_N"]) / w, abs=0.001)


def test_cold_day_equals_the_standard_day(base_b):
    """Below the flat rating the thrust is the standard day's, and so is the gradient (same CAS, same q̄ and Mach):
    the cold corner is reported with the standard day's trim, and says so."""
    cold = {f.condition.loading: f for f in gradients(base_b, "3,700 ft, -40")}
    std = {f.condition.loading: f.value for f in gradients(base_b, "3,700 ft, +7.7")}
    assert cold.keys() == std.keys() and all(cold[k].value == pytest.approx(std[k], abs=1e-9) for k in std)
    assert all("the trim of 3,700 ft, +7.7" in f.reason for f in cold.values())
    assert all(f.condition.get("delta_isa_K") < -40 for f in cold.values())


def test_a_low_airport_envelope_complies(tmp_path):
    """−500…500 ft, up to ISA+10 (below the flat rating at V2): the gradient stays above 2.4 % (about 2.6 % at
    500 ft from the 0.35 %/1,000 ft fall of the baseline's corners): every WAT finding complies."""
    edits = [(ENVELOPE[0], "  pressure_altitude_min: -500 ft"), (ENVELOPE[1], "  pressure_altitude_max: 500 ft"),
             ("  isa_deviation_max: 40 delta_degC", "  isa_deviation_max: 10 delta_degC")]
    r = run_rule("25.121(b)", tmp_path, edits)
    wat = [f for f in own(r) if f.condition.get("airport")]
    assert wat and all(f.status == "complies" for f in wat)


def test_without_an_envelope_only_sea_level_isa(tmp_path, base_b):
    """No takeoff_landing_envelope: the sea-level ISA findings only, unchanged."""
    src = BASELINE.read_text()
    start = src.index("\ntakeoff_landing_envelope:") + 1
    block = src[start:src.index("\n\n", start) + 2]
    r = run_rule("25.121(b)", tmp_path, [(block, "")])
    mine = [(f.check, f.condition.loading, f.value, f.status) for f in own(r)]
    theirs = [(f.check, f.condition.loading, f.value, f.status) for f in own(base_b) if not f.condition.get("airport")]
    assert mine == theirs
