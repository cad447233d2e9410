"""`certkit import jsbsim` on JSBSim's shipped B747 and 737, against JSBSim itself in this process.

Both tools fly the same cruise point: 35 000 ft, Mach 0.8, gear up, fuel frozen. certkit's trim of the imported
file against JSBSim's own trim (do_simple_trim): α, θ and elevator within 0.1°. Short period, roll subsidence and
Dutch roll (and the phugoid, with the altitude state) against the eigenvalues of JSBSim's linearisation
(FGLinearization) within 1 % of |λ|, with JSBSim's
yaw damper (which the importer lists as not mapped) closed on certkit's linear model: B747 δr = 0.7 r (rate gain 2
above 11 psf × rudder scale 0.35 rad, B747.xml "Yaw Damper Rate"), 737 δr = 0.35 r (737.xml yaw channel).
The phugoid against JSBSim's nonlinear response to a +2 m/s airspeed disturbance (the issue asks for the
nonlinear response, not the linearisation): certkit's nonlinear simulation of the imported file, period within
1.5 % and time constant of the decay within 10 %. The mass, CG and inertia the importer forms are JSBSim's own
(its inertia/* properties) to 1e-6.
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from click.testing import CliRunner

jsbsim = pytest.importorskip("jsbsim")

from certkit.aircraft import load_aircraft  # noqa: E402
from certkit.cli.flight_report import condition_from_options, trim_condition  # noqa: E402
from certkit.cli.main import main  # noqa: E402
from certkit.engine.context import Context  # noqa: E402
from certkit.models.dynamics.linearize import linearize  # noqa: E402
from certkit.models.dynamics.modes import identify_modes  # noqa: E402
from certkit.models.dynamics.simulate import simulate  # noqa: E402
from certkit.units import FT, G0, LB  # noqa: E402

pytestmark = pytest.mark.validation

SLUG = LB * G0 / FT
SLUG_FT2 = SLUG * FT * FT
YAW_DAMPER = {"B747": 0.7, "737": 0.35}


def jsbsim_root() -> str:
    """JSBSim's data folder: the installed package's own (the chained dev venvs break get_default_root_dir)."""
    here = os.path.dirname(jsbsim.__file__)
    if os.path.isdir(os.path.join(here, "aircraft")):
        return here
    return jsbsim.get_default_root_dir()


def jsbsim_cruise(name: str):
    fdm = jsbsim.FGFDMExec(jsbsim_root())
    fdm.set_debug_level(0)
    fdm.load_model(name)
    fdm["ic/h-sl-ft"] = 35_000
    fdm["ic/mach"] = 0.8
    fdm["ic/gamma-deg"] = 0.0
    fdm.run_ic()
    fdm["gear/gear-cmd-norm"] = 0
    fdm["gear/gear-pos-norm"] = 0
    fdm["propulsion/set-running"] = -1
    fdm["propulsion/fuel_freeze"] = 1
    fdm["simulation/do_simple_trim"] = 1
    return fdm


def _phugoid(t, V, start=20.0):
    """Period (s) and decay rate σ (1/s) of the oscillation of V after ``start``: mean spacing of upward zero
    crossings of V minus its linear trend, and the log decrement of the half-cycle peaks."""
    keep = t >= start
    t, V = t[keep], V[keep]
    y = V - np.polyval(np.polyfit(t, V, 1), t)
    i = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    up = t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])
    j = np.flatnonzero(np.sign(y[:-1]) != np.sign(y[1:]))
    peaks = [np.max(np.abs(y[a:b])) for a, b in zip(j[:-1], j[1:])]
    period = float(np.mean(np.diff(up)))
    return period, float(np.log(peaks[0] / peaks[-1]) / ((len(peaks) - 1) * period / 2))


@pytest.fixture(scope="module", params=["B747", "737"])
def case(request, tmp_path_factory):
    name = request.param
    fdm = jsbsim_cruise(name)
    jeig = np.linalg.eigvals(np.array(jsbsim.FGLinearization(fdm).system_matrix))
    out = tmp_path_factory.mktemp(name) / f"{name}.yaml"
    xml = os.path.join(jsbsim_root(), "aircraft", name, f"{name}.xml")
    res = CliRunner().invoke(
        main, ["import", "jsbsim", xml, "--out", str(out), "--mach", "0.8", "--altitude", "35000 ft"]
    )
    assert res.exit_code == 0, res.output
    ctx = Context(load_aircraft(out))
    fc = condition_from_options(ctx.aircraft, None, None, None, "clean", None, None, "straight", 0, 0, 0, None)
    batch, model, loading = trim_condition(ctx, fc)
    return name, fdm, jeig, out, res.output, batch, model, loading


def test_mass_properties_are_jsbsims(case):
    _, fdm, _, _, _, _, _, loading = case
    p = loading.properties
    assert p.mass == pytest.approx(fdm["inertia/mass-slugs"] * SLUG, rel=1e-6)
    assert p.cg[0] == pytest.approx(fdm["inertia/cg-x-in"] * 0.0254, abs=1e-6)
    assert p.cg[2] == pytest.approx(fdm["inertia/cg-z-in"] * 0.0254, abs=1e-6)
    for name in ("Ixx", "Iyy", "Izz"):
        assert getattr(p, name) == pytest.approx(fdm[f"inertia/{name.lower()}-slugs_ft2"] * SLUG_FT2, rel=1e-6)
    # JSBSim's inertia/ixz property is the tensor element J_xz = −∫xz dm
    assert p.Ixz == pytest.approx(-fdm["inertia/ixz-slugs_ft2"] * SLUG_FT2, rel=1e-6, abs=1e-3)


def test_trim_angles_match_jsbsim(case):
    _, fdm, _, _, _, batch, _, _ = case
    r = batch.results[0]
    assert r.converged
    assert abs(np.degrees(r.alpha) - fdm["aero/alpha-deg"]) < 0.1
    assert abs(np.degrees(r.theta) - fdm["attitude/theta-deg"]) < 0.1
    assert abs(np.degrees(r.controls["elevator"] - fdm["fcs/elevator-pos-rad"])) < 0.1


def test_short_period_roll_dutch_roll_match_jsbsim(case):
    name, _, jeig, _, _, batch, model, _ = case
    lin = linearize(model, batch.x, batch.u)
    lin.A[0, :, lin.state_names.index("r")] += YAW_DAMPER[name] * lin.B[0, :, model.control_names.index("rudder")]
    modes = identify_modes(lin, 0)
    for mode in ("short_period", "roll", "dutch_roll"):
        lam = modes[mode].eigenvalue
        ref = jeig[np.argmin(np.abs(jeig - lam))]
        assert abs(ref - lam) < 0.01 * abs(ref), (name, mode, lam, ref)


def test_phugoid_with_density_gradient_matches_jsbsims_linearisation(case):
    """JSBSim's linearisation carries the altitude (its state vector ends with Alt): certkit's linear model with
    the altitude state (`certkit modes`' default) gives its phugoid within 1 % of |λ| (found: B747 0.37 %, 737
    0.32 %), where the textbook four-state model is 14–17 % low in frequency (the density gradient's stiffening,
    ω² = 2 g²/V² − g ρ'/ρ, certkit/models/dynamics/modes.py)."""
    name, _, jeig, _, _, batch, model, _ = case
    lin = linearize(model, batch.x, batch.u)
    graded = identify_modes(lin, 0, density_gradient=True)["phugoid"].eigenvalue
    ref = jeig[np.argmin(np.abs(jeig - graded))]
    assert abs(ref - graded) < 0.01 * abs(ref), (name, graded, ref)
    plain = identify_modes(lin, 0)["phugoid"].eigenvalue
    assert abs(plain.imag) < 0.9 * abs(ref.imag), (name, plain, ref)  # without it the gap the issue reported


def test_drag_axis_convention_explains_the_dutch_roll_damping_difference(case):
    """certkit's drag acts along the stability x axis, JSBSim's along the relative wind (certkit/conventions.py):
    JSBSim's sideslip equation has an extra −D/(mV) ≈ −T cos α/(mV) in ∂v̇/∂v. Adding that term to certkit's linear
    model must bring its Dutch-roll damping (real part) at least halfway to JSBSim's (found: B747 1.09 % → 0.47 %,
    737 0.56 % → 0.24 %)."""
    name, _, jeig, _, _, batch, model, loading = case
    lin = linearize(model, batch.x, batch.u)
    lin.A[0, :, lin.state_names.index("r")] += YAW_DAMPER[name] * lin.B[0, :, model.control_names.index("rudder")]
    before = identify_modes(lin, 0)["dutch_roll"].eigenvalue
    r = batch.results[0]
    iv = lin.state_names.index("v")
    lin.A[0, iv, iv] -= sum(r.thrust.values()) * np.cos(r.alpha) / (loading.properties.mass * r.V)
    after = identify_modes(lin, 0)["dutch_roll"].eigenvalue
    ref = jeig[np.argmin(np.abs(jeig - before))]
    assert abs(after.real - ref.real) < 0.5 * abs(before.real - ref.real), (name, before, after, ref)


def test_phugoid_matches_jsbsims_nonlinear_response(case):
    name, _, _, _, _, batch, model, _ = case
    fdm = jsbsim_cruise(name)  # a fresh run: the linearised one holds its clock
    alpha, vt = fdm["aero/alpha-rad"], fdm["velocities/vt-fps"]
    fdm["ic/alpha-rad"] = alpha
    fdm["ic/gamma-rad"] = 0.0
    fdm["ic/vt-fps"] = vt + 2.0 / FT
    fdm.run_ic()
    t, V = [], []
    for _ in range(int(round(300.0 / fdm.get_delta_t()))):
        fdm.run()
        t.append(fdm.get_sim_time())
        V.append(fdm["velocities/vt-fps"] * FT)
    period_j, sigma_j = _phugoid(np.array(t), np.array(V))
    a = batch.results[0].alpha
    x0 = batch.x.copy()
    x0[:, 3] += 2.0 * np.cos(a)
    x0[:, 5] += 2.0 * np.sin(a)
    sim = simulate(model, x0, batch.u, 300.0, dt=0.05, record_every=2)
    period_c, sigma_c = _phugoid(sim.t, sim["V"][:, 0])
    assert period_c == pytest.approx(period_j, rel=0.015), name
    assert sigma_c == pytest.approx(sigma_j, rel=0.10), name


def test_report_of_what_was_not_mapped(case):
    _, _, _, out, output, _, _, _ = case
    text = out.read_text()
    for item in ("flight control system", "CDbeta", "flaps increment"):
        assert item in output and item in text
    assert text.startswith("# certkit aircraft file imported from a JSBSim FDM")


@pytest.mark.parametrize(
    "content, expected",
    [
        (None, "no such JSBSim aircraft file"),
        ("<fdm_config><metrics>\n<wingarea> 10 </wingarea>\n</oops>", ":3:"),
        ("<aircraft/>", "expected <fdm_config>"),
        (
            "<fdm_config name='x'><metrics><wingarea unit='FT2'> lots </wingarea></metrics></fdm_config>",
            "metrics/wingarea: 'lots' is not a number",
        ),
    ],
)
def test_bad_input_is_a_clear_error(tmp_path, content, expected):
    path = tmp_path / "model.xml"
    if content is not None:
        path.write_text(content)
    res = CliRunner().invoke(main, ["import", "jsbsim", str(path)])
    assert res.exit_code == 2 and expected in res.output and "Traceback" not in res.output, res.output
