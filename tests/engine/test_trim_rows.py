"""Trims a Context takes from the rows it trimmed before (certkit.engine.context.Context.trim): a condition's trim does
not depend on the batch it is solved in, so a batch whose rows were trimmed in other batches — other orders, other
neighbours — is, bit for bit, the batch trimmed by itself; a row with any other option is solved afresh."""

import dataclasses

import numpy as np
import pytest

import certkit.models.dynamics.trim as trim_module
from certkit.engine.conditions import CgCorners, ConditionSpace
from certkit.engine.context import Context
from certkit.units import FT, KN

from ..conftest import count_conditions


@pytest.fixture(scope="module")
def points(baseline):
    """Six clean flight points: three loading corners at two altitudes and speeds."""
    corners = ConditionSpace(loading=CgCorners(), configurations=("clean",), altitudes=None).expand(baseline.model)
    chosen = sorted(corners, key=lambda c: (c.mass, c.x_cg))[::2][:3]
    return [
        c.with_(altitude=alt * FT, speed=v * KN, speed_kind="EAS")
        for c in chosen
        for alt, v in ((10_000, 250), (30_000, 280))
    ]


def same_batch(a, b):
    """Every state, control and result field identical (NaN equal to NaN)."""
    np.testing.assert_array_equal(a.x, b.x, strict=True)
    np.testing.assert_array_equal(a.u, b.u, strict=True)
    assert [dataclasses.asdict(r) for r in a.results] == [dataclasses.asdict(r) for r in b.results]


@pytest.fixture
def solved_rows(monkeypatch):
    """The number of rows each call of the trim solver was given."""
    return count_conditions(monkeypatch, trim_module, "trim")


@pytest.mark.parametrize("options", [{}, {"gamma": 0.02, "bank": 0.3, "kind": "turn"}, {"inoperative": "left"}])
def test_a_batch_of_rows_trimmed_elsewhere_is_its_own_trim(baseline, points, options, solved_rows):
    """The batch of all six points after two batches that trimmed them in another order and company (one point twice,
    one alone) equals the six trimmed by a fresh Context; only the one point no earlier batch held is solved."""
    engines = [e.name for e in baseline.model.propulsion.engines]
    opts = {**options, "inoperative": engines[0]} if "inoperative" in options else options
    ctx = Context(baseline)
    ctx.trim([points[4], points[0], points[2]], **opts)
    ctx.trim([points[3], points[1], points[0]], **opts)
    solved_rows.clear()
    again = ctx.trim(points, **opts)
    assert solved_rows == [1]  # points[5], the only one not trimmed before
    same_batch(again, Context(baseline).trim(points, **opts))
    assert [r.index for r in again.results] == list(range(6))


def test_per_condition_options_and_warm_starts(baseline, points, solved_rows):
    """Options given per condition: a row is taken only where its own flight-path angle and warm start match (a NaN
    start is the default start, as no start is); the batch still equals the fresh one."""
    gamma = np.array([0.0, 0.01, 0.0, 0.02, 0.0, 0.01])
    start = {"alpha": np.array([0.04, np.nan, 0.05, 0.06, np.nan, 0.05])}
    ctx = Context(baseline)
    ctx.trim(points[:3], gamma=gamma[:3], initial={"alpha": start["alpha"][:3]})
    ctx.trim(points[3:], gamma=0.0)  # point 4 as below (its NaN start the default); 3 and 5 at another angle
    solved_rows.clear()
    batch = ctx.trim(points, gamma=gamma, initial=start)
    assert solved_rows == [2]
    same_batch(batch, Context(baseline).trim(points, gamma=gamma, initial=start))


def test_another_option_is_trimmed_afresh(baseline, points, solved_rows):
    """The same points with the throttle held, another flight-path angle or the design limits off are new rows."""
    ctx = Context(baseline)
    ctx.trim(points[:2])
    solved_rows.clear()
    ctx.trim(points[:2], throttle=0.8)
    ctx.trim(points[:2], gamma=0.01)
    ctx.trim(points[:2], design_limits=False)
    assert solved_rows == [2, 2, 2]
