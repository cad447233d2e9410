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


def test_unreachable_corners_are_built_from_the_declared_items(baseline, corners):
    """The light corners (310,000 lb at 6 % and 38 % MAC) lie beyond what 2,500 kg of fuel and payload can move the
    declared empty CG (22.1 % MAC): they are built from the declared items with the empty airplane moved as a whole,
    and say so. The CG height is then the moment balance of the items' heights (hand sum over the file's component
    table: the OEW CG is 3.47 ft below the datum, docs/baseline-sources.md §2), not the datum."""
    a = baseline.model
    oew = sum(c.mass for c in a.mass.components)
    z_oew = sum(c.mass * c.cg.z for c in a.mass.components) / oew
    assert z_oew / FT == pytest.approx(-3.465, abs=0.01)  # hand sum of the YAML table in lb·ft: -1,055,072 / 304,488
    for name in ("fwd_light", "aft_light"):
        r = corners[name]
        assert "moved" in r.notes[-1] and "empty airplane moved" in r.construction
        tank_z = {t.name: t.cg.z for t in a.mass.fuel_tanks}
        moment_z = oew * z_oew + sum(m * tank_z[t] for t, m in r.fuel_by_tank.items())  # payload zones at height 0
        assert r.properties.cg[2] == pytest.approx(moment_z / r.properties.mass, abs=1e-6)
        assert r.properties.cg[2] / FT < -3.0


def test_moved_empty_airplane_keeps_the_inertia_about_the_cg(baseline, corners):
    """Moving every item by the same distance leaves the inertia about the CG unchanged (parallel-axis theorem): the
    light corner's tensor is that of its unmoved items, so it follows mass.inertia_used like any loading."""
    from certkit.models.mass.properties import MassComponent, combine

    r = corners["fwd_light"]
    shift = r.properties.cg[0] - sum(c.mass * c.cg[0] for c in r.items) / r.properties.mass  # 0 by construction
    assert abs(shift) < 1e-9
    dx = 3.0  # move the whole set: the inertia about the CG must not change
    moved = [MassComponent(c.name, c.mass, (c.cg[0] + dx, c.cg[1], c.cg[2]), c.inertia) for c in r.items]
    np.testing.assert_allclose(combine(moved).inertia, r.properties.inertia, rtol=1e-9)
    declared = baseline.model.model_copy(
        update={"mass": baseline.model.mass.model_copy(update={"inertia_used": "declared"})}
    )
    c = next(c for c in CgCorners().loadings(declared) if c.name == "fwd_light")
    d = solve_loading(declared, c.mass, c.x_cg, c.name)
    assert d.properties.Iyy == pytest.approx(baseline.model.mass.inertia.Iyy * 310_000 / 656_000, rel=1e-6)
    assert d.properties.cg[2] == pytest.approx(r.properties.cg[2], abs=1e-9)


def test_every_loading_names_how_it_was_built(corners):
    assert corners["fwd_mlw"].construction.startswith("declared items: empty airplane (")
    assert "ballast" in corners["aft_mrw"].construction


def test_point_mass_empty_airplane_sits_at_its_declared_height(baseline):
    """Without a component table the empty airplane is one item at mass.oew_cg, height included."""
    a = baseline.model
    oew_cg = a.mass.oew_cg.model_copy(update={"z": -1.0})
    plain = a.model_copy(update={"mass": a.mass.model_copy(update={"components": None, "oew_cg": oew_cg})})
    r = solve_loading(plain, 140_000, 28.0, "light")
    assert r.properties.cg[0] == pytest.approx(28.0, abs=1e-6)
    empty = a.mass.OEW
    assert r.properties.cg[2] == pytest.approx(
        (
            empty * -1.0
            + sum(m * next(t.cg.z for t in a.mass.fuel_tanks if t.name == k) for k, m in r.fuel_by_tank.items())
        )
        / 140_000,
        abs=1e-6,
    )


#: the component build-up at MTOW against the radii-of-gyration estimate, on each axis
_BUILT_AGAINST_RADII = [
    "Ixx",
    pytest.param(
        "Iyy",
        marks=pytest.mark.xfail(
            strict=True,
            reason="the build-up's Iyy at MTOW is 34 % below the Roskam-radius estimate and 23 % below the 747's "
            "scaled (NASA CR-2144): R̄y 0.31 against the 747's 0.353; the component table lumps systems and operator "
            "items at points near the CG (spread over their extents they would add about 12 %, not the whole gap) — a "
            "named limit of the declared component table, docs/baseline-sources.md §3",
        ),
    ),
    "Izz",
]


@pytest.mark.parametrize("axis", _BUILT_AGAINST_RADII)
def test_inertia_at_mtow_against_radii_of_gyration(baseline, axis):
    """Component build-up vs Roskam Part V radii of gyration for jet transports (R̄x 0.28, R̄y 0.38, R̄z 0.46,
    docs/baseline-sources.md §3), within their stated uncertainty, ±25 % (the declared tensor is that estimate)."""
    a = baseline.model
    p = solve_loading(a, 656_000 * LB, 95.5 * FT).properties
    assert getattr(p, axis) == pytest.approx(getattr(a.mass.inertia, axis), rel=0.25)


def test_inertia_at_mtow_is_a_physical_tensor(baseline):
    """The built tensor obeys the triangle inequality of a rigid body's principal moments (Izz < Ixx + Iyy)."""
    p = solve_loading(baseline.model, 656_000 * LB, 95.5 * FT).properties
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


def test_report_provenance_names_how_each_loading_was_built(baseline):
    """The report's loadings table (Context.provenance, column "Built from") carries the construction of each loading
    solved, the moved empty airplane of a light corner included."""
    from certkit.engine.context import Context

    ctx = Context(baseline)
    for c in CgCorners().loadings(baseline.model):
        if c.name in ("fwd_light", "fwd_mlw"):
            ctx.loading(c.mass, c.x_cg, c.name)
    rows = {r["name"]: r for r in ctx.provenance()["loadings"]}
    assert "empty airplane moved" in rows["fwd_light"]["built"]
    assert rows["fwd_mlw"]["built"].startswith("declared items: empty airplane (")


def test_fuel_beyond_the_tanks_is_refused_by_name_and_within_them_one_group_is_partly_filled(baseline):
    """The declared tanks hold their summed capacity and no more: one kilogram over is refused naming the mass; at
    capacity every tank is full; half of it fills whole groups before the next, so at most one group (a tank and its
    mirror image, at the same fraction) is partly filled."""
    from certkit.models.mass.loading import LoadingError, fuel_by_tank

    tanks = baseline.model.mass.fuel_tanks
    capacity = np.array([t.capacity for t in tanks])
    np.testing.assert_allclose(fuel_by_tank(baseline.model, capacity.sum()), capacity, rtol=1e-12)
    with pytest.raises(LoadingError, match=f"{capacity.sum() + 1:.0f} kg of fuel exceeds the tank capacity"):
        fuel_by_tank(baseline.model, capacity.sum() + 1.0)
    half = fuel_by_tank(baseline.model, 0.5 * capacity.sum())
    assert half.sum() == pytest.approx(0.5 * capacity.sum(), rel=1e-12)
    fraction = half / capacity
    assert np.all((fraction >= 0) & (fraction <= 1 + 1e-12))
    partly = np.unique(np.round(fraction[(fraction > 1e-12) & (fraction < 1 - 1e-12)], 12))
    assert partly.size <= 1 and (fraction > 1 - 1e-12).any()  # the first group full, one group partly filled
