"""Section properties of an idealised two-spar box and laminate moduli.

* Airfoil depth: the NACA 4-digit thickness distribution (Abbott & von Doenhoff, *Theory of Wing
  Sections*, 1959, §6.4), full thickness y/c = 10 t (0.2969 √x − 0.1260 x − 0.3516 x² + 0.2843 x³ −
  0.1015 x⁴), gives the spar heights and the mean box depth between the spars as multiples of the
  local thickness t·c (the "airfoil depth factors" of the box; they do not depend on t).
* Laminates: classical lamination theory for a balanced symmetric laminate, in-plane moduli from the
  inverse of the smeared A-matrix (Jones, *Mechanics of Composite Materials*, 2nd ed., ch. 4; Kassapoglou,
  *Design and Analysis of Composite Structures*, 2013, ch. 3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def naca_thickness(x, thickness_ratio):
    """Full thickness / chord of a NACA 4-digit section of thickness ratio ``thickness_ratio`` at chord fraction x."""
    x = np.asarray(x, dtype=float)
    return 10.0 * thickness_ratio * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1015 * x**4)


@dataclass(frozen=True)
class DepthFactors:
    """Box depths as multiples of the local maximum thickness t·c: front and rear spar heights and the
    mean depth between the spars (NACA 4-digit distribution)."""

    front_spar: float
    rear_spar: float
    mean: float


def depth_factors(front_spar: float, rear_spar: float, n: int = 201) -> DepthFactors:
    """Depth factors of a box between the chord fractions ``front_spar`` < ``rear_spar``."""
    if not 0.0 < front_spar < rear_spar < 1.0:
        raise ValueError(f"spar positions must satisfy 0 < front ({front_spar}) < rear ({rear_spar}) < 1")
    xs = np.linspace(front_spar, rear_spar, n)
    mean = float(np.trapezoid(naca_thickness(xs, 1.0), xs) / (rear_spar - front_spar))
    return DepthFactors(float(naca_thickness(front_spar, 1.0)), float(naca_thickness(rear_spar, 1.0)), mean)


def laminate_moduli(ply: dict, layup: dict) -> tuple[float, float]:
    """In-plane E_x and G_xy of a balanced symmetric laminate (classical lamination theory), in the units of the
    ply data ``ply`` = {E1, E2, G12, nu12}; ``layup`` = {angle in degrees: fraction of the plies}."""
    e1, e2, g12, nu12 = ply["E1"], ply["E2"], ply["G12"], ply["nu12"]
    nu21 = nu12 * e2 / e1
    d = 1.0 - nu12 * nu21
    q11, q22, q12, q66 = e1 / d, e2 / d, nu12 * e2 / d, g12
    a = np.zeros((3, 3))
    for angle, frac in layup.items():
        m, n = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        qb11 = q11 * m**4 + 2 * (q12 + 2 * q66) * m**2 * n**2 + q22 * n**4
        qb22 = q11 * n**4 + 2 * (q12 + 2 * q66) * m**2 * n**2 + q22 * m**4
        qb12 = (q11 + q22 - 4 * q66) * m**2 * n**2 + q12 * (m**4 + n**4)
        qb66 = (q11 + q22 - 2 * q12 - 2 * q66) * m**2 * n**2 + q66 * (m**4 + n**4)
        qb16 = (q11 - q12 - 2 * q66) * m**3 * n + (q12 - q22 + 2 * q66) * m * n**3
        qb26 = (q11 - q12 - 2 * q66) * m * n**3 + (q12 - q22 + 2 * q66) * m**3 * n
        a += frac * np.array([[qb11, qb12, qb16], [qb12, qb22, qb26], [qb16, qb26, qb66]])
    s = np.linalg.inv(a)
    return 1.0 / s[0, 0], 1.0 / s[2, 2]
