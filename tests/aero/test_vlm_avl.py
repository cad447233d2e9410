"""Vortex lattice against AVL 3.52: the stock-AVL output for the Boeing 737 sample, and optvl 2.5.0
(AVL 3.52 with a Python API) run here on the same files.

Conversions written down once:
* AVL's control derivatives are per degree of the control variable; ours per radian of the same
  variable: ours = AVL × 180/π. Both read the same gains, so the variable has the same sign in both
  (the b737 file's aileron, gain −1 on the right wing, is positive right trailing edge *up*, and its
  rudder positive trailing edge *right*: opposite to the certkit/Etkin convention; that does not
  matter for the comparison, which uses the file's own variables).
* AVL's "Stability-axis derivatives" table gives Cl', Cn' about stability axes and rates p', r'
  about stability axes, per radian and per unit p'b/2V, qc/2V, r'b/2V: our ``axes="stability"``.
* Tolerance (the brief): 5 % relative, or 0.02 absolute for small derivatives; the neutral point
  within 1 % of the reference chord.
"""

from __future__ import annotations

import math
import os
import re
from pathlib import Path

import pytest

from certkit.models.aero.vlm import VortexLattice
from certkit.models.aero.vlm.avl_file import read_avl, write_avl

from .vlm_cases import transport

REFERENCE = Path(__file__).parents[2] / ".." / "shared" / "reference" / "avl-b737"
B737 = REFERENCE / "b737.avl"
STOCK = REFERENCE / "stock_avl_outputs" / "b737_avl352_dermats.st"

needs_reference = pytest.mark.skipif(
    not (B737.is_file() and STOCK.is_file()), reason=f"AVL reference data not found in {REFERENCE.resolve()}"
)

# our key -> (AVL .st name, optvl stability-derivative key)
STABILITY = {
    "CL_alpha": ("CLa", "dCL/dalpha"),
    "Cm_alpha": ("Cma", "dCm/dalpha"),
    "CY_beta": ("CYb", "dCY/dbeta"),
    "Cl_beta": ("Clb", "dCl'/dbeta"),
    "Cn_beta": ("Cnb", "dCn'/dbeta"),
    "CL_q": ("CLq", "dCL/dq'"),
    "Cm_q": ("Cmq", "dCm/dq'"),
    "Cl_p": ("Clp", "dCl'/dp'"),
    "Cn_r": ("Cnr", "dCn'/dr'"),
}
CONTROL_COEFFICIENTS = {
    "CL": ("CLd", "CL"),
    "CY": ("CYd", "CY"),
    "Cl": ("Cld", "Cl'"),
    "Cm": ("Cmd", "Cm"),
    "Cn": ("Cnd", "Cn'"),
}
CONTROLS = ("elevator", "aileron", "rudder")


def within(ours: float, reference: float, rel: float = 0.05, absolute: float = 0.02) -> bool:
    return abs(ours - reference) <= max(rel * abs(reference), absolute)


def read_dermats(path: Path) -> dict[str, float]:
    """Values of an AVL 'DERMATS' .st file: every 'numbers | label : name1, name2' line; control
    derivative names 'CLd*' are expanded to 'CLd1', 'CLd2', … in control order."""
    values: dict[str, float] = {}
    for line in path.read_text().splitlines():
        if "|" not in line:
            continue
        numbers, label = line.split("|", 1)
        try:
            nums = [float(v) for v in numbers.split()]
        except ValueError:
            continue
        text = label.split(":", 1)[1] if ":" in label else label
        names = [n.strip() for n in text.split(",")] if "," in text else [text.split()[-1]]
        if len(names) == 1 and names[0].endswith("*"):
            names = [f"{names[0][:-1]}{i + 1}" for i in range(len(nums))]
        for name, v in zip(names, nums):
            values[name] = v
    return values


@pytest.fixture(scope="module")
def b737_stock():
    st = read_dermats(STOCK)
    controls = ["slat", "flap", "aileron", "elevator", "rudder"]
    return st, controls


