"""The angular accelerations of the strip loads' inertial terms (``_rates_dot``: the time derivative of recorded
rates) are ``np.gradient``'s, bit for bit, in compiled code: on one uniform grid, on an uneven one (numpy's
second-order weights), and with a time step per condition (the gradient in records divided by each condition's step).
Hypothesis draws the histories and the grids, two records included."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from certkit.models.loads.response import _rates_dot

finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, width=64)
steps = st.floats(min_value=1e-3, max_value=1.0, allow_nan=False)


def same(a, b) -> bool:
    return a.shape == b.shape and np.array_equal(a, b, equal_nan=True)


@settings(max_examples=200, deadline=None)
@given(st.integers(2, 30), st.integers(1, 6), st.data())
def test_rate_derivatives_are_numpys_gradient(nt, n, data):
    x = data.draw(arrays(np.float64, (nt, n), elements=finite))
    h = data.draw(steps)
    uniform = np.arange(nt) * h
    uneven = np.cumsum(data.draw(arrays(np.float64, nt, elements=steps)))
    per_condition = np.arange(nt)[:, None] * data.draw(arrays(np.float64, n, elements=steps))[None, :]
    assert same(_rates_dot(uniform, x), np.gradient(x, uniform, axis=0))
    assert same(_rates_dot(uneven, x), np.gradient(x, uneven, axis=0))
    assert same(_rates_dot(per_condition, x), np.gradient(x, axis=0) / (per_condition[1] - per_condition[0]))


def test_a_strided_history_and_a_single_record():
    rng = np.random.default_rng(3)
    base = rng.normal(size=(40, 8))
    t = np.linspace(0.0, 2.0, 40)
    view = base[:, ::2]
    assert same(_rates_dot(t, view), np.gradient(view, t, axis=0))
    assert same(_rates_dot(t[:1], base[:1]), np.zeros((1, 8)))
