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


def _knee(slope, plateau, width, rise):
    """A response linear in x up to a knee and nearly flat beyond it — the checked manoeuvre's peak load factor
    against the elevator amplitude near the stall line: a softplus corner of ``width`` between the line slope·x and
    the plateau (rising by ``rise`` per unit x)."""
    return lambda x: plateau - width * np.logaddexp(0.0, (plateau - slope * x) / width) + rise * x


def test_a_probe_of_the_linear_part_brings_a_knee_to_the_resolution_within_the_steps():
    """400 knee-shaped responses (slopes 2–6, plateaus 0.4–1.5, corners 0.005–0.04 wide, aims 90–99 % of the full
    amplitude's response, near the knee): the chord from zero to the full amplitude creeps along the bend and leaves
    many outside a 0.002 residual after 10 steps; a probe at 0.1 of the amplitude and the step its line points to
    bring every one within it in the same 10 steps, with fewer evaluations."""
    from certkit.models.loads.inputs import linear_probe

    rng = np.random.default_rng(11)
    n = 400
    f = _knee(rng.uniform(2, 6, n), rng.uniform(0.4, 1.5, n), rng.uniform(0.005, 0.04, n), rng.uniform(0, 0.15, n))
    full = f(np.ones(n))
    aim = full * rng.uniform(0.9, 0.99, n)
    chord_run, chord_calls = _counting(f)
    x, fx, *_ = bisect_batch(
        chord_run, np.zeros(n), np.ones(n), aim, steps=10, tol=0.002, f_lo=f(np.zeros(n)), f_hi=full
    )
    assert (np.abs(fx - aim) > 0.002).sum() > 20
    run, calls = _counting(f)
    lo, f_lo, hi, f_hi, first = linear_probe(run, aim, full, np.ones(n, dtype=bool), 0.1)
    x, fx, *_ = bisect_batch(run, lo, hi, aim, steps=9, tol=0.002, f_lo=f_lo, f_hi=f_hi, first=first)
    assert np.all(np.abs(fx - aim) <= 0.002)
    assert sum(calls) < 0.7 * sum(chord_calls)


def test_the_first_guess_is_kept_inside_the_bracket_and_a_line_is_exact_after_the_probe():
    """On a straight response the probe's line lands on the root (one step after the probe); a first guess outside
    the bracket is clipped into it."""
    from certkit.models.loads.inputs import linear_probe

    run, calls = _counting(lambda x: 2.0 * x)
    aim = np.array([0.3, 1.0, 1.7])
    lo, f_lo, hi, f_hi, first = linear_probe(run, aim, np.full(3, 2.0), np.ones(3, dtype=bool), 0.1)
    x, fx, *_ = bisect_batch(run, lo, hi, aim, steps=9, tol=1e-12, f_lo=f_lo, f_hi=f_hi, first=first)
    np.testing.assert_allclose(x, [0.15, 0.5, 0.85], rtol=1e-12)
    assert len(calls) == 2  # the probe, then the line's point
    run2, _ = _counting(lambda x: x)
    x, *_ = bisect_batch(
        run2,
        np.zeros(1),
        np.ones(1),
        np.array([0.5]),
        steps=1,
        f_lo=np.zeros(1),
        f_hi=np.ones(1),
        first=np.array([3.0]),
    )
    assert x[0] == 1.0
