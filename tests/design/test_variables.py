"""Design variables applied to the aircraft file: values with units, regenerated planform, clear errors."""

import math

import pytest

from certkit.aircraft.yaml_source import load_yaml
from certkit.design.variables import DesignError, design_aircraft, parse_setting, settings_from
from certkit.models.aero.airplane import lattice_configuration
from certkit.units import FT

BASELINE = "aircraft/lta.yaml"


@pytest.fixture(scope="module")
def source():
    return load_yaml(BASELINE)


def _design(source, **values):
    return design_aircraft(source, settings_from({k.replace("__", "."): v for k, v in values.items()}))


def test_value_with_unit_and_si_number(source):
    a = design_aircraft(source, [parse_setting('geometry.horizontal_tail.area="1250 ft^2"')])
    assert a.geometry.horizontal_tail.area == pytest.approx(1250 * FT**2, rel=1e-12)
    b = design_aircraft(source, settings_from({"geometry.horizontal_tail.sweep_quarter_chord": math.radians(30.0)}))
    assert b.geometry.horizontal_tail.sweep_quarter_chord == pytest.approx(math.radians(30.0))
    # the file itself is unchanged: the next design starts from the declared values
    assert source.data["geometry"]["horizontal_tail"]["area"] == "1119.2 ft^2"


def test_planform_regenerated_in_the_lattice(source):
    """The tail's lattice follows the variables: semispan √(A S)/2 and root chord 2S/(b(1+λ)) (trapezoid), the
    root leading edge stays at the declared station; the elevator's hinge at 1 − c_e/c."""
    values = {
        "geometry.horizontal_tail.area": "1300 ft^2",
        "geometry.horizontal_tail.aspect_ratio": 5.0,
        "geometry.horizontal_tail.taper": 0.3,
        "geometry.horizontal_tail.controls.elevator.chord_ratio": 0.25,
    }
    a = design_aircraft(source, settings_from(values))
    tail = next(s for s in lattice_configuration(a).surfaces if s.name == "horizontal_tail")
    S, A, lam = 1300 * FT**2, 5.0, 0.3
    b = math.sqrt(A * S)
    root, tip = tail.sections[0], tail.sections[-1]
    assert tip.leading_edge[1] - root.leading_edge[1] == pytest.approx(b / 2, rel=1e-9)  # b is the projected span
    assert root.chord == pytest.approx(2 * S / (b * (1 + lam)), rel=1e-9)
    assert tip.chord == pytest.approx(lam * root.chord, rel=1e-9)
    assert root.leading_edge[0] == pytest.approx(168.0 * FT)
    hinges = {c.hinge_x_over_c for sec in tail.sections for c in sec.controls if c.name == "elevator"}
    assert hinges and all(h == pytest.approx(0.75) for h in hinges)


def test_unknown_path_names_the_variable_and_what_exists(source):
    with pytest.raises(DesignError) as err:
        _design(source, geometry__horizontal_tail__aera="1250 ft^2")
    text = str(err.value)
    assert "geometry.horizontal_tail.aera" in text and "aspect_ratio" in text


def test_section_is_not_a_value(source):
    with pytest.raises(DesignError, match="names a section"):
        _design(source, geometry__horizontal_tail__controls=1.0)


@pytest.mark.parametrize(
    "path, value, expected",
    [
        ("geometry.horizontal_tail.taper", 1.2, "less than or equal to 1"),
        ("geometry.horizontal_tail.area", "-5 ft^2", "greater than 0"),
        ("geometry.horizontal_tail.thickness_ratio", "thin", "thin"),
        ("geometry.horizontal_tail.controls.elevator.span_end", 0.01, "outboard of span_start"),
    ],
)
def test_impossible_values_are_errors_naming_the_variable(source, path, value, expected):
    with pytest.raises(DesignError) as err:
        design_aircraft(source, settings_from({path: value}))
    text = str(err.value)
    assert path in text and expected in text


def test_tip_behind_the_fuselage_end(source):
    """A 1,343 ft², aspect-ratio 5.54 tail swept 41.78° from the declared root station puts its tip leading edge at
    x ≈ 168 + 0.5·86.3·(tan 41.78° + 0.43/(5.54·1.26)) ≈ 213 ft, behind the 206.5 ft fuselage."""
    values = {
        "geometry.horizontal_tail.area": "1343 ft^2",
        "geometry.horizontal_tail.aspect_ratio": 5.54,
        "geometry.horizontal_tail.taper": 0.26,
        "geometry.horizontal_tail.sweep_quarter_chord": "41.78 deg",
    }
    with pytest.raises(DesignError) as err:
        design_aircraft(source, settings_from(values))
    text = str(err.value)
    assert "behind the fuselage end" in text and "geometry.horizontal_tail.area" in text
    # the baseline planform is fine
    design_aircraft(source, [])


def test_parse_setting_errors():
    with pytest.raises(DesignError, match="PATH=VALUE"):
        parse_setting("geometry.horizontal_tail.area")
    assert parse_setting("a.b=4.5").value == 4.5
    assert parse_setting("a.b=1250 ft^2").value == "1250 ft^2"
