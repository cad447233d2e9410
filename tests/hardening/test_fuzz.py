"""Property-based fuzzing of the aircraft file (Hypothesis, fixed seed, bounded budget).

Property: every mutated variant of aircraft/lta.yaml (data: values, types, keys, structure; text: lines and YAML
tokens) either loads, with finite numbers only, or raises certkit's UserError. benchmarks/bench_fuzz.py runs the
same strategies with a long budget and reports counts.
"""

from hypothesis import HealthCheck, given, settings

from .fuzz import data_variants, outcome, text_variants

_BOUNDED = settings(
    max_examples=250,
    derandomize=True,
    database=None,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)


@_BOUNDED
@given(data_variants())
def test_mutated_data_loads_or_is_a_user_error(variant):
    result = outcome(variant)
    assert not result.startswith("unexpected"), result


@_BOUNDED
@given(text_variants())
def test_mutated_text_loads_or_is_a_user_error(variant):
    result = outcome(variant)
    assert not result.startswith("unexpected"), result
