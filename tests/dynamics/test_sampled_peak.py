"""The peak of a sampled record between its samples (certkit.models.dynamics.sampled_peak), against closed forms:
a peak that slides across the time grid keeps its value (a sinusoid's crest is 1 wherever the samples fall; a sharp,
asymmetric crest — the shape of a load factor at the lift curve's maximum — keeps its own), where the greatest
sample alone moves by ½ |y''| (Δt/2)² in a saw-tooth."""

import numpy as np
import pytest

from certkit.models.dynamics.sampled_peak import peak_between_samples

DT = 0.04  # s, the checked manoeuvre's step
T = np.arange(0.0, 3.0, DT)


def _shifted(f, shifts):
    y = np.stack([f(T - s) for s in shifts], axis=1)
    return y, np.ones_like(y, dtype=bool)


def test_a_sinusoid_crest_anywhere_on_the_grid():
    """sin(ω t) at ω = 2 rad/s (the short-period frequency of the checked manoeuvre) crests at exactly 1: the
    greatest sample falls short by up to 1 − cos(ω Δt/2) = 8e-4; read between the samples within 1e-5."""
    shifts = np.linspace(0.0, DT, 17)
    y, valid = _shifted(lambda t: np.sin(2.0 * t), shifts)
    assert 1.0 - y.max(axis=0).min() > 5e-4  # the saw-tooth the estimator removes
    assert peak_between_samples(y, valid) == pytest.approx(np.ones(shifts.size), abs=1e-5)


def test_a_sharp_asymmetric_crest_is_read_within_a_fifth_of_the_sampling_error():
    """A crest with curvature −30 g/s² before and −60 g/s² after it (C¹, not C²: the cubic overshoots a little across
    the kink), value 2.5, slid across two steps: the greatest sample falls short by up to ~8e-3 g; the estimate stays
    within 1.5e-3 g of the crest wherever the samples fall."""

    def crest(t):
        u = t - 1.1
        return 2.5 - np.where(u < 0.0, 15.0, 30.0) * u**2

    shifts = np.linspace(0.0, 2 * DT, 81)
    y, valid = _shifted(crest, shifts)
    assert 2.5 - y.max(axis=0).min() > 7e-3
    assert peak_between_samples(y, valid) == pytest.approx(np.full(shifts.size, 2.5), abs=1.5e-3)


def test_window_edges():
    """A record rising to its window's end peaks at the last valid sample (nothing beyond it is read); one valid
    sample short of the cubic's four takes the parabola; a column with no valid sample is −inf."""
    y = np.stack([T, -((T - 1.0) ** 2), T], axis=1)
    valid = np.ones_like(y, dtype=bool)
    valid[T > 1.0 + 1.5 * DT, 1] = False  # the crest's neighbours are valid, the sample after them is not
    valid[:, 2] = False
    valid[T > 2.0, 0] = False
    est = peak_between_samples(y, valid)
    assert est[0] == pytest.approx(T[T <= 2.0].max())
    assert est[1] == pytest.approx(0.0, abs=1e-12)  # the parabola is exact on a parabola
    assert est[2] == -np.inf
