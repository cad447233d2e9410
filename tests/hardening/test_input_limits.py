"""Input: every reproducer either loads or is a located InputError, fast, with the value as written.

References: the issue's reproducer list; the limits are certkit's own (yaml_source.MAX_*, units.MAX_QUANTITY_CHARS).
"""

import math
import time

import pytest

from certkit.aircraft import load_aircraft, validate_aircraft_data
from certkit.aircraft.yaml_source import MAX_DEPTH, MAX_FILE_BYTES, MAX_NODES
from certkit.errors import InputError
from certkit.units import LB, to_si

from .mutate import with_value, write_yaml


def _problems(data) -> dict:
    with pytest.raises(InputError) as err:
        validate_aircraft_data(data)
    return {p.path: p for p in err.value.problems}


def _load_problems(path) -> list:
    start = time.perf_counter()
    with pytest.raises(InputError) as err:
        load_aircraft(path)
    assert time.perf_counter() - start < 3.0, "refused, but not fast"
    return err.value.problems


@pytest.mark.parametrize(
    "path, value, words",
    [
        ("mass.MTOW", "10**1000 lb", "arithmetic is not evaluated"),
        ("mass.MTOW", "9**9**9 lb", "arithmetic is not evaluated"),
        ("mass.MTOW", int("9" * 400), "400 digits"),
        ("mass.inertia.Izz", "10**1000 kg*m^2", "arithmetic is not evaluated"),
        ("mass.inertia.Ixz", math.nan, "finite"),
        ("mass.components.0.inertia.Iyy", "inf kg*m^2", "cannot read"),
        ("geometry.fuselage.length", "nan ft", "cannot read"),
        ("geometry.fuselage.length", "1e400 ft", "finite"),
        ("envelope.ceiling", math.inf, "finite"),
        ("cg_envelope.vertices.0.x", math.nan, "finite"),
        ("geometry.wing.taper", math.nan, "finite"),
        ("mass.MTOW", "1" * 20000 + " lb", "too long"),
        ("mass.MTOW", True, "yes/no"),
    ],
)
def test_unreadable_or_non_finite_numbers_are_located_errors(path, value, words):
    start = time.perf_counter()
    found = _problems(with_value(path, value))
    assert time.perf_counter() - start < 2.0
    assert path in found, list(found)
    assert words in found[path].message
    assert found[path].value == value or (isinstance(value, float) and math.isnan(value))  # as written


def test_bare_number_string_is_si():
    """docs/aircraft-file.md: a bare number is SI. '3e5' is a string to YAML 1.1 (no dot), still a number of
    kilograms."""
    assert to_si("3e5", "mass") == 3e5
    found = _problems(with_value("mass.MTOW", "3e5"))
    assert list(found) == ["mass.MRW"]  # only the relation with the ramp weight (657,000 lb > 300 t) remains


def test_union_member_tags_are_not_in_the_path():
    found = _problems(with_value("structure.wing.0.station", 1.5))
    assert list(found) == ["structure.wing.0.station"]
    message = found["structure.wing.0.station"].message
    assert "root" in message and "1" in message
    assert "literal" not in message and "constrained" not in str(found)


def test_limit_message_shows_the_text_and_its_si_reading():
    found = _problems(with_value("geometry.wing.sweep_quarter_chord", "80 deg"))
    p = found["geometry.wing.sweep_quarter_chord"]
    assert p.value == "80 deg" and "1.396" in p.message  # 80° = 1.39626 rad


def test_nan_criteria_override_is_rejected():
    data = with_value(
        "criteria", {"25.337": {"justification": "a test of a NaN override", "values": {"n_positive_floor": math.nan}}}
    )
    found = _problems(data)
    assert "finite" in found["criteria.25.337.values.n_positive_floor"].message


def test_control_characters_in_the_name_are_rejected():
    for name in ("a\x00b", "a\nb"):
        assert "printable" in _problems(with_value("name", name))["name"].message


def test_deep_nesting_refused(tmp_path):
    path = tmp_path / "deep.yaml"
    path.write_text("a: " + "[" * 1000 + "]" * 1000 + "\n")
    assert f"more than {MAX_DEPTH} levels" in _load_problems(path)[0].message


def test_self_referencing_alias_refused(tmp_path):
    path = tmp_path / "loop.yaml"
    path.write_text("loop: &a [*a]\n")
    assert "recursive" in _load_problems(path)[0].message


@pytest.mark.parametrize("levels", [7, 9])
def test_alias_bomb_refused_before_expansion(tmp_path, levels):
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x]"]
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, levels + 1)]
    path = tmp_path / "bomb.yaml"
    path.write_text("\n".join(lines) + "\n")
    problem = _load_problems(path)[0]
    assert f"{MAX_NODES:,}" in problem.message and problem.line is not None


def test_dev_zero_and_folders_refused(tmp_path):
    assert "not a regular file" in _load_problems("/dev/zero")[0].message
    assert "folder" in _load_problems("/tmp")[0].message
    huge = tmp_path / "huge.yaml"
    with huge.open("wb") as f:  # sparse: no disk space used
        f.truncate(MAX_FILE_BYTES + 1)
    assert "larger than" in _load_problems(huge)[0].message


def test_huge_integer_literal_refused(tmp_path):
    path = tmp_path / "big.yaml"
    path.write_text("MTOW: " + "9" * 5000 + "\n")
    assert _load_problems(path)


def test_baseline_still_loads_with_the_same_values(baseline):
    assert baseline.model.mass.MTOW == pytest.approx(656000 * LB)


def test_written_baseline_variant_round_trips(tmp_path):
    """A variant written back to YAML loads (the test helper itself can fail: this is its check)."""
    loaded = load_aircraft(write_yaml(tmp_path, with_value("mass.MTOW", "656000 lb")))
    assert loaded.model.mass.MTOW == pytest.approx(656000 * LB)


@pytest.mark.parametrize("text", ["nan", "inf", "1e999", "9**9**9 lb", "nan lb"])
def test_command_line_quantities_refuse_non_finite_and_arithmetic(text):
    from certkit.cli.flight_report import _quantity, parse_speed
    from certkit.errors import UserError

    with pytest.raises(UserError):
        _quantity(text, "mass", "--weight")
    with pytest.raises(UserError):
        parse_speed(f"M{text}" if " " not in text else f"{text} MACH")
