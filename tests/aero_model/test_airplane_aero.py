"""The per-configuration aerodynamic model the rules use: sign conventions, declared tables, overrides."""

import json
import textwrap

import numpy as np
import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.models.aero.interface import AeroState

from ..conftest import BASELINE, SHARED_REFERENCE


@pytest.fixture(scope="module")
def clean(baseline):
    return Context(baseline).aero("clean")


def test_sign_conventions_of_the_baseline(clean):
    """certkit.conventions: static stability (Cm_α < 0, Cn_β > 0, Cl_β < 0 with dihedral and sweep),
    damping (Cm_q, Cl_p, Cn_r < 0) and Etkin control signs (positive deflection, negative moment)."""
    d = {k: np.asarray(v) for k, v in clean.table.items()}
    assert np.all(d["CL_alpha"] > 0) and np.all(d["Cm_alpha"] < 0)
    assert np.all(d["Cn_beta"] > 0) and np.all(d["Cl_beta"] < 0) and np.all(d["CY_beta"] < 0)
    assert np.all(d["Cm_q"] < 0) and np.all(d["Cl_p"] < 0) and np.all(d["Cn_r"] < 0)
    assert np.all(d["Cm_elevator"] < 0) and np.all(d["CL_elevator"] > 0)
    assert np.all(d["Cl_aileron"] < 0) and np.all(d["Cn_rudder"] < 0) and np.all(d["CY_rudder"] > 0)


def test_batch_of_500_states_in_one_call(clean):
    rng = np.random.default_rng(1)
    n = 500
    state = AeroState(
        alpha=rng.uniform(-0.05, 0.15, n),
        beta=rng.uniform(-0.05, 0.05, n),
        mach=rng.uniform(0.2, 0.85, n),
        controls={"elevator": rng.uniform(-0.2, 0.2, n)},
    )
    c = clean.model.coefficients(state)
    assert c.CL.shape == (n,) and np.all(np.isfinite(c.Cm))
    # linear region: lift follows CL0 + CL_alpha alpha at each Mach
    one = AeroState(alpha=np.array([0.0, 0.02]), mach=0.6)
    cl = clean.model.coefficients(one).CL
    assert (cl[1] - cl[0]) / 0.02 == pytest.approx(float(clean.model.derivative("CL_alpha", 0.6)), rel=1e-3)


TABLES = textwrap.dedent("""
    aerodynamics:
      derivative_tables:
        clean:
          source: Heffley and Jewell, NASA CR-2144, 747 case (test data)
          mach: [0.25, 0.9]
          derivatives: {CL0: [0.2, 0.3], CL_alpha: [5.0, 6.0], Cm_alpha: -1.2, Cm_q: -20.0, CD0: 0.018, k: 0.045,
                        Cn_beta: 0.15, Cl_beta: -0.2, Cm_elevator: -1.3}
""")


def test_declared_tables_replace_the_lattice_without_geometry(tmp_path):
    text = BASELINE.read_text()
    start, end = text.index("geometry:\n"), text.index("mass:\n")
    f = tmp_path / "tables.yaml"
    f.write_text(text[:start] + text[end:] + TABLES)
    ctx = Context(load_aircraft(f))
    aero = ctx.aero("clean")
    assert aero.source.startswith("declared table") and aero.lattice is None
    assert float(aero.model.derivative("CL_alpha", 0.575)) == pytest.approx(5.5)
    with pytest.raises(ValueError, match="geometry"):
        ctx.aero("takeoff")


def test_overrides_replace_estimates_and_are_recorded(tmp_path):
    f = tmp_path / "o.yaml"
    f.write_text(
        BASELINE.read_text()
        + textwrap.dedent("""
        aerodynamics:
          overrides_source: wind-tunnel entry WT-42 (test)
          overrides:
            clean: {Cm_alpha: -1.5, CD0: 0.0175}
    """)
    )
    aero = Context(load_aircraft(f)).aero("clean")
    assert float(aero.model.derivative("Cm_alpha", 0.5)) == -1.5
    assert aero.overrides["Cm_alpha"]["value"] == -1.5 and len(aero.overrides["Cm_alpha"]["estimate"]) == len(aero.mach)
    assert aero.overrides["CD0"]["source"] == "wind-tunnel entry WT-42 (test)"


def test_misspelt_declared_derivative_is_an_error(tmp_path):
    text = BASELINE.read_text() + TABLES.replace("Cm_q:", "Cm_qq:")
    f = tmp_path / "bad.yaml"
    f.write_text(text)
    from certkit.errors import InputError

    with pytest.raises(InputError, match=r"derivatives\.Cm_qq"):  # at load, with its YAML path and line
        load_aircraft(f)


def test_derivatives_command_on_avl_and_aircraft_files(cli):
    avl = SHARED_REFERENCE / "avl-b737" / "b737.avl"
    if not avl.exists():
        pytest.skip(f"reference data not found at {avl}")
    out = cli("derivatives", avl, "--mach", "0.7", "--alpha", "1.918401", "--json")
    data = json.loads(out.output)
    # stock AVL 3.52 (b737_avl352_dermats.st): CLa 7.2992, CYb -1.3192 — within 1 %
    assert data["lattice"]["CL_alpha"] == pytest.approx(7.2992, rel=0.01)
    assert data["lattice"]["CY_beta"] == pytest.approx(-1.3192, rel=0.01)
    out = cli("derivatives", BASELINE, "--mach", "0.84", "--alpha", "2", "--json")
    data = json.loads(out.output)
    assert set(data) >= {"lattice", "model", "neutral_point", "static_margin", "reference", "conventions"}
    assert data["static_margin"] > 0


