"""Mass properties: parallel-axis theorem and inertia validity checks."""

import numpy as np
import pytest

from certkit.models.dynamics.eom import inertia_tensor
from certkit.models.mass.properties import (
    InertiaError,
    MassComponent,
    check_inertia,
    combine,
    combine_arrays,
    inertia_from_radii,
)


def test_parallel_axis_two_point_masses():
    """Two 1000 kg point masses 10 m apart along X and 2 m apart in Z: CG midway; about the CG
    Iyy = Σ m (dx² + dz²) = 2·1000·(5² + 1²) = 52 000 kg m², Izz = 2·1000·5² = 50 000,
    Ixx = 2·1000·1² = 2000, product Ixz = Σ m x z (body axes); each mass carries a small own
    inertia of 100 kg m² per axis (two collinear point masses alone would have a zero principal
    moment, which check_inertia rightly rejects). Reference: Steiner's theorem; tolerance 1e-9."""
    own = np.eye(3) * 100.0
    mp = combine([MassComponent("a", 1000.0, (0.0, 0.0, 0.0), own), MassComponent("b", 1000.0, (10.0, 0.0, 2.0), own)])
    assert mp.mass == 2000.0
    assert np.allclose(mp.cg, [5.0, 0.0, 1.0])
    assert mp.Iyy == pytest.approx(52_000.0 + 200.0, rel=1e-9)
    assert mp.Izz == pytest.approx(50_000.0 + 200.0, rel=1e-9)
    assert mp.Ixx == pytest.approx(2_000.0 + 200.0, rel=1e-9)
    # body x = −(X − Xcg), z = −(Z − Zcg): a at x=+5, z=+1; b at x=−5, z=−1 → Σ m x z = 2·1000·5
    assert mp.Ixz == pytest.approx(10_000.0, rel=1e-9)


def test_parallel_axis_with_own_inertia():
    """A component's own inertia adds to its transfer term (Steiner); tolerance 1e-9."""
    own = inertia_tensor(100.0, 200.0, 250.0, 10.0)
    mp = combine([MassComponent("a", 10.0, (0, 0, 0), own), MassComponent("b", 10.0, (0, 4.0, 0), own)])
    assert mp.Ixx == pytest.approx(2 * 100.0 + 2 * 10.0 * 2.0**2, rel=1e-9)
    assert mp.Iyy == pytest.approx(2 * 200.0, rel=1e-9)
    assert mp.Ixz == pytest.approx(20.0, rel=1e-9)


def test_non_positive_definite_rejected():
    """Ixz larger than √(Ixx Izz) makes the tensor indefinite: rejected with the principal moments."""
    with pytest.raises(InertiaError, match="not positive definite"):
        check_inertia(inertia_tensor(1.0e6, 2.0e6, 1.5e6, Ixz=2.0e6))


def test_triangle_inequality_rejected():
    """Ixx + Iyy < Izz cannot come from any mass distribution (it would need negative ∫z² dm)."""
    with pytest.raises(InertiaError, match="triangle"):
        check_inertia(np.diag([1.0e6, 1.0e6, 3.0e6]))


def test_radii_reproduce_747():
    """The default radii come from the 747 of Etkin & Reid (Ix 2.47e7, Iy 4.49e7, Iz 6.73e7 kg m²,
    m = 2.8866e5 kg, b = 59.64 m, L = 70.6 m): reproduced within 3 % (radii given to 2 digits)."""
    J = inertia_from_radii(2.8866e5, 59.64, 70.6)
    assert J[0, 0] == pytest.approx(2.47e7, rel=0.03)
    assert J[1, 1] == pytest.approx(4.49e7, rel=0.03)
    assert J[2, 2] == pytest.approx(6.73e7, rel=0.03)


def test_components_as_arrays_combine_as_the_components_do():
    """:func:`combine_arrays` with every component's own tensor as one array (the sized tail's strips) gives the mass,
    CG and inertia :func:`combine` gives for the same components, bit for bit; and Steiner's two point masses of
    the first test by hand (tolerance 1e-9)."""
    rng = np.random.default_rng(5)
    n = 50
    m = rng.uniform(1.0, 50.0, n)
    pos = rng.normal(0.0, 5.0, (n, 3))
    own = np.zeros((n, 3, 3))
    own[:, 1, 1] = own[:, 2, 2] = rng.uniform(0.1, 3.0, n)
    listed = combine([MassComponent(f"s{i}", float(m[i]), tuple(pos[i]), own[i]) for i in range(n)])
    arrays = combine_arrays(m, pos, own)
    assert arrays.mass == listed.mass
    np.testing.assert_array_equal(arrays.cg, listed.cg)
    np.testing.assert_array_equal(arrays.inertia, listed.inertia)
    two = combine_arrays(
        np.array([1000.0, 1000.0]),
        np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 2.0]]),
        np.eye(3)[None] * [[[100.0]], [[100.0]]],
    )
    assert (two.Iyy, two.Izz, two.Ixx, two.Ixz) == pytest.approx((52_200.0, 50_200.0, 2_200.0, 10_000.0), rel=1e-9)
