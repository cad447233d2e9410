"""Mutated aircraft files for property-based fuzzing (Hypothesis): the baseline's data with values, types, keys and
structure changed, and its YAML text with lines and tokens changed. Shared by tests/hardening/test_fuzz.py (bounded,
fixed seed) and benchmarks/bench_fuzz.py (long budget, counts).

The property: every variant loads, or raises certkit's :class:`UserError`; a loaded model holds finite numbers only.
"""

from __future__ import annotations

import math
from collections import Counter

import yaml
from hypothesis import strategies as st

from certkit.aircraft import validate_aircraft_data
from certkit.aircraft.yaml_source import source_from_text
from certkit.errors import UserError

from ..conftest import BASELINE
from .mutate import baseline_data

TEXT = BASELINE.read_text(encoding="utf-8")
LINES = TEXT.splitlines()

HOSTILE_TEXT = [
    "nan ft",
    "inf ft",
    "-inf kg",
    "1e400 ft",
    "-1e400 m",
    "9**9**9 lb",
    "10**1000 lb",
    "3e5",
    "0 ft",
    "-5 kg",
    "1 furlong",
    "kg",
    "",
    " ",
    "1e-320 m",
    "340 kn EAS",
    "340 KEAS",
    "M0.84",
    "1 m^99",
    "1 (((m)))",
    "1 m/(s",
    "ft^2",
    "1e308 lbf*ft",
    "9" * 400 + " lb",
    "root",
    "side_of_body",
    "clean",
    "EAS",
    "1 m m m",
    "1 / / s",
    "2 ** 3 m",
    "1e5 slug*ft^2",
    "12 degC",
    "1 m^-4",
    "0x1F m",
    "1_000 m",
    "½ m",
    "1 µm",
    "日本語",
    "a\x00b",
    "a\nb",
    "1" * 90,
    "25.999",
    "..",
    "%",
    "1 %",
]
UNITS = [
    "ft",
    "lb",
    "kg*m^2",
    "deg",
    "kn EAS",
    "lbf",
    "ft^2",
    "m/s",
    "psi",
    "slug*ft^2",
    "rad/m",
    "kg/m^3",
    "lb/lbf/h",
    "N*m",
    "s",
    "K",
    "",
    "kn",
    "nmi",
    "deg/s",
]
SPECIAL_FLOATS = [math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, 0.0, -0.0, 1e-12, 1e12]

scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(10**6), max_value=10**6),
    st.integers(min_value=10**300, max_value=10**400),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from(SPECIAL_FLOATS),
    st.text(max_size=20),
    st.sampled_from(HOSTILE_TEXT),
    st.builds(
        lambda n, u: f"{n} {u}".strip(),
        st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(), st.sampled_from(["1e400", "nan"])),
        st.sampled_from(UNITS),
    ),
)
keys = st.one_of(
    st.text(max_size=12),
    st.sampled_from(
        [
            "name",
            "x",
            "y",
            "z",
            "mass",
            "inertia",
            "Ixx",
            "clean",
            "VD",
            "25.337",
            "25.999",
            "values",
            "station",
            "<<",
            "kind",
        ]
    ),
)
values = st.recursive(
    scalars, lambda kids: st.lists(kids, max_size=4) | st.dictionaries(keys, kids, max_size=4), max_leaves=8
)


def _paths(node, prefix=()):
    yield prefix
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _paths(v, prefix + (i,))


PATHS = list(_paths(baseline_data()))[1:]


def _parent(data, path):
    node = data
    for key in path[:-1]:
        node = node[key]
    return node


def _scaled(value, factor):
    if isinstance(value, bool):
        return not value
    if isinstance(value, (int, float)):
        try:
            return value * factor
        except OverflowError:  # a 400-digit integer times a float: keep the integer
            return value
    if isinstance(value, str):
        number, _, unit = value.partition(" ")
        try:
            return f"{float(number) * factor!r} {unit}".strip()
        except ValueError:
            return value[::-1]
    return value