@pytest.fixture(scope="module")
def b737_ours(b737_stock):
    st, controls = b737_stock
    cfg = read_avl(B737).with_reference(x_ref=st["Xref"], z_ref=st["Zref"])
    vl = VortexLattice(cfg, mach=st["Mach"])
    alpha = math.radians(st["Alpha"])
    elevator = math.radians(0.8967974687214668)  # trimmed deflection printed in the same .st file
    return vl.stability_derivatives(alpha=alpha, controls={"elevator": elevator})


@pytest.fixture(scope="module")
def b737_optvl(b737_stock):
    optvl = pytest.importorskip("optvl")
    st, _ = b737_stock
    cwd = os.getcwd()
    os.chdir(REFERENCE)  # AVL opens AFILE airfoils relative to the working directory
    try:
        solver = optvl.OVLSolver(geo_file=B737.name, mass_file="b737.mass")
    finally:
        os.chdir(cwd)
    solver.set_parameter("Mach", st["Mach"])
    solver.set_constraint("alpha", "CL", 0.544438)
    solver.set_constraint("elevator", "Cm", 0.0)
    solver.execute_run()
    return (
        solver.get_stab_derivs(),
        solver.get_control_stab_derivs(),
        solver.get_total_forces(),
        solver.get_reference_data(),
    )


@needs_reference
def test_b737_lattice_size(b737_ours, b737_stock):
    """Reference: stock AVL 3.52 paneling of b737.avl (.st header): 11 surfaces, 137 strips, 1505
    vortices. Exact."""
    lat = b737_ours.solution  # noqa: F841 (lattice built)
    st, _ = b737_stock
    cfg = read_avl(B737)
    from certkit.models.aero.vlm import build_lattice

    lattice = build_lattice(cfg)
    assert (len(lattice.patches), lattice.n_strips, lattice.n_vortices) == (11, 137, 1505)


@needs_reference
def test_b737_stability_derivatives_vs_stock_avl(b737_ours, b737_stock):
    """Reference: stock AVL 3.52 stability-axis derivatives (b737_avl352_dermats.st, Mach 0.7,
    α = 1.9184°, elevator 0.8968°, moments about the CG). Tolerance 5 % or 0.02 absolute."""
    st, _ = b737_stock
    for ours_key, (avl_key, _) in STABILITY.items():
        assert within(b737_ours[ours_key], st[avl_key]), (ours_key, b737_ours[ours_key], st[avl_key])


@needs_reference
def test_b737_control_derivatives_vs_stock_avl(b737_ours, b737_stock):
    """Reference: stock AVL 3.52 control derivatives (per degree, ×180/π to per radian). Tolerance
    5 % or 0.02 absolute (per radian)."""
    st, controls = b737_stock
    for name in CONTROLS:
        index = controls.index(name) + 1
        for coef, (avl_prefix, _) in CONTROL_COEFFICIENTS.items():
            ref = st[f"{avl_prefix}{index}"] * 180 / math.pi
            ours = b737_ours[f"{coef}_delta_{name}"]
            assert within(ours, ref), (coef, name, ours, ref)


@needs_reference
def test_b737_neutral_point_and_lift_vs_stock_avl(b737_ours, b737_stock):
    """Reference: stock AVL 3.52 neutral point Xnp = 68.1088 and CL = 0.544438 at the printed α and
    elevator. Tolerance: Xnp within 1 % of Cref (0.11); CL within 1 %; CDi (Trefftz) within 3 %."""
    st, _ = b737_stock
    assert abs(b737_ours.neutral_point - st["Xnp"]) <= 0.01 * st["Cref"]
    assert b737_ours.solution.CL == pytest.approx(st["CLtot"], rel=0.01)
    assert b737_ours.solution.CD_induced == pytest.approx(st["CDff"], rel=0.03)


@needs_reference
def test_b737_vs_optvl(b737_ours, b737_optvl):
    """Reference: optvl 2.5.0 (AVL 3.52) run here on b737.avl/b737.mass, trimmed to CL 0.544438
    with the elevator. Stability and control derivatives within 5 % or 0.02 absolute; Xnp within
    1 % of Cref."""
    derivs, controls, _, ref = b737_optvl
    for ours_key, (_, key) in STABILITY.items():
        assert within(b737_ours[ours_key], derivs[key]), (ours_key, b737_ours[ours_key], derivs[key])
    for name in CONTROLS:
        for coef, (_, key) in CONTROL_COEFFICIENTS.items():
            ref_value = controls[f"d{key}/d{name}"] * 180 / math.pi
            assert within(b737_ours[f"{coef}_delta_{name}"], ref_value), (coef, name)
    assert abs(b737_ours.neutral_point - derivs["neutral point"]) <= 0.01 * ref["Cref"]


