"""The aircraft file: SI conversion, every problem at once with path and line, exit code 2."""

import json
import subprocess
import sys
import textwrap

import pytest

from certkit.aircraft import load_aircraft
from certkit.errors import InputError

from ..conftest import BASELINE


def test_baseline_values_in_si(baseline):
    a = baseline.model
    assert a.geometry.wing.area == pytest.approx(4927.3 * 0.3048**2)
    assert a.propulsion.static_thrust == pytest.approx(97300 * 4.4482216152605)
    assert a.speeds.VD.kind == "EAS" and a.speeds.VD.value == pytest.approx(340 * 1852 / 3600)
    assert len(a.cg_envelope.vertices) == 8
    assert a.geometry.horizontal_tail.controls["elevator"].travel.min == pytest.approx(-30 * 3.141592653589793 / 180)


BAD = textwrap.dedent("""\
    name: bad
    reference: {area: -3 ft^2, span: 10 m, mean_chord: 2 m, moment_point: {x: 1 m}}
    geometry:
      wing: {area: 10, aspect_ratio: 8, taper: 1.4, sweep_quarter_chord: 0, root_leading_edge: {x: 1}}
      horizontal_tail: {area: 2, aspect_ratio: 4, taper: 0.5, sweep_quarter_chord: 0, root_leading_edge: {x: 8}}
      vertical_tail: {area: 2, aspect_ratio: 1.5, taper: 0.5, sweep_quarter_chord: 0, root_leading_edge: {x: 8}}
      fuselage: {length: 10, width: 1, height: 1}
    mass: {MTOW: 1000, MLW: 1200 kg, MZFW: 800, OEW: 500}
    cg_envelope:
      vertices: [{mass: 500, x: 1}, {mass: 1000, x: 2}, {mass: 500, x: 2}, {mass: 1000, x: 1}]
    propulsion: {static_thrust: "10 kg", engines: [{name: a, position: {x: 3}}]}
    configurations: {clean: {CLmax: 1.4}}
    speeds: {VC: "300 kn EAS", VD: "250 kn EAS"}
    envelope: {ceiling: 1000 m, limit_load_factors: {positive: 2.5}}
    aspect: 3
""")


