"""Degenerate geometry and unreadable AVL files must fail loudly, naming where."""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from certkit.models.aero.interface import AeroReference
from certkit.models.aero.vlm import (
    Configuration,
    ControlSpan,
    ControlSurface,
    GeometryError,
    Section,
    SingularLatticeError,
    Surface,
    VortexLattice,
    trapezoidal_surface,
)
from certkit.models.aero.vlm.avl_file import AvlFileError, read_avl

REF = AeroReference(10.0, 10.0, 1.0, 0.25)


def config(*surfaces):
    return Configuration(list(surfaces), REF)


def wing(sections, **kw):
    return Surface("main wing", sections, n_chord=4, n_span=kw.pop("n_span", 8), **kw)


@pytest.mark.parametrize(
    "sections, fragment",
    [
        ([Section((0, 0, 0), 1.0), Section((0.5, 0, 0), 1.0)], "sections 1 and 2: no span"),
        (
            [Section((0, 0, 0), 1.0), Section((0, 5, 0), 1.0), Section((0, 2, 0), 1.0)],
            "section 2: the surface folds back",
        ),
        ([Section((0, 0, 0), 1.0), Section((0, 5, 0), 0.0)], "section 2: chord 0.0"),
        (
            [Section((0, 0, 0), 1.0, controls=[ControlSurface("flap", 0.7)]), Section((0, 5, 0), 1.0)],
            "section 1: control 'flap' is on no neighbouring section",
        ),
        (
            [
                Section((0, 0, 0), 1.0, controls=[ControlSurface("flap", 1.7)]),
                Section((0, 5, 0), 1.0, controls=[ControlSurface("flap", 1.7)]),
            ],
            "hinge x/c 1.7 outside the chord",
        ),
        ([Section((0, 0, 0), 1.0)], "needs at least two sections"),
    ],
)
def test_degenerate_geometry_names_surface_and_section(sections, fragment):
    """Reference: the error contract (brief): zero span, crossing sections, zero-area panels and a
    control outside its surface raise GeometryError naming the surface and the section."""
    with pytest.raises(GeometryError) as info:
        VortexLattice(config(wing(sections)))
    assert "surface 'main wing'" in str(info.value)
    assert fragment in str(info.value)


def test_too_few_spanwise_vortices_for_sections():
    """Reference: AVL's rule that every interior section needs its own strip edge; 2 vortices for 4
    sections cannot, so GeometryError names the surface and section."""
    secs = [Section((0, y, 0), 1.0) for y in (0.0, 0.1, 0.2, 5.0)]
    with pytest.raises(GeometryError, match=r"surface 'main wing', section \d: too few spanwise vortices"):
        VortexLattice(config(wing(secs, n_span=2)))


def test_trapezoid_control_outside_surface():
    """Reference: the trapezoid helper's contract: control span fractions within [0, 1]."""
    with pytest.raises(GeometryError, match="surface 'wing': control 'aileron' span fractions"):
        trapezoidal_surface(
            "wing", area=10, aspect_ratio=8, taper=0.5, controls=[ControlSpan("aileron", 0.8, 1.2, 0.25)]
        )
    with pytest.raises(GeometryError, match="surface 'wing': aspect ratio must be positive"):
        trapezoidal_surface("wing", area=10, aspect_ratio=0.0, taper=0.5)


def test_coincident_surfaces_singular_not_nan():
    """Reference: linear algebra — two identical lifting surfaces give identical influence rows, a
    singular matrix; the solver must raise SingularLatticeError, never return NaN."""
    w = trapezoidal_surface("wing", area=10, aspect_ratio=8, taper=0.5, n_chord=4, n_span=8, component=1)
    w2 = trapezoidal_surface("wing copy", area=10, aspect_ratio=8, taper=0.5, n_chord=4, n_span=8, component=1)
    with pytest.raises(SingularLatticeError, match=r"singular near vortex \d+ \(surface 'wing copy'\)"):
        VortexLattice(config(w, w2))


