"""Strip loads model: a steady pull-up balanced by hand, signs, and the inertial terms.

The pull-up state (α, δe at n = 2.5, q = (n − 1) g / V) is solved by hand from the airplane's linear
derivatives (two equations: lift = nW, moment about the CG = 0). The hand balance then finds the tail
load as the part of nW the wing does not carry, with the wing's load from a vortex lattice of the wing
alone (no tail): N_tail = nW − N_wing. Tolerance 5 % of the tail load (the wing alone lacks the small
upwash of the tail's bound vortex; the normal force differs from the lift by cos α at α ≈ 3°).
"""

import numpy as np
import pytest

from certkit.aircraft import LoadedAircraft
from certkit.atmosphere import density
from certkit.design import evaluate
from certkit.design.variables import design_aircraft, design_data, settings_from
from certkit.engine.context import Context
from certkit.models.aero.airplane import lattice_configuration
from certkit.models.aero.vlm import Configuration, VortexLattice
from certkit.models.loads.model import airplane_loads
from certkit.units import G0, KN, LB

from ..conftest import BASELINE

MACH = 0.6


@pytest.fixture(scope="module")
def setup(baseline):
    ctx = Context(baseline)
    return ctx, airplane_loads(ctx)


def pull_up_state(ctx, mass, x_cg, n, v_eas):
    m = ctx.aero("clean").model
    ref = ctx.aircraft.reference
    S, c, xref = ref.area, ref.mean_chord, ref.moment_point.x
    d = lambda k: float(m.derivative(k, MACH))  # noqa: E731
    qbar = 0.5 * density(0.0) * v_eas**2
    qh = (n - 1) * G0 / v_eas * c / (2 * v_eas)
    arm = (x_cg - xref) / c  # lift at the reference point, ahead of the CG: nose up
    A = np.array(
        [
            [d("CL_alpha"), d("CL_elevator")],
            [d("Cm_alpha") + d("CL_alpha") * arm, d("Cm_elevator") + d("CL_elevator") * arm],
        ]
    )
    rhs = np.array(
        [
            n * mass * G0 / (qbar * S) - d("CL0") - d("CL_q") * qh,
            -(d("Cm0") + d("CL0") * arm + (d("Cm_q") + d("CL_q") * arm) * qh),
        ]
    )
    alpha, de = np.linalg.solve(A, rhs)
    return qbar, {"alpha": alpha, "q_hat": qh, "elevator": de}


def test_steady_pull_up_tail_load_against_hand_balance(setup):
    """400,000 lb, CG 29.5 m, 340 KEAS at sea level (M 0.6 breakpoint), n = 2.5."""
    ctx, loads = setup
    mass, n = 400_000 * LB, 2.5
    qbar, state = pull_up_state(ctx, mass, 29.5, n, 340 * KN)
    assert 0.0 < state["alpha"] < np.radians(5)
    tail = 2 * loads["horizontal_tail"].aero_loads(qbar, MACH, state)[0, 0]  # both halves, root shear
    wing_model = 2 * loads["wing"].aero_loads(qbar, MACH, state)[0, 0]
    cfg = lattice_configuration(ctx.aircraft)
    wing_alone = VortexLattice(Configuration(cfg.surfaces[:1], cfg.reference), mach=MACH)
    sol = wing_alone.solve(alpha=state["alpha"], q_hat=state["q_hat"], rate_axes="body")
    n_wing = -sol.CZ * qbar * ctx.aircraft.reference.area
    hand_tail = n * mass * G0 - n_wing
    assert tail < 0  # a download trims the nose-down wing moment at this CG
    assert tail == pytest.approx(hand_tail, rel=0.05)
    assert wing_model + tail == pytest.approx(n * mass * G0, rel=0.01)


def test_signs(setup):
    """Trailing edge up elevator (negative) pushes the tail down; a nose-up pitch rate loads it up
    (tail moving down meets the air from below); upward load gives positive root bending and, acting
    aft of the 40 % chord axis on a swept tail, nose-down (negative) torsion."""
    ctx, loads = setup
    ht = loads["horizontal_tail"]
    base = ht.aero_loads(20e3, MACH, {"alpha": 0.03})
    up = ht.aero_loads(20e3, MACH, {"alpha": 0.03, "elevator": -0.1})
    pitch = ht.aero_loads(20e3, MACH, {"alpha": 0.03, "q_hat": 0.01})
    assert up[0, 0] < base[0, 0] and pitch[0, 0] > base[0, 0]
    d = ht.aero_loads(20e3, MACH, {"alpha": 0.1}) - base
    assert d[0, 0] > 0 and d[1, 0] > 0 and d[2, 0] < 0
    # shear decreases outboard and vanishes at the tip side
    assert np.all(np.diff(np.abs(d[0])) <= 1e-9)
    fin = loads["vertical_tail"]
    side = fin.aero_loads(20e3, MACH, {"beta": 0.05}) - fin.aero_loads(20e3, MACH, {})
    assert side[0, 0] < 0  # wind from the right pushes the fin to the left (−Y)
    rud = fin.aero_loads(20e3, MACH, {"rudder": 0.1}) - fin.aero_loads(20e3, MACH, {})
    assert rud[0, 0] > 0  # trailing edge left: fin force to the right, nose-left yawing moment


