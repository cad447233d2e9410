"""Evidence data of the Subpart B performance and controllability rules (§§ 25.103–25.161): time histories with
their limits, the VMCA search, margin bars and tables of the trims. Each function takes what its rule already
computed (findings, memoised runs); nothing here computes physics."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from certkit.engine.evidence.data import Axis, Bars, Chart, Column, Limit, Panel, Point, Series, Table
from certkit.engine.results import Condition, Evidence, Finding, margin_key
from certkit.models.flight import control_limits

KN = 1852.0 / 3600.0
FT = 0.3048
DEG = np.pi / 180.0


def critical(findings: Iterable[Finding]) -> Finding | None:
    """The evaluated finding with the smallest normalised margin, or None."""
    ev = [f for f in findings if f.margin is not None]
    if not ev:
        return None
    return min(ev, key=margin_key)


def time_histories(
    t: npt.ArrayLike,
    panels: Sequence[Any],
    labels: Sequence[str],
    critical: int = 0,
    ends: Sequence[float] | np.ndarray | None = None,
    title: str = "",
) -> Chart:
    """Stacked panels sharing the time axis, one line per condition (the critical one bold), each line ending at its
    run's end (``ends`` (n,), s). ``t`` (nt,) or (nt, n); ``panels`` a list of (Axis, values (nt, n) SI, limits,
    points)."""
    t = np.asarray(t, dtype=float)
    out = []
    for axis, values, limits, points in panels:
        values = np.asarray(values, dtype=float)
        series = [
            Series(
                lab,
                t if t.ndim == 1 else t[:, i],
                values[:, i],
                critical=i == critical,
                end=None if ends is None else float(ends[i]),
            )
            for i, lab in enumerate(labels)
        ]
        out.append(Panel(axis, series, list(limits or ()), list(points or ())))
    return Chart(Axis("time", "s"), out, title=title)


def _extreme_point(t: np.ndarray, y: np.ndarray, sense: str, label: str) -> list[Point]:
    y = np.asarray(y, dtype=float)
    if not np.isfinite(y).any():
        return []
    k = int(np.nanargmin(y) if sense == "min" else np.nanargmax(y))
    return [Point(float(t[k]), float(y[k]), label)]


# ---------------------------------------------------------------------------------------------- § 25.111
def _time_at(V: np.ndarray, t: np.ndarray, speeds: npt.ArrayLike) -> np.ndarray:
    """First recorded time at which each run's airspeed V (nt, n) reaches ``speeds`` (n,) (m/s)."""
    reached = V >= np.asarray(speeds)[None, :]
    return np.where(reached.any(axis=0), t[np.argmax(reached, axis=0)], np.nan)


