"""Vortex lattice against analytic limits (lifting-line theory, symmetry, signs, Prandtl–Glauert)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from certkit.models.aero.interface import AeroState
from certkit.models.aero.vlm import VortexLattice
from certkit.models.aero.vlm.solver import _cross

from .vlm_cases import elliptic_wing, rectangular_wing, transport


@pytest.fixture(scope="module")
def transport_lattice():
    return VortexLattice(transport())


@pytest.mark.parametrize("aspect_ratio, tolerance", [(20.0, 0.025), (10.0, 0.04)])
def test_elliptic_lift_slope_lifting_line(aspect_ratio, tolerance):
    """Reference: Prandtl lifting-line theory for an elliptic wing, CLα = 2π·AR/(AR+2) (Anderson,
    *Fundamentals of Aerodynamics*, §5.3.2). Tolerance: 2.5 % at AR 20, 4 % at AR 10 — lifting-line
    theory overestimates the slope by O(1/AR²) relative to lifting-surface (VLM) results."""
    vl = VortexLattice(elliptic_wing(aspect_ratio))
    cla = vl.stability_derivatives(alpha=0.05)["CL_alpha"]
    expected = 2 * math.pi * aspect_ratio / (aspect_ratio + 2)
    assert cla == pytest.approx(expected, rel=tolerance)
    assert cla < expected  # lifting surface below lifting line


def test_elliptic_span_efficiency():
    """Reference: an elliptic planform with no twist carries an elliptic load, e = 1 (Prandtl;
    Anderson §5.3.2). Required: Trefftz-plane e >= 0.98 (and <= 1.02, discretisation)."""
    sol = VortexLattice(elliptic_wing(8.0)).solve(alpha=0.08)
    assert 0.98 <= sol.span_efficiency <= 1.02
    assert sol.CD_induced == pytest.approx(sol.CL_trefftz**2 / (math.pi * 8.0 * sol.span_efficiency), rel=1e-12)


@pytest.mark.parametrize("aspect_ratio", [1.0, 2.0])
def test_low_aspect_ratio_rectangular_helmbold(aspect_ratio):
    """Reference: Helmbold's low-aspect-ratio formula CLα = 2π·AR/(2 + √(AR²+4)) (Helmbold 1942;
    Anderson §5.3.2), which assumes elliptic loading and so bounds a rectangular wing from above.
    Tolerance: ours within 6 % below it."""
    cla = VortexLattice(rectangular_wing(aspect_ratio)).stability_derivatives(alpha=0.05)["CL_alpha"]
    helmbold = 2 * math.pi * aspect_ratio / (2 + math.sqrt(aspect_ratio**2 + 4))
    assert 0.94 * helmbold <= cla <= 1.0 * helmbold


def test_prandtl_glauert_scaling():
    """Reference: Prandtl–Glauert rule CLα(M)/CLα(0) = 1/√(1−M²) for AR → ∞; for finite AR the
    Göthert/Helmbold form CLα ∝ AR/(2 + √(AR²β²+4)) (Anderson, *Modern Compressible Flow*, §9.6).
    AR 20 elliptic wing at M 0.5: within 2 % of 1/β and within 0.5 % of the finite-AR ratio."""
    cfg = elliptic_wing(20.0)
    a0 = VortexLattice(cfg, mach=0.0).stability_derivatives(alpha=0.02)["CL_alpha"]
    a5 = VortexLattice(cfg, mach=0.5).stability_derivatives(alpha=0.02)["CL_alpha"]
    beta = math.sqrt(1 - 0.25)
    finite_ar = (2 + math.sqrt(20**2 + 4)) / (2 + math.sqrt(20**2 * beta**2 + 4))
    assert a5 / a0 == pytest.approx(1 / beta, rel=0.02)
    assert a5 / a0 == pytest.approx(finite_ar, rel=0.005)


def test_symmetry_no_lateral_output(transport_lattice):
    """Reference: mirror symmetry of the configuration. At β = 0 with no lateral rate or control,
    CY, Cl, Cn vanish (tolerance 1e-10) and lateral-by-longitudinal derivatives too."""
    d = transport_lattice.stability_derivatives(alpha=0.06, q_hat=0.01, controls={"elevator": -0.02})
    sol = d.solution
    for value in (
        sol.CY,
        sol.Cl,
        sol.Cn,
        sol.Cl_body,
        sol.Cn_body,
        d["CY_alpha"],
        d["Cl_alpha"],
        d["Cn_q"],
        d["CL_beta"],
        d["Cm_p"],
    ):
        assert abs(value) < 1e-10
    y = sol.strips.for_surface("wing").c_cn
    y_mirror = sol.strips.for_surface("wing (YDUP)").c_cn
    np.testing.assert_allclose(y, y_mirror, rtol=1e-9, atol=1e-12)


def test_derivative_signs(transport_lattice):
    """Reference: classical static and dynamic stability signs (Etkin & Reid, *Dynamics of Flight*,
    ch. 5): Cl_β < 0 with dihedral, Cn_β > 0 with a fin, Cm_q < 0, Cl_p < 0, Cn_r < 0, CL_α > 0, and
    the certkit (Etkin) control signs: positive elevator, aileron, rudder give negative Cm, Cl, Cn."""
    d = transport_lattice.stability_derivatives(alpha=0.05)
    assert d["Cl_beta"] < 0
    assert d["Cn_beta"] > 0
    assert d["Cm_q"] < 0
    assert d["Cl_p"] < 0
    assert d["Cn_r"] < 0
    assert d["CL_alpha"] > 0
    assert d["Cm_delta_elevator"] < 0
    assert d["Cl_delta_aileron"] < 0
    assert d["Cn_delta_rudder"] < 0
    assert d["CY_delta_rudder"] > 0  # trailing edge left pushes the fin right


def test_derivatives_match_finite_differences(transport_lattice):
    """Reference: central finite differences of ``solve`` (step 1e-5). The analytic (superposition)
    derivatives must agree to 1e-5 relative / 1e-7 absolute, in stability and body axes."""
    vl = transport_lattice
    base = dict(
        alpha=0.04, beta=0.02, p_hat=0.01, q_hat=0.005, r_hat=-0.01, controls={"elevator": 0.01, "aileron": 0.02}
    )
    for axes in ("stability", "body"):
        d = vl.stability_derivatives(**base, axes=axes)
        for var, arg in (
            ("alpha", "alpha"),
            ("beta", "beta"),
            ("p", "p_hat"),
            ("r", "r_hat"),
            ("delta_aileron", "aileron"),
        ):
            h = 1e-5
            vals = []
            for sgn in (1, -1):
                kw = dict(base, controls=dict(base["controls"]))
                if arg in kw:
                    kw[arg] = kw[arg] + sgn * h
                else:
                    kw["controls"][arg] = kw["controls"].get(arg, 0.0) + sgn * h
                s = vl.solve(**kw, rate_axes=axes)
                cl = s.Cl if axes == "stability" else s.Cl_body
                cn = s.Cn if axes == "stability" else s.Cn_body
                vals.append(np.array([s.CL, s.CD, s.CY, cl, s.Cm, cn]))
            fd = (vals[0] - vals[1]) / (2 * h)
            ours = np.array([d[f"{c}_{var}"] for c in ("CL", "CD", "CY", "Cl", "Cm", "Cn")])
            np.testing.assert_allclose(ours, fd, rtol=1e-5, atol=1e-7, err_msg=f"{axes} {var}")


def test_batch_coefficients_match_solve(transport_lattice):
    """Reference: ``solve`` at each state. The AeroModel batch evaluation (body rates, body moments)
    must give the same coefficients to 1e-12."""
    vl = transport_lattice
    rng = np.random.default_rng(1)
    alpha, beta, p = rng.uniform(-0.1, 0.2, 7), rng.uniform(-0.1, 0.1, 7), rng.uniform(-0.05, 0.05, 7)
    de = rng.uniform(-0.1, 0.1, 7)
    c = vl.coefficients(AeroState(alpha=alpha, beta=beta, p_hat=p, q_hat=0.01, controls={"elevator": de}))
    for i in range(7):
        s = vl.solve(alpha[i], beta[i], p[i], 0.01, 0.0, {"elevator": de[i]}, rate_axes="body")
        np.testing.assert_allclose(
            [c.CL[i], c.CD[i], c.CY[i], c.Cl[i], c.Cm[i], c.Cn[i]],
            [s.CL, s.CD, s.CY, s.Cl_body, s.Cm, s.Cn_body],
            rtol=1e-10,
            atol=1e-12,
        )


def test_spanwise_loading_integrates_to_total(transport_lattice):
    """Reference: the total force is the sum of the strip forces (consistency, 1e-10)."""
    sol = transport_lattice.solve(alpha=0.07)
    f = sol.strips.force_over_q.sum(axis=0) / transport_lattice.reference.area
    lift = -f[0] * math.sin(0.07) + f[2] * math.cos(0.07)
    assert lift == pytest.approx(sol.CL, rel=1e-10)
    wing = sol.strips.for_surface("wing")
    assert np.all(np.diff(wing.y) > 0) and np.all(wing.area > 0)
    np.testing.assert_allclose(wing.c_cn, wing.chord * wing.cn)


@pytest.mark.parametrize("mach", [0.0, 0.6])
def test_unit_solutions_contract_over_the_inputs_set(mach):
    """The bound-leg velocities of a unit solution (``_vortex_forces``, the strip loads' unit inputs) are contracted
    over the inputs that are set only: the same bits, signed zeros included, as the contraction over all 6 + 6 m
    inputs (those of zero add nothing) — for every unit input alone, its negative, and the freestream with one
    rate or deflection on top."""
    vl = VortexLattice(transport()).at_mach(mach)
    k = vl.unit_bound_velocity.shape[1]
    cases = []
    for j in range(k):
        for value in (1e-4, -1e-4):
            ut = np.zeros(k)
            ut[j] = value
            cases.append(ut)
            with_flow = ut.copy()
            with_flow[0] += 1.0
            cases.append(with_flow)
    lat = vl.lattice
    for ut in cases:
        _, parts, _ = vl._vortex_forces(ut)
        full = np.einsum("ikc,k->ic", vl.unit_bound_velocity, ut)
        expected = 2.0 * (vl.unit_circulation @ ut)[:, None] * _cross(full, lat.rv2 - lat.rv1)
        assert np.array_equal(parts[0], expected) and np.array_equal(np.signbit(parts[0]), np.signbit(expected))