def test_transport_vs_optvl(tmp_path):
    """Reference: optvl 2.5.0 (AVL 3.52) on our own transport (trapezoidal helper: wing with aileron,
    tail with elevator, fin with rudder), written to a temporary .avl file, at Mach 0.6, α = 3°,
    elevator −2°. All stability derivatives of the table and the elevator, aileron and rudder
    derivatives within 5 % or 0.02 absolute (they agree to ~1e-6 in practice); Xnp within 1 % of
    the mean chord; CL within 0.1 %."""
    optvl = pytest.importorskip("optvl")
    cfg = transport(mach=0.6)
    path = write_avl(cfg, tmp_path / "transport.avl")
    alpha, elevator = math.radians(3.0), math.radians(-2.0)
    ours = VortexLattice(cfg).stability_derivatives(alpha=alpha, controls={"elevator": elevator})
    solver = optvl.OVLSolver(geo_file=str(path))
    solver.set_parameter("Mach", 0.6)
    solver.set_constraint("alpha", "alpha", 3.0)
    solver.set_constraint("elevator", "elevator", -2.0)
    solver.execute_run()
    derivs, controls, forces = solver.get_stab_derivs(), solver.get_control_stab_derivs(), solver.get_total_forces()
    for ours_key, (_, key) in STABILITY.items():
        assert within(ours[ours_key], derivs[key]), (ours_key, ours[ours_key], derivs[key])
    for name in CONTROLS:
        for coef, (_, key) in CONTROL_COEFFICIENTS.items():
            assert within(ours[f"{coef}_delta_{name}"], controls[f"d{key}/d{name}"] * 180 / math.pi), (coef, name)
    assert abs(ours.neutral_point - derivs["neutral point"]) <= 0.01 * cfg.reference.chord
    assert ours.solution.CL == pytest.approx(forces["CL"], rel=1e-3)


def test_read_write_roundtrip(tmp_path):
    """Reference: the writer's own output. Reading back what ``write_avl`` wrote gives the same
    lattice coefficients (1e-7: ten significant digits written)."""
    cfg = transport(mach=0.3)
    back = read_avl(write_avl(cfg, tmp_path / "t.avl"))
    a = VortexLattice(cfg).solve(alpha=0.05, beta=0.02, controls={"aileron": 0.1})
    b = VortexLattice(back).solve(alpha=0.05, beta=0.02, controls={"aileron": 0.1})
    for k in ("CL", "CD", "CY", "Cl", "Cm", "Cn"):
        assert getattr(b, k) == pytest.approx(getattr(a, k), rel=1e-7, abs=1e-10)


def test_dermats_reader_sanity():
    """Reference: the stock .st file itself (CLa printed as 7.299206)."""
    if not STOCK.is_file():
        pytest.skip(f"AVL reference data not found in {REFERENCE.resolve()}")
    st = read_dermats(STOCK)
    assert st["CLa"] == pytest.approx(7.299206, abs=1e-6)
    assert re.match(r"^[0-9.]+$", f"{st['Xnp']:.3f}")


#: the lateral derivatives whose change with the lift coefficient the flight model carries (stability axes)
LIFT_DEPENDENT = {
    "Cl_beta": "dCl'/dbeta",
    "Cn_beta": "dCn'/dbeta",
    "Cl_p": "dCl'/dp'",
    "Cn_p": "dCn'/dp'",
    "Cl_r": "dCl'/dr'",
    "Cn_r": "dCn'/dr'",
}