def mutate(draw, data) -> None:
    """One change of ``data`` in place at a drawn path: replace, delete, rename, add a key, rescale, change the
    container, duplicate or empty a list."""
    path = draw(st.sampled_from(PATHS))
    try:
        parent = _parent(data, path)
        key = path[-1]
        current = parent[key]
    except (KeyError, IndexError, TypeError):
        return  # an earlier change removed this path
    op = draw(
        st.sampled_from(
            [
                "replace",
                "replace",
                "replace",
                "scale",
                "delete",
                "rename",
                "add_key",
                "wrap",
                "to_list",
                "duplicate",
                "empty",
            ]
        )
    )
    if op == "replace":
        parent[key] = draw(values)
    elif op == "scale":
        parent[key] = _scaled(current, draw(st.sampled_from([-1, 0, 1e-3, 1e3, 1e300, -1e-300, 10, 0.5])))
    elif op == "delete":
        del parent[key]
    elif op == "rename" and isinstance(parent, dict):
        parent[draw(keys)] = parent.pop(key)
    elif op == "add_key" and isinstance(current, dict):
        current[draw(keys)] = draw(values)
    elif op == "wrap":
        parent[key] = [current]
    elif op == "to_list" and isinstance(current, dict):
        parent[key] = list(current.values())
    elif op == "duplicate" and isinstance(current, list):
        current.extend(current[: draw(st.integers(1, 3))])
    elif op == "empty" and isinstance(current, (list, dict)):
        parent[key] = type(current)()


@st.composite
def data_variants(draw):
    data = baseline_data()
    for _ in range(draw(st.integers(1, 3))):
        mutate(draw, data)
    return data


TOKENS = [
    "&a ",
    "*a",
    "[",
    "]",
    "{",
    "}",
    ":",
    "- ",
    "\t",
    "!!python/object:os.system ",
    "<<: *a",
    "\x00",
    "\ufeff",
    "? ",
    "|",
    ">",
    "'",
    '"',
    "#",
    "%YAML 1.1\n",
    "---\n",
    "...\n",
    "!!float ",
    ".nan",
    ".inf",
    "9" * 400,
    "&b [*b]",
    "&x [1, 2, 3]",
    "1e400",
    "0o777",
    "0x1F",
    "2001-12-14",
    "null",
    "~",
    "yes",
    "NO",
    "=",
    "!!binary ",
    "\\",
]


@st.composite
def text_variants(draw):
    lines = list(LINES)
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(lines) - 1))
        op = draw(st.sampled_from(["delete", "duplicate", "insert", "swap", "indent", "dedent"]))
        if op == "delete":
            del lines[i]
        elif op == "duplicate":
            lines.insert(i, lines[i])
        elif op == "insert":
            at = draw(st.integers(0, len(lines[i])))
            token = draw(st.one_of(st.sampled_from(TOKENS), st.text(max_size=6)))
            lines[i] = lines[i][:at] + token + lines[i][at:]
        elif op == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == "indent":
            lines[i] = "  " + lines[i]
        else:
            lines[i] = lines[i][2:] if lines[i].startswith("  ") else lines[i]
    return "\n".join(lines) + "\n"


def _finite_everywhere(value) -> bool:
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, dict):
        return all(_finite_everywhere(v) for v in value.values())
    if isinstance(value, (list, tuple)):
        return all(_finite_everywhere(v) for v in value)
    return True


def outcome(variant) -> str:
    """ "loads", "user_error", or "unexpected: <what>" for a data (dict) or text (str) variant."""
    try:
        if isinstance(variant, str):
            source = source_from_text(variant, "fuzz.yaml")
            model = validate_aircraft_data(source.data, source)
        else:
            model = validate_aircraft_data(variant)
    except UserError:
        return "user_error"
    except Exception as exc:  # noqa: BLE001 - what the property forbids
        return f"unexpected: {exc.__class__.__name__}: {str(exc)[:200]}"
    if not _finite_everywhere(model.model_dump()):
        return "unexpected: a non-finite number was accepted"
    return "loads"


def tally(outcomes) -> Counter:
    return Counter(o if not o.startswith("unexpected") else "unexpected" for o in outcomes)


def as_yaml(data) -> str:
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True)
