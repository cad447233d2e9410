"""Per-configuration trim limits of a movable stabiliser (``design_limits_by_configuration``).

Reference: 777 AMM 27-41-00, "Horizontal stabilizer control — trim limits" (D633W101-BEJ, p. 69–70): with the flaps
retracted the PFCs limit the stabiliser to +2.25° nose down / −10.25° nose up; with the flaps not retracted the
nose-up PFC limit stays −10.25° and the limit switches set the nose-down limit at +3.75°
(docs/baseline-sources.md §13). The trim cases are chosen to need about +3° of stabiliser (between the two
nose-down limits) with the elevator faired: the solver must reach it with the flaps down and stop at +2.25° clean.
"""

import math
from dataclasses import replace

import pytest

from certkit.aircraft import validate_aircraft_data
from certkit.engine.conditions import Condition
from certkit.engine.context import Context
from certkit.errors import InputError
from certkit.units import FT, KN, LB

from ..hardening.mutate import with_value, write_yaml

FIELD = "geometry.horizontal_tail.stabilizer.design_limits_by_configuration"
AMM_CLEAN = (-10.25, 2.25)  # deg, flaps retracted (PFC)
AMM_FLAPS = (-10.25, 3.75)  # deg, flaps not retracted (PFC nose up, limit switches nose down)


def _deg(lim):
    return (math.degrees(lim.min), math.degrees(lim.max))


def _problems(data) -> dict:
    with pytest.raises(InputError) as err:
        validate_aircraft_data(data)
    return {p.path: p.message for p in err.value.problems}


def test_baseline_declares_the_published_pairs(baseline):
    st = baseline.model.geometry.horizontal_tail.stabilizer
    lim, basis = st.trim_limits("clean")
    assert basis == "design_limits" and _deg(lim) == pytest.approx(AMM_CLEAN, abs=1e-9)
    for name in ("takeoff", "approach", "landing"):  # flaps 15, 20, 30: all extended
        lim, basis = st.trim_limits(name)
        assert basis == f"design_limits_by_configuration.{name}" and _deg(lim) == pytest.approx(AMM_FLAPS, abs=1e-9)
    assert st.trim_limits("takeoff", design=False)[1] == "travel"  # the structural stops: one pair for all


def test_round_trip_through_plain_data(baseline):
    """The validated model written out as plain data (SI) and read back is the same airplane."""
    again = validate_aircraft_data(baseline.model.model_dump(mode="json"))
    assert again.geometry.horizontal_tail.stabilizer == baseline.model.geometry.horizontal_tail.stabilizer
    assert set(again.geometry.horizontal_tail.stabilizer.design_limits_by_configuration) == {
        "takeoff",
        "approach",
        "landing",
    }


def test_unknown_configuration_is_refused_with_its_path():
    problems = _problems(with_value(FIELD, {"takeoff_5": {"min": "-10.25 deg", "max": "3.75 deg"}}))
    assert "unknown configuration" in problems[f"{FIELD}.takeoff_5"]
    assert "takeoff" in problems[f"{FIELD}.takeoff_5"]  # the declared names are listed


def test_limits_outside_the_travel_or_off_the_datum_are_refused():
    """Travel −11°…+4° (structural stops); the datum incidence −2° must lie inside every trim range."""
    data = with_value(
        FIELD, {"takeoff": {"min": "-10.25 deg", "max": "4.5 deg"}, "landing": {"min": "0 deg", "max": "3.75 deg"}}
    )
    problems = _problems(data)
    assert "travel" in problems[f"{FIELD}.takeoff"] and "4.50°" in problems[f"{FIELD}.takeoff"]
    assert "datum" in problems[f"{FIELD}.landing"]
    assert f"{FIELD}.approach" not in problems  # the valid entry is not reported


def test_cli_exits_2_on_an_unknown_configuration(tmp_path, cli):
    path = write_yaml(tmp_path, with_value(FIELD, {"flaps_5": {"min": "-10.25 deg", "max": "3.75 deg"}}))
    result = cli("check", path, "--select", "25.161", "--out", tmp_path / "out", "--quiet")
    assert result.exit_code == 2
    assert f"{FIELD}.flaps_5" in result.output and "unknown configuration" in result.output
    assert not (tmp_path / "out").exists()