def test_inertia_terms(setup):
    """1 g inertial shear at the tail root equals the half-tail's weight, downward, times cos 7° (the
    shear is normal to the tail's plane, 7° dihedral); a nose-up pitch acceleration moves the tail
    (aft of the CG) down, so its inertial force on the structure is upward: m q̇ (X − X_cg) cos 7°."""
    ctx, loads = setup
    ht = loads["horizontal_tail"]
    one_g = ht.inertia_loads({"n_z": 1.0})
    assert one_g[0, 0] == pytest.approx(-ht.structural_mass * G0 * np.cos(np.radians(7.0)), rel=1e-9)
    x_cg = 29.5
    qdot = ht.inertia_loads({"qdot_xcg": 0.1 * x_cg, "qdot": 0.1})
    # tail aft of the CG: nose-up acceleration moves it down, inertial force up on the structure
    assert qdot[0, 0] == pytest.approx(
        ht.structural_mass * 0.1 * (np.average(ht.strip_x, weights=ht.strip_mass) - x_cg) * np.cos(np.radians(7.0)),
        rel=1e-6,
    )
    assert ht.structural_mass * 2 == pytest.approx(5800 * LB, rel=1e-9)


def _unit_vortex_forces(vl, unit):
    """Bound-leg Kutta–Joukowski forces of every vortex per unit q̄ and unit input (central difference)."""
    e = 1e-3
    if unit == "alpha":
        return (vl.vortex_forces(alpha=e, rate_axes="body") - vl.vortex_forces(alpha=-e, rate_axes="body")) / (2 * e)
    plus = vl.vortex_forces(controls={unit: e}, rate_axes="body")
    return (plus - vl.vortex_forces(controls={unit: -e}, rate_axes="body")) / (2 * e)


@pytest.mark.parametrize(("surface", "unit"), [("horizontal_tail", "stabilizer"), ("wing", "alpha")])
def test_root_torsion_of_a_uniform_incidence_change(setup, surface, unit):
    """Root torsion of a uniform incidence change (the all-moving tailplane's stabiliser; the wing's α) about the
    root's 40 % chord axis, two ways not used by the strip model:

    * thin-airfoil theory puts each strip's added lift at its quarter chord (Anderson, *Fundamentals of
      Aerodynamics*, §4.7: the symmetric airfoil's centre of pressure; incompressible, so at M 0.2): Σ N (X_axis −
      X_c/4) with the model's strip forces N, within 5 % (the downwash of a swept surface adds a little induced
      camber);
    * the moments of the lattice solver's own bound-vortex forces (the forces AVL sums for hinge moments) about the
      same axis, within 3 % at every Mach breakpoint up to 0.75.

    The strip model once scaled the whole X from the nose by a force-per-circulation ratio read from another
    input's solution: the tailplane's root torsion per unit stabiliser came out +285 kN·m per unit q̄ instead of
    about −500."""
    from certkit.models.loads.model import _strip_indices

    ctx, loads = setup
    s = loads[surface]
    k = s.inputs.index(unit)
    assert s.station_span[0] == 0.0
    x_axis_root = np.interp(0.0, s.strip_span, s.strip_x)
    for m, mach in enumerate(s.mach[:4]):
        vl = ctx.aero("clean").lattice.at_mach(float(mach))
        lat = vl.lattice
        idx = _strip_indices(lat, surface)
        if m == 0:
            x_quarter = s.strip_x - (s.axis_fraction - 0.25) * lat.chord[idx]
            thin_airfoil = np.sum(s.strip_aero[m, k] * (x_axis_root - x_quarter))
            assert s.aero[m, k, 2, 0] == pytest.approx(thin_airfoil, rel=0.05)
        f = _unit_vortex_forces(vl, unit)
        mine = np.isin(lat.vortex_strip, idx)
        strip = lat.vortex_strip[mine]
        normal = (f[mine, 1] * lat.ensy[strip] + f[mine, 2] * lat.ensz[strip]) * np.sign(lat.ensz[strip])
        solver = np.sum(normal * (x_axis_root - lat.rv[mine, 0]))
        assert s.aero[m, k, 2, 0] == pytest.approx(solver, rel=0.03)


def test_a_point_mass_is_shared_between_the_strips_that_bracket_it():
    """The shares keep the mass and its first moment (span × mass) exactly; at or beyond the outermost strip middles
    the end strip takes it whole."""
    from certkit.models.loads.model import bracketing_shares

    s_mid = np.array([0.5, 2.0, 4.0, 7.0])[[2, 0, 3, 1]]  # strips in any order
    for span in (0.2, 0.5, 1.1, 2.0, 3.3, 6.9, 7.0, 9.0):
        shares = bracketing_shares(s_mid, span)
        assert sum(w for _, w in shares) == pytest.approx(1.0)
        assert all(w >= 0 for _, w in shares)
        inside = min(max(span, 0.5), 7.0)
        assert sum(w * s_mid[j] for j, w in shares) == pytest.approx(inside)


