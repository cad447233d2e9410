"""Wing fuel on the strips (certkit.models.loads.fuel) and the §25.343 fuel states, against closed forms."""

import numpy as np
import pytest
from certkit_rules.part25.support.fuel_states import fuel_range, fuel_states

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.models.loads.fuel import tank_strip_shares
from certkit.models.loads.model import airplane_loads
from certkit.units import G0

from ..conftest import BASELINE

LB = 0.45359237
FT = 0.3048


def _strips(n=400, span=30.0, root=10.0, tip=2.0):
    edges = np.linspace(0.0, span, n + 1)
    mid = 0.5 * (edges[:-1] + edges[1:])
    return edges[:-1], edges[1:], root + (tip - root) * mid / span


def test_rectangular_wing_bay_by_closed_form():
    """Constant chord: the fuel per unit span is uniform, so a bay from a with its centroid at ȳ ends at 2ȳ − a."""
    y1, y2, c = _strips(root=5.0, tip=5.0)
    share, note = tank_strip_shares(y1, y2, c, tank_y=12.0, side_of_body=3.0)
    assert note is None and share.sum() == pytest.approx(1.0)
    mid = 0.5 * (y1 + y2)
    assert mid[share > 0].min() == pytest.approx(3.0, abs=0.04) and mid[share > 0].max() == pytest.approx(
        21.0, abs=0.04
    )
    assert np.sum(share * mid) == pytest.approx(12.0, abs=1e-3)


def test_tapered_bay_centroid_by_closed_form():
    """Chord c(y) = c_r (1 − k y): the fuel per unit span ∝ c², whose centroid over [a, b] is ∫ c² y dy / ∫ c² dy
    (integrated in closed form below); the declared ends are used as they are."""
    y1, y2, c = _strips(n=3000)
    cr, k = 10.0, (1 - 0.2) / 30.0
    a, b = 4.0, 25.0

    def moments(y):  # antiderivatives of (1 − k y)² and y (1 − k y)²
        return (y - k * y**2 + k**2 * y**3 / 3, y**2 / 2 - 2 * k * y**3 / 3 + k**2 * y**4 / 4)

    m0 = moments(b)[0] - moments(a)[0]
    m1 = moments(b)[1] - moments(a)[1]
    share, _ = tank_strip_shares(y1, y2, c, tank_y=m1 / m0, side_of_body=3.0, y_inboard=a, y_outboard=b)
    assert np.sum(share * 0.5 * (y1 + y2)) == pytest.approx(m1 / m0, abs=2e-3)
    assert cr > 0


def test_centre_and_left_tanks():
    y1, y2, c = _strips()
    centre, _ = tank_strip_shares(y1, y2, c, tank_y=0.0, side_of_body=3.0)
    left, _ = tank_strip_shares(y1, y2, c, tank_y=-12.0, side_of_body=3.0)
    assert centre.sum() == pytest.approx(0.5) and np.all(centre[0.5 * (y1 + y2) > 3.0] == 0)
    assert left.sum() == 0.0


@pytest.fixture(scope="module")
def baseline():
    return Context(load_aircraft(BASELINE))


def test_main_tank_bending_relief_is_its_mass_times_arm(baseline):
    """Beam statics (Megson §16.1): a kilogram of main-tank fuel at 1 g relieves the side-of-body bending by g × (its
    declared centroid |y| 43.8 ft − the side of body, half the fuselage width): the bay is placed so that its centroid
    is the declared one; the dihedral's cos Γ cancels between the normal component and the arm along the span. 1 %:
    the strips' discretisation of the bay ends and the station."""
    wing = airplane_loads(baseline)["wing"]
    per_kg = wing.fuel_loads({"n_z": np.array(1.0)})
    k = wing.tank_names.index("right main")
    s = wing.station_names.index("side of body")
    arm = 43.8 * FT - 0.5 * baseline.aircraft.geometry.fuselage.width
    assert per_kg[k, 1, s] == pytest.approx(-G0 * arm, rel=0.01)
    # the whole tank is outboard of the side of body: shear normal to the wing plane, the weight's g cos Γ
    assert per_kg[k, 0, s] == pytest.approx(-G0 * np.cos(baseline.aircraft.geometry.wing.dihedral), rel=1e-6)
    assert np.all(per_kg[wing.tank_names.index("left main")] == 0)
    # the centre tank lies inboard of the side of body: only the strip the station cuts carries a little of it outboard
    centre = per_kg[wing.tank_names.index("centre"), :, s]
    assert np.all(np.abs(centre) < 0.03 * np.abs(per_kg[k, :, s]))


