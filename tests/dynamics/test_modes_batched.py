"""The modes of a batch identified at once (:func:`certkit.models.dynamics.modes.identify_rows`: the eigenproblems of
every condition in one batched LAPACK call) are the modes of each condition identified alone, bit for bit — the
eigenvalues, the scaled eigenvectors and which root is which mode — over a batch from 90 to 260 m/s and from sea
level to 12,000 m, with and without the density gradient's altitude state."""

import pytest

from certkit.models.dynamics.linearize import linearize
from certkit.models.dynamics.modes import identify_modes, identify_rows

from .conftest import trimmed_baseline


@pytest.fixture(scope="module")
def lin(baseline):
    model, batch = trimmed_baseline(baseline, 24, (90, 260), (0, 12000), 0.6)
    return linearize(model, batch.x, batch.u)


@pytest.mark.parametrize("density_gradient", [False, True])
def test_a_batch_s_modes_are_each_condition_s(lin, density_gradient):
    rows = [3, 0, 17, 23, 9]  # any rows, in any order
    together = identify_rows(lin, rows, density_gradient)
    assert len(together) == len(rows)
    for i, modes in zip(rows, together):
        alone = identify_modes(lin, i, density_gradient)
        assert list(modes) == list(alone) and "short_period" in modes and "dutch_roll" in modes
        for name, mode in modes.items():
            assert mode.eigenvalue == alone[name].eigenvalue
            assert mode.eigenvector.tobytes() == alone[name].eigenvector.tobytes()
    assert identify_rows(lin, []) == []
    assert len(identify_rows(lin)) == lin.A.shape[0]
