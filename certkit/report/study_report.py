"""The study report: every analysis of a finished study (:func:`certkit.study.analysis.analyse.analyse`) drawn in
one self-contained offline HTML page. :func:`render` fills the template; :func:`write_study_report` analyses and
writes ``index.html``.
"""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np
import pandas as pd
from jinja2 import Environment

from certkit import __version__
from certkit.report import study_figures as figures
from certkit.report.pages import page_environment
from certkit.study.analysis.analyse import FRONT_CHECKED, Analysis, analyse
from certkit.study.analysis.confirm import MAX_STEPS
from certkit.study.analysis.montecarlo import STAGES
from certkit.study.analysis.optimise import LEAST_VIOLATION
from certkit.study.analysis.planform import planform_from
from certkit.study.analysis.profiler import profiler_json
from certkit.study.analysis.summary import study_summary
from certkit.study.analysis.surrogates import K_FOLDS
from certkit.units import from_si

#: failed cases listed one by one in the report (the count is always given)
FAILED_SHOWN = 200
#: Pareto points listed per front table
FRONT_SHOWN = 50


def _in_unit(value: float, unit: str) -> float:
    """An SI value in the variable's display unit (``deg``, ``ft^2``); unchanged without one."""
    if not unit:
        return value

    try:
        return from_si(value, unit)
    except Exception:  # an unknown display unit: the SI value, rather than no report
        return value


def _num(value, digits: int = 4) -> str:
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "—"
    value = float(value)
    if value != 0 and (abs(value) >= 1e6 or abs(value) < 1e-3):
        return f"{value:.{digits - 1}e}"
    return f"{value:.{digits}g}"


def _environment() -> Environment:
    return page_environment(
        {
            "num": _num,
            "in_unit": _in_unit,
            "pct": lambda p: "—" if p is None else f"{100 * p:.2f} %",
            "ci": lambda iv: "—" if iv is None else f"{100 * iv[0]:.2f} – {100 * iv[1]:.2f} %",
        }
    )


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
        "least_violation": LEAST_VIOLATION,
        "confirm_steps": MAX_STEPS,
    }
    return env.get_template("study_report.html").render(**context)


def write_study_report(study, frame: pd.DataFrame, out_dir: str | Path, **kw) -> Path:
    """Analyse the study and write ``index.html`` and its headline as data, ``summary.json``
    (:func:`certkit.study.analysis.summary.study_summary`), into ``out_dir``; returns the page's path."""
    analysis = analyse(study, frame, **kw)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "index.html"
    path.write_text(render(analysis), encoding="utf-8")
    summary = json.dumps(study_summary(analysis), indent=2, allow_nan=False, ensure_ascii=False)
    (out / "summary.json").write_text(summary + "\n", encoding="utf-8")
    return path


__all__ = ["render", "write_study_report"]
