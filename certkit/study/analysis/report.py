"""The study report: every analysis of a finished study in one self-contained offline HTML page.

:func:`analyse` runs the analyses on the store's frame (surrogates, Monte Carlo, Pareto fronts, optima,
Sobol indices, and — unless switched off — the true-model checks through the study runner); :func:`render`
fills the template; :func:`write_study_report` does both and writes ``index.html``.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
from jinja2 import Environment, PackageLoader, select_autoescape

from certkit import __version__
from certkit.study.analysis import figures
from certkit.study.analysis.cases import cases, study_hash
from certkit.study.analysis.checks import CheckedOptimum, DirectCheck, direct_check, reevaluate_optima
from certkit.study.analysis.montecarlo import STAGES, MonteCarloResult, run_monte_carlo
from certkit.study.analysis.optimise import front_points, optimise, pareto_fronts
from certkit.study.analysis.planform import planform_from
from certkit.study.analysis.profiler import profiler_data, profiler_json
from certkit.study.analysis.ranking import ShowStopper, active_constraints, show_stoppers, without_unattainable
from certkit.study.analysis.sensitivity import SobolTable, sobol_indices
from certkit.study.analysis.surrogates import K_FOLDS, Surrogate, fit_all
from certkit.study.analysis.validity import Validity, fit_validity
from certkit.study.spec import Study

#: failed cases listed one by one in the report (the count is always given)
FAILED_SHOWN = 200
#: Pareto points listed per front table
FRONT_SHOWN = 50
#: points of each NSGA-II front re-evaluated with the true model
FRONT_CHECKED = 5


@dataclass
class Analysis:
    view: Study
    sha256: str
    counts: pd.DataFrame
    failed: pd.DataFrame
    n_cases: dict[str, int]
    surrogates: dict[str, Surrogate]
    not_fitted: dict[str, str]
    mc: MonteCarloResult | None
    mc_note: str
    sobol: list[SobolTable]
    check: DirectCheck | None
    check_note: str
    optima: list[CheckedOptimum]
    profiler: dict
    timings: dict[str, float] = field(default_factory=dict)
    validity: Validity | None = None
    nsga_fronts: list[dict] = field(default_factory=list)
    front_checks: list[CheckedOptimum] = field(default_factory=list)
    show_stoppers: list[ShowStopper] = field(default_factory=list)
    active: dict[str, list[str]] = field(default_factory=dict)


def _in_unit(value: float, unit: str) -> float:
    """An SI value in the variable's display unit (``deg``, ``ft^2``); unchanged without one."""
    if not unit:
        return value
    from certkit.units import from_si

    try:
        return from_si(value, unit)
    except Exception:  # an unknown display unit: the SI value, rather than no report
        return value


def _run_checks(
    usable: Study, every: Study, store, surrogates, mc, optima, run_cases
) -> tuple[DirectCheck | None, list[CheckedOptimum], str]:
    if store is None:
        return None, [], "not run: no study store to record the true-model cases in"
    check = direct_check(usable, store, surrogates, mc, run_cases=run_cases)
    checked = reevaluate_optima(every, store, surrogates, optima, run_cases=run_cases)
    return check, checked, ""


def analyse(
    study: Study,
    frame: pd.DataFrame,
    *,
    store=None,
    samples: int = 1_000_000,
    check: bool = True,
    sha256: str | None = None,
    chunk: int = 100_000,
    log=lambda msg: None,
    run_cases=None,
) -> Analysis:
    """Run every analysis of the study report on the store's ``frame``. ``run_cases``: how the true-model checks
    run (see :func:`~certkit.study.analysis.checks.run_true_model`)."""
    timings = {}
    t = time.perf_counter()
    view = study
    cs = cases(frame, view)
    surrogates, not_fitted = fit_all(view, cs, log)
    timings["surrogates_s"] = time.perf_counter() - t
    usable = view.model_copy(
        update={
            "objectives": [o for o in view.objectives if o.response in surrogates],
            "constraints": [c for c in view.constraints if c.response in surrogates],
        }
    )
    mc_note = "; ".join(f"{r} left out: {not_fitted[r]}" for r in not_fitted)
    t = time.perf_counter()
    validity = fit_validity(frame, view)
    log(f"possible designs: {validity.note}")
    mc = run_monte_carlo(usable, surrogates, n=samples, chunk=chunk, valid=validity.valid)
    every = usable  # show-stoppers are ranked and reported; the stages, fronts and optima are of the rest
    usable, mc = without_unattainable(
        usable,
        surrogates,
        mc,
        lambda rest: run_monte_carlo(rest, surrogates, n=samples, chunk=chunk, valid=validity.valid),
    )
    timings["monte_carlo_s"] = time.perf_counter() - t
    log(f"Monte Carlo: {samples} samples in {mc.seconds:.1f} s")
    t = time.perf_counter()
    sobol = [sobol_indices(view, surrogates[r]) for r in view.analysed_responses() if r in surrogates]
    timings["sobol_s"] = time.perf_counter() - t
    t = time.perf_counter()
    margin = validity.margin if validity.estimator is not None else None
    optima = optimise(usable, surrogates, mc, margin)
    nsga = pareto_fronts(usable, surrogates, margin)
    points = optima + front_points(nsga, FRONT_CHECKED)
    timings["optimiser_s"] = time.perf_counter() - t
    log(f"optimiser: {len(optima)} optima, {len(nsga)} NSGA-II fronts in {timings['optimiser_s']:.1f} s")
    checked, direct, check_note = [], None, "not run (--no-check)"
    if check:
        t = time.perf_counter()
        direct, checked, check_note = _run_checks(usable, every, store, surrogates, mc, points, run_cases)
        timings["true_model_s"] = time.perf_counter() - t
    if not checked:
        checked = [
            CheckedOptimum(
                o,
                "not evaluated",
                check_note,
                {},
                {
                    r: float(surrogates[r].predict(o.x[None, :])[0])
                    for r in every.analysed_responses()
                    if r in surrogates
                },
            )
            for o in points
        ]
    counts = cs.counts()
    n_cases = {"total": len(frame), **frame["status"].value_counts().to_dict()}
    return Analysis(
        view,
        sha256 or study_hash(view),
        counts,
        cs.failed(),
        n_cases,
        surrogates,
        not_fitted,
        mc,
        mc_note,
        sobol,
        direct,
        check_note,
        checked[: len(optima)],
        profiler_data(every, surrogates, validity=validity),
        timings,
        validity,
        nsga,
        checked[len(optima) :],
        show_stoppers(every, mc, cs, not_fitted),
        active_constraints(usable, surrogates, optima),
    )