@pytest.fixture
def bad_file(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text(BAD)
    return path


def test_every_problem_reported_at_once_with_line(bad_file):
    with pytest.raises(InputError) as info:
        load_aircraft(bad_file)
    by_path = {p.path: p for p in info.value.problems}
    expected = {
        "reference.area": (2, "greater than 0"),
        "geometry.wing.taper": (4, "less than or equal to 1"),
        "mass.MLW": (8, "must not exceed MTOW"),
        "cg_envelope.vertices": (10, "crosses itself"),
        "propulsion.static_thrust": (11, "not a force"),
        "speeds.VD": (13, "must not be below VC"),
        "aspect": (15, "unknown field"),
    }
    for path, (line, words) in expected.items():
        assert path in by_path, f"{path} not reported: {list(by_path)}"
        assert by_path[path].line == line
        assert words in by_path[path].message
    assert by_path["mass.MLW"].value == "1200 kg"  # the value as written


def test_cli_exit_2_without_traceback(bad_file):
    proc = subprocess.run([sys.executable, "-m", "certkit.cli", "check", str(bad_file)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr + proc.stdout
    assert "geometry.wing.taper" in proc.stderr and f"{bad_file}:4" in proc.stderr


@pytest.mark.parametrize(
    "text,path,words",
    [
        ("name: x\nname: y\n", "name", "duplicate key"),
        ("!!python/object/apply:os.system ['echo hi']\n", "", "not valid YAML"),
        ("- a\n- b\n", "", "mapping of sections"),
        ("name: [unclosed\n", "", "not valid YAML"),
    ],
)
def test_unsafe_or_malformed_yaml(tmp_path, text, path, words):
    f = tmp_path / "a.yaml"
    f.write_text(text)
    with pytest.raises(InputError) as info:
        load_aircraft(f)
    assert any(p.path == path and words in p.message for p in info.value.problems), info.value


def test_speed_must_state_its_kind(tmp_path):
    text = BASELINE.read_text().replace("VC: 272 kn EAS", "VC: 272 kn")
    f = tmp_path / "a.yaml"
    f.write_text(text)
    with pytest.raises(InputError, match=r"speeds\.VC: .*end with its kind"):
        load_aircraft(f)


@pytest.mark.parametrize(
    "altitude, speed, words",
    [
        ("[0 ft, 10750 ft, 10750 ft]", "[269 kn, 272 kn, 272 kn]", "must increase strictly"),
        ("[0 ft, 10750 ft]", "[269 kn, 272 kn, 275 kn]", "one speed per altitude"),
        ("[0 ft, 10750 ft]", "[269 kn, -272 kn]", "greater than 0"),
    ],
)
def test_a_speed_schedule_that_cannot_be_read_is_an_input_error(tmp_path, altitude, speed, words):
    """speeds.VA as a schedule with altitude: increasing altitudes, one positive speed each (the YAML path named)."""
    text = BASELINE.read_text()
    text = text.replace("    altitude: [0 ft, 10750 ft]", f"    altitude: {altitude}", 1)
    text = text.replace("    speed: [269 kn, 272 kn]", f"    speed: {speed}", 1)
    f = tmp_path / "a.yaml"
    f.write_text(text)
    with pytest.raises(InputError) as info:
        load_aircraft(f)
    assert any(p.path.startswith("speeds.VA") and words in p.message for p in info.value.problems), info.value


def test_missing_file_is_a_user_error(cli, tmp_path):
    with pytest.raises(InputError, match="file not found"):
        load_aircraft(tmp_path / "nope.yaml")


def test_schema_command_prints_json_schema(cli):
    out = cli("schema")
    schema = json.loads(out.output)
    assert out.exit_code == 0
    assert {"reference", "geometry", "mass", "cg_envelope", "speeds"} <= set(schema["properties"])


def test_vfc_must_lie_between_vmo_and_vd(tmp_path):
    """speeds.VFC (§25.253(b)) between VMO and VD, MFC between MMO and MD: a VFC above VD is reported at its line."""
    from ..rules.helpers import edited_baseline

    path = edited_baseline(tmp_path, [("  VMO: 272 kn EAS", "  VFC: 350 kn EAS\n  MFC: 0.86\n  VMO: 272 kn EAS")])
    with pytest.raises(InputError) as info:
        load_aircraft(path)
    by_path = {p.path: p for p in info.value.problems}
    assert "must not be below VFC" in by_path["speeds.VD"].message
    assert "must not be below MMO" in by_path["speeds.MFC"].message
    assert by_path["speeds.MFC"].line == path.read_text().splitlines().index("  MFC: 0.86") + 1


def test_libyaml_and_pure_python_parsers_agree_on_the_baseline():
    """The file is parsed by libyaml when PyYAML has it (10× faster); its data and the line of every value are
    those of PyYAML's own parser (reference: yaml.SafeLoader on the baseline file)."""
    import yaml

    from certkit.aircraft import yaml_source

    text = open(BASELINE, encoding="utf-8").read()
    node, data = yaml_source._parse(text)
    py_node = yaml.compose(text, Loader=yaml.SafeLoader)
    assert data == yaml.load(text, Loader=yaml.SafeLoader)
    lines_c, lines_py = {}, {}
    yaml_source._record(node, (), lines_c, [], BASELINE)
    yaml_source._record(py_node, (), lines_py, [], BASELINE)
    assert lines_c == lines_py and len(lines_c) > 100


def test_takeoff_pilot_defaults_and_bad_values(baseline, tmp_path):
    """The takeoff pilot: AC 25-7D-based defaults when the file says nothing (1 s, 30 deg/s, no nose-wheel steering);
    a negative rate, a reaction beyond 5 s and a steering angle beyond 80° are each reported with path and line."""
    pilot = baseline.model.takeoff_pilot
    assert pilot.rudder_reaction_time == 1.0 and pilot.rudder_rate == pytest.approx(30 * 3.141592653589793 / 180)
    assert pilot.nose_wheel_steering is None
    text = BASELINE.read_text().replace(
        "\nconfigurations:\n",
        "\ntakeoff_pilot:\n  rudder_reaction_time: 7 s\n  rudder_rate: -5 deg/s\n  nose_wheel_steering: 95 deg\n"
        "\nconfigurations:\n",
        1,
    )
    f = tmp_path / "a.yaml"
    f.write_text(text)
    line = text[: text.index("takeoff_pilot:")].count("\n") + 1
    with pytest.raises(InputError) as info:
        load_aircraft(f)
    by_path = {p.path: p for p in info.value.problems}
    for k, (path, words) in enumerate(
        (
            ("takeoff_pilot.rudder_reaction_time", "less than or equal to 5"),
            ("takeoff_pilot.rudder_rate", "greater than 0"),
            ("takeoff_pilot.nose_wheel_steering", "less than or equal to"),
        )
    ):
        assert path in by_path, list(by_path)
        assert words in by_path[path].message and by_path[path].line == line + 1 + k
