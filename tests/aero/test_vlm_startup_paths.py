"""The lattice without numba and scipy.interpolate (`certkit derivatives FILE.avl` start-up), giving the
same bits as the compiled loops and scipy's spline.

* The Biot–Savart sums: numpy blocks against the numba loops on the lattice of examples/lta-clean.avl (compressible
  stretch, per-pair and shared core radii, own-vortex points): equal to the last bit.
* The camber-line spline: against scipy.interpolate.CubicSpline (not-a-knot, the reference implementation) to the
  last bit for the NACA camber lines and random knots, and against the closed form — a not-a-knot spline reproduces
  any cubic exactly (de Boor, *A Practical Guide to Splines*, ch. IV) — to 1e-12.
* The process: `certkit derivatives examples/lta-clean.avl` imports neither numba nor any part of scipy (the solve
  is numpy's LAPACK gesv; scipy.linalg is imported only to name the vortex of a singular lattice), nor numpy.ma or
  the study commands.
"""

import subprocess
import sys

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from certkit.models.aero.vlm import biot_savart_kernels as compiled
from certkit.models.aero.vlm import biot_savart_numpy as plain
from certkit.models.aero.vlm.avl_file import read_avl
from certkit.models.aero.vlm.cubic_spline import NotAKnotSpline
from certkit.models.aero.vlm.geometry import CamberLine
from certkit.models.aero.vlm.lattice import build_lattice

from ..conftest import ROOT

AVL = ROOT / "examples" / "lta-clean.avl"


@pytest.fixture(scope="module")
def lattice_args():
    lat = build_lattice(read_avl(AVL))
    cols = lambda v: tuple(np.ascontiguousarray(c) for c in v.T)  # noqa: E731
    stretch = np.array([1 / np.sqrt(1 - 0.7**2), 1.0, 1.0])
    coords = cols(lat.rc * stretch) + cols(lat.rv1 * stretch) + cols(lat.rv2 * stretch)
    m, n = lat.rc.shape[0], lat.rv1.shape[0]
    rng = np.random.default_rng(0)
    own = np.arange(m, dtype=np.int64)
    own[::3] = -1
    return (
        lat,
        coords,
        own,
        (np.ascontiguousarray(rng.random((1, n)) * 1e-3), np.ascontiguousarray(rng.random((m, n)) * 1e-3)),
    )


def test_numpy_biot_savart_equals_the_compiled_loops_bit_for_bit(lattice_args):
    lat, coords, own, cores = lattice_args
    m, n = lat.rc.shape[0], lat.rv1.shape[0]
    normals = tuple(np.ascontiguousarray(c) for c in lat.normal.T)
    for rc4 in cores:
        a, b = np.empty((m, n)), np.empty((m, n))
        plain.normalwash(*coords, rc4, *normals, own, a)
        compiled._normalwash(*coords, rc4, *normals, own, b)
        assert np.array_equal(a, b)
        a, b = np.empty((3, m, n)), np.empty((3, m, n))
        plain.velocity(*coords, rc4, 0.714, own, a)
        compiled._velocity(*coords, rc4, 0.714, own, b)
        assert np.array_equal(a, b)


@pytest.mark.parametrize("naca", ["2412", "4415", "0012", "6409"])
def test_camber_slope_equals_scipys_spline(naca):
    c = CamberLine.naca(naca)
    xq = np.linspace(-0.05, 1.05, 1001)
    assert np.array_equal(NotAKnotSpline(c.x, c.z).derivative(xq), CubicSpline(c.x, c.z)(xq, 1))


@pytest.mark.parametrize("n", [4, 5, 9, 50, 200])
def test_spline_equals_scipys_on_random_knots(n):
    rng = np.random.default_rng(n)
    x, y = np.sort(rng.random(n)), rng.random(n)
    xq = np.linspace(x[0] - 0.1, x[-1] + 0.1, 97)
    s, ref = NotAKnotSpline(x, y), CubicSpline(x, y)
    assert np.array_equal(s.derivative(xq), ref(xq, 1))
    assert np.allclose(s(xq), ref(xq), rtol=0, atol=1e-13 * np.max(np.abs(ref(xq))))  # values: unused by the lattice


@pytest.mark.parametrize("n", [2, 3, 4, 7, 30])
def test_spline_reproduces_polynomials_of_its_degree(n):
    """Not-a-knot reproduces a cubic (n ≥ 4), the parabola through 3 points, the line through 2."""
    x = np.sort(np.random.default_rng(7).random(n)) * 2.0 - 0.5
    coef = [0.3, -1.2, 0.7, 2.0][-min(n, 4) :]
    y, dy = np.polyval(coef, x), np.polyder(coef)
    xq = np.linspace(-0.6, 1.6, 50)
    assert np.allclose(NotAKnotSpline(x, y).derivative(xq), np.polyval(dy, xq), rtol=0, atol=1e-9)


#: what the `certkit derivatives FILE.avl` process must not load: numba and its cached kernels (0.3 s), scipy (its
#: import, 0.15-0.25 s, cost more than the whole lattice solution), numpy.ma (np.unique imports it: 10 ms) and the
#: study commands (5 ms)
NOT_LOADED = ("numba", "scipy", "numpy.ma", "certkit.cli.study")


def test_derivatives_process_imports_nothing_it_does_not_need():
    code = (
        "import sys\nfrom certkit.cli.main import main\nsys.argv = ['certkit', 'derivatives', sys.argv[1]]\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
        f"print('LOADED', [m for m in {NOT_LOADED!r} if m in sys.modules])"
    )
    out = subprocess.run([sys.executable, "-c", code, str(AVL)], capture_output=True, text=True, cwd=ROOT).stdout
    assert out.strip().splitlines()[-1] == "LOADED []"
