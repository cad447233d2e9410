"""The baseline's rudder power from the vortex lattice against an independent handbook estimate.

Reference: the USAF DATCOM / Roskam (Airplane Design Part VI, §10.3.8) build-up for a rudder,
    CY_δr = CL_α,v · τ · K_b · η_v · S_v/S,     Cn_δr = −CY_δr · l_v/b,
with CL_α,v the Helmbold/DATCOM slope of the fin at its effective aspect ratio (geometric h²/S_v times the
fuselage end-plate factor A_v(B)/A_v ≈ 1.5 read from DATCOM §5.3.1.1 for a fin span about 2.4 fuselage radii at
its root, horizontal tail low on the fuselage), τ the flap effectiveness — thin-airfoil 1 − (θ_f − sin θ_f)/π
with cos θ_f = 2 c_f/c − 1, times 0.8 for the viscous loss at t/c 0.10 (DATCOM §6.1.1.1; 1 for inviscid flow)
and 1.1 for the low-aspect-ratio gain (DATCOM §6.1.4.1) —, K_b ≈ 0.95 for a rudder over 0–93 % of the fin span (DATCOM
§6.1.5.1, taper 0.3), η_v = 0.95, l_v from the CG to the fin's MAC quarter chord. The lattice is inviscid linear
theory: its CY_δr must lie between the viscous and the inviscid handbook values (3 % allowance each side for the
chart readings); the lever arm Cn_δr/CY_δr within 10 % of the fin arm (the lattice puts the rudder's load where
it is, a little aft of the fin's quarter chord).
"""

import math

import pytest

from certkit.models.aero import planform
from certkit.models.aero.derivative_kernel import N_BASE


@pytest.fixture(scope="module")
def rudder(baseline):
    from certkit.engine.context import Context

    ctx = Context(baseline)
    model = ctx.aero("takeoff").model
    T = model.kernel_data[0]
    j = list(model.control_names).index("rudder")
    return ctx.aircraft, model, float(T[N_BASE + 6 * j + 2, 0]), float(T[N_BASE + 6 * j + 5, 0])


def handbook_cy_dr(ac, mach=0.2, viscous=0.8):
    v = ac.geometry.vertical_tail
    rud = v.controls["rudder"]
    a_eff = 1.5 * v.aspect_ratio
    sweep_half = planform.sweep_at(0.5, v.sweep_quarter_chord, 2 * v.aspect_ratio, v.taper)  # fin = half wing
    beta2 = 1 - mach**2
    a_v = (
        2 * math.pi * a_eff / (2 + math.sqrt(4 + a_eff**2 * beta2 / 0.95**2 * (1 + math.tan(sweep_half) ** 2 / beta2)))
    )
    theta_f = math.acos(2 * rud.chord_ratio - 1)
    tau = (1 - (theta_f - math.sin(theta_f)) / math.pi) * viscous * 1.1
    return a_v * tau * 0.95 * 0.95 * v.area / ac.reference.area


def fin_arm(ac, x_cg):
    v = ac.geometry.vertical_tail
    A2 = 2 * v.aspect_ratio  # the fin as half of a wing of twice its area
    z_mac = planform.mac_spanwise_position(2 * v.area, A2, v.taper)
    mac = planform.mean_aerodynamic_chord(2 * v.area, A2, v.taper)
    x_le = v.root_leading_edge.x + z_mac * math.tan(planform.sweep_at(0.0, v.sweep_quarter_chord, A2, v.taper))
    return x_le + 0.25 * mac - x_cg


def test_rudder_side_force_against_datcom(rudder):
    ac, model, cy_dr, cn_dr = rudder
    low, high = handbook_cy_dr(ac), handbook_cy_dr(ac, viscous=1.0)
    print(
        f"CY_δr lattice {cy_dr:.4f}/rad, handbook {low:.4f} (viscous) – {high:.4f} (inviscid)/rad; "
        f"Cn_δr lattice {cn_dr:.4f}/rad"
    )
    assert 0.97 * low <= cy_dr <= 1.03 * high


def test_rudder_yaw_lever_is_the_fin_arm(rudder):
    ac, model, cy_dr, cn_dr = rudder
    arm = fin_arm(ac, ac.reference.moment_point.x)
    assert -cn_dr / cy_dr * ac.reference.span == pytest.approx(arm, rel=0.10)