def _aft_light(config, kcas):
    """Lightest weight (310,000 lb) with the CG 2.2 ft aft of the envelope's aft limit (100.82 ft), sea level: a trim
    that asks for more nose-down stabiliser than the flaps-up limit (a test of the stops, not a certified loading)."""
    return Condition(
        mass=310000 * LB, x_cg=103.0 * FT, configuration=config, altitude=0.0, speed=kcas * KN, speed_kind="CAS"
    )


def _without_field(loaded):
    g = loaded.model.geometry
    st = g.horizontal_tail.stabilizer.model_copy(update={"design_limits_by_configuration": {}})
    tail = g.horizontal_tail.model_copy(update={"stabilizer": st})
    return replace(
        loaded, model=loaded.model.model_copy(update={"geometry": g.model_copy(update={"horizontal_tail": tail})})
    )


@pytest.fixture(scope="module")
def trims(baseline):
    """Full-throttle climbs light and aft that need more nose-down stabiliser than the flaps-up limit (+2.25°): flaps
    15 at 200 KCAS (about +3.2°), clean at 260 KCAS (about +2.5°) — on the baseline and without the per-configuration
    field."""
    cases = (("takeoff", 200, 1.0), ("clean", 260, 1.0))
    out = {}
    for label, aircraft in (("declared", baseline), ("single pair", _without_field(baseline))):
        ctx = Context(aircraft)
        out[label] = {cfg: ctx.trim([_aft_light(cfg, v)], throttle=th)[0] for cfg, v, th in cases}
    return out


def test_flaps_extended_trim_reaches_past_the_flaps_up_limit(trims):
    r = trims["declared"]["takeoff"]
    need = math.degrees(r.stabilizer_required)
    assert r.converged and AMM_CLEAN[1] + 0.3 < need < AMM_FLAPS[1]  # a case between the two nose-down limits
    assert not r.stabilizer_at_stop and math.degrees(r.stabilizer) == pytest.approx(need, abs=1e-9)
    assert r.controls["elevator"] == 0.0  # trimmed by the stabiliser alone


def test_clean_trim_stops_at_the_flaps_up_limit(trims):
    r = trims["declared"]["clean"]
    assert r.converged and math.degrees(r.stabilizer_required) > AMM_CLEAN[1] + 0.1
    assert r.stabilizer_at_stop == "nose-down" and math.degrees(r.stabilizer) == pytest.approx(AMM_CLEAN[1], abs=1e-9)
    assert r.controls["elevator"] > 0.0  # the elevator holds the rest, trailing edge down


def test_one_pair_for_every_configuration_without_the_field(trims):
    """Without the field the flaps-extended trim stops at +2.25° as before; the incidence the trim needs does not
    depend on the limits, and the clean trim is the same."""
    single, declared = trims["single pair"], trims["declared"]
    r = single["takeoff"]
    assert r.stabilizer_at_stop == "nose-down" and math.degrees(r.stabilizer) == pytest.approx(AMM_CLEAN[1], abs=1e-9)
    assert r.stabilizer_required == pytest.approx(declared["takeoff"].stabilizer_required, abs=1e-9)
    assert single["clean"].stabilizer == declared["clean"].stabilizer
    assert single["clean"].controls == declared["clean"].controls


def test_cli_trim_names_the_limits_at_the_stop(tmp_path, cli):
    """A narrow flaps-15 range (−10.25°…+1°): the light aft-CG level trim at 200 KCAS needs about +1.7° and stops at
    +1°; ``certkit trim`` names the range and the field it comes from."""
    data = with_value(f"{FIELD}.takeoff", {"min": "-10.25 deg", "max": "1 deg"})
    path = write_yaml(tmp_path, data)
    out = cli(
        "trim",
        path,
        "--weight",
        "310000 lb",
        "--cg",
        "100.82 ft",
        "--config",
        "takeoff",
        "--speed",
        "200 kn CAS",
        "--altitude",
        "0 ft",
    ).output
    line = next(ln for ln in out.splitlines() if ln.strip().startswith("stabilizer"))
    assert (
        "nose-down stop" in line and "-10.25 to 1.00 deg" in line and "design_limits_by_configuration.takeoff" in line
    )
