"""Evidence plots and tables for the Subpart B performance and controllability rules (§§ 25.103–25.161).

Each function takes what its rule already computed (findings, memoised runs) and returns a list of
:class:`certkit.results.Evidence`; nothing here computes physics.
"""

from __future__ import annotations

import numpy as np

from certkit.report.evidence_time_histories import time_histories_svg
from certkit.report.plots import figure_to_svg, subplots, text_width
from certkit.results import Evidence
from certkit.units import FT, KN


def _critical(findings):
    """The evaluated finding with the smallest normalised margin, or None."""
    ev = [f for f in findings if f.margin is not None]
    if not ev:
        return None
    return min(ev, key=lambda f: f.normalized_margin if f.normalized_margin is not None else f.margin)


# ---------------------------------------------------------------------------------------------- § 25.111
def _time_at(V, t, speeds):
    """First recorded time at which each run's airspeed V (nt, n) reaches ``speeds`` (n,) (m/s)."""
    reached = V >= np.asarray(speeds)[None, :]
    return np.where(reached.any(axis=0), t[np.argmax(reached, axis=0)], np.nan)


def takeoff_evidence(ctx, conds, findings, run, engine, vef, crit) -> list[Evidence]:
    """§25.111: time histories (speed, wheel height, elevator, rudder, heading, lateral deviation, bank) of the
    engine-out runs of every loading (the critical one bold) and of the critical loading with all engines; a
    table of the key speeds and deflections."""
    from certkit.models.flight import control_limits

    worst = _critical(findings)
    if worst is None:
        return []
    n = len(conds)
    k = next((i for i, c in enumerate(conds) if c.x_cg == worst.condition.x_cg), 0)
    cols = list(range(n)) + [n + k]
    labels = [f"{c.loading}, {engine} engine out" for c in conds] + [f"{conds[k].loading}, all engines"]
    sim = run.sim
    je, jr = sim.control_names.index("elevator"), sim.control_names.index("rudder")
    lim = {s: np.degrees(v) for s, v in control_limits(ctx.aircraft).items() if s != "throttle"}
    d = worst.details
    panels = [
        ("V (kn)", sim["V"][:, cols] / KN, {"VEF": d["vef_kn"], "VR": d["vr_kn"], "V2": d["v2_kn"]}),
        ("wheel height (ft)", run.wheel_height[:, cols] / FT, {f"{crit.screen_height:.0f} ft": crit.screen_height}),
        ("elevator (deg)", np.degrees(sim.controls[:, cols, je]), {"design limit": lim["elevator"][0]}),
        ("rudder (deg)", np.degrees(sim.controls[:, cols, jr]), {"design limits": lim["rudder"][0],
                                                                 "": lim["rudder"][1]}),
        ("heading ψ (deg)", np.degrees(sim["psi"][:, cols]), {}),
        ("lateral deviation (ft)", (sim["y_E"][:, cols] - sim["y_E"][:1, cols]) / FT, {}),
        ("bank φ (deg)", np.degrees(sim["phi"][:, cols]), {f"{crit.bank_deg:g}°": crit.bank_deg}),
    ]
    # from a few seconds before the failure: the ground roll before it is the same in every run
    t_fail = _time_at(sim["V"][:, :n], sim.t, vef[:n])
    k0 = max(0, int(np.searchsorted(sim.t, np.nanmin(t_fail) - 5.0))) if np.isfinite(t_fail).any() else 0
    panels = [(lab, vals[k0:], lim_) for lab, vals, lim_ in panels]
    svg = time_histories_svg(sim.t[k0:], panels, labels, critical=k,
                             title=f"§25.111 takeoff, {engine} engine failed at VEF, from brake release")
    rows = []
    for f in findings:
        if f.check.startswith("(a) rudder") and f.margin is not None:
            dd = f.details
            rows.append({"condition": f.condition.loading, "VEF kn": dd["vef_kn"], "V at recognition kn": dd["v_recognition_kn"],
                         "VLOF kn": dd["vlof_kn"], "V35 kn": dd["v35_kn"], "V2 kn": dd["v2_kn"],
                         "rudder min deg": dd["rudder_min_deg"], "rudder design limit deg": f.limit,
                         "max heading dev deg": dd["max_heading_deviation_deg"],
                         "lateral dev at 35 ft ft": dd["lateral_deviation_at_35ft_ft"],
                         "gradient after 35 ft %": dd["mean_gradient_after_35ft_pct"]})
    caption = (f"Critical condition {conds[k].loading} ({worst.check}: margin {worst.margin:.2f} {worst.unit}) with its "
               f"neighbours, {engine} engine failed at VEF (from 5 s before the failure); the last line is the critical "
               "loading with all engines. The rudder holds the runway heading over its full travel; dashed lines are "
               "the design limits.")
    return [Evidence("Engine-out takeoff time histories", svg, caption, rows)]


