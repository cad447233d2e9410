"""The lattice represents the declared linear twist of a tapered wing, whatever its control edges.

AVL (and certkit's lattice after it) interpolates a strip's incidence between two sections through the chord
projections, c sin i and c cos i, which on a tapered wing keeps the larger inboard chord's angle over most of the
interval. With sections only at the root, the control edges and the tip, the baseline's wing (taper 0.18, 4° of
washout) had up to 0.77° more incidence than the declared linear twist at mid-semispan, and its zero-α lift changed by
7 % when a flap edge added two sections.
"""

import numpy as np
import pytest

from certkit.models.aero.airplane import lattice_configuration
from certkit.models.aero.vlm import VortexLattice


def _symmetric_section_wing(aircraft):
    wing = aircraft.geometry.wing.model_copy(update={"airfoil": "NACA 0011"})
    return aircraft.model_copy(update={"geometry": aircraft.geometry.model_copy(update={"wing": wing})})


def test_strip_incidence_follows_the_declared_linear_twist(baseline):
    """Symmetric sections, so that each control point's normal tilts by the strip's incidence alone: the incidence at
    every strip of the right wing equals i_root + twist × y / (b/2) at the strip's centre within 0.05°."""
    aircraft = _symmetric_section_wing(baseline.model)
    wing = aircraft.geometry.wing
    lat = VortexLattice(lattice_configuration(aircraft), mach=0.2).lattice
    right = np.flatnonzero((lat.component == 1) & (lat.rle[:, 1] > 0))
    normal = lat.normal[lat.first[right]]
    incidence = np.arctan2(normal[:, 0], np.hypot(normal[:, 1], normal[:, 2]))
    y = lat.rle[right, 1]
    declared = wing.incidence + wing.tip_twist * y / lat.rle2[right, 1].max()
    assert np.degrees(np.abs(incidence - declared)).max() < 0.05


def test_zero_alpha_lift_does_not_depend_on_the_flap_edges(baseline):
    """The lattice with the wing's flap as a control (sections at the flap's ends, the strip loads' lattice) and
    without it: the same zero-α lift and lift slope within 1 % (they differed by 7 % in CL0 before the twist
    sections)."""
    plain = VortexLattice(lattice_configuration(baseline.model), mach=0.2)
    flap = VortexLattice(lattice_configuration(baseline.model, flap=True), mach=0.2)
    assert "flap" in flap.control_names and "flap" not in plain.control_names
    a, b = plain.solve(alpha=0.0), flap.solve(alpha=0.0)
    assert b.CL == pytest.approx(a.CL, rel=0.01)
    slope = [(v.solve(alpha=0.01).CL - v.solve(alpha=0.0).CL) / 0.01 for v in (plain, flap)]
    assert slope[1] == pytest.approx(slope[0], rel=0.01)
