"""The baseline's pitch control power against the Boeing 747's published one.

Reference (no one here wrote it): Boeing 747, M 0.8, 40,000 ft (Etkin & Reid, *Dynamics of Flight*, 3rd ed., §6.2,
from Heffley & Jewell, NASA CR-2144; data in ``tests/dynamics/b747_etkin.py``): CL_δe 0.3648, Cm_δe −1.444 per rad
(S 5,500 ft², c̄ 27.31 ft). The 747's tailplane: 1,469.6 ft², arm 106.6 ft (JSBSim's B747 model, metrics
``htailarea`` and ``htailarm``, the peer tool's data).

The two tails differ in size and arm, so the elevator's lift is compared per unit of tailplane area
(CL_δe · S / S_h: the tail's lift slope times the elevator's effectiveness τ) and its moment per unit of tail volume
(Cm_δe / V_H, V_H = S_h l_h / (S c̄)); tolerance ±30 %, as for the directional derivatives
(tests/aero/test_directional_against_747.py). The lattice's control derivatives themselves agree with AVL's
(tests/aero/test_vlm_avl.py): a gap here is the inviscid method's against the airplane's, not the implementation's.
"""

import math

import pytest

from certkit.models.aero.planform import mac_spanwise_position, mean_aerodynamic_chord, sweep_at
from certkit.units import FT
from tests.aero.test_directional_against_747 import BAND
from tests.dynamics.b747_etkin import CBAR as CBAR_747_M
from tests.dynamics.b747_etkin import CL_DE, CM_DE
from tests.dynamics.b747_etkin import S as S_747_M2

SH_747, LH_747 = 1469.6 * FT**2, 106.6 * FT  # JSBSim B747 metrics
V_H_747 = SH_747 * LH_747 / (S_747_M2 * CBAR_747_M)


@pytest.fixture(scope="module")
def pitch(baseline):
    from certkit.engine.context import Context

    model = Context(baseline).aero("clean").model
    ht, ref = baseline.model.geometry.horizontal_tail, model.reference
    A, lam = ht.aspect_ratio, ht.taper
    # the tail's arm: the quarter chord of its mean aerodynamic chord behind the moment reference
    y_mac = mac_spanwise_position(ht.area, A, lam)
    x_mac = y_mac * math.tan(sweep_at(0.0, ht.sweep_quarter_chord, A, lam))
    arm = ht.root_leading_edge.x + x_mac + 0.25 * mean_aerodynamic_chord(ht.area, A, lam) - ref.x_ref
    return {
        "CL": float(model.derivative("CL_elevator", 0.8)),
        "Cm": float(model.derivative("Cm_elevator", 0.8)),
        "S": ref.area,
        "S_h": ht.area,
        "V_H": ht.area * arm / (ref.area * ref.chord),
    }


def test_the_747_reference_is_read_as_published():
    """The 747's tail volume from the JSBSim metrics and Etkin's wing: about 1.04 (a large tail, as on the 747)."""
    assert V_H_747 == pytest.approx(1.043, abs=0.002)


@pytest.mark.xfail(
    strict=True,
    reason="the elevator's lift per unit tailplane area at M 0.8 is 1.80 × the 747's (CL_δe S/S_h 2.45 against "
    "1.37) and its moment per unit tail volume 1.84 × (Cm_δe/V_H −2.55 against −1.38): the lattice's control "
    "effectiveness is thin-airfoil theory's (τ ≈ 0.65 at 29 % chord), with no viscous (DATCOM's empirical factor, "
    "about 0.8 at this chord), gap, large-deflection or aeroelastic loss; part of the rest may be the two elevators' "
    "layouts, which the published data do not give. A named model limit, docs/baseline-sources.md §16 "
    "'Pitch control power'",
)
@pytest.mark.parametrize("which", ["lift per unit tail area", "moment per unit tail volume"])
def test_elevator_power_at_cruise_against_the_747(pitch, which):
    if which == "lift per unit tail area":
        ours, theirs = pitch["CL"] * pitch["S"] / pitch["S_h"], CL_DE * S_747_M2 / SH_747
    else:
        ours, theirs = pitch["Cm"] / pitch["V_H"], CM_DE / V_H_747
    assert ours / theirs == pytest.approx(1.0, abs=BAND)


def test_the_elevator_lever_is_the_geometry_s(pitch):
    """Cm_δe/CL_δe is the elevator lift's lever in chords: the baseline's tail arm over its c̄ (about 3.2–3.4), the
    747's 3.96 over its own; the pitch-power gap above is the lift's, not the lever's."""
    assert pitch["Cm"] / pitch["CL"] == pytest.approx(-pitch["V_H"] * pitch["S"] / pitch["S_h"], rel=0.12)
