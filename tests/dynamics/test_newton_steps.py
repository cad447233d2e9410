"""A condition's trim does not depend on the other conditions of its batch: a singular Newton step of one condition
leaves the others' steps as they are alone."""

import numpy as np

from certkit.models.dynamics.trim import newton_steps


def test_a_singular_newton_step_leaves_the_other_conditions_steps_as_alone():
    rng = np.random.default_rng(5)
    J, r = rng.normal(size=(12, 5, 5)), rng.normal(size=(12, 5))
    alone = np.concatenate([newton_steps(J[i : i + 1], r[i : i + 1]) for i in range(12)])
    assert newton_steps(J, r).tobytes() == alone.tobytes()
    J[4] = 0.0  # a condition with no Jacobian at all: its step from the pseudo-inverse (nothing)
    steps = newton_steps(J, r)
    assert np.delete(steps, 4, axis=0).tobytes() == np.delete(alone, 4, axis=0).tobytes()
    assert np.all(steps[4] == 0.0)
