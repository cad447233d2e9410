"""Evidence of the loads rules: time histories of the critical conditions, load envelopes along the
span, and the critical-case table (one row per surface, station, quantity and sense)."""

from __future__ import annotations

import numpy as np

from certkit.models.loads.model import QUANTITIES
from certkit.report.plots import figure_to_svg, subplots, text_width
from certkit.results import Evidence

#: matplotlib's default colour cycle ("C0", "C1", … as colour names)
COLOURS = tuple(f"C{k}" for k in range(10))
_KIND = {0: "scaled sinusoid", 1: "held input", 2: "maximal held input"}


def _critical_indices(run, surface) -> list[int]:
    env = run["envelope"]
    picks = []
    for sense in ("max", "min"):
        _, i = env.extreme(surface, "shear", 0, sense)
        if i >= 0 and i not in picks:
            picks.append(i)
    kind = run.get("kind")
    if kind is not None:
        for k in (0, 1, 2):
            idx = np.flatnonzero(kind == k)
            if idx.size:
                root = env.peaks[surface][idx, 1, 0, 0]
                j = int(idx[np.nanargmax(np.abs(root))]) if np.any(np.isfinite(root)) else int(idx[0])
                if j not in picks:
                    picks.append(j)
    return picks[:5]


def time_history_svg(run, surface: str, control: str, signals=("n_z", "q")) -> str:
    sim, hist, valid = run["sim"], run["loads"][surface], run["valid"]
    picks = _critical_indices(run, surface)
    fig, axes = subplots(4, 1, figsize=(6.8, 7.2), sharex=True)
    j = list(sim.control_names).index(control)
    kind = run.get("kind")
    for i in picks:
        m = valid[:, i]
        label = run["conditions"][i].label()
        if kind is not None:
            label += f" [{_KIND[int(kind[i])]}]"
        axes[0].plot(sim.t[m], np.degrees(sim.controls[m, i, j]), lw=1.2, label=label)
        axes[1].plot(sim.t[m], sim[signals[0]][m, i], lw=1.2)
        axes[2].plot(sim.t[m], np.degrees(sim[signals[1]][m, i]), lw=1.2)
        axes[3].plot(sim.t[m], hist[m, i, 0, 0] / 1e3, lw=1.2)
    axes[0].set_ylabel(f"{control} (deg)")
    axes[1].set_ylabel(signals[0])
    axes[2].set_ylabel(f"{signals[1]} (deg/s)")
    axes[3].set_ylabel("root shear (kN)")
    axes[3].set_xlabel("time (s)")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=6, loc="upper right")
    return figure_to_svg(fig)


