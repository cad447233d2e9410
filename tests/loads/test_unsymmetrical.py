"""Unsymmetrical wing air load (§25.349(b), certkit.models.loads.unsymmetrical) on the baseline's wing loads model:
the moment about the plane of symmetry against the strips' forces and positions, the 100/80 % split by hand with the
inertia tables zeroed, the unbalance and its reacting accelerations by hand, the signs of the roll reaction, and the
degenerate cases (equal fractions, the increment basis with no increment)."""

from dataclasses import replace

import numpy as np
import pytest

from certkit.engine.context import Context
from certkit.models.loads.model import _strip_indices, airplane_loads
from certkit.models.loads.unsymmetrical import half_wing_moment, unsymmetrical_wing
from certkit.units import G0

QBAR, MACH, ALPHA = 20e3, 0.8, np.radians(4.0)  # Pa, –, rad: a gust-loaded cruise state
MASS = np.array([250e3])  # kg
CG = np.array([[30.0, 0.0, 0.5]])  # m, airplane frame (X aft, Z up)
J = np.diag([2.0e7, 3.0e7, 4.8e7])[None]  # kg·m², body axes


@pytest.fixture(scope="module")
def wing_case(baseline):
    ctx = Context(baseline)
    wing = airplane_loads(ctx)["wing"]
    inputs = {"alpha": np.array([ALPHA])}
    aero = wing.aero_loads(np.array([QBAR]), np.array([MACH]), inputs)  # (1, 3, S)
    inertia = wing.inertia_loads({"n_z": np.array([1.8])})
    return ctx, wing, aero, inertia, inputs


def test_half_wing_moment_against_strip_forces(wing_case):
    """Σ N_j (y_j n_z,j − (z_j − Z_root) n_y,j) over the lattice strips (forces at the strip centres, normals of
    the strips): the moment of the half wing's normal forces about the X axis through the root, which for a plane
    half wing is the root bending B plus S × Y_root. Tolerance 1 %: the strip normals are also tilted by the
    incidence and twist (a few degrees: cos 5° = 0.996), which the plane-surface formula of the station loads
    does not see (0.37 % on the baseline)."""
    ctx, wing, aero, _, inputs = wing_case
    lat = ctx.aero("clean").lattice.lattice
    idx = _strip_indices(lat, "wing")
    N = wing.strip_normal_force(np.array([QBAR]), np.array([MACH]), inputs)[0]
    sign = np.sign(lat.ensz[idx])
    ny, nz = lat.ensy[idx] * sign, lat.ensz[idx] * sign
    y = 0.5 * (lat.rle1[idx, 1] + lat.rle2[idx, 1])
    z = 0.5 * (lat.rle1[idx, 2] + lat.rle2[idx, 2])
    z_root = min(lat.rle1[idx[0], 2], lat.rle2[idx[0], 2])
    by_strips = float(np.sum(N * (y * nz - (z - z_root) * ny)))
    assert by_strips > 0
    assert float(half_wing_moment(wing, aero)[0]) == pytest.approx(by_strips, rel=1e-2)


def test_split_without_wing_mass_and_the_unbalance_by_hand(wing_case):
    """With the wing's inertia tables zeroed the sides are exactly 1.0 A + I and 0.8 A + I (§25.349(b)); the
    unbalance by hand from the root loads: ΔF = −0.2 S, Δn = ΔF/(m g); ΔL = −0.2 M (M = B + S Y_root, body axes,
    the full side on the right rolls it up: negative); ṗ = ΔL/I_xx; q̇ = ΔF (X_cg − X_cp)/I_yy with
    X_cp = X_axis − T/S. Tolerance 1e-9 relative (arithmetic)."""
    _, wing, aero, inertia, _ = wing_case
    massless = replace(wing, inertia=np.zeros_like(wing.inertia))
    u = unsymmetrical_wing(massless, aero, inertia, MASS, CG, J)
    np.testing.assert_allclose(u.full, aero + inertia, rtol=1e-12)
    np.testing.assert_allclose(u.reduced, 0.8 * aero + inertia, rtol=1e-12)
    S, B, T = (float(aero[0, k, 0]) for k in range(3))
    M = B + S * wing.station_y[0]
    assert float(u.delta_n_z[0]) == pytest.approx(-0.2 * S / (MASS[0] * G0), rel=1e-9)
    assert float(u.rolling_moment[0]) == pytest.approx(-0.2 * M, rel=1e-9)
    assert float(u.pdot[0]) == pytest.approx(-0.2 * M / J[0, 0, 0], rel=1e-9)
    x_axis = float(np.interp(0.0, wing.strip_span, wing.strip_x))
    x_cp = x_axis - T / S
    assert float(u.qdot[0]) == pytest.approx(-0.2 * S * (CG[0, 0] - x_cp) / J[0, 1, 1], rel=1e-9)
    # sanity of the hand numbers: an up load of a few meganewtons, the roll acceleration of a large airplane
    assert S > 1e6 and -1.0 < float(u.pdot[0]) < 0.0


