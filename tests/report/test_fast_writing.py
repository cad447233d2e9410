"""The fast paths of writing a check (a finding's results.json line, a findings table's rows, one number as the
report shows it) give the same text as the general path they shortcut — the generic cleaning and encoding of
results.json (:mod:`certkit.engine.results_json`), and the Jinja markup of a findings row. Hypothesis draws the
findings: numbers of every magnitude and sign, NaN and infinities, -0.0, None, written details that come rounded or
not, and details that repeat a written key."""

from __future__ import annotations

import math
from functools import partial

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from jinja2 import Environment
from markupsafe import Markup

from certkit.engine.results import Condition, Finding, RuleResult
from certkit.engine.results_json import Rounded, RoundedRows, clean, compact, encode, round_rows, rounded_table
from certkit.report.display import decimals, format_number, format_value
from certkit.report.html import _environment, finding_rows

numbers = st.floats(allow_nan=True, allow_infinity=True, width=64)
finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e12, max_value=1e12)
texts = st.one_of(
    st.text(alphabet=st.sampled_from(list("ab <>&'\"§25.3(b)_·é")), max_size=24),
    st.sampled_from(["§25.331(b) at VA", "see 14 CFR 25.303 & <§25.999>", "", "a 'quoted' \"reason\""]),
)


def _table(values: np.ndarray, keys: tuple[str, ...]) -> dict:
    return rounded_table(keys, values, 1)


@st.composite
def findings(draw):
    cond = Condition(
        loading=draw(st.sampled_from(["fwd_light", "aft_heavy", None])),
        mass=draw(st.one_of(st.none(), finite, numbers)),
        x_cg=draw(st.one_of(st.none(), finite)),
        altitude=draw(st.one_of(st.none(), finite)),
        speed=draw(st.one_of(st.none(), finite)),
        speed_kind="EAS",
    )
    f = Finding(
        cond,
        draw(texts),
        draw(st.sampled_from(["complies", "fails", "not_evaluated"])),
        value=draw(st.one_of(st.none(), numbers)),
        limit=draw(st.one_of(st.none(), numbers)),
        margin=draw(st.one_of(st.none(), numbers)),
        unit=draw(st.sampled_from(["", "N", "N·m", "m/s", "kg", "rad", "g<>"])),
        reason=draw(texts),
        details=draw(
            st.dictionaries(st.sampled_from(["a", "b", "k0", "source"]), st.one_of(numbers, texts, st.none()))
        ),
    )
    rows = draw(st.integers(0, 3))
    if draw(st.booleans()):
        values = np.array(
            draw(st.lists(st.one_of(finite, numbers, st.floats(-1e9, 1e9)), min_size=2 * rows, max_size=2 * rows))
        ).reshape(rows, 2)
        f.written_details = partial(_table, values, tuple(f"k{i}" for i in range(rows)))
    return f


@settings(max_examples=400, deadline=None)
@given(findings(), st.booleans())
def test_a_findings_line_is_the_general_encoding(f, shared):
    conditions: dict = {}
    if shared:  # a condition's text kept from an earlier finding of the rule
        f.json_line(conditions)
    line, count = f.json_line(conditions)
    data, n = clean(f.as_dict())
    assert line == compact(data)
    assert count == n


@settings(max_examples=400, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=0, max_size=12), st.integers(0, 4))
def test_a_rounded_table_is_what_cleaning_gives(values, places):
    """A :class:`Rounded` table is left as it is by the cleaning, so it must already be what the cleaning makes of it:
    every number the same, finite, never -0.0."""
    table = rounded_table([f"k{i}" for i in range(len(values))], np.array(values).reshape(-1, 1), places)
    data, n = clean(dict(table))
    if type(table) is Rounded:
        assert n == 0
        assert data == table
        assert all(math.copysign(1.0, v[0]) > 0 or v[0] != 0.0 for v in table.values())
        assert all(repr(a[0]) == repr(b[0]) for a, b in zip(table.values(), data.values()))
    else:  # plain: cleaned when written
        assert any(not math.isfinite(v) or abs(v) >= 10.0 ** (9 - places) for v in values)


def test_a_rule_with_shared_conditions_writes_what_the_general_encoding_writes():
    cond = Condition(loading="fwd_light", mass=140613.6354, x_cg=28.05381, altitude=float("nan"), speed=94.10123)
    f1 = Finding.compare(cond, "torsion at root (max)", 703209.31912, 5204000.0, at_least=False, unit="N·m")
    f1.written_details = partial(_table, np.array([[-146.34, -146.36], [float("nan"), 2.0]]), ("shear", "bending"))
    f2 = Finding.compare(cond, "bending at root (max)", -0.0, 1e-12, at_least=False, unit="N·m", source="§25.331(b)")
    f2.written_details = partial(_table, np.array([[1234.56, -0.04]]), ("shear",))
    result = RuleResult(id="25.427(b)", symbol="R", title="t", findings=[f1, f2])
    assert result.to_json() == encode(clean(result.as_dict())[0], depth=2)
    # written null: the condition's altitude in both findings and as the critical condition, a NaN of f1's details
    assert result.non_finite == 4 == clean(result.as_dict())[1]
    assert '"shear": [-146.3, -146.4]' in result.to_json() and '"shear": [1234.6, 0.0]' in result.to_json()


