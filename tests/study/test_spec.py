"""The study file: SI conversion, every error with its YAML path and line, exit code 2, the JSON Schema."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

from certkit.errors import InputError
from certkit.study.spec import load_study
from tests.study.conftest import write_study

ROOT = Path(__file__).resolve().parents[2]


def test_seed_study_in_si():
    study = load_study(ROOT / "studies" / "ht-redesign.yaml")
    v = {x.path.rsplit(".", 1)[-1]: x for x in study.variables}
    assert v["aspect_ratio"].bounds == (3.70, 5.54) and v["aspect_ratio"].baseline == 4.62
    assert v["sweep_quarter_chord"].lower == pytest.approx(math.radians(27.86), rel=1e-12)
    assert v["sweep_quarter_chord"].unit_label == "deg"
    assert v["area"].baseline == pytest.approx(1119 * 0.3048**2, rel=1e-12)  # 1 ft = 0.3048 m (exact)
    assert v["span_start"].bounds == (0.0, 0.20) and v["span_start"].baseline == 0.0
    assert study.aircraft == str((ROOT / "aircraft" / "lta.yaml").resolve())
    absolute = [c for c in study.constraints if not (c.min_from_baseline or c.max_from_baseline)]
    controls = [c for c in absolute if c.response.startswith(("travel.", "control."))]
    assert len(controls) > 30 and all(c.max == 0.70 and c.min is None for c in controls)
    # "no worse than the baseline" beside the regulation's own bound, never instead of it
    relative = [c for c in study.constraints if c.min_from_baseline or c.max_from_baseline]
    assert relative and study.needs_baseline
    assert all(any(a.response == c.response for a in absolute) for c in relative)


def test_seed_study_constrains_every_subpart_b_and_c_rule():
    """The certification-driven study: a margin constraint (≥ 0) on every registered rule of Subparts B and C
    (§§25.101–25.255, 25.301–25.459), the §25.143(h) cases' controls and §25.125's touchdown rate of descent."""
    from certkit.engine.registry import DiscoveryOptions, discover

    study = load_study(ROOT / "studies" / "ht-redesign.yaml")
    margins = {
        c.response: c.min for c in study.constraints if c.response.startswith("rule.") and not c.min_from_baseline
    }
    ids = [
        r.id
        for r in discover(DiscoveryOptions())
        if 101 <= int(r.id.split(".")[1].split("(")[0].rstrip("abcdefgh")) <= 459
    ]
    assert ids and all(margins.get(f"rule.{rid}.margin") == 0 for rid in ids)
    responses = {c.response for c in study.constraints}
    assert {
        f"control.25.143(h).{case}.{c}"
        for case in (
            "takeoff_oei_v2_30deg",
            "takeoff_aeo_v2_xx_40deg",
            "en_route_oei_vfto_40deg",
            "landing_aeo_vref_40deg",
        )
        for c in ("elevator", "aileron", "rudder")
    } <= responses
    assert "subcheck.25.125.touchdown_rate_of_descent.margin" in responses
    relaxed = [r.responses for r in study.analysis.level_relaxation]
    assert "level.phugoid.*.takeoff" in relaxed and any(c.startswith("level.phugoid.") for c in responses)


def test_percent_bounds(small_study):
    sweep = load_study(small_study).variables[1]
    assert sweep.lower == pytest.approx(math.radians(34.82) * 0.9, rel=1e-12)
    assert sweep.upper == pytest.approx(math.radians(34.82) * 1.1, rel=1e-12)


def _errors(tmp_path, text: str) -> str:
    (tmp_path / "aircraft.yaml").write_text("name: stand-in\n")
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(InputError) as err:
        load_study(path)
    return str(err.value)


BAD = """\
aircraft: aircraft.yaml
variables:
  - path: geometry.horizontal_tail.area
    baseline: 1119 ft^2
    bounds: [1343 ft^2, 895.4 ft^2]
  - path: geometry.horizontal_tail.sweep_quarter_chord
    baseline: 34.82 deg
    bounds: [30 blargs, 40 deg]
  - path: geometry.horizontal_tail.taper
    baseline: 0.33
    bounds: ±20 %
  - path: geometry.horizontal_tail.taper
    baseline: 0.5
    bounds: [0.26, 0.40]
