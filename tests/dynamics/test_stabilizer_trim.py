"""Movable horizontal stabiliser: lattice effectiveness against thin-aerofoil theory, trims that solve for
the stabiliser with the elevator at its trim setting, the stop, and airplanes without the declaration."""

import math
from dataclasses import replace

import numpy as np
import pytest

from certkit.engine.conditions import Condition
from certkit.engine.context import Context
from certkit.units import FT, KN, LB


def _without_stabilizer(loaded):
    g = loaded.model.geometry
    tail = g.horizontal_tail.model_copy(update={"stabilizer": None})
    return replace(
        loaded, model=loaded.model.model_copy(update={"geometry": g.model_copy(update={"horizontal_tail": tail})})
    )


def _with_travel(loaded, lo_deg, hi_deg):
    g = loaded.model.geometry
    st = g.horizontal_tail.stabilizer
    from certkit.aircraft.model import Limits

    lim = Limits(min=math.radians(lo_deg), max=math.radians(hi_deg))
    tail = g.horizontal_tail.model_copy(
        update={"stabilizer": st.model_copy(update={"travel": lim, "design_limits": lim})}
    )
    return replace(
        loaded, model=loaded.model.model_copy(update={"geometry": g.model_copy(update={"horizontal_tail": tail})})
    )


@pytest.fixture(scope="module")
def ctx(baseline):
    return Context(baseline)


def test_elevator_per_stabiliser_effectiveness_matches_thin_aerofoil_theory(ctx):
    """Cm_δe / Cm_δs of the lattice against an independent estimate: the elevator's two-dimensional flap effectiveness
    τ = 1 − (θf − sin θf)/π with cos θf = 2 cf/c − 1 (Glauert, thin-aerofoil theory; Abbott & von Doenhoff §8.4),
    times the share of an elliptic span loading over the elevator's span (0.07–0.94 of the semispan: (2/π)(η√(1−η²) +
    asin η) between the ends), times cos Λ of the hinge line, the swept-flap factor of Raymer eq. 12.22, against a
    stabiliser turning the whole section about the pitch axis. Tolerance 10 % (linear theory both ways)."""
    el = ctx.aircraft.geometry.horizontal_tail
    e = el.controls["elevator"]
    theta_f = math.acos(2.0 * e.chord_ratio - 1.0)
    tau = 1.0 - (theta_f - math.sin(theta_f)) / math.pi
    share = lambda eta: 2.0 / math.pi * (eta * math.sqrt(1.0 - eta * eta) + math.asin(eta))  # noqa: E731
    kb = share(e.span_end) - share(e.span_start)
    x_hinge = 1.0 - e.chord_ratio
    tan_h = math.tan(el.sweep_quarter_chord) - 4.0 * (x_hinge - 0.25) * (1.0 - el.taper) / (
        el.aspect_ratio * (1.0 + el.taper)
    )
    expected = tau * kb * math.cos(math.atan(tan_h))
    table = ctx.aero("clean").table
    ratio = table["Cm_elevator"][0] / table["Cm_stabilizer"][0]  # lowest Mach breakpoint (0.2)
    assert ratio == pytest.approx(expected, rel=0.10)
    # and "each degree of stabiliser relieves about 2° of elevator": 1/ratio between 1.6 and 2.4
    assert 1.6 < 1.0 / ratio < 2.4


def test_other_derivatives_are_unchanged_by_the_stabiliser_control(ctx, baseline):
    """The stabiliser adds a control to the lattice; every other derivative is that of the airplane without it."""
    plain = Context(_without_stabilizer(baseline)).aero("clean").table
    table = ctx.aero("clean").table
    assert "Cm_stabilizer" not in plain
    for key, values in plain.items():
        assert np.allclose(table[key], values, rtol=1e-9, atol=1e-12), key


def _cond(mass_lb, cg_ft, config, kcas, altitude_ft=0.0):
    return Condition(
        mass=mass_lb * LB,
        x_cg=cg_ft * FT,
        configuration=config,
        altitude=altitude_ft * FT,
        speed=kcas * KN,
        speed_kind="CAS",
    )


