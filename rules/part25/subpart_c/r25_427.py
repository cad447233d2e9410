"""§25.427(b) Unsymmetrical loads on the horizontal tail: 100 % of the loading of the symmetrical manoeuvre
conditions of §25.331 and of the vertical gusts of §25.341(a) on the surface on one side of the plane of symmetry,
80 % on the other; the stabiliser root loads of each side against the declared tailplane capability and the torsion
the unbalance puts into the fuselage at the tail, against the declared fuselage capability there
(``structure.fuselage``,
station ``tail``, quantity ``torsion``).

Text verified against an eCFR mirror of Amdt. 25-86 (pilotfriend.com, Sec. 25.427): "(b) The horizontal tail must
be assumed to be subjected to unsymmetrical loading conditions determined as follows: (1) 100 percent of the maximum
loading from the symmetrical maneuver conditions of §25.331 and the vertical gust conditions of §25.341(a) acting
separately on the surface on one side of the plane of symmetry; and (2) 80 percent of these loadings acting on the
other side." Every symmetric condition is split (the maximum loading is among them); the fractions apply to the
air load, the inertial load of each half stays (:func:`certkit.models.loads.unsymmetrical.unsymmetrical_tail`).

Sources of the symmetric loadings: the §25.331(b) balanced manoeuvres, the §25.331(c)(2) checked manoeuvres and the
§25.341(a) gusts (the same runs, shared in one process with §25.331(b), §25.331(c)(2), §25.341(a) and §25.349(b)),
each along the time window its paragraph considers. The §25.331(c)(1) maximum pitch control displacement is not
included: said by a not-evaluated finding. The fuselage torsion at the tail is compared with a declared
``structure.fuselage`` capability (station ``tail``, quantity ``torsion``); without one it is reported, not evaluated.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from certkit_rules.part25.support.balanced_runs import (
    BALANCED_CONDITIONS,
    BALANCED_REQUIRES,
    BALANCED_RUN_CRITERIA,
    balanced_runs,
)
from certkit_rules.part25.support.gust_runs import GUST_CONDITIONS, GUST_RUN_CRITERIA, gust_runs
from certkit_rules.part25.support.pitch_runs import (
    CHECKED_CONDITIONS,
    CHECKED_CRITERIA,
    DISPLACEMENT_CONDITIONS,
    DISPLACEMENT_CRITERIA,
    checked_runs,
    displacement_runs,
)
from certkit_rules.part25.support.stability_speeds import flap_altitude_findings
from certkit_rules.part25.support.structural_checks import SAFETY, capability_finding

from certkit.engine.conditions import ConditionSpace
from certkit.engine.evidence.loads import allowables, envelope_evidence
from certkit.engine.registry import Criterion, SimulationRule, rule
from certkit.engine.results import Condition, Finding, LoadsRun
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope
from certkit.models.loads.unsymmetrical import unsymmetrical_tail_peaks

TAIL = "horizontal_tail"
#: the condition spaces of the symmetric loads rules whose tail loads are split
SOURCES = {
    "25.331(b)": BALANCED_CONDITIONS,
    "25.331(c)(1)": DISPLACEMENT_CONDITIONS,
    "25.331(c)(2)": CHECKED_CONDITIONS,
    "25.341(a)": GUST_CONDITIONS,
}
#: the condition axes that name a condition of each source beside its loading, configuration and altitude
KEY_AXES = {
    "25.331(b)": ("point", "trim"),
    "25.331(c)(1)": (),
    "25.331(c)(2)": ("entry_speed", "direction", "trim"),
    "25.341(a)": ("speed_point", "gust"),
}
REG = "14 CFR 25.427(b) (Amdt. 25-86; text from an eCFR mirror, pilotfriend.com)"
NO_FUSELAGE = (
    "no fuselage torsion capability at the tail is declared (structure.fuselage, station tail, quantity "
    "torsion): the fuselage torsion at the tail is reported, not compared"
)

LIMITATIONS = (
    "Symmetric loadings from §25.331(b), §25.331(c)(1), §25.331(c)(2) and §25.341(a); every symmetric condition is "
    "split, not only the maximum; each half's inertial load kept, the unbalanced moment taken by the fuselage "
    "(tail roll inertia relief neglected); the fuselage torsion compared only where a fuselage capability "
    "at the tail is declared."
)


@dataclass
class TailSplitRun(LoadsRun):
    """The split tail loads: the 100 % and reduced sides' envelopes and the largest fuselage torsion at the tail
    (N·m, with the label of its condition)."""

    largest_fuselage_torsion: tuple = (0.0, None)


@dataclass(frozen=True)
class SymmetricSources(ConditionSpace):
    """The conditions of the symmetric loads rules, each tagged with its ``source`` rule."""

    def expand(self, aircraft):
        out = []
        for rid, space in SOURCES.items():
            out += [c.with_(source=rid) for c in space.expand(aircraft)]
        return out

    def describe(self):
        return "the conditions of " + " and ".join(f"§{k} ({v.describe()})" for k, v in SOURCES.items())


def _untag(c: Condition) -> Condition:
    return c.without("source")


def _key(c: Condition, source: str):
    return (c.loading, c.configuration, c.altitude) + tuple(c.get(a) for a in KEY_AXES[source])


@rule
class UnsymmetricalTailLoads(SimulationRule):
    id = "25.427(b)"
    symbol = "unsymmetrical-tail-loads"
    title = "Unsymmetrical horizontal-tail loads: 100 % on one side, 80 % on the other"
    amendment = "25-86"
    cost = 3
    run_with = "discrete-gust"  # shares the §25.341(a) gust runs in one process
    requirement = """
        The horizontal tail is subjected to 100 % of the maximum loading from the symmetrical manoeuvre
        conditions of §25.331 and the vertical gusts of §25.341(a), acting separately, on the surface on one side
        of the plane of symmetry, and 80 % of these loadings on the other side (§25.427(b)(1), (2)); the
        structure carries the limit loads and 1.5 × them (§25.303, §25.305).
    """
    margin = """
        Per symmetric condition and side (100 %, 80 %): the smallest of (allowable limit load − |limit load|) and
        (allowable ultimate load − 1.5 × |limit load|) over the declared tailplane stations and quantities; the
        fuselage torsion at the tail (its limit and 1.5 × limit value) against the declared fuselage capability at the
        tail, one finding per condition; without one it is reported, not evaluated.
    """
    references = ("25.331", "25.341", "25.303", "25.305", "25.349")
    requires = BALANCED_REQUIRES + ("speeds.VB",)
    criteria = {
        **BALANCED_RUN_CRITERIA,
        **CHECKED_CRITERIA,
        **DISPLACEMENT_CRITERIA,
        **GUST_RUN_CRITERIA,
        "full_side_fraction": Criterion(1.0, "", REG + " (b)(1)", "fraction of the tail air load on one side"),
        "reduced_side_fraction": Criterion(0.8, "", REG + " (b)(2)", "fraction of the tail air load on the other side"),
        **SAFETY,
    }
    conditions = SymmetricSources()
    limitations = LIMITATIONS
    implementation = "partial"
    unevaluated = (
        (
            "25.427(b)(1)",
            "the §25.345(a)(2) flaps-extended gusts' tail loads are not split (§25.345(a)(2) reports them whole)",
        ),
        (
            "25.427(b)(1)",
            "the §25.341(b) continuous-turbulence tail loads are not split (a design-envelope band per station, not a "
            "loading with its air and inertial parts; on the baseline 20–42 % of the split cases' envelope)",
        ),
        (
            "25.427(a)",
            "unsymmetrical empennage loads from slipstream and aerodynamic interference in the lateral gust, yaw and "
            "roll manoeuvre conditions are not assessed as such: the fin and tailplane loads of §25.341(a), §25.349 "
            "and §25.351 are the vortex lattice's (its wing–tail interference; no propeller slipstream)",
        ),
        (
            "25.427(c)",
            "gusts of §25.341(a) in any orientation normal to the flight path are not computed; (c) asks for them "
            "where the tailplane has more than ±10° of dihedral or is carried by the fin (the baseline's, 7° on the "
            "fuselage, is not)",
        ),
        ("25.427(d)", "unsymmetrical empennage loads in the buffet conditions of §25.305(e) are not computed"),
    )

    def simulate(self, ctx, conditions, crit):
        return unsymmetrical_tail_loads(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        if self.run is None or not self.run.simulated:
            return []
        env = self.run.envelope
        return envelope_evidence(
            env, env.peaks, "100/80 % split", plot=False, allow=allowables(ctx, crit.ultimate_factor)
        )


def _split_sources(ctx, conditions, crit, tail, full: float, reduced: float) -> dict:
    """{(source, condition key): (100 % side peaks (2, 3, S), reduced side peaks, fuselage torsion (min, max), refined
    condition)} of every symmetric condition computed by its source (over every gust gradient and time)."""
    by_source: dict[str, list] = {}
    for c in conditions:
        by_source.setdefault(c.get("source"), []).append(_untag(c))
    parts = []  # (source, aero (T, n, 3, S), inertia, refined conditions)
    if "25.331(b)" in by_source:
        run = balanced_runs(ctx, by_source["25.331(b)"], crit)
        if run.simulated:
            aero, inertia = run.tail_parts
            parts.append(("25.331(b)", aero[None], inertia[None], run.conditions))
    for source, runs in (("25.331(c)(1)", displacement_runs), ("25.331(c)(2)", checked_runs)):
        if source in by_source:
            run = runs(ctx, by_source[source], crit)
            if run.simulated:
                aero, inertia = run.tail_parts()
                parts.append((source, aero, inertia, run.conditions))
    if "25.341(a)" in by_source:
        runs = gust_runs(ctx, by_source["25.341(a)"], crit)
        if runs.conditions:  # every gradient's time history one after the other
            parts.append(
                (
                    "25.341(a)",
                    np.concatenate([a for _, a, _ in runs.tail]),
                    np.concatenate([i for _, _, i in runs.tail]),
                    runs.conditions,
                )
            )
    out = {}
    for source, aero, inertia, conds in parts:
        p_full, p_red, t_lo, t_hi = unsymmetrical_tail_peaks(tail, aero, inertia, full, reduced)  # (n, 2, 3, S), (n,)
        for i, c in enumerate(conds):
            out[(source,) + _key(c, source)] = (p_full[i], p_red[i], (float(t_lo[i]), float(t_hi[i])), c)
    return out


def fuselage_torsion_finding(cond, capabilities, t_lo: float, t_hi: float, ultimate_factor, **details) -> Finding:
    """The fuselage torsion at the tail of one split condition against the declared capability (§25.305): the smaller
    normalised margin of allowable limit − |T| and allowable ultimate − factor × |T|, in the torsion's sense."""
    sense, load = ("positive", t_hi) if abs(t_hi) >= abs(t_lo) else ("negative", t_lo)
    best = None
    for cap in capabilities:
        for which, factor in (("limit", 1.0), ("ultimate", float(ultimate_factor))):
            value = getattr(cap, which)
            allowable = float(getattr(value, sense) if hasattr(value, sense) else value)
            design = factor * abs(load)
            norm = (allowable - design) / allowable
            if best is None or norm < best[0]:
                best = (norm, which, design, allowable)
    _, which, design, allowable = best
    return Finding.compare(
        cond,
        f"(b) fuselage torsion at the tail: {which} ({sense})",
        design,
        allowable,
        at_least=False,
        unit="N·m",
        **details,
    )


