"""Bad mission input: errors that name the field, the value and the expectation (exit code 2 in the CLI);
a design short of the range requirement is a result, not an error."""

import json

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.errors import InputError, UserError
from certkit.models.performance.mission import fly_missions

from ..conftest import BASELINE


@pytest.fixture(scope="module")
def aero_memo(baseline):
    ctx = Context(baseline)
    ctx.aero("clean")
    return {
        k: v for k, v in ctx._memo.items() if k == "lattice_derivatives" or (isinstance(k, tuple) and k[0] == "aero")
    }


def variant(tmp_path, old, new):
    text = BASELINE.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "variant.yaml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path


def context(path, memo):
    """A Context of a variant whose geometry is the baseline's: the aerodynamic model is reused."""
    ctx = Context(load_aircraft(path))
    ctx._memo.update(memo)
    return ctx


def test_payload_above_maximum_is_an_input_error_with_line(tmp_path):
    path = variant(tmp_path, "design_payload: 68625 lb", "design_payload: 130000 lb")
    with pytest.raises(InputError) as err:
        load_aircraft(path)
    assert any(p.path == "mission.design_payload" and "max_payload" in p.message and p.line for p in err.value.problems)


def test_fuel_capacity_above_the_tanks(tmp_path):
    path = variant(tmp_path, "max_fuel: 302900 lb", "max_fuel: 350000 lb")
    with pytest.raises(InputError) as err:
        load_aircraft(path)
    assert any(p.path == "mass.max_fuel" and "capacity" in p.message for p in err.value.problems)


def test_unreachable_first_cruise_level(tmp_path, aero_memo):
    path = variant(tmp_path, "initial_altitude: 31000 ft", "initial_altitude: 43000 ft")
    ctx = context(path, aero_memo)
    with pytest.raises(
        UserError, match=r"mission\.initial_altitude: .*cannot reach the first cruise level 43000 ft \(thrust"
    ):
        fly_missions(ctx.aircraft, ctx.aero("clean"))


def test_nominal_mission_beyond_the_fuel(tmp_path, aero_memo):
    path = variant(tmp_path, "nominal_distance: 5000 nmi", "nominal_distance: 12000 nmi")
    ctx = context(path, aero_memo)
    with pytest.raises(UserError, match=r"mission\.nominal_distance: 12000 nmi"):
        fly_missions(ctx.aircraft, ctx.aero("clean"))


def test_short_range_is_a_result_not_an_error(tmp_path, aero_memo):
    path = variant(tmp_path, "range_requirement: 7530 nmi", "range_requirement: 11000 nmi")
    ctx = context(path, aero_memo)
    r = fly_missions(ctx.aircraft, ctx.aero("clean"))
    assert r.range_margin_m < 0 and r.responses()["constraint.range_margin_m"] == r.range_margin_m


def test_oew_override_leaving_no_payload(baseline):
    with pytest.raises(UserError, match="mission.design_payload"):
        fly_missions(baseline.model, oew_kg=baseline.model.mass.MZFW - 1000.0)


def test_no_mission_section(tmp_path):
    text = BASELINE.read_text(encoding="utf-8")
    start, end = text.index("\nmission:"), text.index("\nsources:")
    path = tmp_path / "nomission.yaml"
    path.write_text(text[:start] + text[end:], encoding="utf-8")
    with pytest.raises(UserError, match="no mission: section"):
        fly_missions(load_aircraft(path).model)


def test_cli_exit_codes_and_json(cli, tmp_path):
    bad = variant(tmp_path, "design_payload: 68625 lb", "design_payload: 130000 lb")
    out = cli("mission", bad)
    assert out.exit_code == 2 and "mission.design_payload" in out.output and "Traceback" not in out.output
    svg = tmp_path / "pr.svg"
    out = cli("mission", BASELINE, "--json", "--svg", svg)
    assert out.exit_code == 0, out.output
    data = json.loads(out.output)
    assert data["schema"] == "certkit.mission/1"
    assert set(data["responses"]) == {
        "objective.cruise_CD",
        "objective.block_fuel_kg",
        "objective.block_time_s",
        "mission.design_range_m",
        "constraint.range_margin_m",
    }
    assert svg.read_text().startswith("<svg") and "payload" in svg.read_text()
    schema = json.loads(cli("schema").output)
    assert "mission" in schema["properties"]