def test_trim_solves_the_stabiliser_with_the_elevator_at_its_setting(ctx):
    conds = [_cond(656000, 97.25, "clean", 300, 10000), _cond(460000, 101.92, "clean", 250)]
    batch = ctx.trim(conds)
    datum = ctx.aircraft.geometry.horizontal_tail.incidence
    for r in batch.results:
        assert r.converged
        assert r.controls["elevator"] == 0.0  # the declared trim setting
        assert r.stabilizer == pytest.approx(datum + r.controls["stabilizer"], abs=1e-12)
        assert not r.stabilizer_at_stop
    # the same trim by hand: holding the stabiliser 1° nose-down of its trim, the elevator must move nose-up by the
    # elevator-per-stabiliser ratio of the linear pitching-moment balance, Δδe = −Δδs Cm_δs/Cm_δe (α barely changes:
    # the two surfaces' lift is small against the wing's), within 5 %
    table = ctx.aero("clean").table
    shifted = np.array([r.controls["stabilizer"] for r in batch.results[:1]]) + math.radians(1.0)
    again = ctx.trim(conds[:1], stabilizer=shifted)[0]
    assert again.stabilizer_frozen
    mach = np.interp(0.5, [0.2, 0.4], [0, 1])  # ~M 0.5 at 300 KCAS, 10,000 ft: between the first two breakpoints
    ratio = np.interp(mach, [0, 1], np.array(table["Cm_stabilizer"][:2]) / np.array(table["Cm_elevator"][:2]))
    assert math.degrees(again.controls["elevator"]) == pytest.approx(-ratio, rel=0.05)


def test_stabiliser_at_its_stop_leaves_the_rest_to_the_elevator(ctx):
    """Forward CG, landing flaps, low speed: more nose-up trim than the stabiliser has; it stays at its stop and the
    elevator carries the rest — by the effectiveness ratio within 5 %."""
    r = ctx.trim([_cond(460000, 92.04, "landing", 140)])[0]
    lo = ctx.aircraft.geometry.horizontal_tail.stabilizer.design_limits.min
    assert r.stabilizer_at_stop == "nose-up"
    assert r.stabilizer == pytest.approx(lo, abs=1e-12)
    assert r.stabilizer_required < lo
    table = ctx.aero("landing").table
    ratio = table["Cm_stabilizer"][0] / table["Cm_elevator"][0]
    assert r.controls["elevator"] == pytest.approx(ratio * (r.stabilizer_required - lo), rel=0.05)


def test_airplane_without_the_declaration_trims_with_the_elevator(baseline):
    ctx = Context(_without_stabilizer(baseline))
    r = ctx.trim([_cond(656000, 97.25, "clean", 300, 10000)])[0]
    assert r.stabilizer is None and "stabilizer" not in r.controls
    assert r.converged and r.controls["elevator"] != 0.0


def test_declaration_relations_are_checked_together(tmp_path):
    """The datum incidence outside the trim range and an elevator trim setting beyond the elevator's limits are both
    reported, with their YAML paths."""
    from certkit.aircraft import load_aircraft
    from certkit.errors import InputError

    from ..rules.helpers import edited_baseline

    path = edited_baseline(
        tmp_path, [("incidence: -2.0 deg", "incidence: 3.0 deg"), ("elevator_trim: 0 deg", "elevator_trim: 20 deg")]
    )
    with pytest.raises(InputError) as err:
        load_aircraft(path)
    text = str(err.value)
    assert "geometry.horizontal_tail.incidence" in text and "datum" in text
    assert "geometry.horizontal_tail.stabilizer.elevator_trim" in text


def test_cruise_trims_lie_within_the_published_trim_range(ctx):
    """Plausibility against the airplane the baseline stands for: a certificated 777 trims in cruise at every CG in its
    flaps-up PFC trim limits, +2.25° nose down to −10.25° nose up (777 AMM 27-41-00). At M 0.84, 35,000 ft, the
    forward and aft CG at MTOW and at the lightest corner trim inside that range with the elevator at 0°, and the aft
    CG needs less nose-up stabiliser than the forward one."""
    from certkit.atmosphere import convert_speed

    v = float(convert_speed(0.84, "MACH", "CAS", 35000 * FT)) / KN
    corners = [(656000, 94.23), (656000, 100.28), (310000, 92.04), (310000, 100.82)]
    batch = ctx.trim([_cond(m, x, "clean", v, 35000) for m, x in corners])
    lo, hi = -10.25, 2.25
    incidence = [math.degrees(r.stabilizer) for r in batch.results]
    assert all(r.converged and not r.stabilizer_at_stop for r in batch.results)
    assert all(lo < s < hi for s in incidence)
    assert incidence[1] > incidence[0] and incidence[3] > incidence[2]


def test_cli_trim_prints_the_incidence_and_the_stop(cli):
    from ..conftest import BASELINE

    out = cli(
        "trim", BASELINE, "--corner", "fwd_mlw", "--config", "landing", "--speed", "140 kn CAS", "--altitude", "0 ft"
    ).output
    line = next(ln for ln in out.splitlines() if ln.strip().startswith("stabilizer"))
    assert "-10.2500 deg incidence" in line and "nose-up stop" in line
