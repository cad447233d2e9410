"""A run's recorded histories (:class:`certkit.models.dynamics.simulate.Histories`): the Euler angles are converted
from the recorded attitude quaternions when first read. They must be the angles of the state at every record (checked
at the run's end against the final state, and at its start against the trim's attitude), every recorded name must be
there in :data:`RECORDED` order, and runs joined end to end must give the angles each run gives on its own, bit for
bit (:meth:`Histories.joined`, as a gust's two phases are joined)."""

import numpy as np
import pytest

from certkit.models.dynamics.eom import quat_to_euler
from certkit.models.dynamics.simulate import EULER, RECORDED, Function, Histories, simulate

from .conftest import trimmed_baseline


@pytest.fixture(scope="module")
def rolled(baseline):
    """Four trimmed conditions given aileron and rudder steps: bank and heading move."""
    model, trims = trimmed_baseline(baseline, 4, (150, 220), (0, 8000), 0.7)
    inputs = {
        "aileron": Function(lambda t: 0.05 * np.minimum(t, 1.0) * np.ones(4)),
        "rudder": Function(lambda t: 0.03 * np.minimum(t, 1.0) * np.ones(4)),
    }
    return model, trims, inputs


def test_euler_angles_are_the_attitude_at_each_record(rolled):
    model, trims, inputs = rolled
    sim = simulate(model, trims.x, trims.u, 3.0, 0.02, inputs=inputs)
    assert list(sim.history) == list(RECORDED) and len(sim.history) == len(RECORDED)
    end = quat_to_euler(sim.final_state[:, 9:13])  # no stop criterion: the last record is the final state
    for j, name in enumerate(EULER):
        np.testing.assert_array_equal(sim[name][-1], end[:, j], err_msg=name)
        # the trim's attitude through the quaternion and back: round-off only
        np.testing.assert_allclose(sim[name][0], trims.x[:, 9 + j], rtol=0, atol=1e-12, err_msg=name)
    assert np.degrees(np.abs(sim["phi"][-1])).min() > 1.0  # the steps do roll the airplane
    assert {k: v.shape for k, v in dict(sim.history).items()} == {k: sim["V"].shape for k in RECORDED}


def test_joined_runs_give_each_run_s_angles(rolled):
    model, trims, inputs = rolled
    first = simulate(model, trims.x, trims.u, 1.0, 0.02, inputs=inputs)
    second = simulate(model, first.final_state, trims.u, 1.5, 0.05)
    joined = Histories.joined([first.history, second.history])
    for name in RECORDED:
        np.testing.assert_array_equal(joined[name], np.concatenate([first[name], second[name][1:]]), err_msg=name)