@pytest.mark.parametrize("gap", [1e-9, 1e-4])
def test_nearly_coincident_surfaces(gap):
    """Reference: Munk's biplane limit — two lifting sheets at zero gap act as one sheet, so a pair 1e-4 m
    apart (1e-5 of the span) must be solved with the single wing's CL_α (to 1e-6); at 1e-9 m the two rows
    agree to rounding (condition number ~1e20, above the 1e12 limit) and the solver must refuse, naming the copy."""
    w = trapezoidal_surface("wing", area=10, aspect_ratio=8, taper=0.5, n_chord=4, n_span=8, component=1)
    w2 = trapezoidal_surface(
        "wing copy",
        area=10,
        aspect_ratio=8,
        taper=0.5,
        n_chord=4,
        n_span=8,
        component=1,
        root_leading_edge=(0.0, 0.0, gap),
    )
    if gap < 1e-6:
        with pytest.raises(SingularLatticeError, match=r"singular near vortex \d+ \(surface 'wing copy'\)"):
            VortexLattice(config(w, w2))
    else:
        single = VortexLattice(config(w)).stability_derivatives().CL_alpha
        pair = VortexLattice(config(w, w2)).stability_derivatives().CL_alpha
        assert pair == pytest.approx(single, rel=1e-6)


def test_unknown_control_rejected():
    """Reference: API contract — deflecting a control the lattice does not have is a KeyError."""
    vl = VortexLattice(config(trapezoidal_surface("wing", area=10, aspect_ratio=8, taper=0.5, n_chord=4, n_span=8)))
    with pytest.raises(KeyError, match="unknown control"):
        vl.solve(alpha=0.1, controls={"elevator": 0.1})
    assert np.isfinite(vl.solve(alpha=0.1).CL)


GOOD_HEADER = """\
test aircraft
0.2
0 0 0.0
10.0 1.0 10.0
0.25 0.0 0.0
"""


def avl_text(body: str) -> str:
    return GOOD_HEADER + textwrap.dedent(body)


@pytest.mark.parametrize(
    "body, line, keyword",
    [
        ("SURFACE\nwing\n4 1.0 8 1.0\nSECTION\n0 0 0 1.0\n", 10, "SECTION"),  # 4 numbers, 5 needed
        ("SURFACE\nwing\n4 1.0\nSECTION\n0 0 0 1 0\nFOO\n", 11, "SECTION"),  # unknown keyword
        ("SURFACE\nwing\n4 1.0 8 1.0\nSCALE\n1 1\n", 10, "SCALE"),
        ("SURFACE\nwing\n4 1.0 8 1.0\nSECTION\n0 0 0 1 0\nAFILE\nmissing.dat\n", 12, "AFILE"),
        ("SURFACE\nwing\n4 1.0 8 1.0\nSECTION\n0 0 0 1 0\nCONTROL\nflap 1.0 0.7\n", 12, "CONTROL"),
        ("SURFACE\nwing\n4 1.0 8 1.0\nSECTION\n0 0 0 1 0\nNACA\n24x2\n", 12, "NACA"),
    ],
)
def test_bad_avl_file_names_file_line_keyword(tmp_path, body, line, keyword):
    """Reference: the reader's error contract (brief): file name, line number and keyword."""
    path = tmp_path / "bad.avl"
    path.write_text(avl_text(body))
    with pytest.raises(AvlFileError) as info:
        read_avl(path)
    msg = str(info.value)
    assert str(path) in msg and f"line {line}" in msg and keyword in msg, msg


def test_bad_header(tmp_path):
    """Reference: the header layout of AVL files (Mach on line 2)."""
    path = tmp_path / "bad.avl"
    path.write_text("title\nfast\n")
    with pytest.raises(AvlFileError, match=r"bad.avl: line 2 \(header\): expected Mach"):
        read_avl(path)


