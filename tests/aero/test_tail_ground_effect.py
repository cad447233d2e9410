"""Ground effect on the downwash at the horizontal tail (certkit.models.aero.tail_ground_effect) against closed forms
and AVL."""

import contextlib
import io
import math

import numpy as np
import pytest

from certkit.models.aero import planform
from certkit.models.aero.tail_ground_effect import (
    LiftingLine,
    downwash_ratio,
    downwash_table,
    induced_upwash,
    lifting_line,
    mirror,
    span_load,
    vertical_velocity,
    wing_horseshoes,
)


def hand_horseshoe_downwash(l, z, s):
    """Downwash per unit Γ/(2π) of a horseshoe of semi-span s, l behind its bound leg and z above it on its centre
    plane, derived by hand from the Biot–Savart law of a straight segment, Γ/(4πd)(cos θ₁ − cos θ₂): the bound leg
    (length 2s, distance d = √(l² + z²)) gives 2s/(d√(s² + d²)) × l/d downward; each trailing leg (distance
    √(s² + z²), from the bound leg to +∞, the point l along it) (1 + l/√(s² + l² + z²))/√(s² + z²) × s/√(s² + z²)."""
    d2 = l * l + z * z
    return s * l / (d2 * math.sqrt(s * s + d2)) + s * (1 + l / math.sqrt(s * s + d2)) / (s * s + z * z)


@pytest.mark.parametrize("l,z", [(5.0, 0.5), (25.0, 2.0), (25.0, -3.0), (80.0, 10.0)])
def test_one_horseshoe_against_its_closed_form(l, z):
    # tolerance 1e-10 relative: the same law, summed segment by segment (no core)
    s = 20.0
    up = induced_upwash(np.array([l, 0.0, z]), np.array([[0.0, -s, 0.0]]), np.array([[0.0, s, 0.0]]), 0.0)[0]
    assert -up / 2.0 == pytest.approx(hand_horseshoe_downwash(l, z, s), rel=1e-10)  # ×4π/Γ → ×2π/Γ


def munk_factor(z, s):
    """Far-wake downwash of an elliptically loaded flat sheet of semispan s above its centre, over its value in the
    sheet: 1 − z/√(z² + s²) (the flat plate moving normal to itself in the Trefftz plane; Munk; Katz & Plotkin,
    Low-Speed Aerodynamics, §8.1)."""
    return 1.0 - abs(z) / math.sqrt(z * z + s * s)


def _flat_wing(semi):
    return LiftingLine((0.0, 0.0), (0.0, semi, 0.0), (5.0, 5.0), (0.0, 0.0))


@pytest.mark.parametrize("height", [0.1, 0.2, 0.4])
def test_far_wake_of_an_elliptic_load_with_its_image(height):
    """A point 40 spans behind an unswept elliptically loaded wing (200 strips) at height h_w = ``height`` spans,
    on the centre plane 0.1 span above the wake: the wake alone and the wake with its image in the runway against
    the Trefftz-plane closed form, ε_g/ε = 1 − F(h_t + h_w)/F(h_t − h_w), F = munk_factor. Tolerance 0.01 absolute
    (discrete strips and the far end of the trailing legs 40 spans away)."""
    semi, n = 10.0, 200
    wing = _flat_wing(semi)
    a, b, _, _ = wing_horseshoes(wing, n)
    eta = 0.5 * (a[:, 1] + b[:, 1]) / semi
    gamma = np.sqrt(1.0 - eta**2)
    l, dz, hw = 40 * 2 * semi, 0.1 * 2 * semi, height * 2 * semi
    point = np.array([l, 0.0, dz])
    free = -vertical_velocity(point, a, b, gamma, 1e-3)
    reference = -vertical_velocity(np.array([l, 0.0, 0.5 * semi]), a, b, gamma, 1e-3)
    assert free / reference == pytest.approx(munk_factor(dz, semi) / munk_factor(0.5 * semi, semi), abs=0.01)
    ia, ib, ig = mirror(a, b, gamma, -hw)
    ground = free - vertical_velocity(point, ia, ib, ig, 1e-3)
    expected = 1.0 - munk_factor(dz + 2 * hw, semi) / munk_factor(dz, semi)
    assert ground / free == pytest.approx(expected, abs=0.01)


