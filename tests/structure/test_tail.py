"""Horizontal-tail group sizing (certkit.models.structure.tail) on the baseline.

Calibration reference: the baseline's declared horizontal-tail component, 5,800 lb ("5.2 lb/ft^2 composite
stabiliser", aircraft/lta.yaml, docs/baseline-sources.md §2), sized here from the limit-load envelope the
Subpart C rules compute for the baseline (tests/structure/data, see baseline_envelope.py) × 1.5, with the
declared non-optimum factor. Tolerance 10 %: the envelope is the rules' with the declared tail mass, not the design
loop's; the 3 % calibration check sizes through the loop (tests/design/test_sizing_loop.py).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from certkit.aircraft import validate_aircraft_data
from certkit.aircraft.model import MassComponent as FileComponent
from certkit.errors import InputError
from certkit.models.structure.box import UltimateLoads
from certkit.models.structure.tail import ITEMS, size_horizontal_tail
from certkit.units import LB

from .baseline_envelope import DATA, station_span


@pytest.fixture(scope="module")
def envelope(baseline):
    env = json.loads(DATA.read_text())["stations"]
    names = sorted(env, key=lambda n: station_span(baseline.model, n))
    span = np.array([station_span(baseline.model, n) for n in names])
    limit = np.array([[env[n][q][0] for n in names] for q in ("shear", "bending", "torsion")])
    return UltimateLoads(span, *(1.5 * limit))


@pytest.fixture(scope="module")
def sized(baseline, envelope):
    return size_horizontal_tail(baseline.model, envelope)


def test_calibration_reproduces_the_declared_tail_mass(baseline, sized):
    """The sized group with the declared non-optimum factor is within 10 % of the declared 5,800 lb."""
    declared = next(c.mass for c in baseline.model.mass.components if c.name == "horizontal tail")
    assert declared == pytest.approx(5800 * LB)
    assert sized.non_optimum_factor == baseline.model.sizing.horizontal_tail.non_optimum_factor
    assert sized.mass == pytest.approx(declared, rel=0.10)
    assert set(sized.masses) == set(ITEMS) and all(v >= 0 for v in sized.masses.values())


def test_bending_and_minimum_gauges_both_govern(sized):
    """On the baseline, bending sizes the inboard covers and the minimum gauge the outboard ones (the loads fall
    to zero at the tip)."""
    governs = sized.box.cover_governs
    assert governs[0] == "bending" and governs[-1] == "minimum gauge"
    rows = sized.station_table()
    assert rows[0]["cover_mm"] > rows[-1]["cover_mm"] == pytest.approx(2.5)


def test_more_bending_and_more_area_are_heavier(baseline, envelope, sized):
    """Monotonicity: doubling the bending envelope adds box mass; a 20 % larger tail with the same loads is
    heavier (more secondary area, more minimum-gauge material)."""
    double = UltimateLoads(envelope.span, envelope.shear, 2 * envelope.bending, envelope.torsion)
    assert size_horizontal_tail(baseline.model, double).masses["covers"] > 1.5 * sized.masses["covers"]
    ht = baseline.model.geometry.horizontal_tail.model_copy(
        update={"area": 1.2 * baseline.model.geometry.horizontal_tail.area}
    )
    bigger = baseline.model.model_copy(
        update={"geometry": baseline.model.geometry.model_copy(update={"horizontal_tail": ht})}
    )
    assert size_horizontal_tail(bigger, envelope).mass > sized.mass


def test_mass_properties(baseline, sized):
    """CG on the plane of symmetry, within the tail's X extent and above its root (dihedral); the inertia of a
    nearly flat lamina obeys the perpendicular-axis theorem Izz ≈ Ixx + Iyy (the 7° dihedral adds 2 Σ m z²,
    about 2 tan² 7° = 3 % of Ixx: tolerance 5 %). Ixx checked against the strip sum Σ m y² within 5 %."""
    p = sized.properties
    ht = baseline.model.geometry.horizontal_tail
    assert p.mass == pytest.approx(sized.mass, rel=1e-9)
    assert abs(p.cg[1]) < 1e-9
    assert ht.root_leading_edge.x < p.cg[0] < ht.root_leading_edge.x + 15.0 and p.cg[2] > ht.root_leading_edge.z
    assert p.Izz == pytest.approx(p.Ixx + p.Iyy, rel=0.05)
    assert p.Ixx > 0 and p.Iyy > 0
    comp = sized.component()
    assert isinstance(comp, FileComponent) and comp.mass == pytest.approx(sized.mass) and comp.group == "structure"


def test_sizing_section_relations_are_checked(baseline):
    """Bad input: a rear spar ahead of the front spar, and an elevator hinge line ahead of the rear spar, are
    reported with their YAML paths."""
    data = baseline.source.data
    bad = json.loads(json.dumps(data))
    bad["sizing"]["horizontal_tail"]["rear_spar"] = 0.10
    with pytest.raises(InputError, match="sizing.horizontal_tail.rear_spar"):
        validate_aircraft_data(bad)
    bad = json.loads(json.dumps(data))
    bad["sizing"]["horizontal_tail"]["rear_spar"] = 0.75
    with pytest.raises(InputError, match="hinge line"):
        validate_aircraft_data(bad)
