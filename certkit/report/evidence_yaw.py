"""Evidence of §25.351: rudder, sideslip and vertical-tail root shear time histories of the critical yaw
manoeuvre (largest root shear magnitude over the four phases), and the critical-case table."""

from __future__ import annotations

import numpy as np

from certkit.report.plots import figure_to_svg, subplots
from certkit.results import Evidence


def critical_condition(run) -> int:
    """Index of the condition with the largest |vertical-tail root shear| over both simulation phases."""
    held, back = run["held_loads"][:, :, 0, 0], run["returned_loads"][:, :, 0, 0]
    peak = np.fmax(np.nanmax(np.abs(held), axis=0), np.nanmax(np.abs(back), axis=0))
    return int(np.nanargmax(peak))


def yaw_history_svg(run, i: int) -> str:
    r = run["run"]
    jr = run["rudder_index"]
    t1 = r.held.t
    live = t1 <= r.t_steady[i] + 1e-9
    t2 = r.returned.t + r.t_steady[i]
    fig, axes = subplots(3, 1, figsize=(6.8, 6.0), sharex=True, top=0.35)
    axes[0].plot(t1[live], np.degrees(r.held.controls[live, i, jr]), t2, np.degrees(r.returned.controls[:, i, jr]), lw=1.2)
    axes[1].plot(t1[live], np.degrees(r.held["beta"][live, i]), t2, np.degrees(r.returned["beta"][:, i]), lw=1.2)
    axes[2].plot(t1[live], run["held_loads"][live, i, 0, 0] / 1e3, t2, run["returned_loads"][:, i, 0, 0] / 1e3, lw=1.2)
    for ax, lab in zip(axes, ("rudder (deg)", "sideslip β (deg)", "fin root shear (kN)")):
        ax.set_ylabel(lab)
        ax.grid(True, alpha=0.3)
        for tt in (r.t_full, r.t_overswing[i], r.t_steady[i]):
            ax.axvline(tt, color="0.6", lw=0.6, ls="--")
    axes[-1].set_xlabel("time (s)")
    axes[0].set_title(run["conditions"][i].label(), fontsize=8)
    return figure_to_svg(fig)


def yaw_evidence(run) -> list[Evidence]:
    i = critical_condition(run)
    out = [Evidence("Critical yaw manoeuvre: rudder, sideslip and fin root shear", yaw_history_svg(run, i),
                    caption="Phases (a) rudder applied, (b) overswing, (c) settled sideslip (dashed lines), then (d) "
                            "rudder returned to neutral; roll held wings level by the ailerons."),
           Evidence("Vertical-tail critical cases (condition — phase)", table=run["envelope"].table("vertical_tail"))]
    if run.get("failed"):
        out.append(Evidence("Conditions not simulated", table=[{"condition": c, "reason": r} for c, r in run["failed"]]))
    return out
