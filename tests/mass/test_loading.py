"""Loading conditions at the CG-envelope corners: exact mass and CG, physical inertia, stated fallbacks."""

import numpy as np
import pytest

from certkit.engine.conditions import CgCorners
from certkit.models.mass.loading import bays, solve_loading
from certkit.units import FT, LB


@pytest.fixture(scope="module")
def corners(baseline):
    a = baseline.model
    return {c.name: solve_loading(a, c.mass, c.x_cg, c.name) for c in CgCorners().loadings(a)}


def test_every_corner_reaches_its_mass_and_cg_exactly(baseline, corners):
    for c in CgCorners().loadings(baseline.model):
        p = corners[c.name].properties
        assert p.mass == pytest.approx(c.mass, rel=1e-9)
        assert p.cg[0] == pytest.approx(c.x_cg, abs=1e-6)
        assert np.all(np.linalg.eigvalsh(p.inertia) > 0)


def test_reachable_corners_use_real_payload_and_fuel(corners):
    """fwd_mlw (460,000 lb, 6 % MAC) is reached with cabin/hold payload and tank fuel, no ballast."""
    r = corners["fwd_mlw"]
    assert not r.notes
    assert r.payload + r.fuel == pytest.approx(460_000 * LB - 304_488 * LB, rel=1e-6)
    assert r.payload <= (430_000 - 304_488) * LB + 1e-6  # zero-fuel mass within MZFW
    assert sum(r.fuel_by_tank.values()) == pytest.approx(r.fuel)


def test_unreachable_corners_say_how_they_were_built(corners):
    """The light corners lie far from the OEW CG: no distribution reaches them, and the result says so."""
    for name in ("fwd_light", "aft_light"):
        assert corners[name].notes and "cannot be built" in corners[name].notes[-1]


def test_inertia_at_mtow_against_radii_of_gyration(baseline):
    """Component build-up vs Roskam Part V radii of gyration for jet transports (R̄x 0.28, R̄y 0.38, R̄z 0.46,
    docs/baseline-sources.md §3, stated uncertainty ±25 %): agreement within 40 % on each axis."""
    a = baseline.model
    p = solve_loading(a, 656_000 * LB, 95.5 * FT).properties
    declared = a.mass.inertia
    for built, roskam in ((p.Ixx, declared.Ixx), (p.Iyy, declared.Iyy), (p.Izz, declared.Izz)):
        assert built == pytest.approx(roskam, rel=0.40)
    assert p.Izz < p.Ixx + p.Iyy


def test_bays_split_capacity_and_extent(baseline):
    zones = baseline.model.mass.payload_zones
    split = bays(zones, per_zone=4)
    assert len(split) == 4 * len(zones)
    assert sum(b.capacity for b in split) == pytest.approx(sum(z.capacity for z in zones))


def test_below_empty_mass_is_scaled_and_noted(baseline):
    r = solve_loading(baseline.model, 200_000 * LB, 95.0 * FT)
    assert "below the operating empty mass" in r.notes[-1]
    assert r.properties.Ixx == pytest.approx(baseline.model.mass.inertia.Ixx * 200_000 / 656_000, rel=1e-9)


def test_fuel_never_moves_the_cg_sideways(baseline, corners):
    """Mirror-image wing tanks fill together: every corner's CG is on the plane of symmetry."""
    for r in corners.values():
        assert abs(r.properties.cg[1]) < 1e-9
        assert abs(r.properties.inertia[0, 1]) < 1e-6 * r.properties.Ixx
