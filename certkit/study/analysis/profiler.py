"""Data of the interactive prediction profiler: each objective and chosen constraint response against each
variable through the current point, evaluated in the page from the exported surrogates (by the page's script); a
handling-quality level derived from its mode quantities is shown as those quantities (damping ratio, frequency, CAP).

Slider ranges reach ``OVERHANG`` of each variable's range beyond its bounds; that part is drawn greyed, as
outside the sampled region (extrapolation).
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

import numpy as np

from certkit.study.analysis.export import export_surrogate
from certkit.study.analysis.labels import display_factor, response_label
from certkit.study.analysis.surrogates import Surrogate
from certkit.study.spec import Study

if TYPE_CHECKING:
    from certkit.study.analysis.derived_levels import DerivedLevel
    from certkit.study.analysis.validity import Validity

OVERHANG = 0.1


def profiler_data(
    study: Study,
    surrogates: dict[str, Surrogate],
    start: np.ndarray | None = None,
    validity: Validity | None = None,
    levels: dict[str, DerivedLevel] | None = None,
) -> dict[str, Any]:
    """Everything the page needs: variables with bounds and slider range, the responses' exported models
    with their thresholds and flags, the classifier of possible designs (``validity``,
    :meth:`certkit.study.analysis.validity.Validity.export`; None when nothing is masked) and the starting point
    (the baseline unless given). Values are SI; each variable and response carries the ``factor`` (SI per shown
    unit) and ``unit`` it is shown in, a response its words (``title``)."""
    start = study.baseline if start is None else np.asarray(start, dtype=float)
    limits = {c.response: (c.min, c.max) for c in study.constraints}
    names = [o.response for o in study.objectives]
    for name in study.profiled_constraints():  # a derived level is shown as the quantities it comes from
        names += list(levels[name].source.sources.values()) if levels and name in levels else [name]
    responses = []
    for name in dict.fromkeys(names):
        if name not in surrogates:
            continue
        s = surrogates[name]
        lo, hi = limits.get(name, (None, None))
        words, unit, factor = response_label(name)
        responses.append(
            {
                "name": name,
                "model": export_surrogate(s),
                "min": lo,
                "max": hi,
                "flagged": s.flagged,
                "label": s.kept.label,
                "title": words,
                "unit": unit,
                "factor": factor,
            }
        )
    variables = []
    for v, x0 in zip(study.variables, start):
        span = v.upper - v.lower
        variables.append(
            {
                "path": v.path,
                "label": v.short,
                "lower": v.lower,
                "upper": v.upper,
                "from": v.lower - OVERHANG * span,
                "to": v.upper + OVERHANG * span,
                "value": float(x0),
                "unit": v.unit_label,
                "factor": display_factor(v.unit_label),
            }
        )
    classifier = validity.export() if validity is not None else None
    return {"variables": variables, "responses": responses, "validity": classifier}


def profiler_json(data: dict[str, Any]) -> str:
    """JSON for a ``<script type="application/json">`` element (``</`` escaped so the element cannot close)."""
    return json.dumps(data, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
