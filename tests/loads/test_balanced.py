"""Balanced symmetric manoeuvres (certkit.models.loads.balanced) against the textbook balancing tail load.

Reference: the moment balance of an airplane in a steady pull-out (Megson, *Aircraft Structures for Engineering
Students*, 4th ed., §14.1 "symmetric manoeuvre loads": the tail load P from moments about the CG of the wing-body
lift L_wb at its aerodynamic centre, the wing-body moment M₀ and the tail load at the tail arm, with L_wb + P = nW),
which gives the tail's lift P = (n W d + M₀) / l_t for a wing-body aerodynamic centre a distance d ahead of the CG and
the tail's lift a distance l_t behind that centre; and the pull-up rate q = g (n − 1)/V (Etkin & Reid, *Dynamics of
Flight*, 3rd ed., §6.7). The two-surface airplane below is built from those parts, so the tail lift of the solved
state can be read off its own terms and compared with the hand balance.
"""

import numpy as np
import pytest

from certkit.models.aero.derivative_model import StabilityDerivativeModel, StallModel
from certkit.models.aero.interface import AeroReference
from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.trim import assemble_state
from certkit.models.loads.balanced import balanced_states, linear_lift

G = 9.80665
S, B, C = 100.0, 30.0, 3.5
A_WB, A_T, TAU, L_T, CM0 = 5.0, 0.6, 0.5, 15.0, -0.08  # wing-body slope, tail slope (on S), elevator τ, arm (m), Cm₀


def two_surface(x_cg, stall=None, stabilizer=False):
    """Wing-body at its aerodynamic centre X = 10 m (the moment reference), tail lift a_t (α + τ δe + q l_t/V) on S at
    L_T behind it; no downwash, no engines. Derivatives per radian and per q̂ = q c̄ / 2V. With ``stabilizer`` the
    tail's incidence i_s is a control too, adding a_t i_s to the tail's lift."""
    d = {
        "CL_alpha": A_WB + A_T,
        "CL_elevator": A_T * TAU,
        "CL_q": 2 * A_T * L_T / C,
        "Cm0": CM0,
        "Cm_alpha": -A_T * L_T / C,
        "Cm_elevator": -A_T * TAU * L_T / C,
        "Cm_q": -2 * A_T * (L_T / C) ** 2,
        "CD0": 0.02,
        "k": 0.04,
    }
    controls = ("elevator",)
    if stabilizer:
        d.update({"CL_stabilizer": A_T, "Cm_stabilizer": -A_T * L_T / C})
        controls += ("stabilizer",)
    aero = StabilityDerivativeModel(
        AeroReference(S, B, C, x_ref=10.0, z_ref=0.0), d, control_names=controls, stall=stall
    )
    mass = np.array([40000.0, 40000.0])
    return AircraftModel(aero, mass, np.array([[x_cg, 0.0, 0.0]] * 2), np.diag([1e6, 2e6, 3e6]))


@pytest.mark.parametrize("n", [1.0, 2.5, -1.0, 0.0])
def test_balancing_tail_load_matches_the_moment_balance(n):
    x_cg = 10.6  # the wing-body lift acts 0.6 m ahead of the CG
    model = two_surface(x_cg)
    V = np.array([120.0, 180.0])
    x0 = assemble_state(V, np.array([0.0, 3000.0]), 0.05, 0.0, 0.0, 0.0, 0.0)
    st = balanced_states(model, x0, np.zeros((2, 1)), n)
    assert st.converged.all()
    rho = np.array([1.225, 0.9093])  # ISA sea level, 3,000 m
    qbar = 0.5 * rho * V**2
    W = 40000.0 * G
    # pull-up rate of Etkin & Reid §6.7
    np.testing.assert_allclose(st.pitch_rate, G * (n - 1.0) / V, rtol=1e-9)
    # tail lift of the solved state, from its own terms: a_t (α + τ δe + q l_t / V) q̄ S
    alpha, de, q = st.alpha, st.u[:, 0], st.pitch_rate
    tail = A_T * (alpha + TAU * de + q * L_T / V) * qbar * S
    hand = (n * W * (x_cg - 10.0) + CM0 * qbar * S * C) / L_T  # Megson §14.1: P = (n W d + M₀)/l_t
    # the path-normal force balance holds the total lift to n W within the drag's share along the body normal
    # (D sin α with α ≤ 0.3 rad: ≤ 0.3 % of nW here) — 0.5 % of nW on the tail load
    np.testing.assert_allclose(tail, hand, atol=5e-3 * abs(W) * max(abs(n), 1.0))
    lift = (A_WB + A_T) * alpha * qbar * S + A_T * (TAU * de + 2 * L_T / C * q * C / (2 * V)) * qbar * S
    np.testing.assert_allclose(lift, n * W, rtol=5e-3, atol=5e-3 * W)