def unsymmetrical_tail_loads(ctx, conditions, crit) -> TailSplitRun:
    loads = airplane_loads(ctx)
    tail = loads[TAIL]
    caps = declared_capabilities(ctx, TAIL)
    st = getattr(ctx.aircraft, "structure", None)
    fuselage = [c for c in (st.fuselage if st is not None else ()) if c.station == "tail" and c.quantity == "torsion"]
    full, reduced = float(crit.full_side_fraction), float(crit.reduced_side_fraction)
    with warnings.catch_warnings():  # all-NaN rows (states that were not balanced) are refused below
        warnings.simplefilter("ignore", RuntimeWarning)
        sym = _split_sources(ctx, conditions, crit, tail, full, reduced)
    findings, labels, peaks = [], [], {"100 % side": [], "80 % side": []}
    worst = (0.0, None)
    for c in conditions:
        source = c.get("source")
        hit = sym.get((source,) + _key(c, source))
        checks = [f"(b)(1) {full:.0%} side, horizontal tail", f"(b)(2) {reduced:.0%} side, horizontal tail"]
        high = flap_altitude_findings(ctx, c, float(crit.flap_altitude_max), checks)
        if high:  # the source's condition does not apply (a flap configuration above the flap altitude limit)
            findings += high
            continue
        if hit is None or not np.isfinite(hit[0]).any():
            findings += [
                Finding.not_evaluated(
                    c, k, f"no symmetric loads of this condition (§{source} could not trim or balance it)"
                )
                for k in checks
            ]
            continue
        p_full, p_red, (t_lo, t_hi), refined = hit
        cond = refined.with_(source=source)
        label = cond.label()
        if max(abs(t_lo), abs(t_hi)) > worst[0]:
            worst = (max(abs(t_lo), abs(t_hi)), label)
        details = {
            "fuselage torsion at the tail max/min (kN·m)": [round(t_hi / 1e3, 1), round(t_lo / 1e3, 1)],
            "source": f"§{source}",
        }
        if fuselage:
            findings.append(fuselage_torsion_finding(cond, fuselage, t_lo, t_hi, crit.ultimate_factor, **details))
        findings.append(
            capability_finding(cond, checks[0], TAIL, p_full, tail.station_names, caps, crit.ultimate_factor, **details)
        )
        findings.append(
            capability_finding(cond, checks[1], TAIL, p_red, tail.station_names, caps, crit.ultimate_factor, **details)
        )
        labels.append(label)
        peaks["100 % side"].append(p_full)
        peaks["80 % side"].append(p_red)
    if worst[1] is not None and not fuselage:
        findings.append(
            Finding.not_evaluated(
                Condition(),
                "(b) fuselage torsion at the tail",
                NO_FUSELAGE,
                largest_torsion_kNm=round(worst[0] / 1e3, 1),
                critical_condition=worst[1],
            )
        )
    if not labels:
        return TailSplitRun(findings, reason="no symmetric loads to split (see the findings)")
    stations = {s: tail.station_names for s in peaks}
    P = {s: np.stack(v) for s, v in peaks.items()}  # (n, 2, 3, S)
    env = LoadEnvelope(stations, P, {s: np.zeros_like(v) for s, v in P.items()}, labels)
    return TailSplitRun(findings, envelope=env, largest_fuselage_torsion=worst)