def test_inertia_reaction_signs(wing_case):
    """With the wing's masses, the rising full side is relieved by its strips' roll inertia and the falling reduced
    side loaded more: compared with the vertical reaction alone (Δn, q̇), the full side's root bending is lower and
    the reduced side's higher, by the same roll term (mirror image)."""
    _, wing, aero, inertia, _ = wing_case
    u = unsymmetrical_wing(wing, aero, inertia, MASS, CG, J)
    xcg = CG[:, 0]
    vertical = wing.inertia_loads({"n_z": u.delta_n_z, "qdot": u.qdot, "qdot_xcg": u.qdot * xcg})
    roll_full = u.full - (aero + inertia + vertical)
    roll_reduced = u.reduced - (0.8 * aero + inertia + vertical)
    assert roll_full[0, 1, 0] < 0 < roll_reduced[0, 1, 0]
    np.testing.assert_allclose(roll_full[0, :2], -roll_reduced[0, :2], rtol=1e-9, atol=1e-6)
    assert u.delta_n_z[0] < 0  # the reduced side's lost lift


def test_equal_fractions_and_increment_without_increment_change_nothing(wing_case):
    """100 %/100 %: no unbalance, both sides are the symmetric loads; the increment basis with the trim air load
    equal to the air load (no gust increment) also changes nothing."""
    _, wing, aero, inertia, _ = wing_case
    same = unsymmetrical_wing(wing, aero, inertia, MASS, CG, J, full=1.0, reduced=1.0)
    none = unsymmetrical_wing(wing, aero, inertia, MASS, CG, J, trim_aero=aero)
    for u in (same, none):
        np.testing.assert_allclose(u.full, aero + inertia, rtol=1e-12)
        np.testing.assert_allclose(u.reduced, aero + inertia, rtol=1e-12)
        assert float(u.rolling_moment[0]) == 0.0 and float(u.delta_n_z[0]) == 0.0


def test_tail_split_peaks_are_the_extremes_of_the_split_histories(wing_case):
    """§25.427(b) reduces each split time history to its extremes: the one-pass peaks equal NaN-ignoring min/max of
    the split histories (an all-NaN time column, a state that was not balanced, stays NaN)."""
    import warnings

    from certkit.models.loads.unsymmetrical import unsymmetrical_tail, unsymmetrical_tail_peaks

    ctx = wing_case[0] if isinstance(wing_case, tuple) else wing_case
    tail = airplane_loads(ctx)["horizontal_tail"]
    rng = np.random.default_rng(3)
    S = tail.station_span.size
    aero, inertia = rng.normal(size=(2, 50, 4, 3, S)) * 1e5
    aero[10:20, 1] = np.nan
    aero[:, 3] = np.nan
    split = unsymmetrical_tail(tail, aero, inertia, 1.0, 0.8)
    p_full, p_red, t_lo, t_hi = unsymmetrical_tail_peaks(tail, aero, inertia, 1.0, 0.8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        for peaks, hist in ((p_full, split.full), (p_red, split.reduced)):
            np.testing.assert_array_equal(peaks[:, 0], np.nanmin(hist, axis=0))
            np.testing.assert_array_equal(peaks[:, 1], np.nanmax(hist, axis=0))
        np.testing.assert_array_equal(t_lo, np.nanmin(split.fuselage_torsion, axis=0))
        np.testing.assert_array_equal(t_hi, np.nanmax(split.fuselage_torsion, axis=0))
    assert np.isnan(p_full[3]).all() and np.isfinite(p_full[:3]).all()
