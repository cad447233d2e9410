"""Designs of experiments: points of the unit cube [0, 1]^k per design block, scaled to the variables' bounds.

The classical designs come from pydoe (the maintained pyDOE: ``fracfact_by_res``, ``ff2n``, ``star``,
``bbdesign``), the Latin hypercube from scipy.stats.qmc, uniform points from numpy's PCG64 generator. pydoe's
``ccdesign`` builds on the full 2^k factorial only (its notes: "fractional factorial designs are not (yet)
available here"), so the face-centred composite design is assembled here from its three parts: the
two-level (fractional) factorial, the 2k axial points at ±1 and the centre (Montgomery, Design and Analysis
of Experiments, §11.4.2; NIST/SEMATECH e-Handbook §5.3.3.6).
"""

from __future__ import annotations

import itertools

import numpy as np

from certkit.study.spec import BoxBehnkenBlock, CcdBlock, DesignBlock, LhsBlock, RandomBlock, Variable

MIN_RESOLUTION = 5


def defining_words(design: np.ndarray) -> list[tuple[int, ...]]:
    """Words of the defining relation of a regular two-level design in ±1 coding: every set of columns whose
    elementwise product is a constant column (I or −I). The resolution is the length of the shortest word
    (Box & Hunter 1961); a full factorial has none."""
    design = np.asarray(design)
    k = design.shape[1]
    words = []
    for size in range(1, k + 1):
        for cols in itertools.combinations(range(k), size):
            product = np.prod(design[:, cols], axis=1)
            if np.all(product == product[0]):
                words.append(cols)
    return words


def resolution(design: np.ndarray) -> float:
    """Length of the shortest word of the defining relation (inf for a full factorial)."""
    words = defining_words(design)
    return float(min(len(w) for w in words)) if words else float("inf")


def _unique_rows(coded: np.ndarray) -> np.ndarray:
    """Rows in first-seen order, repeats dropped (repeated centre points would be the same case)."""
    _, first = np.unique(coded, axis=0, return_index=True)
    return coded[np.sort(first)]


def ccd_face_centred(k: int, fraction: str = "resolution-v", center: int = 1) -> np.ndarray:
    """Coded face-centred central composite design, factorial rows first, then axial, then centre."""
    import pydoe  # deferred: pydoe loads scipy.stats (0.5 s): only for CCD blocks

    if fraction == "full":
        factorial = pydoe.ff2n(k)
    else:
        factorial = pydoe.fracfact_by_res(k, MIN_RESOLUTION)
        found = resolution(factorial)
        if found < MIN_RESOLUTION:  # pydoe promises "resolution res or better"; a broken release must not pass
            raise RuntimeError(f"pydoe.fracfact_by_res({k}, {MIN_RESOLUTION}) returned a resolution-{found:g} design")
    axial, _alpha = pydoe.star(k, alpha="faced", center=(0, 0))
    parts = [factorial, axial] + ([np.zeros((center, k))] if center else [])
    return _unique_rows(np.vstack(parts).astype(float))


def box_behnken(k: int, center: int = 0) -> np.ndarray:
    import pydoe  # deferred: pydoe loads scipy.stats (0.5 s): only for Box–Behnken blocks

    return _unique_rows(np.asarray(pydoe.bbdesign(k, center=center), dtype=float))


def latin_hypercube(k: int, n: int, seed: int, criterion: str = "random-cd") -> np.ndarray:
    from scipy.stats import qmc  # deferred: scipy.stats (0.45 s) only for Latin hypercube blocks

    optimization = None if criterion == "none" else criterion
    points: np.ndarray = qmc.LatinHypercube(d=k, optimization=optimization, rng=np.random.default_rng(seed)).random(n)
    return points


def uniform_random(k: int, n: int, seed: int) -> np.ndarray:
    """Row-major draws: the first rows of a larger ``n`` are the same points."""
    return np.random.default_rng(seed).random((n, k))


def unit_points(block: DesignBlock, k: int) -> np.ndarray:
    """Points of ``block`` in the unit cube [0, 1]^k (coded −1, 0, +1 → 0, ½, 1)."""
    if isinstance(block, CcdBlock):
        return (ccd_face_centred(k, block.fraction, block.center) + 1.0) / 2.0
    if isinstance(block, BoxBehnkenBlock):
        return (box_behnken(k, block.center) + 1.0) / 2.0
    if isinstance(block, LhsBlock):
        return latin_hypercube(k, block.n, block.seed, block.criterion)
    if isinstance(block, RandomBlock):
        return uniform_random(k, block.n, block.seed)
    raise TypeError(f"unknown design block {block!r}")


def scale(unit: np.ndarray, variables: list[Variable]) -> np.ndarray:
    """Unit-cube points → SI values; 0 and 1 map exactly onto the bounds (convex combination, no rounding past)."""
    lower = np.array([v.lower for v in variables])
    upper = np.array([v.upper for v in variables])
    values: np.ndarray = lower * (1.0 - unit) + upper * unit
    return values
