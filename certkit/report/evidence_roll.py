"""Evidence of §25.349(a): aileron, roll rate and wing-root bending of both halves for the critical rolling
condition (largest |wing root bending| over both halves), and the critical-case tables."""

from __future__ import annotations

import numpy as np

from certkit.report.plots import figure_to_svg, subplots
from certkit.results import Evidence


def critical_condition(run) -> int:
    """Index of the condition with the largest |wing root bending| over both halves and the time history."""
    bend = np.fmax(np.nanmax(np.abs(run["right"]["wing"][:, :, 1, 0]), axis=0),
                   np.nanmax(np.abs(run["left"]["wing"][:, :, 1, 0]), axis=0))
    return int(np.nanargmax(bend))


def roll_history_svg(run, i: int) -> str:
    sim, ja = run["sim"], run["aileron_index"]
    t = sim.t
    fig, axes = subplots(4, 1, figsize=(6.8, 7.4), sharex=True, top=0.35)
    axes[0].plot(t, np.degrees(sim.controls[:, i, ja]), lw=1.2)
    axes[1].plot(t, np.degrees(sim["p"][:, i]), lw=1.2, label="roll rate p")
    axes[1].plot(t, np.degrees(sim["beta"][:, i]), lw=1.0, ls="--", label="sideslip β")
    axes[1].legend(fontsize=7)
    axes[2].plot(t, run["right"]["wing"][:, i, 1, 0] / 1e6, lw=1.2, label="right (down-going)")
    axes[2].plot(t, run["left"]["wing"][:, i, 1, 0] / 1e6, lw=1.2, label="left (up-going)")
    axes[2].legend(fontsize=7)
    axes[3].plot(t, run["right"]["wing"][:, i, 2, 0] / 1e6, lw=1.2, label="right (down-going)")
    axes[3].plot(t, run["left"]["wing"][:, i, 2, 0] / 1e6, lw=1.2, label="left (up-going)")
    for ax in axes:
        ax.axvline(run["t_end"][i], color="0.6", lw=0.6, ls="--")
    for ax, lab in zip(axes, ("aileron (deg)", "p (deg/s), β (deg)", "wing root bending (MN·m)", "wing root torsion (MN·m)")):
        ax.set_ylabel(lab, fontsize=8)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("time (s)")
    axes[0].set_title(run["conditions"][i].label(), fontsize=8)
    return figure_to_svg(fig)


def roll_evidence(run) -> list[Evidence]:
    i = critical_condition(run)
    out = [Evidence("Critical rolling manoeuvre: aileron, roll rate, wing-root bending and torsion of both halves",
                    roll_history_svg(run, i),
                    caption="Aileron ramped to its deflection from a steady symmetric manoeuvre; loads are considered up "
                            "to the steady rolling velocity (dashed line, where the roll rate first stops growing); the left "
                            "half's loads are those of the right half in the mirror-image response."),
           Evidence("Wing critical cases (condition — half)", table=run["env_sides"].table("wing")),
           Evidence("Horizontal-tail critical cases (condition — half)", table=run["env_sides"].table("horizontal_tail")),
           Evidence("Vertical-tail critical cases", table=run["env_fin"].table("vertical_tail"))]
    if run.get("failed"):
        out.append(Evidence("Conditions not simulated", table=[{"condition": c, "reason": r} for c, r in run["failed"]]))
    return out