# ---------------------------------------------------------------------------------------------- § 25.149
def vmca_evidence(findings, rows, limits) -> list[Evidence]:
    """§25.149: rudder and aileron of the straight OEI trims the VMCA search visited, against speed, for the
    critical condition's banks, with the design limits, the computed VMCA and 1.13 VSR."""
    worst = _critical([f for f in findings if f.check.startswith("(c)")])
    if worst is None:
        return []
    engine = worst.condition.get("inoperative")
    idx = [j for j, e in enumerate(rows["engines"]) if e == engine]
    fig, axes = subplots(1, 2, figsize=(9.0, 3.4), sharex=True, top=0.35)
    for j in idx:
        pts = sorted((h["speed"] / KN, np.degrees(h["trim"].controls["rudder"]), np.degrees(h["trim"].controls["aileron"]))
                     for h in rows["history"][j] if h["trim"].converged and np.isfinite(h["usage"]))
        if not pts:
            continue
        v, dr, da = map(np.array, zip(*pts))
        lab = f"bank {np.degrees(rows['banks'][j]):.0f}°"
        axes[0].plot(v, dr, "o-", ms=3, label=lab)
        axes[1].plot(v, da, "o-", ms=3, label=lab)
    for ax, name in zip(axes, ("rudder", "aileron")):
        lo, hi = np.degrees(limits[name])
        for y in (lo, hi):
            ax.axhline(y, ls="--", lw=0.8, color="k")
        ax.axvline(worst.value / KN, color="C3", lw=1.0, label=f"VMCA {worst.value / KN:.1f} kn")
        ax.axvline(worst.limit / KN, color="C2", lw=1.0, ls=":", label=f"1.13 VSR {worst.limit / KN:.1f} kn")
        ax.set_xlabel("calibrated airspeed (kn)")
        ax.set_ylabel(f"{name} (deg)")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    axes[0].set_title(f"§25.149 straight flight, {engine} engine inoperative", fontsize=9)
    svg = figure_to_svg(fig)
    table = [dict(r) for r in worst.details.get("search", [])]
    caption = (f"Rudder and aileron of the one-engine-inoperative straight trims visited by the VMCA search (operating engine "
               f"at full throttle, {worst.condition.loading}), wings level to 5° banked toward the operating engine; dashed: "
               "design limits. VMCA is the lowest over the banks of the speed where a control reaches its limit.")
    return [Evidence("VMCA: controls against speed", svg, caption, table)]


# ---------------------------------------------------------------------------------------------- generic
def _cond_label(c) -> str:
    parts = [c.loading or "", c.configuration or ""]
    if c.speed_name:
        parts.append(c.speed_name)
    if c.altitude:
        parts.append(f"{c.altitude / FT:.0f} ft")
    extra = [str(v) for k, v in c.extra if k in ("inoperative", "direction", "transition")]
    return " ".join(p for p in parts + extra if p)


def _scaled(v, unit):
    """A finding's number for a table: gradients in percent."""
    return round(float(v) * 100, 3) if unit == "gradient" else round(float(v), 4)