def test_no_flow_through_the_runway():
    """The wing's vortices and their image leave no velocity normal to the runway (the image's definition), with the
    load solved in ground effect (Weissinger strips): points on the plane, around and behind a swept wing with
    dihedral, within 1e-12 of the wing's own field."""
    wing = LiftingLine((10.0, 0.0), (20.0, 15.0, 2.0), (6.0, 2.0), (14.0, 0.8))
    ground = -3.0
    load = span_load(wing, 30.0, ground)
    a, b, _, _ = wing_horseshoes(wing)
    ia, ib, ig = mirror(a, b, load, ground)
    pts = np.array([[x, y, ground] for x in (0.0, 12.0, 30.0, 60.0) for y in (-20.0, -4.0, 0.0, 7.0)])
    own = vertical_velocity(pts, a, b, load, 0.3)
    total = own + vertical_velocity(pts, ia, ib, ig, 0.3)
    assert np.max(np.abs(total)) < 1e-12 * np.max(np.abs(own))


@pytest.fixture(scope="module")
def baseline_lines(baseline):
    g = baseline.model.geometry
    span = float(planform.span(g.wing.area, g.wing.aspect_ratio))
    return lifting_line(g.wing), lifting_line(g.horizontal_tail), span, g.landing_gear.main.z


def test_far_field_decay(baseline_lines):
    """Far above the runway the image's field at the tail falls as 1/(h_t + h_w)²: (1 − R) h² is constant within 8 %
    between h/b = 1 and 2, and R is within 0.5 % of 1 at h/b = 2 (where the wing's ground effect also ends)."""
    wing, tail, span, _ = baseline_lines
    table = downwash_table(wing, tail, span, 2.0)
    dz = tail.reference[1] - wing.reference[1]
    c = [(1.0 - downwash_ratio(table, hb, dz)) * hb**2 for hb in (1.0, 1.5, 1.95)]
    assert c[1] == pytest.approx(c[0], rel=0.08) and c[2] == pytest.approx(c[0], rel=0.08)
    assert 0.995 < downwash_ratio(table, 2.0, dz) < 1.0
    assert np.all(np.diff([downwash_ratio(table, hb, dz) for hb in np.linspace(0.08, 2.0, 40)]) > 0.0)


def _avl_tail_and_wing_slopes(config, ground_z, path):
    """AVL (optvl) lift slopes per 2° of α of the horizontal tail and the wing (C_L per surface, both halves), with the
    ground plane at Z = ``ground_z`` (IZsym = 1) or none."""
    optvl = pytest.importorskip("optvl")
    from certkit.models.aero.vlm.avl_file import write_avl

    write_avl(config, path)
    lines = path.read_text().splitlines()
    lines[2] = "0  0  0.0" if ground_z is None else f"0  1  {ground_z}"
    path.write_text("\n".join(lines) + "\n")
    out = {}
    with contextlib.redirect_stdout(io.StringIO()):
        solver = optvl.OVLSolver(geo_file=str(path))
        solver.set_parameter("Mach", 0.2)
        for alpha in (0.0, 2.0):
            solver.set_constraint("alpha", "alpha", alpha)
            solver.execute_run()
            out[alpha] = solver.get_surface_forces()

    def slope(name):
        return sum(out[2.0][k]["CL"] - out[0.0][k]["CL"] for k in out[0.0] if k.startswith(name))

    return slope("horizontal_tail"), slope("wing")


@pytest.mark.parametrize("height", [0.0, 5.0, 10.0, 20.0, 40.0])
def test_downwash_ratio_against_avl_ground_plane(baseline, baseline_lines, height, tmp_path):
    """AVL 3.52 (optvl 2.5.0) with its ground plane (IZsym = 1) on the baseline's downwash lattice (wing, 64 strips,
    and horizontal tail; :func:`certkit.models.aero.airplane.downwash_configurations`) and the tail alone, at zero
    attitude with the runway ``height`` m below the gear: the downwash gradient at the tail
    dε/dα = 1 − C_Lα,t(with wing)/C_Lα,t(alone), per unit wing lift, over its free-air value,
    [dε/dα / C_Lα,w](ground) / [dε/dα / C_Lα,w](free), against R. Tolerance 0.02 absolute (on the runway R = 0.50,
    AVL 0.50; 0.64 against 0.65 5 m higher)."""
    from certkit.models.aero.airplane import downwash_configurations

    wing, tail, span, gear_z = baseline_lines
    on, alone = downwash_configurations(baseline.model)

    def per_lift(ground_z):
        t_on, w_on = _avl_tail_and_wing_slopes(on, ground_z, tmp_path / "on.avl")
        t_alone, _ = _avl_tail_and_wing_slopes(alone, ground_z, tmp_path / "alone.avl")
        return (1.0 - t_on / t_alone) / w_on

    avl = per_lift(gear_z - height) / per_lift(None)
    table = downwash_table(wing, tail, span, 2.0)
    h_wing = wing.reference[1] - (gear_z - height)
    r = downwash_ratio(table, h_wing / span, tail.reference[1] - wing.reference[1])
    assert r == pytest.approx(avl, abs=0.02)
