"""Evidence data of §25.349(a): aileron, roll rate, sideslip, and wing-root bending and torsion of both halves for
the critical rolling condition (largest |wing root bending| over both halves), and the critical-case tables."""

from __future__ import annotations

import numpy as np

from certkit.engine.evidence.data import Axis, Chart, Limit, Panel, Series
from certkit.engine.evidence.loads import Allowables, Run, _peak_point, case_table, not_simulated
from certkit.engine.results import Evidence


def critical_condition(run: Run) -> int:
    """Index of the condition with the largest |wing root bending| over both halves and the time history."""
    bend = np.fmax(
        np.nanmax(np.abs(run.right["wing"][:, :, 1, 0]), axis=0),
        np.nanmax(np.abs(run.left["wing"][:, :, 1, 0]), axis=0),
    )
    return int(np.nanargmax(bend))


def roll_history(run: Run, i: int, allow: Allowables | None = None) -> Chart:
    sim, ja = run.records, run.aileron_index
    t = sim.t
    steady = [Limit(float(run.t_end[i]), "steady roll rate", axis="x", kind="event")]
    halves = (("right (down-going)", run.right), ("left (up-going)", run.left))
    root = run.env_sides.stations["wing"][0]
    caps = (allow or {}).get("wing", {})

    def side_panel(q: int, name: str, quantity: str) -> Panel:
        lines = [
            Series(lab, t, loads["wing"][:, i, q, 0], critical=k == 0, colour=k)
            for k, (lab, loads) in enumerate(halves)
        ]
        cap = caps.get((root, quantity))
        lims = (
            [Limit(cap[0], "allowable (−)", kind="allowable"), Limit(cap[1], "allowable (+)", kind="allowable")]
            if cap
            else []
        )
        return Panel(
            Axis(name, "N·m", "kN·m"),
            lines,
            steady + lims,
            _peak_point(max(lines, key=lambda s: np.nanmax(np.abs(s.y)))),
        )

    panels = [
        Panel(Axis("aileron", "rad"), [Series("aileron", t, sim.controls[:, i, ja], colour=6)], steady),
        Panel(Axis("roll rate p", "rad/s"), [Series("roll rate p", t, sim["p"][:, i], colour=2)], steady),
        Panel(Axis("sideslip β", "rad"), [Series("sideslip β", t, sim["beta"][:, i], colour=3)], steady),
        side_panel(1, "wing root bending", "bending"),
        side_panel(2, "wing root torsion", "torsion"),
    ]
    return Chart(Axis("time", "s"), panels, title=run.conditions[i].label())


def roll_evidence(run: Run, allow: Allowables | None = None) -> list[Evidence]:
    i = critical_condition(run)
    sides, fin = run.env_sides, run.env_fin
    return [
        Evidence(
            "Critical rolling manoeuvre: aileron, roll rate, sideslip, wing-root bending and torsion of both halves",
            roll_history(run, i, allow),
            caption="Aileron ramped to its deflection from a steady symmetric manoeuvre; loads are considered up "
            "to the steady rolling velocity (dotted line, where the roll rate first stops growing); the left "
            "half's loads are those of the right half in the mirror-image response.",
        ),
        Evidence("Wing critical cases (condition — half)", table=case_table(sides, "wing", allow=allow)),
        Evidence(
            "Horizontal-tail critical cases (condition — half)", table=case_table(sides, "horizontal_tail", allow=allow)
        ),
        Evidence("Vertical-tail critical cases", table=case_table(fin, "vertical_tail", allow=allow)),
    ] + not_simulated(run.failed)