def test_linear_lift_reaches_cn_max_a_rounded_stall_does_not():
    """A stall-line point asks for C_N,max: with a rounded stall model (CLmax 1.2) the balance at C_L ≈ 1.32 cannot be
    found; the linear-lift copy finds it."""
    stall = StallModel(CLmax=1.2)
    model = two_surface(10.6, stall=stall)
    W = 40000.0 * G
    V = np.sqrt(2 * 2.5 * W / (1.225 * S * 1.32))  # 2.5 g at C_L = 1.32 = 1.1 × CLmax (sea level)
    x0 = assemble_state(np.array([V, V]), np.zeros(2), 0.05, 0.0, 0.0, 0.0, 0.0)
    rounded = balanced_states(model, x0, np.zeros((2, 1)), 2.5)
    linear = balanced_states(linear_lift(model), x0, np.zeros((2, 1)), 2.5)
    assert not rounded.converged.any()
    assert linear.converged.all()
    assert linear.outputs.CL[0] == pytest.approx(1.32, rel=0.01)


def test_a_balance_beyond_the_elevator_stop_retrims_the_stabiliser():
    """Where the elevator alone would pass its stop the stabiliser is retrimmed; the tail's balancing lift is set by
    the moment balance (Megson §14.1), not by the control that makes it, so the stabiliser does what the elevator
    would have: i_s = τ δe with the elevator back at its trim, i_s = τ (δe − δe_stop) with the elevator at its stop
    when the stabiliser alone would pass its own stop. A state beyond both stops is returned as it is."""
    from certkit.models.loads.balanced import (
        ELEVATOR_ALONE,
        ELEVATOR_AT_STOP,
        STABILIZER_RETRIMMED,
        balanced_within_stops,
    )

    model = two_surface(10.6, stabilizer=True)
    V = np.array([120.0, 120.0])
    x0 = assemble_state(V, np.zeros(2), 0.05, 0.0, 0.0, 0.0, 0.0)
    u0 = np.zeros((2, 2))
    free, _ = balanced_within_stops(model, x0, u0, -1.0, {"elevator": (-1.0, 1.0)})
    de = free.u[0, 0]
    assert de > np.radians(2.0)  # the push-over needs trailing edge down elevator

    wide = {"elevator": (-0.5 * de, 0.5 * de), "stabilizer": (-1.0, 1.0)}
    st, scheme = balanced_within_stops(model, x0, u0, -1.0, wide)
    assert (scheme == STABILIZER_RETRIMMED).all() and st.converged.all()
    np.testing.assert_allclose(st.u[:, 0], 0.0, atol=1e-12)
    np.testing.assert_allclose(st.u[:, 1], TAU * de, rtol=1e-5)
    np.testing.assert_allclose(st.alpha, free.alpha, rtol=1e-6)

    narrow = {"elevator": (-0.5 * de, 0.5 * de), "stabilizer": (-1.0, 0.4 * TAU * de)}
    st, scheme = balanced_within_stops(model, x0, u0, -1.0, narrow)
    assert (scheme == ELEVATOR_AT_STOP).all()
    np.testing.assert_allclose(st.u[:, 0], 0.5 * de, rtol=1e-12)
    np.testing.assert_allclose(st.u[:, 1], TAU * 0.5 * de, rtol=1e-5)
    assert (st.u[:, 1] > narrow["stabilizer"][1]).all()  # beyond the stabiliser's stop: the caller fails it

    within, scheme = balanced_within_stops(model, x0, u0, -1.0, {**wide, "elevator": (-2 * de, 2 * de)})
    assert (scheme == ELEVATOR_ALONE).all()
    np.testing.assert_allclose(within.u[:, 1], 0.0)
