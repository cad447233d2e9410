"""Physical consistency of the batch 6-DoF equations, trim, linearisation and RK4 simulation."""

import numpy as np
import pytest

from certkit.models.aero.interface import AeroReference, Coefficients
from certkit.models.dynamics.eom import AircraftModel, energy, euler_to_quat, inertia_tensor
from certkit.models.dynamics.linearize import linearize
from certkit.models.dynamics.modes import identify_modes
from certkit.models.dynamics.simulate import Pulse, simulate
from certkit.models.dynamics.trim import trim
from certkit.units import G0

from . import b747_etkin as ref


class NoAero:
    """An AeroModel that produces nothing (vacuum)."""

    reference = AeroReference(area=100.0, span=30.0, chord=4.0, x_ref=10.0)
    control_names = ()

    def coefficients(self, state):
        z = np.zeros(np.shape(state.alpha))
        return Coefficients(z, z, z, z, z, z)


def test_energy_conserved_ballistic_with_rotation():
    """Aero and thrust off, a tumbling body with a full inertia tensor (Ixz ≠ 0) in free fall:
    kinetic + rotational + potential energy is constant. Reference: conservation of energy;
    tolerance 1e-8 relative over 20 s with RK4 at 100 Hz (RK4 local error O(dt⁵))."""
    J = inertia_tensor(2.0e7, 4.5e7, 6.0e7, Ixz=-2.0e6)
    model = AircraftModel(NoAero(), mass=2.5e5, cg=(10.0, 0.0, 0.0), inertia=J, n=3)
    x = np.zeros((3, 13))
    x[:, 2] = 10_000.0
    x[:, 3:6] = [[200.0, 5.0, 10.0], [100.0, 0.0, 0.0], [50.0, -20.0, 30.0]]
    x[:, 6:9] = [[0.3, 0.1, -0.2], [1.0, 0.0, 0.5], [0.0, 0.8, 0.05]]
    x[:, 9:13] = euler_to_quat(np.array([0.1, 1.0, -0.5]), np.array([0.2, 0.0, 1.2]), np.zeros(3))
    e0 = energy(model, x)
    res = simulate(model, x, np.zeros((3, 0)), 20.0, dt=0.01)
    e1 = energy(model, res.final_state)
    assert np.all(np.abs(e1 - e0) / np.abs(e0) < 1e-8)
    # angular momentum magnitude is conserved too (torque-free about the CG)
    w = res.final_state[:, 6:9]
    h0 = np.linalg.norm(np.einsum("nij,nj->ni", model.inertia, x[:, 6:9]), axis=1)
    h1 = np.linalg.norm(np.einsum("nij,nj->ni", model.inertia, w), axis=1)
    assert np.allclose(h0, h1, rtol=1e-8)


def test_trimmed_state_stays_trimmed_60s():
    """The Etkin 747 trimmed at 40 000 ft stays put for 60 s of simulation (RK4, 50 Hz):
    |Δα| < 1e-6 rad, |ΔV| < 1e-4 m/s, |Δh| < 1e-2 m — limited only by the trim tolerance."""
    model, h = ref.build(n=2)
    tb = trim(model, [ref.U0, 220.0], h)
    assert tb.converged.all()
    res = simulate(model, tb.x, tb.u, 60.0, dt=0.02)
    assert np.max(np.abs(res["alpha"] - res["alpha"][0])) < 1e-6
    assert np.max(np.abs(res["V"] - res["V"][0])) < 1e-4
    assert np.max(np.abs(res["h"] - res["h"][0])) < 1e-2
    assert np.allclose(res["n_z"], res["n_z"][0], atol=1e-6)  # = cos θ in level flight


def test_linear_and_nonlinear_pulse_responses_agree():
    """A 0.2° elevator pulse (1 s) on the 747: the nonlinear RK4 response and the linear
    response of the central-difference A, B (python-control) agree to 1 % of the peak in α and q
    over 30 s. Reference: small-perturbation theory (Etkin & Reid ch. 4)."""
    import control

    model, h = ref.build(n=1)
    tb = trim(model, ref.U0, h)
    de = np.radians(0.2)
    res = simulate(model, tb.x, tb.u, 30.0, dt=0.01, inputs={"elevator": Pulse(1.0, 1.0, de)})
    lin = linearize(model, tb.x, tb.u)
    sys = lin.statespace(0, inputs=["elevator"])
    t = res.t
    u = np.where((t >= 1.0) & (t < 2.0), de, 0.0)
    lr = control.forced_response(sys, T=t, U=u)
    names = lin.state_names
    w_lin = lr.states[names.index("w")]
    q_lin = lr.states[names.index("q")]
    alpha_lin = w_lin / ref.U0
    d_alpha = res["alpha"][:, 0] - res["alpha"][0, 0]
    d_q = res["q"][:, 0]
    assert np.max(np.abs(d_alpha - alpha_lin)) < 0.01 * np.max(np.abs(d_alpha))
    assert np.max(np.abs(d_q - q_lin)) < 0.01 * np.max(np.abs(d_q))