def test_derivatives_command_bad_input_exit_2(tmp_path):
    import subprocess
    import sys

    bad = tmp_path / "bad.avl"
    bad.write_text("title\n0.5\n0 0 0\n-1 1 1\n0 0 0\n")
    proc = subprocess.run(
        [sys.executable, "-m", "certkit.cli", "derivatives", str(bad)], capture_output=True, text=True
    )
    assert proc.returncode == 2 and "Traceback" not in proc.stderr and "bad.avl" in proc.stderr


def test_report_lists_every_override(tmp_path):
    """The report lists every coefficient the aircraft file overrides (models.aerodynamics)."""
    from certkit.engine.registry import discover
    from certkit.engine.results import RunResult
    from certkit.engine.scheduler import _merge_provenance
    from certkit.report.html import render_html

    f = tmp_path / "o.yaml"
    f.write_text(
        BASELINE.read_text()
        + textwrap.dedent("""
        aerodynamics:
          overrides_source: flight-test polar FT-7 (test)
          overrides:
            clean: {CD0: 0.0171}
    """)
    )
    ctx = Context(load_aircraft(f))
    ctx.aero("clean")
    ctx.loading(ctx.aircraft.mass.MTOW, 29.0, "test loading")
    models = _merge_provenance([ctx.provenance()])
    assert models["aerodynamics"]["clean"]["overrides"]["CD0"]["value"] == 0.0171
    assert models["loadings"][0]["name"] == "test loading"
    html = render_html(RunResult("0", "x", "0" * 64, str(f), "now", [], models), discover())
    assert "flight-test polar FT-7 (test)" in html and "CD0: 0.0171" in html


def test_the_lattice_reaches_the_declared_md(clean, baseline):
    """The baseline's MD (0.94) lies beyond the default breakpoints (up to 0.90): the lattice is solved there too, and
    its lift-curve slope grows from M 0.2 to MD as the DATCOM/Helmbold swept-wing slope does (USAF DATCOM §4.1.3.2:
    a = 2πA / (2 + √(A²β²(1 + tan²Λ½/β²) + 4)), κ = 1), within 10 % (the lattice holds the tail's share too)."""
    from certkit.models.aero.airplane import DEFAULT_MACHS, MAX_MACH_BREAKPOINT, mach_breakpoints

    assert clean.mach[-1] == pytest.approx(0.94) and tuple(clean.mach[:-1]) == DEFAULT_MACHS
    assert any("lattice solved up to MD" in n for n in clean.notes)
    ac = baseline.model
    w = ac.geometry.wing
    tan_half = np.tan(w.sweep_quarter_chord) - 4 / w.aspect_ratio * 0.25 * (1 - w.taper) / (1 + w.taper)

    def datcom(m):
        b2 = 1 - m * m
        return 2 * np.pi * w.aspect_ratio / (2 + np.sqrt(w.aspect_ratio**2 * (b2 + tan_half**2) + 4))

    lattice = np.asarray(clean.table["CL_alpha"])
    assert lattice[-1] / lattice[0] == pytest.approx(datcom(0.94) / datcom(0.2), rel=0.10)
    # MD at or below the last default breakpoint, or beyond the highest one solved: the defaults
    for md, expected in ((0.90, DEFAULT_MACHS), (MAX_MACH_BREAKPOINT + 0.02, DEFAULT_MACHS)):
        changed = ac.model_copy(update={"speeds": ac.speeds.model_copy(update={"MD": md})})
        assert mach_breakpoints(changed) == expected


def test_a_control_segment_moves_with_its_control(tmp_path):
    """A flaperon declared as a segment of the aileron (``segments:``) adds roll power in proportion to its gain: the
    lattice is linear in the deflections, so on one mesh (gains 0.5, 1.0, 1.5) Cl_δa changes by equal steps
    (1e-6), and the segment adds to the aileron's own roll power (same sign, more than 5 %)."""
    limits = "        design_limits: {min: -25 deg, max: 25 deg}  # estimate: 5 deg short of travel"

    def cl_aileron(gain):
        text = BASELINE.read_text()
        if gain:
            segment = (
                "\n        segments: [{name: flaperon, span_start: 0.30, span_end: 0.38, chord_ratio: 0.25, "
                f"gain: {gain}}}]"
            )
            text = text.replace(limits, limits + segment)
        f = tmp_path / f"seg{gain}.yaml"
        f.write_text(text)
        return float(Context(load_aircraft(f)).aero("clean").model.derivative("Cl_aileron", 0.5))

    alone, half, full, more = cl_aileron(0), cl_aileron(0.5), cl_aileron(1.0), cl_aileron(1.5)
    assert (more - full) == pytest.approx(full - half, rel=1e-6)
    assert (full - alone) / alone > 0.05