def takeoff_evidence(
    ctx: Any, conds: Sequence[Any], findings: list[Finding], run: Any, engine: Any, vef: Any, crit: Any
) -> list[Evidence]:
    """§25.111: time histories (speed, wheel height, elevator, rudder, heading, lateral deviation, bank) of the
    engine-out runs of every loading (the critical one bold) and of the critical loading with all engines; a
    table of the key speeds and deflections."""
    worst = critical(findings)
    if worst is None:
        return []
    n = len(conds)
    k = next((i for i, c in enumerate(conds) if c.x_cg == worst.condition.x_cg), 0)
    cols = list(range(n)) + [n + k]
    labels = [f"{c.loading}, {engine} engine out" for c in conds] + [f"{conds[k].loading}, all engines"]
    sim = run.sim
    je, jr = sim.control_names.index("elevator"), sim.control_names.index("rudder")
    lim = {s: v for s, v in control_limits(ctx.aircraft).items() if s != "throttle"}
    d = worst.details
    # from a few seconds before the failure: the ground roll before it is the same in every run
    t_fail = _time_at(sim["V"][:, :n], sim.t, vef[:n])
    k0 = max(0, int(np.searchsorted(sim.t, np.nanmin(t_fail) - 5.0))) if np.isfinite(t_fail).any() else 0
    t = sim.t[k0:]
    rudder = sim.controls[k0:, cols, jr]
    panels = [
        (
            Axis("airspeed V", "m/s"),
            sim["V"][k0:, cols],
            [
                Limit(d["vef_kn"] * KN, "VEF", kind="reference"),
                Limit(d["vr_kn"] * KN, "VR", kind="reference"),
                Limit(d["v2_kn"] * KN, "V2", kind="reference"),
            ],
            [],
        ),
        (
            Axis("wheel height", "m"),
            run.wheel_height[k0:, cols],
            [Limit(crit.screen_height * FT, f"screen {crit.screen_height:.0f} ft")],
            [],
        ),
        (
            Axis("elevator", "rad"),
            sim.controls[k0:, cols, je],
            [Limit(lim["elevator"][0], "design limit", kind="allowable")],
            [],
        ),
        (
            Axis("rudder", "rad"),
            rudder,
            [
                Limit(lim["rudder"][0], "design limit", kind="allowable"),
                Limit(lim["rudder"][1], "design limit", kind="allowable"),
            ],
            _extreme_point(t, rudder[:, k], "min", "critical: rudder extreme")
            if worst.check.startswith("(a) rudder")
            else [],
        ),
        (Axis("heading ψ", "rad"), sim["psi"][k0:, cols], [], []),
        (Axis("lateral deviation", "m"), sim["y_E"][k0:, cols] - sim["y_E"][:1, cols], [], []),
        (Axis("bank φ", "rad"), sim["phi"][k0:, cols], [Limit(crit.bank_deg * DEG, f"{crit.bank_deg:g}°")], []),
    ]
    chart = time_histories(
        t,
        panels,
        labels,
        critical=k,
        ends=np.asarray(sim.stop_time)[cols],
        title=f"§25.111 takeoff, {engine} engine failed at VEF",
    )
    rows = []
    for f in findings:
        if f.check.startswith("(a) rudder") and f.margin is not None:
            dd = f.details
            rows.append(
                [
                    f.condition.loading,
                    dd["vef_kn"],
                    dd["v_recognition_kn"],
                    dd["vlof_kn"],
                    dd["v35_kn"],
                    dd["v2_kn"],
                    dd["rudder_min_deg"],
                    f.limit,
                    dd["max_heading_deviation_deg"],
                    dd["lateral_deviation_at_35ft_ft"],
                    dd["mean_gradient_after_35ft_pct"],
                ]
            )
    table = Table(
        [
            Column("condition", "condition", kind="text"),
            Column("vef", "VEF", "kn"),
            Column("v_rec", "V at recognition", "kn"),
            Column("vlof", "VLOF", "kn"),
            Column("v35", "V at 35 ft", "kn"),
            Column("v2", "V2", "kn"),
            Column("rudder_min", "rudder minimum", "deg"),
            Column("rudder_limit", "rudder design limit", "deg"),
            Column("heading", "largest heading deviation", "deg"),
            Column("lateral", "lateral deviation at 35 ft", "ft"),
            Column("gradient", "mean gradient after 35 ft", "%"),
        ],
        rows,
    )
    caption = (
        f"Critical condition {conds[k].loading} ({worst.check}: margin {worst.margin:.2f} {worst.unit}) with its "
        f"neighbours, {engine} engine failed at VEF (from 5 s before the failure); the last line is the critical "
        "loading with all engines; each line ends where its run ended. The rudder holds the runway heading over "
        "its full travel; dash-dot lines are the design limits; the star marks the critical rudder deflection."
    )
    return [Evidence("Engine-out takeoff time histories", chart, caption, table)]


# ---------------------------------------------------------------------------------------------- § 25.107(e)(1)(iv)
def unstick_evidence(
    findings: list[Finding], loadings: Sequence[str], all_engines: Any, engine_out: Any
) -> list[Evidence]:
    """§25.107(e)(1)(iv): the unstick speed against the pitch attitude of each loading (``loadings``: their names, in
    the order of the :class:`certkit.models.dynamics.unstick.Unstick` columns), all engines and engine out, with the
    lift-off speed of the least-margin finding of each."""
    if critical(findings) is None:
        return []
    panels = []
    for name, u, oei in (("all engines", all_engines, False), ("one engine inoperative", engine_out, True)):
        series = [
            Series(label or f"loading {i + 1}", u.attitudes, u.speeds[:, i], marker="o", colour=i)
            for i, label in enumerate(loadings)
        ]
        least = critical([f for f in findings if (f.condition.get("inoperative") is not None) == oei])
        lims = [Limit(float(u.attitudes[0]), "tail strike", axis="x", kind="limit")]
        if least is not None:
            lims.append(Limit(least.details["VLOF"], f"VLOF {least.condition.loading}", kind="reference"))
        panels.append(
            Panel(Axis("unstick speed (CAS)", "m/s"), series, lims, title=name, x=Axis("pitch attitude", "rad"))
        )
    chart = Chart(Axis("pitch attitude", "rad"), panels, title="§25.107(e)(1)(iv) unstick speed", arrangement="row")
    caption = (
        "Speed at which lift and thrust carry the weight at each pitch attitude on the runway, the elevator holding "
        "the attitude (gaps: beyond its travel); VMU is the lowest, at the tail-strike attitude on a "
        "geometry-limited airplane. Horizontal line: the lift-off speed of the simulated takeoff rotated at the "
        "maximum practicable rate at the loading with the least margin."
    )
    return [Evidence("Unstick speed against attitude", chart, caption)]


