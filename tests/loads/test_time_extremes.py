"""The compiled extremes over time of load histories (:func:`certkit.models.loads.response.time_extremes`, read by
every :meth:`LoadEnvelope.from_histories`) are numpy's own: the record index of ``np.argmin``/``np.argmax`` of the
histories with NaN filled by ±inf (the first of equal extremes, 0 where every time is NaN) and the values there, bit
for bit (the sign of a zero included). Hypothesis draws the histories: NaN runs, infinities, repeated extremes, -0.0
against 0.0, one record, one condition."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from certkit.models.loads.response import LoadEnvelope, time_extremes

values = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, width=64),
    st.sampled_from([0.0, -0.0, 1.0, -1.0, np.nan, np.inf, -np.inf]),
)


def numpy_extremes(L):
    ilo = np.argmin(np.where(np.isnan(L), np.inf, L), axis=0)
    ihi = np.argmax(np.where(np.isnan(L), -np.inf, L), axis=0)
    lo = np.take_along_axis(L, ilo[None], axis=0)[0]
    hi = np.take_along_axis(L, ihi[None], axis=0)[0]
    return ilo, ihi, np.stack([lo, hi], axis=1)


def same(a, b) -> bool:
    return (
        a.shape == b.shape
        and a.dtype == b.dtype
        and np.array_equal(a, b, equal_nan=True)
        and np.array_equal(np.signbit(a), np.signbit(b))
    )


@settings(max_examples=300, deadline=None)
@given(
    arrays(
        np.float64,
        st.tuples(st.integers(1, 9), st.integers(1, 4), st.just(3), st.integers(1, 3)),
        elements=values,
    )
)
def test_extremes_over_time_are_numpys(L):
    for ours, theirs in zip(time_extremes(L), numpy_extremes(L)):
        assert same(ours, theirs)


def test_an_envelope_of_strided_histories_reads_them_as_they_are():
    """A history that is a view (every second record, conditions reversed) gives the envelope of its copy."""
    rng = np.random.default_rng(7)
    base = rng.normal(size=(40, 6, 3, 4))
    base[rng.random(base.shape) < 0.2] = np.nan
    view = base[::2, ::-1]
    ilo, ihi, peaks = time_extremes(view)
    ref = numpy_extremes(np.array(view))
    assert same(ilo, ref[0]) and same(ihi, ref[1]) and same(peaks, ref[2])
    assert peaks.flags["C_CONTIGUOUS"]


def test_from_histories_times_the_extremes_on_a_grid_per_condition():
    """With a time step per condition (t (nt, n)), each extreme's time is read on its own condition's grid."""
    from types import SimpleNamespace

    n_s = 5
    loads = {"horizontal_tail": SimpleNamespace(station_names=tuple(f"s{k}" for k in range(n_s)))}
    nt, n = 5, 2
    L = np.zeros((nt, n, 3, n_s))
    L[3, 0, 1, 0] = 7.0  # condition 0: bending at the root peaks at record 3
    L[1, 1, 1, 0] = -2.0  # condition 1: its minimum at record 1
    t = np.arange(nt)[:, None] * np.array([[0.1, 0.25]])
    env = LoadEnvelope.from_histories(loads, {"horizontal_tail": L}, t, ["a", "b"])
    assert env.peaks["horizontal_tail"][0, 1, 1, 0] == 7.0 and env.times["horizontal_tail"][0, 1, 1, 0] == 0.1 * 3
    assert env.peaks["horizontal_tail"][1, 0, 1, 0] == -2.0 and env.times["horizontal_tail"][1, 0, 1, 0] == 0.25


def test_an_empty_history_is_an_error_as_in_numpy():
    with pytest.raises(ValueError):
        time_extremes(np.zeros((0, 3, 3, 2)))