def test_fuel_states_at_the_baseline_weights(baseline):
    """§25.343(a) range at the envelope's weights by hand (aircraft/lta.yaml: MZFW 430,000 lb, OEW 304,500 lb, tanks
    2 × 64,050 + 174,870 lb, max fuel 302,900 lb): at MRW 657,000 lb from 227,000 lb (the mains full) to 302,900 lb; at
    MLW 460,000 lb from 30,000 lb (all in the mains, used last) to 155,500 lb."""
    ac = baseline.aircraft
    lo, hi = fuel_range(ac, 657000 * LB)
    assert lo == pytest.approx(227000 * LB) and hi == pytest.approx(302900 * LB)
    names, fuel = fuel_states(ac, 460000 * LB)
    tanks = [t.name for t in ac.mass.fuel_tanks]
    assert fuel.shape == (4, 3)
    least = dict(zip(tanks, fuel[0]))
    assert least["right main"] == pytest.approx(15000 * LB) and least["centre"] == 0.0
    most = dict(zip(tanks, fuel[-1]))
    assert most["right main"] == pytest.approx(64050 * LB) and most["centre"] == pytest.approx((155500 - 128100) * LB)
    assert names[0].startswith("least fuel") and names[-1].startswith("most fuel")
    assert "left main and right main full" in names[1]


def test_compiled_fuel_state_peaks_equal_the_plain_sums():
    """The compiled per-state peaks equal, state by state, the NumPy sum total + Σ_k m_k Σ_j x_j T_kj (the per-kilogram
    loads of each tank from the inertial terms) and its NaN-ignoring extremes over time (all-NaN stays NaN)."""
    from certkit.models.loads.response import fuel_state_peaks

    rng = np.random.default_rng(3)
    nt, n, k, j, s = 40, 6, 3, 5, 4
    total, x = rng.normal(size=(nt, n, 3, s)), rng.normal(size=(nt, n, j))
    tables, fuel = rng.normal(size=(k, j, 3, s)), rng.uniform(size=(n, 4, k))
    total[5:9, 2] = np.nan
    total[:, 4] = np.nan
    got = fuel_state_peaks(total, (x, tables), fuel)
    units = np.einsum("tnj,kjqs->tnkqs", x, tables)
    for m in range(4):
        loads = total + np.einsum("tnkqs,nk->tnqs", units, fuel[:, m])
        lo, hi = np.fmin.reduce(loads, axis=0), np.fmax.reduce(loads, axis=0)
        assert np.allclose(got[m, :, 0], lo, equal_nan=True) and np.allclose(got[m, :, 1], hi, equal_nan=True)
    assert np.all(np.isnan(got[:, 4]))


def test_a_tank_bay_that_does_not_hold_its_centroid_is_an_input_error(tmp_path, cli):
    """Bad input: declared bay ends that do not bracket the tank's centroid are reported with the YAML path and line,
    and the CLI exits 2."""
    from certkit.errors import InputError

    from ..rules.helpers import edited_baseline

    bad = edited_baseline(
        tmp_path,
        [
            (
                "{name: right main, capacity: 64050 lb, cg: {x: 104.7 ft, y: 43.8 ft, z: -2.0 ft}}",
                "{name: right main, capacity: 64050 lb, cg: {x: 104.7 ft, y: 43.8 ft, z: -2.0 ft}, "
                "y_inboard: 50 ft, y_outboard: 90 ft}",
            )
        ],
    )
    with pytest.raises(InputError) as info:
        load_aircraft(bad)
    (p,) = [p for p in info.value.problems if p.path.startswith("mass.fuel_tanks.1")]
    assert "must lie between y_inboard" in p.message
    assert p.line == next(i for i, t in enumerate(bad.read_text().splitlines(), 1) if "y_inboard: 50 ft" in t)
    assert cli("check", bad, "--select", "25.331(b)", "--out", tmp_path / "out").exit_code == 2