def test_the_flight_model_and_the_strip_loads_share_one_lattice(setup):
    """One lattice per airplane: the strip loads' unit solutions come from the flight model's lattice, whose wing flap
    (the loads spread the configurations' flap lift with it) is not a control of the flight model — so each design's
    lattice is solved once per Mach number."""
    from certkit.models.aero.airplane import FLAP_CONTROL

    ctx, loads = setup
    aero = ctx.aero("clean")
    assert FLAP_CONTROL in aero.lattice.control_names
    assert FLAP_CONTROL not in aero.model.control_names
    assert FLAP_CONTROL in loads["wing"].inputs
    assert ctx.aero("takeoff").lattice is aero.lattice
    solutions = ctx._memo[("aero", "loads unit solutions", "clean", id(aero.lattice))]
    unit = [key for key in solutions if isinstance(key[0], float)]  # (Mach, input, value); the rest strip tables
    assert unit and {mach for mach, *_ in unit} <= {float(m) for m in aero.mach}


def test_a_swept_small_tail_keeps_its_root_torsion_at_high_mach():
    """A study corner's tail (1,006 ft², aspect ratio 4.5, 39.8° sweep, elevator from 15 % span): at M 0.94 the
    lattice's root strips hardly change their circulation with α, and the force per unit circulation read as the
    quotient of the two differences was 10⁴ × the Kutta–Joukowski value (negative on the neighbouring strips). The
    root torsion per unit α and per unit q̂ then jumped 17× and 6× from M 0.90 to 0.94, and a VD condition between
    the two sized the tail for 33 MN·m (against about 1 MN·m at the side of body). Physical expectation: the strip
    loads move smoothly with Mach (Prandtl–Glauert: a few tens of percent between M 0.90 and 0.94) — the root
    torsion stays within 1.5× of the M 0.90 value, with its sign."""

    values = {  # SI, as the study drew them
        "geometry.horizontal_tail.aspect_ratio": 4.513893511730139,
        "geometry.horizontal_tail.taper": 0.36275296352826814,
        "geometry.horizontal_tail.thickness_ratio": 0.08731380397253782,
        "geometry.horizontal_tail.sweep_quarter_chord": 0.6942428720173881,
        "geometry.horizontal_tail.area": 93.43595932886856,
        "geometry.horizontal_tail.controls.elevator.span_start": 0.15373161588016943,
        "geometry.horizontal_tail.controls.elevator.span_end": 0.9223246435174545,
        "geometry.horizontal_tail.controls.elevator.chord_ratio": 0.264750735012785,
    }
    source = evaluate._source(str(BASELINE))  # the design layer's reading of the file
    settings = settings_from(values)
    aircraft = design_aircraft(source, settings, design_data(source, settings))
    loaded = LoadedAircraft(model=aircraft, path=str(BASELINE), sha256=source.sha256, source=source)
    tail = airplane_loads(Context(loaded))["horizontal_tail"]
    m = list(np.round(tail.mach, 6))
    i90, i94 = m.index(0.9), m.index(0.94)
    root, torsion = tail.station_names.index("root"), 2
    for name in ("alpha", "q_hat", "elevator"):
        k = tail.inputs.index(name)
        at90, at94 = tail.aero[i90, k, torsion, root], tail.aero[i94, k, torsion, root]
        assert at94 / at90 == pytest.approx(1.0, abs=0.5), name


def test_airplanes_of_one_lattice_share_the_aerodynamic_tables():
    """The sizing loop's passes (one geometry, the tail's mass changed) share the lattice and its aerodynamic strip
    tables: the second airplane's tables are the first's, bit for bit those of its own build, and only the inertial
    tables follow the new mass (the tail's doubled: its inertial loads per unit load factor double)."""
    source = evaluate._source(str(BASELINE))
    data = design_data(source, [])
    heavier = dict(data)
    heavier["mass"] = dict(data["mass"])
    components = [dict(c) for c in data["mass"]["components"]]
    (tail,) = [c for c in components if c["name"].strip().lower() == "horizontal tail"]
    tail["mass"] = f"{2 * float(str(tail['mass']).split()[0])} lb"  # declared "5800 lb"
    heavier["mass"]["components"] = components

    def context(d):
        model = design_aircraft(source, [], d)
        return Context(LoadedAircraft(model=model, path=str(BASELINE), sha256=source.sha256, source=source))

    first, second = context(data), context(heavier)
    one = airplane_loads(first)
    second.share_aerodynamics(first)  # as the loop's next pass shares the pass before's
    two, alone = airplane_loads(second), airplane_loads(context(heavier))
    for name in ("wing", "horizontal_tail", "vertical_tail"):
        assert two[name].aero is one[name].aero
        for table in ("aero", "strip_aero", "vertical_force", "inertia"):
            np.testing.assert_array_equal(getattr(two[name], table), getattr(alone[name], table), strict=True)
    ratio = two["horizontal_tail"].inertia[0] / one["horizontal_tail"].inertia[0]
    assert np.nanmax(np.abs(ratio[np.isfinite(ratio)] - 2.0)) < 1e-9