def envelope_svg(run, surface: str) -> str:
    env = run["envelope"]
    P = env.peaks[surface]  # (n, 2, 3, S)
    stations = env.stations[surface]
    # station names turned 40°: their height below the axes is width × sin 40° plus a line
    fig, axes = subplots(1, 3, figsize=(8.4, 2.8), left=0.6, top=0.35, bottom=0.3 + 0.643 * text_width(stations, 7),
                         wspace=0.4)
    x = np.arange(len(stations))
    for q, (ax, quantity) in enumerate(zip(axes, QUANTITIES)):
        hi = np.nanmax(P[:, 1, q, :], axis=0) / 1e3
        lo = np.nanmin(P[:, 0, q, :], axis=0) / 1e3
        ax.fill_between(x, lo, hi, alpha=0.25)
        ax.plot(x, hi, "o-", lw=1.2, label="max")
        ax.plot(x, lo, "s-", lw=1.2, label="min")
        ax.set_xticks(x, stations, rotation=40, fontsize=7)
        ax.set_title(f"{quantity} ({'kN' if q == 0 else 'kN·m'})", fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    return figure_to_svg(fig)


def maneuver_evidence(run, surface: str, control: str, signals=("n_z", "q")) -> list[Evidence]:
    name = surface.replace("_", " ")
    out = [
        Evidence(f"Critical conditions: {control}, {signals[0]}, {signals[1]} and {name} root shear",
                 time_history_svg(run, surface, control, signals),
                 "The conditions with the largest positive and negative root shear and, for each input kind, the one "
                 "with the largest root load; curves end where the paragraph stops considering loads."),
        Evidence(f"Load envelope along the {name} span", envelope_svg(run, surface),
                 "Maximum and minimum over every condition and time (limit loads)."),
        Evidence(f"Critical-case table, {name}", caption="Critical condition and time of every station and quantity.",
                 table=run["envelope"].table(surface)),
    ]
    failed = run["envelope"].failed
    if failed:
        out.append(Evidence("Conditions not simulated", table=[{"condition": run["envelope"].labels[i], "reason": r} for i, r in failed]))
    return out


# --------------------------------------------------------------------------- discrete gusts (§25.341(a))

def _gust_picks(run) -> list[tuple[int, int]]:
    """(condition, gradient index) of the extreme wing root bending and tail root shear, both senses."""
    env, which = run["envelope"], run["which"]
    picks = []
    for surface, quantity in (("wing", "bending"), ("horizontal_tail", "shear")):
        q = QUANTITIES.index(quantity)
        for sense in ("max", "min"):
            _, i = env.extreme(surface, quantity, 0, sense)
            if i >= 0:
                pick = (i, int(which[surface][i, 1 if sense == "max" else 0, q, 0]))
                if pick not in picks:
                    picks.append(pick)
    return picks


def gust_time_history_svg(replays, conditions) -> str:
    fig, axes = subplots(4, 1, figsize=(6.8, 7.2), sharex=True)
    for i, H, r in replays:
        sim = r.sim
        label = f"{conditions[i].label()} · H {H / 0.3048:.0f} ft"
        axes[0].plot(sim.t, np.degrees(r.alpha_gust["wing"][:, 0]), lw=1.2, label=label)
        axes[1].plot(sim.t, sim["n_z"][:, 0], lw=1.2)
        axes[2].plot(sim.t, r.loads["wing"][:, 0, 1, 0] / 1e3, lw=1.2)
        axes[3].plot(sim.t, r.loads["horizontal_tail"][:, 0, 0, 0] / 1e3, lw=1.2)
    for ax, name in zip(axes, ("gust angle at the wing (deg)", "n_z", "wing root bending (kN·m)", "tail root shear (kN)")):
        ax.set_ylabel(name, fontsize=8)
        ax.grid(True, alpha=0.3)
    axes[3].set_xlabel("time (s)")
    axes[0].legend(fontsize=6, loc="upper right")
    return figure_to_svg(fig)


def gust_evidence(run) -> list[Evidence]:
    replays = run["replay"](_gust_picks(run))
    out = [Evidence("Critical discrete-gust conditions: gust angle, load factor, wing root bending, tail root shear",
                    gust_time_history_svg(replays, run["conditions"]),
                    "The conditions and gradients with the largest positive and negative wing root bending and tail "
                    "root shear; the gust reaches the tail a tail arm / V after the wing.")]
    for surface in ("wing", "horizontal_tail"):
        name = surface.replace("_", " ")
        out += [Evidence(f"Gust load envelope along the {name} span", envelope_svg(run, surface),
                         "Maximum and minimum over every condition, gust gradient and time (limit loads)."),
                Evidence(f"Critical-case table, {name} (discrete gust)", caption="Critical condition, gradient and time "
                         "of every station and quantity.", table=gust_case_table(run, surface))]
    return out


def gust_case_table(run, surface: str) -> list[dict]:
    """The envelope's critical-case table of ``surface`` with the gust gradient of each case (``H_ft``)."""
    env, H, which = run["envelope"], run["gradients"], run["which"][surface]
    table = env.table(surface)
    for row, c in zip(table, [c for c in env.critical_cases() if c.surface == surface]):
        q, s = QUANTITIES.index(c.quantity), env.stations[surface].index(c.station)
        row["H_ft"] = round(float(H[which[c.condition, 1 if c.sense == "max" else 0, q, s]] / 0.3048))
    return table


# --------------------------------------------------------------------------- unsymmetrical gusts (§25.349(b))

def _unsymmetrical_picks(run) -> list[tuple[int, int]]:
    """(condition, gradient index) of the largest root bending on each side and of the largest rolling moment."""
    env, which = run["envelope"], run["which"]
    b = QUANTITIES.index("bending")
    picks = []
    for side in env.peaks:
        for sense in ("max", "min"):
            _, i = env.extreme(side, "bending", 0, sense)
            if i >= 0 and (i, int(which[side][i, 1 if sense == "max" else 0, b, 0])) not in picks:
                picks.append((i, int(which[side][i, 1 if sense == "max" else 0, b, 0])))
    roll = np.abs(run["roll"])
    j, i = np.unravel_index(int(np.argmax(roll)), roll.shape)
    if (int(i), int(j)) not in picks:
        picks.append((int(i), int(j)))
    return picks[:4]


def unsymmetrical_time_history_svg(run, picks) -> str:
    from certkit.models.loads.unsymmetrical import unsymmetrical_wing

    runs, (full, reduced) = run["runs"], run["fractions"]
    fig, axes = subplots(4, 1, figsize=(6.8, 7.6), sharex=True, left=1.0, top=0.75)
    for (i, H, r), colour in zip(runs.replay(picks), COLOURS):
        aero, inertia = r.parts["wing"]
        m = runs.batch.model.subset([i])
        u = unsymmetrical_wing(runs.loads["wing"], aero, inertia, m.mass, m.cg, m.inertia, full, reduced,
                               trim_aero=aero[0] if run["basis"] == "increment" else None)
        t = r.sim.t
        label = f"{runs.conditions[i].label()} · H {H / 0.3048:.0f} ft"
        axes[0].plot(t, (aero + inertia)[:, 0, 1, 0] / 1e3, color=colour, lw=0.8, ls=":")
        axes[0].plot(t, u.full[:, 0, 1, 0] / 1e3, color=colour, lw=1.2, label=label)
        axes[0].plot(t, u.reduced[:, 0, 1, 0] / 1e3, color=colour, lw=1.2, ls="--")
        axes[1].plot(t, u.rolling_moment[:, 0] / 1e6, color=colour, lw=1.2)
        axes[2].plot(t, np.degrees(u.pdot[:, 0]), color=colour, lw=1.2)
        axes[3].plot(t, r.sim["n_z"][:, 0] + u.delta_n_z[:, 0], color=colour, lw=1.2)
    names = (f"wing root bending (kN·m)\n— {full:.0%}  -- {reduced:.0%}  ·· symmetric", "unbalanced rolling\nmoment (MN·m)",
             "roll acceleration\n(deg/s²)", "n_z with the\nair load removed")
    for ax, name in zip(axes, names):
        ax.set_ylabel(name, fontsize=7)
        ax.grid(True, alpha=0.3)
    axes[3].set_xlabel("time (s)")
    axes[0].legend(fontsize=6, loc="lower left", bbox_to_anchor=(0.0, 1.02), borderaxespad=0.0)
    return figure_to_svg(fig)


def sides_envelope_svg(run) -> str:
    """Root-to-tip envelopes of both sides with the symmetric §25.341(a) envelope, per quantity."""
    env, sym = run["envelope"], run["symmetric"]
    cases = [(side, env.peaks[side], "-") for side in env.peaks] + [("symmetric §25.341(a)", sym.peaks["wing"], ":")]
    stations = env.stations[next(iter(env.peaks))]
    x = np.arange(len(stations))
    fig, axes = subplots(1, 3, figsize=(8.4, 2.9), left=0.6, top=0.35, bottom=0.3 + 0.643 * text_width(stations, 7),
                         wspace=0.4)
    for q, (ax, quantity) in enumerate(zip(axes, QUANTITIES)):
        for (name, P, ls), colour in zip(cases, COLOURS):
            ax.plot(x, np.nanmax(P[:, 1, q, :], axis=0) / 1e3, ls=ls, marker="o", ms=3, color=colour, lw=1.2, label=name)
            ax.plot(x, np.nanmin(P[:, 0, q, :], axis=0) / 1e3, ls=ls, marker="s", ms=3, color=colour, lw=1.2)
        ax.set_xticks(x, stations, rotation=40, fontsize=7)
        ax.set_title(f"{quantity} ({'kN' if q == 0 else 'kN·m'})", fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=6)
    return figure_to_svg(fig)


def unsymmetrical_gust_evidence(run) -> list[Evidence]:
    full, reduced = run["fractions"]
    out = [Evidence(f"Critical unsymmetrical-gust conditions: wing root bending on the {full:.0%} and {reduced:.0%} "
                    "sides, unbalanced rolling moment, roll acceleration and load factor",
                    unsymmetrical_time_history_svg(run, _unsymmetrical_picks(run)),
                    "The §25.341(a) responses with the largest root bending on either side and with the largest "
                    f"unbalanced rolling moment; the wing air load is {'the gust increment' if run['basis'] == 'increment' else 'the whole air load'} "
                    f"× {full:.0%} on one side and × {reduced:.0%} on the other, the unbalance reacted by the rigid "
                    "airplane's vertical, roll and pitch accelerations."),
           Evidence("Unsymmetrical-gust load envelopes along the wing span", sides_envelope_svg(run),
                    "Maximum (circles) and minimum (squares) over every condition, gust gradient and time (limit "
                    "loads), each side against the symmetric gust.")]
    for side in run["envelope"].peaks:
        out.append(Evidence(f"Critical-case table, {side} (unsymmetrical gust)",
                            caption="Critical condition, gradient and time of every station and quantity.",
                            table=gust_case_table(run, side)))
    return out


# --------------------------------------------------------------------------- steady load cases (§25.331(b), …)

def envelope_evidence(run, surfaces, what: str, plot: bool = True) -> list[Evidence]:
    """The critical-case table of each of ``surfaces`` (skipping a surface with no computed load) and, with ``plot``,
    its load envelope along the span (a plot costs about a second: the tables alone where the rule's own plots
    already show the case)."""
    env = run["envelope"]
    out = []
    for surface in surfaces:
        if surface not in env.peaks or not np.any(np.isfinite(env.peaks[surface])):
            continue
        name = surface.replace("_", " ")
        if plot:
            out.append(Evidence(f"Load envelope along the {name} span ({what})", envelope_svg(run, surface),
                                "Maximum and minimum over every condition (limit loads)."))
        out.append(Evidence(f"Critical-case table, {name} ({what})", caption="Critical condition of every station, "
                            "quantity and sense.", table=env.table(surface)))
    return out
