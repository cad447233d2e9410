"""Evidence data of the loads rules: time histories of the critical conditions, load envelopes along the span with
the allowables the margins are measured against, and the critical-case tables (one row per surface, station,
quantity and sense)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from certkit.engine.evidence.data import Axis, Chart, Column, Limit, Panel, Point, Series, Table
from certkit.engine.results import Evidence
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.model import QUANTITIES
from certkit.models.loads.unsymmetrical import unsymmetrical_wing

if TYPE_CHECKING:
    from certkit.engine.context import Context

#: surface → {(station, quantity): (negative, positive) governing allowable limit loads}
Allowables = dict[str, dict[tuple[str, str], tuple[float, float]]]
#: a rule's run or load envelope (its own dataclass, defined with the rule or the loads model): the evidence reads its
#: fields
Run = Any

_KIND = {0: "scaled sinusoid", 1: "held input", 2: "maximal held input"}
#: palette entries of the maximum and minimum of each envelope drawn (entry 5, vermillion, is the allowables')
_PAIRS = ((0, 1), (2, 3), (4, 7))
#: SI unit of each load quantity, and the unit a reviewer reads it in
UNITS = {"shear": ("N", "kN"), "bending": ("N·m", "kN·m"), "torsion": ("N·m", "kN·m")}
FT = 0.3048


def allowables(
    ctx: Context, ultimate_factor: float, surfaces: Sequence[str] = ("wing", "horizontal_tail", "vertical_tail")
) -> Allowables:
    """surface → {(station, quantity): (negative, positive) governing allowable limit loads}: per sense the smaller
    of the allowable limit load and the allowable ultimate load ÷ the factor of safety (the load the two margins of
    :func:`certkit.models.loads.capability.worst_margin` reach zero at), signed."""
    out: Allowables = {}
    for surface in surfaces:
        caps = {}
        for cap in declared_capabilities(ctx, surface):
            neg = min(cap.allowable("limit", "min"), cap.allowable("ultimate", "min") / ultimate_factor)
            pos = min(cap.allowable("limit", "max"), cap.allowable("ultimate", "max") / ultimate_factor)
            caps[(cap.station, cap.quantity)] = (-abs(neg), abs(pos))
        out[surface] = caps
    return out


def _root_load(quantity: str) -> Axis:
    si, shown = UNITS[quantity]
    return Axis(f"root {quantity}", si, shown)


def _critical_indices(run: Run, surface: str) -> list[int]:
    env = run.envelope
    picks = []
    for sense in ("max", "min"):
        _, i = env.extreme(surface, "shear", 0, sense)
        if i >= 0 and i not in picks:
            picks.append(i)
    kind = run.kind
    if kind is not None:
        for k in (0, 1, 2):
            idx = np.flatnonzero(kind == k)
            if idx.size:
                root = env.peaks[surface][idx, 1, 0, 0]
                j = int(idx[np.nanargmax(np.abs(root))]) if np.any(np.isfinite(root)) else int(idx[0])
                if j not in picks:
                    picks.append(j)
    return picks[:5]


def _peak_point(series: Series, label: str = "critical") -> list[Point]:
    """The largest |y| of a series, as the critical point."""
    if not series.y.size or not np.isfinite(series.y).any():
        return []
    k = int(np.nanargmax(np.abs(series.y)))
    return [Point(float(series.x[k]), float(series.y[k]), label)]


def time_history(
    run: Run, surface: str, control: str, signals: Sequence[str] = ("n_z", "q"), allow: Allowables | None = None
) -> Chart:
    """Control, the two response signals and the root shear of the critical conditions of a manoeuvre's run (its
    records, ``loads`` and ``kind``), each curve ending where the paragraph stops considering loads (the run's valid
    mask); the critical condition (largest root shear) bold."""
    sim, hist, valid = run.records, run.loads[surface], run.valid
    picks = _critical_indices(run, surface)
    j = list(sim.control_names).index(control)
    kind = run.kind
    lines: list[list[Series]] = [[], [], [], []]
    for rank, i in enumerate(picks):
        m = valid[:, i]
        label = run.conditions[i].label() + (f" [{_KIND[int(kind[i])]}]" if kind is not None else "")
        t, crit = sim.t[m], rank == 0
        lines[0].append(Series(label, t, sim.controls[m, i, j], critical=crit))
        lines[1].append(Series(label, t, sim[signals[0]][m, i], critical=crit))
        lines[2].append(Series(label, t, sim[signals[1]][m, i], critical=crit))
        lines[3].append(Series(label, t, hist[m, i, 0, 0], critical=crit))
    root = (allow or {}).get(surface, {}).get((run.envelope.stations[surface][0], "shear"))
    shear_limits = (
        [Limit(root[0], "allowable (−)", kind="allowable"), Limit(root[1], "allowable (+)", kind="allowable")]
        if root
        else []
    )
    panels = [
        Panel(Axis(control, "rad"), lines[0]),
        Panel(Axis("load factor" if signals[0] == "n_z" else signals[0], "g" if signals[0] == "n_z" else ""), lines[1]),
        Panel(Axis("pitch rate" if signals[1] == "q" else signals[1], "rad/s"), lines[2]),
        Panel(_root_load("shear"), lines[3], shear_limits, _peak_point(lines[3][0]) if lines[3] else []),
    ]
    return Chart(Axis("time", "s"), panels)


def envelope_chart(
    peaks: dict[str, np.ndarray],
    stations: Sequence[str],
    allow: dict[tuple[str, str], tuple[float, float]] | None = None,
    title: str = "",
) -> Chart:
    """Root-to-tip maximum and minimum of each quantity (``peaks``: name → (n, 2, 3, S) arrays, the first the
    envelope, others drawn for comparison), the governing allowables at the stations that declare one, and the
    critical point (the station and sense nearest its allowable, else the largest magnitude)."""
    x = np.arange(len(stations), dtype=float)
    panels = []
    for q, quantity in enumerate(QUANTITIES):
        si, shown = UNITS[quantity]
        series = []
        for k, (name, P) in enumerate(peaks.items()):
            with np.errstate(all="ignore"):
                hi = np.nanmax(P[:, 1, q, :], axis=0) if P.shape[0] else np.full(len(stations), np.nan)
                lo = np.nanmin(P[:, 0, q, :], axis=0) if P.shape[0] else np.full(len(stations), np.nan)
            style = "-" if k == 0 else ":"
            c_hi, c_lo = _PAIRS[k % len(_PAIRS)]
            series += [
                Series(f"{name} max" if len(peaks) > 1 else "max", x, hi, marker="o", style=style, colour=c_hi),
                Series(f"{name} min" if len(peaks) > 1 else "min", x, lo, marker="s", style=style, colour=c_lo),
            ]
        points = _critical_station(series[0].y, series[1].y, x, quantity, stations, allow)
        found = [(s, (allow or {}).get((st, quantity))) for s, st in enumerate(stations)]
        caps = [(s, c) for s, c in found if c is not None]
        if caps:
            xs = np.array([float(s) for s, _ in caps])
            series += [
                Series(
                    "allowable limit load", xs, np.array([c[1] for _, c in caps]), style="none", marker="v", colour=5
                ),
                Series(
                    "allowable limit load", xs, np.array([c[0] for _, c in caps]), style="none", marker="^", colour=5
                ),
            ]
        panels.append(Panel(Axis(quantity, si, shown), series, points=points, band=(0, 1)))
    return Chart(Axis("station", categories=list(stations)), panels, title=title, arrangement="row")


def _critical_station(
    hi: np.ndarray,
    lo: np.ndarray,
    x: np.ndarray,
    quantity: str,
    stations: Sequence[str],
    allow: dict[tuple[str, str], tuple[float, float]] | None,
) -> list[Point]:
    best = None
    for s, st in enumerate(stations):
        cap = (allow or {}).get((st, quantity))
        for v, sense in ((hi[s], 1), (lo[s], 0)):
            if not np.isfinite(v):
                continue
            score = abs(v) / abs(cap[sense]) if cap and cap[sense] else abs(v) * 1e-30
            if best is None or score > best[0]:
                best = (score, s, v, bool(cap))
    if best is None:
        return []
    _, s, v, has_cap = best
    return [Point(float(x[s]), float(v), "critical (nearest its allowable)" if has_cap else "largest load")]


def case_table(
    env: Run, surface: str, allow: Allowables | None = None, gradients: Any = None, which: Any = None
) -> Table:
    """The critical cases of ``surface`` in the load envelope ``env``: station, quantity, sense, limit load (kN,
    kN·m), the governing allowable where declared, condition and time; with ``gradients`` and ``which`` the gust
    gradient H of each."""
    cases = [c for c in env.critical_cases() if c.surface == surface]
    # a "critical" load of zero (nothing loads the surface in that sense) has no critical condition: which of the
    # zero loads came first is round-off, so it is not named
    scale = max((abs(c.value) for c in cases if np.isfinite(c.value)), default=0.0)
    rows = []
    for c in cases:
        cap = (allow or {}).get(surface, {}).get((c.station, c.quantity))
        loaded = abs(c.value) > max(1e-9 * scale, 1e-6)
        row = [
            c.station,
            c.quantity,
            c.sense,
            c.value / 1e3,
            (cap[1] if c.sense == "max" else cap[0]) / 1e3 if cap else None,
            env.labels[c.condition] if loaded else "none (no load in this sense)",
            c.time if loaded else None,
        ]
        if gradients is not None:
            q, s = QUANTITIES.index(c.quantity), env.stations[surface].index(c.station)
            row.append(float(gradients[which[c.condition, 1 if c.sense == "max" else 0, q, s]]) if loaded else None)
        rows.append(row)
    columns = [
        Column("station", "station", kind="text"),
        Column("quantity", "quantity", kind="text"),
        Column("sense", "sense", kind="text"),
        Column("load", "limit load", "kN | kN·m"),
        Column("allowable", "allowable limit load", "kN | kN·m"),
        Column("condition", "condition", kind="text"),
        Column("time", "time", "s"),
    ]
    if gradients is not None:
        columns.append(Column("H", "gust gradient H", "m"))
    return Table(columns, rows)


def not_simulated(failed: Sequence[tuple[Any, str]]) -> list[Evidence]:
    if not failed:
        return []
    return [
        Evidence(
            "Conditions not simulated",
            table=Table(
                [Column("condition", "condition", kind="text"), Column("reason", "reason", kind="text")],
                [[c, r] for c, r in failed],
            ),
        )
    ]


def maneuver_evidence(
    run: Run, surface: str, control: str, signals: Sequence[str] = ("n_z", "q"), allow: Allowables | None = None
) -> list[Evidence]:
    name = surface.replace("_", " ")
    env = run.envelope
    return [
        Evidence(
            f"Critical conditions: {control}, load factor, pitch rate and {name} root shear",
            time_history(run, surface, control, signals, allow),
            "The conditions with the largest positive and negative root shear and, for each input kind, the one "
            "with the largest root load; curves end where the paragraph stops considering loads; the star marks "
            "the critical root shear, dash-dot lines the governing allowables.",
        ),
        Evidence(
            f"Load envelope along the {name} span",
            envelope_chart({"envelope": env.peaks[surface]}, env.stations[surface], (allow or {}).get(surface)),
            "Maximum and minimum over every condition and time (limit loads); triangles: the governing allowable "
            "limit load (the smaller of the allowable limit load and the allowable ultimate load ÷ the factor of "
            "safety, §25.303).",
        ),
        Evidence(
            f"Critical-case table, {name}",
            caption="Critical condition and time of every station and quantity.",
            table=case_table(env, surface, allow=allow),
        ),
    ] + not_simulated([(env.labels[i], r) for i, r in env.failed])


# --------------------------------------------------------------------------- discrete gusts (§25.341(a))


def _gust_picks(run: Run) -> list[tuple[int, int]]:
    """(condition, gradient index) of the extreme wing root bending and tail root shear, both senses."""
    env, which = run.envelope, run.which
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


def gust_time_history(
    replays: Sequence[Any], conditions: Sequence[Any], allow: Allowables | None = None, stations: Any = None
) -> Chart:
    lines: list[list[Series]] = [[], [], [], []]
    for rank, (i, H, r) in enumerate(replays):
        sim = r.sim
        label = f"{conditions[i].label()} · H {H / FT:.0f} ft"
        crit = rank == 0
        lines[0].append(Series(label, sim.t, r.alpha_gust["wing"][:, 0], critical=crit))
        lines[1].append(Series(label, sim.t, sim["n_z"][:, 0], critical=crit))
        lines[2].append(Series(label, sim.t, r.loads["wing"][:, 0, 1, 0], critical=crit))
        lines[3].append(Series(label, sim.t, r.loads["horizontal_tail"][:, 0, 0, 0], critical=crit))

    def root_limits(surface: str, quantity: str) -> list[Limit]:
        cap = (allow or {}).get(surface, {}).get((stations[surface][0], quantity)) if stations else None
        return (
            [Limit(cap[0], "allowable (−)", kind="allowable"), Limit(cap[1], "allowable (+)", kind="allowable")]
            if cap
            else []
        )

    panels = [
        Panel(Axis("gust angle at the wing", "rad"), lines[0]),
        Panel(Axis("load factor", "g"), lines[1]),
        Panel(
            Axis("wing root bending", "N·m", "kN·m"),
            lines[2],
            root_limits("wing", "bending"),
            _peak_point(lines[2][0]) if lines[2] else [],
        ),
        Panel(Axis("tail root shear", "N", "kN"), lines[3], root_limits("horizontal_tail", "shear")),
    ]
    return Chart(Axis("time", "s"), panels)


def gust_evidence(run: Run, allow: Allowables | None = None) -> list[Evidence]:
    env = run.envelope
    replays = run.replay(_gust_picks(run))
    out = [
        Evidence(
            "Critical discrete-gust conditions: gust angle, load factor, wing root bending, tail root shear",
            gust_time_history(replays, run.conditions, allow, env.stations),
            "The conditions and gradients with the largest positive and negative wing root bending and tail "
            "root shear; the gust reaches the tail a tail arm / V after the wing; dash-dot lines: governing "
            "allowables at the root.",
        )
    ]
    for surface in ("wing", "horizontal_tail"):
        name = surface.replace("_", " ")
        out += [
            Evidence(
                f"Gust load envelope along the {name} span",
                envelope_chart({"envelope": env.peaks[surface]}, env.stations[surface], (allow or {}).get(surface)),
                "Maximum and minimum over every condition, gust gradient and time (limit loads); triangles: "
                "the governing allowable limit load.",
            ),
            Evidence(
                f"Critical-case table, {name} (discrete gust)",
                caption="Critical condition, gradient and time of every station and quantity.",
                table=case_table(env, surface, allow=allow, gradients=run.gradients, which=run.which[surface]),
            ),
        ]
    return out


# --------------------------------------------------------------------------- unsymmetrical gusts (§25.349(b))


def _unsymmetrical_picks(run: Run) -> list[tuple[int, int]]:
    """(condition, gradient index) of the largest root bending on each side and of the largest rolling moment."""
    env, which = run.envelope, run.which
    b = QUANTITIES.index("bending")
    picks = []
    for side in env.peaks:
        for sense in ("max", "min"):
            _, i = env.extreme(side, "bending", 0, sense)
            if i >= 0 and (i, int(which[side][i, 1 if sense == "max" else 0, b, 0])) not in picks:
                picks.append((i, int(which[side][i, 1 if sense == "max" else 0, b, 0])))
    roll = np.abs(run.roll)
    j, i = np.unravel_index(int(np.argmax(roll)), roll.shape)
    if (int(i), int(j)) not in picks:
        picks.append((int(i), int(j)))
    return picks[:4]


def unsymmetrical_time_history(run: Run, picks: Sequence[tuple[int, int]]) -> Chart:
    runs, (full, reduced) = run.runs, run.fractions
    lines: list[list[Series]] = [[], [], [], []]
    for k, (i, H, r) in enumerate(runs.replay(picks)):
        aero, inertia = r.parts["wing"]
        m = runs.batch.model.subset([i])
        u = unsymmetrical_wing(
            runs.loads["wing"],
            aero,
            inertia,
            m.mass,
            m.cg,
            m.inertia,
            full,
            reduced,
            trim_aero=aero[0] if run.basis == "increment" else None,
        )
        t = r.sim.t
        label = f"{runs.conditions[i].label()} · H {H / FT:.0f} ft"
        lines[0] += [
            Series(label, t, u.full[:, 0, 1, 0], colour=k, critical=k == 0),
            Series("", t, u.reduced[:, 0, 1, 0], colour=k, style="--"),
            Series("", t, (aero + inertia)[:, 0, 1, 0], colour=k, style=":"),
        ]
        lines[1].append(Series(label, t, u.rolling_moment[:, 0], colour=k))
        lines[2].append(Series(label, t, u.pdot[:, 0], colour=k))
        lines[3].append(Series(label, t, r.sim["n_z"][:, 0] + u.delta_n_z[:, 0], colour=k))
    sides = f"wing root bending: — {full:.0%}, -- {reduced:.0%}, ·· symmetric"
    panels = [
        Panel(Axis(sides, "N·m", "kN·m"), lines[0], points=_peak_point(lines[0][0]) if lines[0] else []),
        Panel(Axis("unbalanced rolling moment", "N·m", "kN·m"), lines[1]),
        Panel(Axis("roll acceleration", "rad/s²"), lines[2]),
        Panel(Axis("load factor, air load removed", "g"), lines[3]),
    ]
    return Chart(Axis("time", "s"), panels)


def unsymmetrical_gust_evidence(run: Run, allow: Allowables | None = None) -> list[Evidence]:
    full, reduced = run.fractions
    env, sym = run.envelope, run.symmetric
    stations = env.stations[next(iter(env.peaks))]
    peaks = {side: env.peaks[side] for side in env.peaks} | {"symmetric §25.341(a)": sym.peaks["wing"]}
    wing_allow = (allow or {}).get("wing")
    out = [
        Evidence(
            f"Critical unsymmetrical-gust conditions: wing root bending on the {full:.0%} and {reduced:.0%} "
            "sides, unbalanced rolling moment, roll acceleration and load factor",
            unsymmetrical_time_history(run, _unsymmetrical_picks(run)),
            "The §25.341(a) responses with the largest root bending on either side and with the largest "
            "unbalanced rolling moment; the wing air load is "
            f"{'the gust increment' if run.basis == 'increment' else 'the whole air load'} "
            f"× {full:.0%} on one side and × {reduced:.0%} on the other, the unbalance reacted by the rigid "
            "airplane's vertical, roll and pitch accelerations.",
        ),
        Evidence(
            "Unsymmetrical-gust load envelopes along the wing span",
            envelope_chart(peaks, stations, wing_allow),
            "Maximum (circles) and minimum (squares) over every condition, gust gradient and time (limit "
            "loads), each side against the symmetric gust (dotted); triangles: the governing allowable limit load.",
        ),
    ]
    for side in env.peaks:
        out.append(
            Evidence(
                f"Critical-case table, {side} (unsymmetrical gust)",
                caption="Critical condition, gradient and time of every station and quantity.",
                table=case_table(
                    env,
                    side,
                    gradients=run.gradients,
                    which=run.which[side],
                    allow={side: wing_allow} if wing_allow else None,
                ),
            )
        )
    return out


# --------------------------------------------------------------------------- steady load cases (§25.331(b), …)


def run_envelope_evidence(
    run: Run, ctx: Context, ultimate_factor: float, surfaces: Sequence[str], what: str
) -> list[Evidence]:
    """:func:`envelope_evidence` of a loads rule's run against the declared allowables; none when nothing was
    simulated."""
    if run is None or not run.simulated:
        return []
    return envelope_evidence(run.envelope, surfaces, what, allow=allowables(ctx, ultimate_factor))


def envelope_evidence(
    env: Run, surfaces: Iterable[str], what: str, plot: bool = True, allow: Allowables | None = None
) -> list[Evidence]:
    """The critical-case table of each of ``surfaces`` in the load envelope ``env`` (skipping a surface with no
    computed load) and, with ``plot``, its load envelope along the span (the tables alone where the rule's own plots
    already show the case)."""
    out = []
    for surface in surfaces:
        if surface not in env.peaks or not np.any(np.isfinite(env.peaks[surface])):
            continue
        name = surface.replace("_", " ")
        if plot:
            out.append(
                Evidence(
                    f"Load envelope along the {name} span ({what})",
                    envelope_chart({"envelope": env.peaks[surface]}, env.stations[surface], (allow or {}).get(surface)),
                    "Maximum and minimum over every condition (limit loads); triangles: the governing "
                    "allowable limit load.",
                )
            )
        out.append(
            Evidence(
                f"Critical-case table, {name} ({what})",
                caption="Critical condition of every station, quantity and sense.",
                table=case_table(env, surface, allow=allow),
            )
        )
    return out
