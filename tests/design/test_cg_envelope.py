"""Weight–CG corners that follow the design's loading (``sizing.cg_envelope: loading``).

References: the loading solver's own reach (a CG the payload zones and fuel tanks reach is solved without ballast,
one 5 cm beyond is not); the moment balance (a heavier tail aft of every corner moves the empty airplane's CG aft,
so the most forward CG the loading reaches moves aft); the declared envelope bounds every corner.
"""

from certkit.aircraft import load_aircraft
from certkit.aircraft.model import Sizing
from certkit.design.cg_envelope import follows_loading, loading_corners
from certkit.engine.conditions import cg_limits_at
from certkit.models.mass.loading import reachable_cg_range, solve_loading
from certkit.units import LB
from tests.rules.helpers import edited_baseline

TAIL = "- {name: horizontal tail, group: structure, mass: 5800 lb,"


def _ballasted(loading) -> bool:
    return any("ballast" in n for n in loading.notes)


def test_off_by_default(baseline):
    assert Sizing().cg_envelope == "declared" and not follows_loading(baseline.model)


def test_reachable_range_is_the_loading_solvers_reach(baseline):
    ac = baseline.model
    mass = 500000 * LB
    fwd, aft = reachable_cg_range(ac, mass)
    assert fwd < aft
    assert not _ballasted(solve_loading(ac, mass, fwd + 0.01)) and not _ballasted(solve_loading(ac, mass, aft - 0.01))
    assert _ballasted(solve_loading(ac, mass, fwd - 0.05)) and _ballasted(solve_loading(ac, mass, aft + 0.05))
    assert reachable_cg_range(ac, 0.5 * ac.mass.OEW) is None  # below the empty weight: no loading


def test_corners_stay_within_the_declared_envelope(baseline):
    ac = baseline.model
    corners = loading_corners(ac, ac)
    assert [c["name"] for c in corners] == [v.name for v in ac.cg_envelope.vertices]
    for c in corners:
        fwd, aft = cg_limits_at(ac, c["mass"])
        assert fwd - 1e-9 <= c["x"] <= aft + 1e-9
        if c["reachable_x"] is not None and c["x"] != c["declared_x"]:  # moved: onto the loading's reach
            assert min(abs(c["x"] - r) for r in c["reachable_x"]) < 1e-9


def test_a_heavier_tail_moves_the_forward_corners_aft(tmp_path, baseline):
    """Deficient by mass: the tail 3,000 lb heavier (at its station, 187 ft, aft of every corner) moves the empty
    CG aft; wherever the loading cannot reach the declared forward limit the forward corner moves aft with it."""
    heavy = load_aircraft(edited_baseline(tmp_path, [(TAIL, TAIL.replace("5800 lb", "8800 lb"))])).model
    ac = baseline.model
    light, loaded = loading_corners(ac, ac), loading_corners(heavy, ac)
    moved = 0
    for a, b in zip(light, loaded):
        fwd, _ = cg_limits_at(ac, a["mass"])
        if abs(a["declared_x"] - fwd) < 1e-9 and b["reachable_x"] is not None:
            assert b["reachable_x"][0] > a["reachable_x"][0]  # the loading's forward reach moves aft
            assert b["x"] >= a["x"] - 1e-9
            moved += b["x"] > a["x"] + 1e-6
    assert moved >= 1


def test_the_sizing_loop_evaluates_the_design_at_its_own_corners(tmp_path):
    """With the option the loop flies the corners of the airplane carrying its sized tail group: the record lists
    them (moved corners on the reach of that airplane's loading, every corner inside the declared envelope) and the
    loads rules' conditions are at those CGs."""
    from certkit.design.evaluate import evaluate_design

    path = edited_baseline(tmp_path, [("sizing:\n", "sizing:\n  cg_envelope: loading\n")])
    rec = evaluate_design(str(path), {}, responses=["sizing.*"])
    corners = rec["details"]["sizing"]["cg_envelope"]
    declared = load_aircraft(path).model
    assert [c["name"] for c in corners] == [v.name for v in declared.cg_envelope.vertices]
    assert any(c["x"] != c["declared_x"] for c in corners)
    for c in corners:
        fwd, aft = cg_limits_at(declared, c["mass"])
        assert fwd - 1e-9 <= c["x"] <= aft + 1e-9
    crit = rec["details"]["sizing"]["envelope"]["critical"]
    xs = {round(c["x"] / 0.3048, 2) for c in corners}
    assert any(f"CG {x:.2f} ft" in k["condition"] for k in crit for x in xs)