def test_body_skipped_with_warning_and_comments(tmp_path):
    """Reference: AVL file format (BODY blocks, ``#``/``!`` comments, keywords by 4 letters). A BODY
    is skipped with a warning that says so; the surface around it still reads."""
    path = tmp_path / "body.avl"
    path.write_text(
        avl_text("""\
        # comment line
        BODY
        fuselage
        12 1.0
        BFIL
        fuse.dat
        SURFACE ! a wing
        wing
        4 1.0 8 1.0
        YDUPLICATE
        0.0
        NOWAKE
        SECTION
        0 0 0 1 2.0   # incidence in degrees
        NACA
        2412
        SECT
        0 5 0 1 0
        CDCL
        0 0.01 0.5 0.008 1.0 0.02
        """)
    )
    with pytest.warns(UserWarning, match="BODY 'fuselage' skipped"):
        cfg = read_avl(path)
    (s,) = cfg.surfaces
    assert s.name == "wing" and s.y_duplicate == 0.0 and not s.wake
    assert s.sections[0].incidence == pytest.approx(math.radians(2.0))
    assert cfg.mach == 0.2 and cfg.reference.area == 10.0


def test_control_edge_closer_to_the_tip_than_one_strip():
    """A control ending 0.13 % of the semispan short of the tip (a design study's corner) gets a narrow strip of its
    own instead of an error; its effectiveness is continuous with the control that reaches the tip (within 1 %: the
    shifted strip edges change the discretisation by about 0.2 %) and above that of a control ending at 0.98."""

    def cl_delta(eta_out):
        s = trapezoidal_surface(
            "tail",
            area=100.0,
            aspect_ratio=4.5,
            taper=0.35,
            sweep_quarter_chord=0.6,
            n_span=20,
            controls=[ControlSpan("elevator", 0.002, eta_out, 0.3)],
        )
        vl = VortexLattice(Configuration([s], AeroReference(100.0, math.sqrt(450.0), 5.0, 0.0)), mach=0.3)
        d = 1e-3
        return (vl.solve(controls={"elevator": d}).CL - vl.solve(controls={"elevator": -d}).CL) / (2 * d)

    near, full, short = cl_delta(0.9987), cl_delta(1.0), cl_delta(0.98)
    assert near == pytest.approx(full, rel=0.01)
    assert short < near and short < full


def test_control_in_two_segments_leaves_the_gap_undeflected():
    """A control in two segments of one name (an outboard aileron and an inboard flaperon): a control acts between
    two sections that both carry it, so a section without it sits in the gap; every interval between carrying
    sections lies within a segment."""
    spans = [ControlSpan("aileron", 0.78, 0.98, 0.17), ControlSpan("aileron", 0.30, 0.38, 0.25, gain=0.6)]
    wing = trapezoidal_surface("wing", area=100.0, aspect_ratio=9.0, taper=0.3, controls=spans)
    semi = math.sqrt(900.0) / 2.0
    y = [s.leading_edge[1] / semi for s in wing.sections]
    carries = [any(c.name == "aileron" for c in s.controls) for s in wing.sections]
    for k in range(len(y) - 1):
        if carries[k] and carries[k + 1]:
            assert any(c.eta_inboard - 1e-9 <= y[k] and y[k + 1] <= c.eta_outboard + 1e-9 for c in spans), (
                y[k],
                y[k + 1],
            )
    assert any(0.38 < e < 0.78 and not c for e, c in zip(y, carries))


@pytest.mark.parametrize(
    "spans, fragment",
    [
        ([("aileron", 0.3, 0.5, 0.2), ("aileron", 0.4, 0.9, 0.2)], "overlapping segments"),
        ([("aileron", 0.3, 0.5, 0.2), ("aileron", 0.5, 0.9, 0.3)], "abutting segments"),
    ],
)
def test_control_segments_that_cannot_be_represented(spans, fragment):
    with pytest.raises(GeometryError, match=fragment):
        trapezoidal_surface("wing", area=100.0, aspect_ratio=9.0, taper=0.3, controls=[ControlSpan(*s) for s in spans])