def margins_evidence(findings, title: str, caption: str, detail_keys=(), worst: int = 24, plot: bool = False) -> list[Evidence]:
    """Generic evidence of a trim-based rule: a table of every evaluated finding with its value, limit, margin and the
    trim's ``detail_keys``, worst first; with ``plot`` also the ``worst`` findings by normalised margin as a bar chart
    (failing in red). Tables cost nothing; a plot costs about 0.2 s of a check, so it is drawn where it says more."""
    ev = [f for f in findings if f.margin is not None and f.value is not None]
    if not ev:
        return []
    ev.sort(key=lambda f: f.normalized_margin if f.normalized_margin is not None else f.margin)
    shown = ev[:worst]
    svg = ""
    if plot:
        labels = [f"{f.check[:48]} · {_cond_label(f.condition)}"[:90] for f in shown]
        fig, ax = subplots(figsize=(8.0, 0.28 * len(shown) + 1.2), left=text_width(labels, 6) + 0.15, top=0.35)
        nm = [f.normalized_margin if f.normalized_margin is not None else f.margin for f in shown]
        y = np.arange(len(shown))[::-1]
        ax.barh(y, nm, color=["C3" if f.status == "fails" else "C0" for f in shown])
        ax.set_yticks(y, labels, fontsize=6)
        ax.axvline(0.0, color="k", lw=0.8)
        ax.set_xlabel("normalised margin (margin / |limit|; ≥ 0 complies)")
        ax.set_title(title, fontsize=9)
        ax.grid(axis="x", alpha=0.3)
        svg = figure_to_svg(fig)
    keys = [k for k in detail_keys if any(f.details.get(k) is not None for f in ev)]
    table = []
    for f in ev:
        row = {"condition": _cond_label(f.condition), "check": f.check,
               "value": _scaled(f.value, f.unit), "limit": _scaled(f.limit, f.unit),
               "unit": "%" if f.unit == "gradient" else f.unit, "margin": _scaled(f.margin, f.unit), "status": f.status}
        for k in keys:  # every row has the same columns (the report takes its header from the first row)
            v = f.details.get(k)
            row[k] = round(float(v), 3) if isinstance(v, (int, float, np.floating)) and not isinstance(v, bool) else v
        table.append(row)
    more = f" The {len(shown)} smallest margins of {len(ev)} are drawn." if plot and len(ev) > len(shown) else ""
    return [Evidence(title, svg, caption + more, table)]


def climb_gradient_evidence(findings, title: str) -> list[Evidence]:
    """§25.121: the steady one-engine-inoperative gradient of each condition against the segment's minimum, and
    the trim table (controls at the gradient)."""
    grads = [f for f in findings if f.unit == "gradient" and f.value is not None]
    out = []
    if grads:
        labels = [_cond_label(f.condition) for f in grads]
        # labels turned 20° and ending at their bar: sin 20° of their width below the axes (the first one's
        # reach to the left is taken in by figure_to_svg)
        fig, ax = subplots(figsize=(7.0, 3.0), top=0.35, bottom=0.3 + 0.342 * text_width(labels, 7))
        x = np.arange(len(grads))
        ax.bar(x, [f.value * 100 for f in grads], color=["C3" if f.status == "fails" else "C0" for f in grads])
        ax.axhline(grads[0].limit * 100, color="k", ls="--", lw=1.0, label=f"minimum {grads[0].limit * 100:.1f} %")
        ax.set_xticks(x, labels, rotation=20, ha="right", fontsize=7)
        ax.set_ylabel("steady climb gradient (%)")
        ax.set_title(title, fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(axis="y", alpha=0.3)
        out.append(Evidence(title + ": gradients", figure_to_svg(fig),
                            "Steady gradient with the critical engine inoperative (trim at the gradient the thrust gives) "
                            "per condition, against the segment's minimum."))
    out += margins_evidence(findings, title + ": trims", "Controls of the one-engine-inoperative climb trims against their "
                            "design limits, and the gradients.",
                            ("alpha_deg", "beta_deg", "bank_deg", "elevator_deg", "aileron_deg", "rudder_deg",
                             "thrust_available_N", "thrust_at_trim_N"))
    return out
