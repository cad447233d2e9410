"""Numbers beyond any physical value, found in the plain data of an input file before validation.

Quantities with a unit are range-checked when read (:func:`certkit.units.physical`); this walk covers the plain
numbers (ratios, coefficients, counts, derivative tables) and numbers written as text ("1e300"), which pydantic would
accept as written: any magnitude above :data:`certkit.units.MAX_SI_MAGNITUDE` is refused, with its YAML path.
"""

from __future__ import annotations

import math

from certkit.units import MAX_SI_MAGNITUDE

_MESSAGE = (
    f"number beyond any physical value certkit takes (magnitude above {MAX_SI_MAGNITUDE:.0e}; NaN and "
    "infinities are refused too)"
)


def scalars(data: object, prefix: tuple = ()):
    """(location, value) of every value of plain YAML data that is not a mapping or a list (keys and indices)."""
    stack = [(prefix, data)]
    while stack:
        loc, node = stack.pop()
        if isinstance(node, dict):
            stack.extend((loc + (k,), v) for k, v in node.items())
        elif isinstance(node, list):
            stack.extend((loc + (i,), v) for i, v in enumerate(node))
        else:
            yield loc, node


def extreme_numbers(data: object, prefix: tuple = ()) -> list[tuple[tuple, str, object]]:
    """(location, message, value) of every number in ``data`` that is not finite or exceeds the range."""
    return [
        (loc, _MESSAGE, node)
        for loc, node in scalars(data, prefix)
        if isinstance(node, (int, float, str)) and not isinstance(node, bool) and _extreme(node)
    ]


def _extreme(value: int | float | str) -> bool:
    if isinstance(value, str):
        if not value or len(value) > 40 or not (value[0].isdigit() or value[0] in "+-."):
            return False
        try:
            value = float(value)
        except ValueError:
            return False
    elif isinstance(value, int):
        return abs(value) > MAX_SI_MAGNITUDE
    return not math.isfinite(value) or abs(value) > MAX_SI_MAGNITUDE
