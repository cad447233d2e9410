"""Evidence tables as the report shows them: human headers with the display unit, numbers converted to aviation
units and rounded per column (:mod:`certkit.report.display`), no ``None``/``-0``/``NaN`` cells."""

from __future__ import annotations

import math

import numpy as np

from certkit.engine.evidence import Table
from certkit.report.display import DASH, axis_label, decimals, format_number, unit_and_factor


def formatted(table: Table) -> dict:
    """``{"headers": [...], "rows": [[(text, is_number), ...], ...]}`` of ``table``."""
    headers, columns = [], []
    keys = [c.key for c in table.columns]
    row_units = {c.unit_key for c in table.columns if c.unit_key in keys}
    for j, col in enumerate(table.columns):
        cells = [row[j] for row in table.rows]
        unit, factor = unit_and_factor(col.unit, col.display)
        headers.append(axis_label(col.name, unit))
        if col.key in row_units:  # a unit column: each row's unit as shown
            columns.append([(unit_and_factor(v)[0] if isinstance(v, str) else _text(v), False) for v in cells])
            continue
        if col.kind == "text" or not any(_number(v) for v in cells):
            columns.append([(_text(v), False) for v in cells])
            continue
        if col.unit_key in keys:  # mixed units: each row converted by its own unit
            k = keys.index(col.unit_key)
            factors = [unit_and_factor(row[k])[1] if isinstance(row[k], str) else 1.0 for row in table.rows]
            shown = [v / f if _number(v) else v for v, f in zip(cells, factors)]
        else:
            shown = [v / factor if _number(v) else v for v in cells]
        places = 0 if col.kind == "integer" else decimals([v for v in shown if _number(v)])
        columns.append([(format_number(v, places), True) if _number(v) else (_text(v), False) for v in shown])
    rows = [list(r) for r in zip(*columns)] if columns else []
    return {"headers": headers, "rows": rows}


def _number(v) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))


def _text(v) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return DASH
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (list, tuple)):
        return ", ".join(_text(x) for x in v)
    return str(v)