# ---------------------------------------------------------------------------------------------- § 25.149
def vmca_evidence(findings: list[Finding], rows: Mapping[str, Any], limits: Any) -> list[Evidence]:
    """§25.149: rudder and aileron of the straight OEI trims the VMCA search visited, against speed, for the
    critical condition's banks, with the design limits, the computed VMCA and 1.13 VSR."""
    worst = critical([f for f in findings if f.check.startswith("(c)")])
    if worst is None or worst.value is None or worst.limit is None:
        return []
    engine = worst.condition.get("inoperative")
    idx = [j for j, e in enumerate(rows["engines"]) if e == engine]
    panels = []
    for name in ("rudder", "aileron"):
        series = []
        for k, j in enumerate(idx):
            pts = sorted(
                (h["speed"], h["trim"].controls["rudder"], h["trim"].controls["aileron"])
                for h in rows["history"][j]
                if h["trim"].converged and np.isfinite(h["usage"])
            )
            if not pts:
                continue
            v, dr, da = map(np.array, zip(*pts))
            series.append(
                Series(
                    f"bank {np.degrees(rows['banks'][j]):.0f}°", v, dr if name == "rudder" else da, marker="o", colour=k
                )
            )
        lo, hi = limits[name]
        lims = [
            Limit(lo, "design limit", kind="allowable"),
            Limit(hi, "design limit", kind="allowable"),
            Limit(worst.value, f"VMCA {worst.value / KN:.1f} kn", axis="x", kind="limit"),
            Limit(worst.limit, f"1.13 VSR {worst.limit / KN:.1f} kn", axis="x", kind="reference"),
        ]
        panels.append(Panel(Axis(name, "rad"), series, lims, x=Axis("calibrated airspeed", "m/s")))
    chart = Chart(
        Axis("calibrated airspeed", "m/s"),
        panels,
        title=f"§25.149 straight flight, {engine} engine inoperative",
        arrangement="row",
    )
    caption = (
        f"Rudder and aileron of the one-engine-inoperative straight trims visited by the VMCA search (operating engine "
        f"at full throttle, {worst.condition.loading}), wings level to 5° banked toward the operating engine; "
        "dash-dot: "
        "design limits. VMCA is the lowest over the banks of the speed where a control reaches its limit."
    )
    return [
        Evidence("VMCA: controls against speed", chart, caption, [dict(r) for r in worst.details.get("search", [])])
    ]


# ---------------------------------------------------------------------------------------------- generic
def condition_label(c: Condition) -> str:
    parts = [c.loading or "", c.configuration or ""]
    if c.speed_name:
        parts.append(c.speed_name)
    if c.altitude:
        parts.append(f"{c.altitude / FT:.0f} ft")
    extra = [str(v) for k, v in c.extra if k in ("inoperative", "direction", "transition")]
    return " ".join(p for p in parts + extra if p)


def _shown_unit(unit: str) -> str:
    return "%" if unit == "gradient" else unit


def _scaled(v: float | None, unit: str) -> float | None:
    """A finding's number in its table unit: gradients in percent."""
    return None if v is None else float(v) * 100 if unit == "gradient" else float(v)