def test_lanchester_phugoid_period():
    """With the speed (Mach) derivatives removed and a tenth of the drag, the 747 phugoid period
    approaches Lanchester's T = π √2 V / g = 106.8 s (Etkin & Reid §6.3). Lanchester neglects
    the pitch dynamics; with the 747's pitch damping M_q the exact root is 6 % longer (Etkin's
    linear matrix with the same data gives 113.15 s, and 106.4 s with M_q = M_ẇ = 0), so the
    tolerance is 7 % against Lanchester and 0.5 % against the full linear matrix."""
    model, h = ref.build(n=1, mach_effects=False, cd=0.0043)
    tb = trim(model, ref.U0, h)
    modes = identify_modes(linearize(model, tb.x, tb.u), 0)
    lanchester = np.pi * np.sqrt(2.0) * ref.U0 / ref.G
    assert modes["phugoid"].period == pytest.approx(lanchester, rel=0.07)
    assert modes["phugoid"].period == pytest.approx(113.15, rel=0.005)
    assert modes["phugoid"].damping_ratio < 0.02


def test_phugoid_density_gradient_stiffening():
    """The phugoid with the density gradient (Etkin & Reid, 3rd ed., §6.5, the Lanchester estimate with the density
    gradient's lift stiffness): ω² = 2 g²/V² − g (dρ/dh)/ρ, i.e. ω² grows by the factor
    1 − (dρ/dh)/ρ · V²/(2 g) over the constant-density phugoid. In the Lanchester conditions above (no Mach effects,
    a tenth of the drag) at the 747's 12.13 km, in the isothermal layer where (dρ/dh)/ρ is the log-slope of the
    ISO 2533 table densities 0.31194 kg/m³ (12 km) and 0.26660 kg/m³ (13 km): factor 1.4455. The pitch dynamics
    scale both roots alike (the 6 % of the Lanchester test), so the ratio is compared, within 1 %."""
    model, h = ref.build(n=1, mach_effects=False, cd=0.0043)
    tb = trim(model, ref.U0, h)
    lin = linearize(model, tb.x, tb.u)
    plain = identify_modes(lin, 0)["phugoid"]
    graded = identify_modes(lin, 0, density_gradient=True)["phugoid"]
    slope = np.log(0.26660 / 0.31194) / 1000.0
    expected = 1.0 - slope * ref.U0**2 / (2.0 * ref.G)
    assert (graded.natural_frequency / plain.natural_frequency) ** 2 == pytest.approx(expected, rel=0.01)
    assert graded.period < 0.85 * plain.period  # 15–20 % shorter at cruise altitude


def test_batch_equals_single():
    """Conditions are independent: a condition trimmed and simulated inside a batch of 4 gives
    the same result as alone (to round-off)."""
    model4, h = ref.build(n=4)
    V = np.array([200.0, 235.9, 250.0, 220.0])
    tb4 = trim(model4, V, h)
    model1, _ = ref.build(n=1)
    tb1 = trim(model1, V[2], h)
    assert tb4[2].alpha == pytest.approx(tb1[0].alpha, abs=1e-10)
    r4 = simulate(model4, tb4.x, tb4.u, 5.0, inputs={"elevator": Pulse(0.5, 0.5, 0.01)})
    r1 = simulate(model1, tb1.x, tb1.u, 5.0, inputs={"elevator": Pulse(0.5, 0.5, 0.01)})
    assert np.allclose(r4["n_z"][:, 2], r1["n_z"][:, 0], atol=1e-9)


def test_gravity_constant_is_used():
    assert G0 == pytest.approx(9.80665)


def test_trim_warm_start():
    """``initial``: a trim started from its own solution is a fixed point of Newton (converged in at most one step,
    same state within 1e-9); a NaN start keeps the default start (the same iterations as without ``initial``); a key
    that is not an unknown of the trim (``phi`` in straight flight, ``flap``) is ignored."""
    model, h = ref.build(n=2)
    cold = trim(model, [ref.U0, 220.0], h)
    assert cold.converged.all() and min(r.iterations for r in cold.results) >= 2
    start = {k: np.array([r.start()[k] for r in cold.results]) for k in cold.results[0].start()}
    warm = trim(model, [ref.U0, 220.0], h, initial={**start, "phi": 0.3, "flap": 0.2})
    assert warm.converged.all() and all(r.iterations <= 1 for r in warm.results)
    assert np.allclose(warm.x, cold.x, atol=1e-9) and np.allclose(warm.u, cold.u, atol=1e-9)
    half = trim(model, [ref.U0, 220.0], h, initial={k: np.array([np.nan, v[1]]) for k, v in start.items()})
    assert half.results[0].iterations == cold.results[0].iterations and half.results[1].iterations <= 1
