"""The steady flight the stability rules trim at (rules/part25/support/stability_speeds.py): level flight, or beyond
the level-flight ceiling the steady descent at full thrust (below the idle floor the climb at idle). A trim stub
returns what a trim at each throttle setting would: the selection logic is checked against the flight-path signs."""

from types import SimpleNamespace

import numpy as np
from certkit_rules.part25.support.stability_speeds import LEVEL_PATH_TOLERANCE, steady_flight_trims

THROTTLE_LIMITED = SimpleNamespace(converged=False, limits_exceeded=[SimpleNamespace(control="throttle")], gamma=0.0)


class StubContext:
    """``trim(conds, kind, beta, throttle=None)``: level flight throttle-limited; at full thrust the path ``full``; at
    idle ``idle`` (rad). The kind and sideslips asked are kept (``asked``)."""

    def __init__(self, full: float, idle: float):
        self.full, self.idle = full, idle
        self.asked = []

    def trim(self, conds, kind="straight", beta=0.0, throttle=None):
        self.asked.append((kind, np.atleast_1d(beta).tolist(), throttle))
        if throttle is None:
            return SimpleNamespace(results=[THROTTLE_LIMITED for _ in conds])
        gamma = self.full if throttle >= 1.0 else self.idle
        return SimpleNamespace(
            results=[SimpleNamespace(converged=True, limits_exceeded=[], gamma=gamma) for _ in conds]
        )


def test_beyond_the_ceiling_the_full_thrust_descent():
    results, stops = steady_flight_trims(StubContext(full=-0.01, idle=-0.1), ["c"])
    assert stops == [1.0] and results[0].gamma == -0.01


def test_at_the_ceiling_the_full_thrust_trim_is_level_flight():
    """A level trim that needs full thrust to within its own tolerance reports 'more than full throttle' while the
    full-thrust trim climbs by 7e-7 rad (a design of the horizontal-tail study, aft_mrw landing at 20,000 ft): the
    full-thrust trim is kept, not a 'not evaluated' condition; a real climb at full thrust is not."""
    results, stops = steady_flight_trims(StubContext(full=7e-7, idle=-0.1), ["c"])
    assert stops == [1.0]
    results, stops = steady_flight_trims(StubContext(full=10 * LEVEL_PATH_TOLERANCE, idle=-0.1), ["c"])
    assert stops == [None] and not results[0].converged


def test_below_the_idle_floor_the_idle_climb():
    results, stops = steady_flight_trims(StubContext(full=0.05, idle=0.01), ["c"])
    assert stops == [0.0] and results[0].gamma == 0.01


def test_sideslips_are_retried_at_the_stop_with_their_own_sideslip():
    """A steady-heading sideslip beyond the ceiling is trimmed again at full thrust with the same kind and, row by row,
    the sideslip of the condition retried (the others keep their level trims)."""
    stub = StubContext(full=-0.01, idle=-0.1)
    results, stops = steady_flight_trims(stub, ["a", "b"], kind="sideslip", beta=[0.05, 0.1])
    assert stops == [1.0, 1.0] and [r.gamma for r in results] == [-0.01, -0.01]
    assert stub.asked == [("sideslip", [0.05, 0.1], None), ("sideslip", [0.05, 0.1], 1.0)]