def _pairs(stack: np.ndarray) -> np.ndarray:
    """(N, 2, K) → (N, K, 2): a batched table layout, elementwise (scaled) like a station summary."""
    return stack.transpose(0, 2, 1) / 1e3


@settings(max_examples=300, deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(1, 3), st.lists(st.one_of(finite, numbers), min_size=6, max_size=6)),
        min_size=0,
        max_size=8,
    ),
    st.integers(-1, 3),
)
def test_tables_rounded_together_are_those_rounded_one_at_a_time(drawn, places):
    """:func:`round_rows` forms and rounds tables of one layout in one pass: each dict, and whether it comes
    :class:`Rounded`, as the table's own call gives it (NaN, infinities, -0.0, numbers too large to scale)."""
    tables = [
        RoundedRows(tuple(f"k{i}" for i in range(k)), np.array(v[: 2 * k]).reshape(2, k), _pairs, places)
        for k, v in drawn
    ]
    together = round_rows(tables)
    for table, got in zip(tables, together):
        alone = table()
        assert type(got) is type(alone)
        assert list(got) == list(alone)
        assert all(repr(a) == repr(b) for k in alone for a, b in zip(alone[k], got[k]))


def test_a_rule_writes_tables_rounded_together_as_the_general_encoding_writes_them():
    cond = Condition(loading="fwd_light", mass=140613.6354, x_cg=28.05381, altitude=1000.0, speed=94.10123)
    stack = np.array([[[146340.0, 1.0e20], [-146360.0, 2.0]], [[1234560.0, -40.0], [float("nan"), -0.0]]])
    found = []
    for i, values in enumerate(stack):
        f = Finding.compare(cond.with_(k=i), "bending at root (max)", 7.0, 9.0, at_least=False, unit="N·m")
        f.written_details = RoundedRows(("shear", "bending"), values, _pairs, 1)
        found.append(f)
    result = RuleResult(id="25.427(b)", symbol="R", title="t", findings=found)
    assert result.to_json() == encode(clean(result.as_dict())[0], depth=2)
    assert result.non_finite == clean(result.as_dict())[1] == 1


#: a findings row in the report's Jinja markup, the general path :func:`finding_rows` shortcuts
ROW = (
    '{% for f in findings %}\n<tr{% if f is sameas critical %} class="critical"{% endif %}>'
    "<td>{{ f.condition.label() }}</td><td>{{ f.check | refs }}</td>\n"
    '<td class="num">{{ f.value | value(f.unit) }}</td><td class="num">{{ f.limit | value(f.unit) }}</td>'
    '<td class="num">{{ f.margin | margin(f.unit, f.limit) }}</td>\n'
    '<td class="num">{{ f.normalized_margin | pct }}</td><td class="{{ f.status }}">'
    "{{ f.status | replace('_', ' ') }}</td><td>{{ f.reason | refs }}</td></tr>\n{% endfor %}"
)


@settings(max_examples=200, deadline=None)
@given(st.lists(findings(), min_size=1, max_size=5), st.integers(0, 5))
def test_findings_rows_are_the_jinja_rows(found, pick):
    rule_ids = {"25.331(b)", "25.303"}
    env: Environment = _environment(rule_ids)
    env.trim_blocks = env.lstrip_blocks = True
    critical = found[pick] if pick < len(found) else None
    expected = env.from_string(ROW).render(findings=found, critical=critical)
    assert finding_rows(found, critical, rule_ids) == Markup(expected)


@settings(max_examples=1000, deadline=None)
@given(st.one_of(numbers, st.floats(-1e-3, 1e-3), st.floats(999.0, 1001.0)))
def test_one_number_as_the_report_shows_it(x):
    expected = format_number(x, decimals([x])) if math.isfinite(x) else "—"
    assert format_value(x) == expected


json_data = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(-(10**12), 10**12), finite, texts),
    lambda children: st.one_of(
        st.lists(children, max_size=4), st.dictionaries(texts, children, max_size=4), st.tuples(children, children)
    ),
    max_leaves=20,
)


@settings(max_examples=300, deadline=None)
@given(json_data)
def test_compact_lines_are_the_standard_encoders_text(data):
    """results.json's compact lines (one C encoder made once) are the text of the standard library's encoder with the
    same options, for any cleaned data: containers, scalars, text with escapes and non-ASCII letters."""
    import json

    expected = json.dumps(data, ensure_ascii=False, separators=(", ", ": "), allow_nan=False)
    assert compact(data) == expected
