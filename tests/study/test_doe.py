"""Designs of experiments: counts, resolution, bounds, reproducibility.

References: Montgomery, Design and Analysis of Experiments (8th ed.), §8.2 (resolution = length of the shortest
word of the defining relation; in a resolution-V design main effects and two-factor interactions are aliased
only with interactions of three or more factors), §11.4.2 (face-centred CCD: 2^(k-p) + 2k + centre points);
Box & Behnken, Technometrics 2 (1960) 455 (8 factors: 28 pairs × 4 = 112 runs without centre points);
McKay, Beckman & Conover, Technometrics 21 (1979) 239 (Latin hypercube: one point in each of n equal
intervals of every variable). The seed study's plan: 81 + 112 = 193 CCD + Box–Behnken points.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest

from certkit.study import doe
from certkit.study.plan import CaseContext, block_points, plan_study
from certkit.study.spec import load_study

ROOT = Path(__file__).resolve().parents[2]
HT = ROOT / "studies" / "ht-redesign.yaml"


@pytest.fixture(scope="module")
def ht():
    return load_study(HT)


@pytest.fixture(scope="module")
def ht_plan(ht):
    return plan_study(ht, CaseContext.of(ht, "tests.study.evaluators:analytic"))


def _interaction_matrix(design: np.ndarray) -> np.ndarray:
    """Columns of the model with intercept, main effects and all two-factor interactions."""
    k = design.shape[1]
    cols = [np.ones(len(design))] + [design[:, i] for i in range(k)]
    cols += [design[:, i] * design[:, j] for i, j in itertools.combinations(range(k), 2)]
    return np.column_stack(cols)


def test_fraction_is_resolution_v_with_unaliased_main_effects_and_two_factor_interactions():
    import pydoe

    fraction = pydoe.fracfact_by_res(8, 5)
    assert fraction.shape == (64, 8)  # 2^(8-2)
    words = doe.defining_words(fraction)
    assert len(words) == 3  # 2^p - 1 words for a 2^(k-p) fraction
    assert min(len(w) for w in words) >= 5
    # independent of the word search: intercept, 8 main effects and 28 two-factor interactions are mutually
    # orthogonal (X'X = N·I), which is what resolution V means for estimating them
    x = _interaction_matrix(fraction)
    assert np.array_equal(x.T @ x, 64 * np.eye(37))


def test_resolution_check_can_fail_on_a_resolution_iv_fraction():
    import pydoe

    fraction = pydoe.fracfact_by_res(8, 4)  # 16 runs: two-factor interactions aliased with each other
    assert doe.resolution(fraction) == 4
    x = _interaction_matrix(fraction)
    assert not np.array_equal(x.T @ x, 16 * np.eye(37))


def test_full_factorial_has_no_defining_relation():
    import pydoe

    assert doe.resolution(pydoe.ff2n(4)) == float("inf")


def test_ccd_and_box_behnken_counts():
    ccd = doe.ccd_face_centred(8)
    bb = doe.box_behnken(8)
    assert len(ccd) == 64 + 16 + 1 == 81
    assert len(bb) == 112
    assert len(np.unique(np.vstack([ccd, bb]), axis=0)) == 193
    # face-centred: three levels only, axial points on the faces
    assert set(np.unique(ccd)) == {-1.0, 0.0, 1.0}
    assert sum(np.count_nonzero(row) == 1 for row in ccd) == 16
    # Box–Behnken: exactly two factors off centre in every run, each pair 4 times
    assert all(np.count_nonzero(row) == 2 for row in bb)
    pairs = {tuple(np.flatnonzero(row)) for row in bb}
    assert len(pairs) == 28


def test_seed_plan_counts_and_roles(ht_plan):
    by_block = {}
    for case in ht_plan.cases:
        by_block.setdefault((case.block, case.role), 0)
        by_block[case.block, case.role] += 1
    assert by_block == {
        ("ccd", "training"): 81,
        ("box-behnken", "training"): 112,
        ("lhs", "training"): 600,
        ("validation", "validation"): 200,
    }
    assert len(ht_plan.cases) == 993
    assert len({c.key for c in ht_plan.cases}) == 993
    assert ht_plan.duplicates == {}


def test_points_within_bounds_and_on_them_where_coded_so(ht, ht_plan):
    lower = {v.path: v.lower for v in ht.variables}
    upper = {v.path: v.upper for v in ht.variables}
    for case in ht_plan.cases:
        for path, value in case.values.items():
            assert lower[path] <= value <= upper[path], (case.block, path, value)
    ccd = [c for c in ht_plan.cases if c.block == "ccd"]
    area = "geometry.horizontal_tail.area"
    assert {c.values[area] for c in ccd} == {lower[area], upper[area], 0.5 * (lower[area] + upper[area])}
    # 895.4 ft^2 and 1343 ft^2 in m^2 (1 ft = 0.3048 m exactly)
    assert lower[area] == pytest.approx(895.4 * 0.3048**2, rel=1e-12)
    assert upper[area] == pytest.approx(1343 * 0.3048**2, rel=1e-12)


def test_lhs_is_a_latin_hypercube_and_space_filling():
    from scipy.stats import qmc

    n, k = 50, 8
    points = doe.latin_hypercube(k, n, seed=7)
    for j in range(k):  # one point in each of the n equal intervals of every variable
        assert sorted(np.floor(points[:, j] * n).astype(int)) == list(range(n))
    plain = doe.latin_hypercube(k, n, seed=7, criterion="none")
    assert qmc.discrepancy(points) < qmc.discrepancy(plain)  # random-cd lowers the centred L2-discrepancy


def test_seeds_reproducible(ht):
    lhs = next(b for b in ht.designs if b.name == "lhs")
    small = lhs.model_copy(update={"n": 20})
    assert block_points(ht, small) == block_points(ht, small)
    assert block_points(ht, small) != block_points(ht, small.model_copy(update={"seed": small.seed + 1}))
    validation = next(b for b in ht.designs if b.name == "validation")
    more = block_points(ht, validation.model_copy(update={"n": 250}))
    assert more[:200] == block_points(ht, validation)  # a larger random block keeps its first points
