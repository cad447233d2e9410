"""Confidence intervals of a probability estimated by k successes in n independent trials.

The Wilson score interval (Wilson 1927, *JASA* 22: 209–212; recommended over the Wald interval
p ± z√(p(1−p)/n) by Brown, Cai & DasGupta 2001, *Statistical Science* 16: 101–133): the set of p whose
score test does not reject k/n,

    centre = (k + z²/2) / (n + z²),   half-width = z √(k(n−k)/n + z²/4) / (n + z²).

Unlike the Wald interval it never collapses to a point at k = 0 or k = n (there its upper or lower end is
z²/(n + z²) away), and its coverage stays near the nominal level for small p·n.
"""

from __future__ import annotations

import math

#: two-sided 95 % normal quantile
Z95 = 1.959963984540054


def wilson(k: int, n: int, z: float = Z95) -> tuple[float, float]:
    """(lower, upper) Wilson score interval of k successes in n trials; (0, 1) without trials."""
    if n <= 0:
        return 0.0, 1.0
    z2 = z * z
    centre = (k + 0.5 * z2) / (n + z2)
    half = z * math.sqrt(k * (n - k) / n + 0.25 * z2) / (n + z2)
    return max(0.0, centre - half), min(1.0, centre + half)


def interval_se(k: int, n: int, z: float = Z95) -> float:
    """A standard error read from the Wilson interval (its half-width / z): positive even at k = 0 or n."""
    lo, hi = wilson(k, n, z)
    return 0.5 * (hi - lo) / z
