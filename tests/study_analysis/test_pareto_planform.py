"""Pareto fronts of known sets (closed-form fronts) and the tail planform geometry against direct integration."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from certkit.study.analysis.pareto import FrontAccumulator, nondominated
from certkit.study.analysis.planform import Planform, planform_from, polygon_area


def _zdt1_like(seed=0):
    """Points on the ZDT1 front f2 = 1 − √f1 (Zitzler, Deb & Thiele 2000), points each dominated by one of
    them (both objectives raised by non-negative amounts, one of them positive: it cannot dominate any front
    point, since the front's f2 falls as f1 grows), and duplicates of front points."""
    rng = np.random.default_rng(seed)
    f1 = np.unique(rng.random(300))
    front = np.column_stack([f1, 1 - np.sqrt(f1)])
    k = rng.integers(0, len(front), 5000)
    raise_ = rng.uniform(0, 0.3, (5000, 2)) * (rng.random((5000, 2)) < 0.7)
    raise_[raise_.sum(axis=1) == 0, 1] = 1e-9
    above = front[k] + raise_
    pts = np.concatenate([above, front, front[:40]])
    perm = rng.permutation(len(pts))
    return pts[perm], front


def test_front_of_a_known_bi_objective_set_exactly():
    pts, front = _zdt1_like()
    got = pts[nondominated(pts)]
    assert len(got) == len(front)
    np.testing.assert_array_equal(got[np.argsort(got[:, 0])], front)


def test_chunked_front_equals_the_one_shot_front():
    pts, front = _zdt1_like(1)
    acc = FrontAccumulator(2, (0, 1), (False, False))
    for chunk in np.array_split(np.arange(len(pts)), 7):
        acc.add(pts[chunk], pts[chunk])  # design points: the objective vectors themselves
    f, x = acc.front()
    np.testing.assert_array_equal(f, front)
    np.testing.assert_array_equal(x, front)
    # three objectives, one maximised: the accumulator agrees with the one-shot set
    rng = np.random.default_rng(2)
    cloud = rng.random((20_000, 3))
    acc = FrontAccumulator(3, (0, 1, 2), (False, True, False))
    for chunk in np.array_split(cloud, 5):
        acc.add(chunk, chunk)
    one = cloud[nondominated(cloud, (False, True, False))]
    assert sorted(map(tuple, acc.front()[0])) == sorted(map(tuple, one))


BASE = Planform(1119.2 * 0.09290304, 4.62, 0.33, math.radians(34.82), (0.07, 0.94, 0.29))


def test_planform_area_and_aerodynamic_centre_by_integration():
    p = BASE
    assert polygon_area(p.outline()) == pytest.approx(p.area, rel=1e-12)
    s = p.span / 2
    # MAC and its leading edge as chord-weighted integrals over the semispan (the definition of the MAC)
    half = quad(p.chord, 0, s)[0]
    mac = quad(lambda y: p.chord(y) ** 2, 0, s)[0] / half
    x_le_mac = quad(lambda y: p.chord(y) * p.leading_edge(y), 0, s)[0] / half
    assert p.mac == pytest.approx(mac, rel=1e-10)
    assert p.x_ac == pytest.approx(x_le_mac + mac / 4, rel=1e-10)
    # aligned at the a.c.: the outline's x is measured from it
    assert p.outline()[0, 0] == pytest.approx(-p.x_ac)


def test_elevator_area_by_integration():
    p = BASE
    s = p.span / 2
    right, left = p.elevator_outlines()
    expected = 0.29 * quad(p.chord, 0.07 * s, 0.94 * s)[0]
    assert polygon_area(right) == pytest.approx(expected, rel=1e-12)
    assert polygon_area(left) == pytest.approx(expected, rel=1e-12)
    # the elevator's trailing edge is the planform's: its aftmost point lies on the outline's trailing edge
    y = 0.94 * s
    assert right[:, 0].max() == pytest.approx(float(p.leading_edge(y) + p.chord(y)) - p.x_ac)


def test_planform_needs_its_variables():
    p, note = planform_from({"geometry.horizontal_tail.area": 100.0})
    assert p is None and "aspect_ratio" in note
