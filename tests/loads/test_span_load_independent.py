"""The wing strips' span load against an independent one: Weissinger's three-quarter-chord method written in the
test helper (tests/loads/hand_span_load.py, from Bertin & Cummings §7.5 and Katz & Plotkin §12.2, compressibility by
the Göthert rule), itself checked against the textbook's worked example and the lifting-line limit. The strips come
from certkit's multi-panel
vortex lattice with dihedral and the fuselage-crossing root: a wrong span load, a wrong Mach dependence or a
strip-to-station mistake moves the centroid of the additional load, which sets the wing's bending per unit lift."""

import numpy as np
import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.models.loads.model import airplane_loads

from ..conftest import BASELINE
from .hand_span_load import lift_centroid, weissinger


def _cl_alpha(area, ar, taper, sweep, panels):
    y, gamma = weissinger(area, ar, taper, sweep, panels=panels)
    return 2 * 2 * np.sum(gamma) * (y[1] - y[0]) / area  # both halves: CL = 2 Σ Γ Δy / (V S), Γ per unit V α


def test_weissinger_helper_against_the_textbook_example_and_the_2d_limit():
    """Bertin & Cummings, *Aerodynamics for Engineers*, worked example of the vortex-lattice method (one chordwise
    panel, four spanwise panels per half): a wing of aspect ratio 5, taper 1, 45° sweep has C_L = 3.443 α (0.1 %);
    and a wing of aspect ratio 1000 has the 2-D slope reduced by lifting-line theory, 2π A / (A + 2) (0.5 %)."""
    assert _cl_alpha(5.0, 5.0, 1.0, np.radians(45.0), 4) == pytest.approx(3.443, rel=1e-3)
    assert _cl_alpha(1000.0, 1000.0, 1.0, 0.0, 200) == pytest.approx(2 * np.pi * 1000 / 1002, rel=5e-3)


@pytest.mark.parametrize("mach", [0.5, 0.85])
def test_additional_span_load_centroid_against_weissinger(mach):
    """The spanwise centroid of the strips' normal force per unit α (the additional load; twist and camber drop out of
    the derivative) at two Mach numbers, against Weissinger's on the declared trapezoid (area, aspect ratio, taper,
    quarter-chord sweep of aircraft/lta.yaml) — 0.42 and 0.43 of the semispan: within 2 % (one chordwise panel against
    several, the dihedral and the lattice's spanwise spacing); and both move outboard from M 0.5 to 0.85."""
    ctx = Context(load_aircraft(BASELINE))
    wing = airplane_loads(ctx)["wing"]
    g = ctx.aircraft.geometry.wing
    force = wing.strip_normal_force(1.0, mach, {"alpha": 1.0}) - wing.strip_normal_force(1.0, mach, {"alpha": 0.0})
    y_strip = wing.strip_span * np.cos(g.dihedral)
    strips = np.sum(force * y_strip) / np.sum(force)
    yw, gw = weissinger(g.area, g.aspect_ratio, g.taper, g.sweep_quarter_chord, mach)
    assert strips == pytest.approx(lift_centroid(yw, gw), rel=0.02)
    low = wing.strip_normal_force(1.0, 0.5, {"alpha": 1.0}) - wing.strip_normal_force(1.0, 0.5, {"alpha": 0.0})
    yl, gl = weissinger(g.area, g.aspect_ratio, g.taper, g.sweep_quarter_chord, 0.5)
    if mach > 0.5:
        assert strips > np.sum(low * y_strip) / np.sum(low) and lift_centroid(yw, gw) > lift_centroid(yl, gl)