def test_lift_dependence_of_lateral_derivatives_vs_optvl(tmp_path):
    """Reference: optvl 2.5.0 (AVL 3.52) on our transport at Mach 0.6, α = 0° and 6°. The change of Cl_β, Cn_β,
    Cl_p, Cn_p, Cl_r, Cn_r per unit lift coefficient between the two (what the flight model's ``<name>_CL`` slopes
    carry, :func:`certkit.models.aero.airplane.lattice_derivatives`) within 5 % or 0.005 absolute; Cn_p's and Cl_r's
    slopes are the large ones (the tilt of the lift in a roll, the lift's asymmetry in a yaw: Etkin & Reid §5.4)."""
    optvl = pytest.importorskip("optvl")
    cfg = transport(mach=0.6)
    path = write_avl(cfg, tmp_path / "transport.avl")
    vl = VortexLattice(cfg)
    solver = optvl.OVLSolver(geo_file=str(path))
    solver.set_parameter("Mach", 0.6)
    ours, theirs = [], []
    for alpha_deg in (0.0, 6.0):
        ours.append(vl.stability_derivatives(alpha=math.radians(alpha_deg)))
        solver.set_constraint("alpha", "alpha", alpha_deg)
        solver.execute_run()
        theirs.append((solver.get_stab_derivs(), solver.get_total_forces()["CL"]))
    d_cl_ours = ours[1].solution.CL - ours[0].solution.CL
    d_cl_avl = theirs[1][1] - theirs[0][1]
    assert d_cl_ours == pytest.approx(d_cl_avl, rel=1e-3)
    for name, key in LIFT_DEPENDENT.items():
        slope_ours = (ours[1][name] - ours[0][name]) / d_cl_ours
        slope_avl = (theirs[1][0][key] - theirs[0][0][key]) / d_cl_avl
        assert within(slope_ours, slope_avl, absolute=0.005), (name, slope_ours, slope_avl)
    assert abs((theirs[1][0]["dCn'/dp'"] - theirs[0][0]["dCn'/dp'"]) / d_cl_avl) > 0.05  # a real lift dependence


def test_control_in_two_segments_vs_optvl(tmp_path):
    """Reference: optvl 2.5.0 (AVL 3.52). A roll control in two segments of one name — an outboard aileron and an
    inboard flaperon moving 0.6 × as far, a gap of plain wing between them — written to an .avl file (each
    segment's CONTROL lines on its own sections) at Mach 0.3, α = 4°: the control's derivatives within 5 % or
    0.02 absolute per radian; and the gap does not move (the two-segment Cl_δ equals the sum of the segments'
    alone within 1e-9 on the same sections: the lattice is linear in the deflections)."""
    optvl = pytest.importorskip("optvl")
    wing = dict(
        area=124.6,
        aspect_ratio=9.45,
        taper=0.24,
        sweep_quarter_chord=math.radians(25.0),
        dihedral=math.radians(5.0),
        camber="24",
        n_chord=8,
        n_span=24,
    )
    from certkit.models.aero.interface import AeroReference
    from certkit.models.aero.vlm import Configuration, ControlSpan, trapezoidal_surface

    def config(spans):
        surface = trapezoidal_surface("wing", controls=spans, section_etas=(0.30, 0.38, 0.58, 0.78, 0.98), **wing)
        return Configuration([surface], AeroReference(124.6, math.sqrt(124.6 * 9.45), 4.17, 3.0), name="wing", mach=0.3)

    both = [ControlSpan("aileron", 0.78, 0.98, 0.17), ControlSpan("aileron", 0.30, 0.38, 0.25, gain=0.6)]
    alpha = math.radians(4.0)
    ours = VortexLattice(config(both)).stability_derivatives(alpha=alpha)
    parts = [VortexLattice(config([span])).stability_derivatives(alpha=alpha) for span in both]
    assert ours["Cl_delta_aileron"] == pytest.approx(sum(p["Cl_delta_aileron"] for p in parts), rel=1e-9)
    path = write_avl(config(both), tmp_path / "two_segments.avl")
    solver = optvl.OVLSolver(geo_file=str(path))
    solver.set_parameter("Mach", 0.3)
    solver.set_constraint("alpha", "alpha", 4.0)
    solver.execute_run()
    controls = solver.get_control_stab_derivs()
    for coef, (_, key) in CONTROL_COEFFICIENTS.items():
        assert within(ours[f"{coef}_delta_aileron"], controls[f"d{key}/daileron"] * 180 / math.pi), coef
