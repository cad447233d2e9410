"""Physical consistency: CG envelope ahead of the main gear, stations on the airplane, inertia within the
bounds the mass distribution allows. The baseline (a certificated airplane) passes every check."""

import pytest

from certkit.aircraft import validate_aircraft_data
from certkit.errors import InputError

from .mutate import baseline_data, with_value


def _paths(data) -> set:
    with pytest.raises(InputError) as err:
        validate_aircraft_data(data)
    return {p.path for p in err.value.problems}


def test_baseline_passes_every_new_check():
    validate_aircraft_data(baseline_data())


def test_aft_cg_behind_the_main_gear_is_refused():
    """Reproducer: aft CG 109.9 ft with the main gear at 107 ft [b777-apd] was accepted."""
    assert "cg_envelope.vertices.5.x" in _paths(with_value("cg_envelope.vertices.5.x", "109.9 ft"))


def test_nose_gear_behind_the_main_gear_is_refused():
    assert "geometry.landing_gear.nose.x" in _paths(with_value("geometry.landing_gear.nose.x", "120 ft"))


@pytest.mark.parametrize(
    "path",
    ["mass.components.0.cg.x", "mass.fuel_tanks.0.cg.x", "mass.payload_zones.0.x_end", "geometry.landing_gear.main.x"],
)
def test_stations_far_outside_the_fuselage_are_refused(path):
    assert path in _paths(with_value(path, "900 ft"))  # fuselage 206.5 ft long


def test_inertia_beyond_popoviciu_bound_is_refused():
    """Iyy ≤ MTOW (Δx² + Δz²)/4 (Popoviciu's inequality): 4.2e9 kg·m² for a 297,557 kg airplane 63 m long would need
    a radius of gyration of 119 m."""
    assert "mass.inertia.Iyy" in _paths(with_value("mass.inertia.Iyy", "4.2e9 kg*m^2"))


def test_inertia_below_the_components_own_is_refused():
    """The declared components alone give Iyy ≈ 2.0e7 kg·m² about their CG (parallel-axis theorem); 1.0e6 slug·ft²
    (1.36e6 kg·m², a unit slip of the declared 31.4e6 slug·ft²) is impossible."""
    assert "mass.inertia.Iyy" in _paths(with_value("mass.inertia.Iyy", "1.0e6 slug*ft^2"))