designs:
  - {name: a, generator: ccd}
  - {name: b, generator: latin, n: 5}
  - {name: c, generator: lhs, n: 5}
responses: [objective.*]
constraints:
  - {name: range, response: constraint.range_margin_m, min: 0}
"""


def test_every_problem_with_its_line(tmp_path):
    message = _errors(tmp_path, BAD)
    found = dict(re.findall(r"bad\.yaml:(\d+): (\S+):", message))
    assert found.get("5") == "variables.0.bounds", message  # lower > upper
    assert "must be below the upper bound" in message
    assert found.get("8") == "variables.1.bounds", message  # a unit that is no unit
    assert "cannot read '30 blargs' as a number or a quantity with a unit" in message
    assert found.get("14") == "variables.3.bounds", message  # baseline outside its bounds
    assert "outside the bounds" in message
    assert found.get("17") == "designs.1", message  # unknown generator
    assert "'ccd', 'box-behnken', 'lhs', 'random'" in message
    assert found.get("18") == "designs.2.seed", message  # LHS without its seed
    assert "5 problems found" in message  # the relations are checked once the fields are valid


def test_relations_checked_with_lines(tmp_path):
    text = (
        BAD.split("designs:")[0]
        .replace("[1343 ft^2, 895.4 ft^2]", "[895.4 ft^2, 1343 ft^2]")
        .replace("[30 blargs, 40 deg]", "[30 deg, 40 furlongs]")
        .replace("baseline: 0.5", "baseline: 0.3")
    )
    text += """\
designs:
  - {name: a, generator: box-behnken}
  - {name: a, generator: random, n: 4, seed: 1}
responses: [objective.*]
objectives:
  - {response: mission.design_range_m}
aircraft_typo: x
"""
    message = _errors(tmp_path, text)
    assert (
        "bad.yaml:6: variables.1: baseline and bounds are written in units of different kinds (angle, length)"
        in message
    )
    assert "aircraft_typo: unknown field (check the spelling; `certkit study schema` lists the fields)" in message
    (tmp_path / "bad.yaml").write_text(text.replace("aircraft_typo: x\n", "").replace("40 furlongs", "40 deg"))
    with pytest.raises(InputError) as err:
        load_study(tmp_path / "bad.yaml")
    message = str(err.value)
    found = dict(re.findall(r"bad\.yaml:(\d+): (\S+):", message))
    assert found.get("12") == "variables.3.path" and "duplicate (first at variables.2)" in message, message
    assert found.get("17") == "designs.1.name", message
    assert found.get("20") == "objectives.0.response" and "not recorded" in message, message


def test_missing_aircraft_file(tmp_path):
    path = write_study(tmp_path)
    path.write_text(path.read_text().replace("aircraft: aircraft.yaml", "aircraft: nowhere.yaml"))
    with pytest.raises(InputError, match=r"small\.yaml:2: aircraft: aircraft file not found"):
        load_study(path)


def test_cli_exit_code_2_without_traceback(tmp_path, cli):
    path = tmp_path / "bad.yaml"
    (tmp_path / "aircraft.yaml").write_text("name: stand-in\n")
    path.write_text(BAD)
    result = cli("study", "run", path, "--executor", "serial")
    assert result.exit_code == 2
    assert "bad.yaml:5: variables.0.bounds" in result.output
    assert "Traceback" not in result.output
    assert not (tmp_path / "bad.sqlite").exists()


def test_schema_command(cli):
    result = cli("study", "schema")
    schema = json.loads(result.output)
    assert schema["title"] == "certkit study file"
    assert {"aircraft", "variables", "designs"} <= set(schema["required"])
    assert set(schema["$defs"]) >= {"CcdBlock", "BoxBehnkenBlock", "LhsBlock", "RandomBlock", "Variable"}
