"""Hinge moments from the vortex lattice (certkit.models.aero.hinge_moment) against AVL 3.52 through optvl 2.5
(``OVLSolver.get_hinge_moments``: CHINGE = H / (q Sref Cref)) on the AVL Boeing 737 sample
(/work/shared/reference/avl-b737, elevator hinged at 60–75 % chord), Mach 0.5. AVL's coefficient is ours
H/q divided by Sref·Cref. Tolerance: 2 % relative or 2e-6 absolute (they agree to ~0.5 % in practice)."""

from __future__ import annotations

import math
import os

import pytest

from certkit.models.aero.hinge_moment import hinge_moment_derivatives, hinge_moment_over_q
from certkit.models.aero.vlm import VortexLattice
from certkit.models.aero.vlm.avl_file import read_avl

from ..conftest import ROOT, SHARED_REFERENCE

# the checkout's sibling shared/ folder, or (from a git worktree one level deeper) its parent's
REFERENCE = next(
    (
        p / "avl-b737"
        for p in (SHARED_REFERENCE, ROOT.parents[1] / "shared" / "reference")
        if (p / "avl-b737" / "b737.avl").is_file()
    ),
    SHARED_REFERENCE / "avl-b737",
)
STATES = ((0.0, 0.0), (2.0, 0.0), (0.0, 2.0), (3.0, -2.0))  # (α, elevator) in degrees
pytestmark = pytest.mark.skipif(not (REFERENCE / "b737.avl").is_file(), reason="AVL b737 sample not found")


@pytest.fixture(scope="module")
def avl():
    optvl = pytest.importorskip("optvl")
    cwd = os.getcwd()
    os.chdir(REFERENCE)
    try:
        solver = optvl.OVLSolver(geo_file="b737.avl", mass_file="b737.mass")
    finally:
        os.chdir(cwd)
    solver.set_parameter("Mach", 0.5)
    out = {}
    for a, d in STATES:
        solver.set_constraint("alpha", "alpha", a)
        solver.set_constraint("elevator", "elevator", d)
        solver.execute_run()
        out[(a, d)] = float(solver.get_hinge_moments()["elevator"])
    return out


@pytest.fixture(scope="module")
def lattice():
    return VortexLattice(read_avl(REFERENCE / "b737.avl"), mach=0.5)


def test_hinge_moment_vs_avl(lattice, avl):
    ref = lattice.reference.area * lattice.reference.chord
    for (a, d), expected in avl.items():
        ours = hinge_moment_over_q(lattice, "elevator", math.radians(a), {"elevator": math.radians(d)}) / ref
        assert abs(ours - expected) <= max(0.02 * abs(expected), 2e-6), (a, d, ours, expected)


def test_derivatives_vs_avl_finite_differences(lattice, avl):
    """Ch_α and Ch_δ (per radian, referred to the elevator's area and mean chord) against AVL's differences over
    2° (AVL's CHINGE is linear in α and δ at fixed geometry: exact up to round-off)."""
    d = hinge_moment_derivatives(lattice, "elevator")
    scale = lattice.reference.area * lattice.reference.chord / (d.area * d.chord)
    ch_alpha = (avl[(2.0, 0.0)] - avl[(0.0, 0.0)]) / math.radians(2.0) * scale
    ch_delta = (avl[(0.0, 2.0)] - avl[(0.0, 0.0)]) / math.radians(2.0) * scale
    assert d.Ch_alpha == pytest.approx(ch_alpha, rel=0.02)
    assert d.Ch_delta == pytest.approx(ch_delta, rel=0.02)
    assert d.Ch_delta < 0 and d.Ch_alpha < 0  # restoring; thin-airfoil signs (Abbott & von Doenhoff §8.7)
    assert d.moment(1e4, 0.0, 0.0) == pytest.approx(1e4 * d.area * d.chord * d.Ch_0)
