"""The batched bracketing search (certkit.models.loads.inputs.bisect_batch) on closed forms: a near-linear response
converges on its residual in a few steps; a response that flattens (a load factor growing by thousandths of g in a
hold) is only pinned by the bracket's width."""

import numpy as np

from certkit.models.loads.inputs import bisect_batch


def _counting(f):
    calls = []

    def run(x, mask):
        calls.append(int(mask.sum()))
        return np.where(mask, f(x), np.nan)

    return run, calls


def test_a_linear_response_converges_on_its_residual():
    run, calls = _counting(lambda x: 2.0 * x)
    x, fx, *_ = bisect_batch(run, np.zeros(3), np.ones(3), np.array([0.3, 1.0, 1.7]), steps=10, tol=1e-9)
    assert np.allclose(x, [0.15, 0.5, 0.85], atol=1e-8)
    assert len(calls) <= 3  # regula falsi: exact on a straight line after the first step (and the bracket ends)


def test_a_flat_response_is_pinned_by_the_bracket_width():
    """f(x) = 0.006 (1 − exp(−x/0.04)) with the target 0.0018 (root x* = −0.04 ln 0.7 = 0.014267): every x above
    0.0072 is within a 0.002 residual of the target, so a residual criterion leaves x anywhere in [0.0072, 0.0254];
    with ``x_tol`` = 1e-3 the bracket's upper end is within 1e-3 above the root."""
    root = -0.04 * np.log(0.7)
    run, _ = _counting(lambda x: 0.006 * (1.0 - np.exp(-x / 0.04)))
    loose = bisect_batch(run, np.zeros(1), np.ones(1), 0.0018, steps=10, tol=0.002)
    tight = bisect_batch(run, np.zeros(1), np.ones(1), 0.0018, steps=10, tol=0.0, x_tol=1e-3)
    assert abs(loose[4][0] - root) > 1e-3  # the residual alone stopped it far from the root
    assert 0.0 <= tight[4][0] - root <= 1e-3
    assert tight[2][0] <= root  # the lower end stays below