def margins_evidence(
    findings: list[Finding],
    title: str,
    caption: str,
    detail_keys: Sequence[str] = (),
    worst: int = 24,
    plot: bool = False,
) -> list[Evidence]:
    """Generic evidence of a trim-based rule: a table of every evaluated finding with its value, limit, margin and the
    trim's ``detail_keys``, worst first; with ``plot`` also the ``worst`` findings by normalised margin as bars
    (failing in vermillion, hatched)."""
    ev = [f for f in findings if f.margin is not None and f.value is not None]
    if not ev:
        return []
    ev.sort(key=margin_key)
    shown = ev[:worst]
    figure = None
    if plot:
        figure = Bars(
            [f"{f.check[:40]} · {condition_label(f.condition)}" for f in shown],
            [margin_key(f) for f in shown],
            Axis("normalised margin (margin / |limit|)"),
            [f.status == "fails" for f in shown],
            Limit(0.0, "0: complies at or above"),
            title=title,
        )
    keys = [k for k in detail_keys if any(f.details.get(k) is not None for f in ev)]
    rows = []
    for f in ev:
        row = {
            "condition": condition_label(f.condition),
            "check": f.check,
            "value": _scaled(f.value, f.unit),
            "limit": _scaled(f.limit, f.unit),
            "margin": _scaled(f.margin, f.unit),
            "unit": _shown_unit(f.unit),
            "status": f.status.replace("_", " "),
        }
        for k in keys:
            v = f.details.get(k)
            row[k] = float(v) if isinstance(v, (int, float, np.floating)) and not isinstance(v, bool) else v
        rows.append(row)
    table = Table.from_dicts(
        rows,
        [
            Column("condition", "condition", kind="text"),
            Column("check", "check", kind="text"),
            Column("value", "value", unit_key="unit"),
            Column("limit", "limit", unit_key="unit"),
            Column("margin", "margin", unit_key="unit"),
            Column("unit", "unit", kind="text"),
            Column("status", "status", kind="text"),
        ],
    )
    more = f" The {len(shown)} smallest margins of {len(ev)} are drawn." if plot and len(ev) > len(shown) else ""
    return [Evidence(title, figure, caption + more, table)]


def climb_gradient_evidence(findings: list[Finding], title: str) -> list[Evidence]:
    """§25.121: the steady one-engine-inoperative gradient of each condition against the segment's minimum, and
    the trim table (controls at the gradient)."""
    grads = [f for f in findings if f.unit == "gradient" and f.value is not None]
    out = []
    if grads:
        if grads[0].limit is None:
            raise ValueError(f"the climb gradient finding {grads[0].check!r} has no minimum")
        minimum = float(grads[0].limit)
        bars = Bars(
            [condition_label(f.condition) for f in grads],
            [float(f.value) for f in grads if f.value is not None],
            Axis("steady climb gradient", "gradient"),
            [f.status == "fails" for f in grads],
            Limit(minimum, f"minimum {minimum * 100:.1f} %"),
            title=title,
            horizontal=False,
        )
        out.append(
            Evidence(
                title + ": gradients",
                bars,
                "Steady gradient with the critical engine inoperative (trim at the gradient the thrust gives) "
                "per condition, against the segment's minimum.",
            )
        )
    out += margins_evidence(
        findings,
        title + ": trims",
        "Controls of the one-engine-inoperative climb trims against their design limits, and the gradients.",
        (
            "alpha_deg",
            "beta_deg",
            "bank_deg",
            "elevator_deg",
            "aileron_deg",
            "rudder_deg",
            "thrust_available_N",
            "thrust_at_trim_N",
        ),
    )
    return out + wat_limit_evidence(findings, title)


def wat_limit_evidence(findings: list[Finding], title: str) -> list[Evidence]:
    """§25.121 over weight–altitude–temperature: per weight-limited corner of the takeoff and landing envelope, the
    WAT limit weight (the flight-manual weight limitation of §25.1533(a)) against the lowest operating weight."""
    limited = [f for f in findings if f.unit == "kg" and f.check.endswith("WAT limit weight")]
    if not limited:
        return []
    table = Table(
        [
            Column("corner", "airport pressure altitude, temperature", kind="text"),
            Column("limit", "WAT limit weight", "kg"),
            Column("lowest", "lowest operating weight", "kg"),
            Column("status", "status", kind="text"),
            Column("cg", "most unfavourable CG", kind="text"),
            Column("gradient", "gradient at the design weight", ""),
        ],
        [
            [
                f.condition.get("airport"),
                f.value,
                f.limit,
                f.status,
                f.details.get("most_unfavourable_cg"),
                f.details.get("design_weight_gradient"),
            ]
            for f in limited
        ],
    )
    return [
        Evidence(
            title + ": WAT limit weights",
            None,
            "Corners of the takeoff and landing envelope where the "
            "minimum gradient is not met at the design weight: the weight at which it is met (a weight "
            "limitation the flight manual must carry, §25.1533(a)), against the lightest declared weight; "
            "a corner fails when no operating weight meets the gradient.",
            table,
        )
    ]