def _num(value, digits: int = 4) -> str:
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "—"
    value = float(value)
    if value != 0 and (abs(value) >= 1e6 or abs(value) < 1e-3):
        return f"{value:.{digits - 1}e}"
    return f"{value:.{digits}g}"


def _environment() -> Environment:
    env = Environment(
        loader=PackageLoader("certkit.study.analysis", "templates"),
        autoescape=select_autoescape(["html"]),
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters["num"] = _num
    env.filters["in_unit"] = _in_unit
    env.filters["pct"] = lambda p: "—" if p is None else f"{100 * p:.2f} %"
    env.filters["ci"] = lambda iv: "—" if iv is None else f"{100 * iv[0]:.2f} – {100 * iv[1]:.2f} %"
    return env


def _planform_figures(a: Analysis) -> list[dict]:
    """Per objective: the baseline and the objective's unconstrained, constrained and preferred optima."""
    paths = [v.path for v in a.view.variables]
    base, note = planform_from(dict(zip(paths, a.view.baseline)))
    if base is None:
        return [{"objective": "", "svg": "", "note": note}]
    out = []
    for objective in a.mc.objectives:
        items, notes = [("baseline", base)], [note] if note else []
        for o in (c.optimum for c in a.optima if c.optimum.objective == objective):
            p, _ = planform_from(dict(zip(paths, o.x)))
            items.append((f"{o.stage} optimum", p))
        out.append({"objective": objective, "svg": figures.planforms_svg(items), "note": "; ".join(notes)})
    return out


def render(a: Analysis) -> str:
    """The report page (a string of HTML)."""
    env = _environment()
    mc = a.mc
    stage_rows = []
    for stage in STAGES:
        p, se = mc.stage_p(stage)
        stage_rows.append(
            {"stage": stage, "count": mc.stage_counts[stage], "p": p, "se": se, "interval": mc.stage_interval(stage)}
        )
    fronts = []
    for (stage, cols), acc in mc.fronts.items():
        f, x = acc.front()
        fronts.append(
            {
                "stage": stage,
                "objectives": [mc.objectives[c] for c in cols],
                "size": len(f),
                "rows": [list(fr) + list(xr) for fr, xr in zip(f[:FRONT_SHOWN], x[:FRONT_SHOWN])],
            }
        )
    context = {
        "a": a,
        "view": a.view,
        "mc": mc,
        "version": __version__,
        "created": time.strftime("%Y-%m-%d %H:%M:%S"),
        "stage_rows": stage_rows,
        "k_folds": K_FOLDS,
        "fronts": fronts,
        "front_shown": FRONT_SHOWN,
        "front_checked": FRONT_CHECKED,
        "nsga": [
            {
                "objectives": f["objectives"],
                "size": len(f["f"]),
                "checks": [c for c in a.front_checks if c.optimum.objective == " × ".join(f["objectives"])],
            }
            for f in a.nsga_fronts
        ],
        "fits": [{"s": s, "svg": figures.fit_svg(s)} for s in a.surrogates.values()],
        "cdfs": [{"o": o, "svg": figures.cdf_svg(o)} for o in mc.ranked()],
        "matrix": figures.scatter_matrix_svg(mc, mc.objectives) if len(mc.objectives) >= 2 else "",
        "planforms": _planform_figures(a),
        "failed_rows": a.failed.head(FAILED_SHOWN),
        "failed_shown": FAILED_SHOWN,
        "definition": json.dumps(a.view.model_dump(mode="json"), indent=2, default=str),
        "profiler_json": profiler_json(a.profiler),
        "profiler_js": env.loader.get_source(env, "profiler.js")[0],
        "flagged": [r for r, s in a.surrogates.items() if s.flagged],
    }
    return env.get_template("study_report.html").render(**context)


def write_study_report(study, frame: pd.DataFrame, out_dir: str | Path, **kw) -> Path:
    """Analyse the study and write ``index.html`` into ``out_dir``; returns its path."""
    analysis = analyse(study, frame, **kw)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "index.html"
    path.write_text(render(analysis), encoding="utf-8")
    return path


__all__ = ["Analysis", "analyse", "render", "write_study_report"]
