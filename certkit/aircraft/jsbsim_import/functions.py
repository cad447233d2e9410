"""Evaluation of JSBSim's XML function elements (``<function>``, ``<product>``, ``<table>`` …) at given property
values, for the importer. Written from JSBSim's published XML format (JSBSim Reference Manual, "Functions" and
"Tables"): a function holds one operation; tables interpolate linearly and hold their end values outside.

Only what aircraft aerodynamics and turbine engines use is understood: product, sum, difference, quotient,
value, property, table (1-D and 2-D), abs, pow, min, max. Anything else raises :class:`Unsupported` naming the
element, so the importer can report it instead of guessing.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import Mapping

import numpy as np


class Unsupported(ValueError):
    """An element or property the evaluator does not know."""


def _property_value(name: str, props: Mapping[str, float]) -> float:
    name = name.strip()
    sign = 1.0
    if name.startswith("-"):
        sign, name = -1.0, name[1:]
    if name not in props:
        raise Unsupported(f"property {name!r}")
    return sign * float(props[name])


def table_arrays(table: ET.Element) -> tuple[list[str], np.ndarray, np.ndarray | None, np.ndarray]:
    """(independent variable names, row breakpoints, column breakpoints or None, data) of a 1-D or 2-D table."""
    names = [v.text.strip() for v in table.findall("independentVar")]
    data = table.find("tableData")
    if data is None or table.find("tableData[@breakPoint]") is not None or len(names) > 2:
        raise Unsupported("3-D table")
    rows = [[float(x) for x in line.split()] for line in data.text.strip().splitlines() if line.strip()]
    if len(names) == 1:
        arr = np.array(rows)
        return names, arr[:, 0], None, arr[:, 1]
    cols = np.array(rows[0])
    body = np.array(rows[1:])
    order = {
        v.get("lookup", "row" if i == 0 else "column"): n
        for i, (v, n) in enumerate(zip(table.findall("independentVar"), names))
    }
    return [order["row"], order["column"]], body[:, 0], cols, body[:, 1:]


def interpolate_table(table: ET.Element, props: Mapping[str, float]) -> float:
    names, rows, cols, data = table_arrays(table)
    x = _property_value(names[0], props)
    if cols is None:
        return float(np.interp(x, rows, data))
    y = _property_value(names[1], props)
    along_rows = np.array([np.interp(x, rows, data[:, j]) for j in range(data.shape[1])])
    return float(np.interp(y, cols, along_rows))


def evaluate(element: ET.Element, props: Mapping[str, float]) -> float:
    """The value of a function element (or of its single operation) at the property values."""
    tag = element.tag
    if tag == "function":
        ops = [c for c in element if c.tag != "description"]
        if len(ops) != 1:
            raise Unsupported(f"function {element.get('name')!r} with {len(ops)} operations")
        return evaluate(ops[0], props)
    if tag == "value":
        return float(element.text)
    if tag == "property":
        return _property_value(element.text, props)
    if tag == "table":
        return interpolate_table(element, props)
    args = [evaluate(c, props) for c in element if c.tag != "description"]
    if tag == "product":
        return float(np.prod(args))
    if tag == "sum":
        return float(np.sum(args))
    if tag == "difference":
        return args[0] - float(np.sum(args[1:]))
    if tag == "quotient":
        return args[0] / args[1]
    if tag == "abs":
        return abs(args[0])
    if tag == "pow":
        return args[0] ** args[1]
    if tag == "min":
        return min(args)
    if tag == "max":
        return max(args)
    raise Unsupported(f"element <{tag}>")


def properties_used(element: ET.Element) -> set[str]:
    """Every property a function reads (as property or table variable)."""
    names = {p.text.strip().lstrip("-") for p in element.iter("property")}
    names |= {v.text.strip().lstrip("-") for v in element.iter("independentVar")}
    return names
