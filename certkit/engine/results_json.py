"""The text of ``results.json``: strict JSON, numbers rounded, human-diffable, written by CPython's C encoder.

Conventions (the schema ``certkit/data/results.schema.json`` states them field by field):

- every float is rounded to :data:`SIGNIFICANT_DIGITS` significant digits (``-0.0`` is written ``0.0``); a NaN or
  an infinity (a value that could not be computed) is written ``null`` and counted;
- containers down to nesting depth :data:`INDENTED_DEPTH` are indented by two spaces, one member a line; anything
  deeper (a finding, its condition and details) is one compact line, so that a diff shows one finding per line;
- the object ``run`` (time stamp, duration, processes: what varies between identical runs) is one line, the last of
  the top-level object, so that two runs compare equal line by line once that line is left out.

The compact parts are encoded with ``json.dumps`` without an indent, which CPython does in C (the indenting
encoder is pure Python, about four times slower on a results.json of several MB).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from importlib.resources import files
from typing import Any

import numpy as np

#: version of the results.json layout: the major number changes when a field is removed or changes meaning
SCHEMA_VERSION = "1.0"
SIGNIFICANT_DIGITS = 9
INDENTED_DEPTH = 4
#: the top-level key of what varies between identical runs
VOLATILE_KEY = "run"

_compact_encoder = json.JSONEncoder(ensure_ascii=False, separators=(", ", ": "), allow_nan=False)
_key = json.JSONEncoder(ensure_ascii=False).encode


def _c_compact() -> Callable[[object], str] | None:
    """``_compact_encoder.encode`` for cleaned data (acyclic: no check for circular references), with the one C encoder
    ``JSONEncoder.encode`` builds at each call made once (a finding's line is three such calls; the same text)."""
    make = getattr(json.encoder, "c_make_encoder", None)
    if make is None:  # an interpreter without the C encoder
        return None
    e = _compact_encoder
    separators = (e.key_separator, e.item_separator)
    c = make(None, e.default, json.encoder.encode_basestring, None, *separators, False, False, False)

    def encode(data: object) -> str:
        return "".join(c(data, 0)) if isinstance(data, (dict, list, tuple)) else e.encode(data)

    return encode


_compact = _c_compact() or _compact_encoder.encode


class Rounded(dict):  # type: ignore[type-arg]
    """A mapping already as results.json writes it (plain JSON data, every number finite and at most
    :data:`SIGNIFICANT_DIGITS` significant digits, no ``-0.0``): :func:`clean` leaves it as it is, and the C encoder
    writes it without a walk through its numbers (:func:`rounded_table`)."""


class Encoded(str):
    """Text already encoded as :func:`encode` would write it at its depth (a finding's line): placed as it is."""


def rounded_table(keys: Iterable[str], values: np.ndarray, decimals: int) -> dict[str, Any]:
    """``keys`` → the rows of ``values`` (K, …) rounded to ``decimals`` (≥ 0) decimals, as lists: a :class:`Rounded`
    mapping when every rounded number is finite and below 10^(SIGNIFICANT_DIGITS − decimals) in magnitude (then it
    has at most :data:`SIGNIFICANT_DIGITS` significant digits and is the nearest double to its decimal — numpy rounds
    by scaling, rounding to an integer and dividing — so :func:`clean` would give each number back unchanged), a plain
    dict (cleaned when written) otherwise."""
    return _rounded_tables(keys, np.asarray(values, dtype=float)[None], decimals)[0]


def _rounded_tables(keys: Iterable[str], values: np.ndarray, decimals: int) -> list[dict[str, Any]]:
    """:func:`rounded_table` of each of the tables ``values`` (N, K, …), rounded in one numpy pass."""
    with np.errstate(over="ignore", invalid="ignore"):  # a number too large to scale is no longer finite: plain
        rounded = np.round(values, decimals) + 0.0  # + 0.0: -0.0 becomes 0.0
    as_is = np.zeros(len(rounded), dtype=bool)
    if decimals >= 0:
        plain = np.abs(rounded) < 10.0 ** (SIGNIFICANT_DIGITS - decimals)
        as_is = np.broadcast_to(plain.reshape(len(rounded), -1).all(axis=1), len(rounded))
    keys = tuple(keys)
    return [
        Rounded(zip(keys, table)) if ok else dict(zip(keys, table))
        for table, ok in zip(rounded.tolist(), as_is.tolist())
    ]


@dataclass(frozen=True, eq=False)
class RoundedRows:
    """Details computed only when written (a :attr:`~certkit.engine.results.Finding.written_details`): ``keys`` → the
    rows of ``rows(source[None])[0]`` (K, m) rounded to ``decimals``, as :func:`rounded_table` gives them. ``rows`` maps
    a stack of sources (N, …) to their tables (N, K, m) elementwise, so that :func:`round_rows` forms and rounds a
    rule's thousands of such tables in one numpy pass (the same numbers as one at a time)."""

    keys: tuple[str, ...]
    source: np.ndarray
    rows: Callable[[np.ndarray], np.ndarray]
    decimals: int

    def __call__(self) -> dict[str, Any]:
        return rounded_table(self.keys, self.rows(self.source[None])[0], self.decimals)


def round_rows(tables: Sequence[RoundedRows]) -> list[dict[str, Any]]:
    """``[t() for t in tables]``, the tables of one ``rows``, keys, source shape and decimals formed together."""
    out: list[dict[str, Any]] = [{}] * len(tables)
    groups: dict[tuple[Any, ...], list[int]] = {}
    for i, t in enumerate(tables):
        groups.setdefault((t.rows, t.keys, t.source.shape, t.decimals), []).append(i)
    for (rows, keys, _, decimals), members in groups.items():
        values = rows(np.stack([tables[i].source for i in members]).astype(float, copy=False))
        for i, mapping in zip(members, _rounded_tables(keys, values, decimals)):
            out[i] = mapping
    return out


def clean(obj: object) -> tuple[object, int]:
    """``obj`` as plain JSON data: floats rounded, non-finite numbers ``None`` (their count returned), numpy scalars
    and arrays as numbers and lists, tuples as lists, other objects as their ``str``."""
    count = [0]
    fmt = f".{SIGNIFICANT_DIGITS}g"
    isfinite = math.isfinite

    def walk(o: Any) -> Any:
        t = type(o)
        if t is float:
            if not isfinite(o):
                count[0] += 1
                return None
            return float(format(o, fmt)) + 0.0  # + 0.0: -0.0 becomes 0.0
        if t is str or t is int or t is bool or o is None or t is Rounded:
            return o
        if t is dict:
            return {k if type(k) is str else str(k): walk(v) for k, v in o.items()}
        if t is list or t is tuple:
            return [walk(v) for v in o]
        if isinstance(o, dict):
            return {str(k): walk(v) for k, v in o.items()}
        if isinstance(o, (list, tuple)):
            return [walk(v) for v in o]
        if isinstance(o, float):
            return walk(float(o))
        if isinstance(o, (str, int)):
            return o
        return walk(_numpy(o))

    return walk(obj), count[0]


def _numpy(o: object) -> object:
    if isinstance(o, np.bool_):
        return bool(o)
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.floating):
        return float(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    return str(o)


def encode(data: object, depth: int = 0) -> str:
    """Cleaned ``data`` (:func:`clean`) as text at nesting ``depth`` (a rule's object sits at depth 2: the top-level
    object, then ``rules``): indented down to :data:`INDENTED_DEPTH`, compact below."""
    if type(data) is Encoded:
        return data
    if depth >= INDENTED_DEPTH or not data or not isinstance(data, (dict, list)):
        return _compact(data)
    pad, close = "  " * (depth + 1), "  " * depth
    if isinstance(data, dict):
        items = [
            f"{pad}{_key(k)}: {_compact(v) if k == VOLATILE_KEY and depth == 0 else encode(v, depth + 1)}"
            for k, v in data.items()
        ]
        return "{\n" + ",\n".join(items) + "\n" + close + "}"
    return "[\n" + ",\n".join(pad + encode(v, depth + 1) for v in data) + "\n" + close + "]"


def compact(data: object) -> str:
    """Cleaned ``data`` as one compact line (the form below :data:`INDENTED_DEPTH`)."""
    return _compact(data)


def stable_lines(text: str) -> str:
    """``results.json`` text without its ``run`` line: what two runs of the same input and options write alike."""
    return "\n".join(line for line in text.splitlines() if not line.startswith(f'  "{VOLATILE_KEY}": '))


def schema() -> dict[str, Any]:
    """The JSON Schema of results.json shipped with certkit."""
    loaded: dict[str, Any] = json.loads(
        files("certkit").joinpath("data/results.schema.json").read_text(encoding="utf-8")
    )
    return loaded
