"""Evidence data of §25.351: rudder, sideslip and vertical-tail root shear time histories of the critical yaw
manoeuvre (largest root shear magnitude over the four phases), and the critical-case table."""

from __future__ import annotations

import numpy as np

from certkit.engine.evidence.data import Axis, Chart, Limit, Panel, Series
from certkit.engine.evidence.loads import Allowables, Run, _peak_point, case_table, not_simulated
from certkit.engine.results import Evidence


def critical_condition(run: Run) -> int:
    """Index of the condition with the largest |vertical-tail root shear| over both simulation phases."""
    held, back = run.held_loads[:, :, 0, 0], run.returned_loads[:, :, 0, 0]
    peak = np.fmax(np.nanmax(np.abs(held), axis=0), np.nanmax(np.abs(back), axis=0))
    return int(np.nanargmax(peak))


def yaw_history(run: Run, i: int, allow: Allowables | None = None) -> Chart:
    """The held phase up to the settled sideslip, then the return to neutral, as one curve per quantity."""
    r, jr = run.yaw, run.rudder_index
    t1 = r.held.t
    live = t1 <= r.t_steady[i] + 1e-9
    t = np.concatenate([t1[live], r.returned.t + r.t_steady[i]])

    def joined(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.concatenate([a[live], b])

    events = [
        Limit(float(r.t_full), "(a) full rudder", axis="x", kind="event"),
        Limit(float(r.t_overswing[i]), "(b) overswing", axis="x", kind="event"),
        Limit(float(r.t_steady[i]), "(c) settled, (d) returned", axis="x", kind="event"),
    ]
    shear = Series("fin root shear", t, joined(run.held_loads[:, i, 0, 0], run.returned_loads[:, i, 0, 0]), colour=0)
    root = run.envelope.stations["vertical_tail"][0]
    cap = (allow or {}).get("vertical_tail", {}).get((root, "shear"))
    lims = (
        [Limit(cap[0], "allowable (−)", kind="allowable"), Limit(cap[1], "allowable (+)", kind="allowable")]
        if cap
        else []
    )
    panels = [
        Panel(
            Axis("rudder", "rad"),
            [Series("rudder", t, joined(r.held.controls[:, i, jr], r.returned.controls[:, i, jr]), colour=6)],
            events,
        ),
        Panel(
            Axis("sideslip β", "rad"),
            [Series("sideslip β", t, joined(r.held["beta"][:, i], r.returned["beta"][:, i]), colour=2)],
            events,
        ),
        Panel(Axis("fin root shear", "N", "kN"), [shear], events + lims, _peak_point(shear)),
    ]
    return Chart(Axis("time", "s"), panels, title=run.conditions[i].label())


def yaw_evidence(run: Run, allow: Allowables | None = None) -> list[Evidence]:
    i = critical_condition(run)
    return [
        Evidence(
            "Critical yaw manoeuvre: rudder, sideslip and fin root shear",
            yaw_history(run, i, allow),
            caption="Phases (a) rudder applied, (b) overswing, (c) settled sideslip (dotted lines), then (d) "
            "rudder returned to neutral; roll held wings level by the ailerons.",
        ),
        Evidence(
            "Vertical-tail critical cases (condition — phase)",
            table=case_table(run.envelope, "vertical_tail", allow=allow),
        ),
    ] + not_simulated(run.failed)
