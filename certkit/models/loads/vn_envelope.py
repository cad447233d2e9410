"""The manoeuvring envelope (V–n diagram) of §25.333(b) at one weight and altitude: the stall lines
n = ±(V / V_S1)², V_S1 = √(2 W / (ρ₀ S C_N)) EAS from ±C_N,max (the 1-g stall speed at that normal-force
coefficient, :func:`certkit.models.performance.stall.stall_speed_eas`), bounded by the limit load factors n₊ (A to D)
and n₋ (F to H), VD (D to E) and the line E–F. Where the clean configuration declares C_Lmax against Mach
(``CLmax_by_mach``), the positive stall line is n = ½ ρ₀ V² S C_N,max(M) / W with the Mach number of each speed at
the altitude (§25.333(b)'s "maximum normal force coefficient" is the airplane's at that Mach number): V_S1 and point A
are where it reaches 1 and n₊.
Corners A (the +C_N,max line at n₊), D (VD, n₊), E (VD, 0), F (VC, n₋), H (the −C_N,max line at n₋); speeds in
m/s EAS, VC and VD Mach-limited at the altitude (:meth:`certkit.engine.context.Context.design_speed_eas`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from certkit.atmosphere import RHO0, convert_speed
from certkit.models.performance.stall import stall_speed_eas
from certkit.units import G0


@dataclass(frozen=True)
class VnEnvelope:
    """Corners of the manoeuvring envelope (speeds m/s EAS)."""

    vs1_pos: float
    vs1_neg: float
    n_pos: float
    n_neg: float
    v_a: float  # positive stall line meets n_pos (point A)
    v_c: float
    v_d: float
    v_h: float  # negative stall line meets n_neg (point H)
    #: n on the positive stall line at EAS speeds (m/s) when C_N,max varies with Mach; None: (V / V_S1,pos)²
    stall_pos: Callable[[np.ndarray], np.ndarray] | None = field(default=None, compare=False, repr=False)

    def n_stall_pos(self, v):
        """Load factor on the positive stall line at EAS ``v`` (m/s)."""
        v = np.asarray(v, dtype=float)
        return (v / self.vs1_pos) ** 2 if self.stall_pos is None else self.stall_pos(v)

    def corners(self) -> dict[str, tuple[float, float]]:
        a = (self.v_a, self.n_pos) if np.isfinite(self.v_a) else (self.v_d, float(self.n_stall_pos(self.v_d)))
        return {
            "A": a,
            "D": (self.v_d, self.n_pos),
            "E": (self.v_d, 0.0),
            "F": (self.v_c, self.n_neg),
            "H": (self.v_h, self.n_neg),
        }

    def outline(self, samples: int = 60) -> tuple[np.ndarray, np.ndarray]:
        """Closed outline: stall line to A, A–D, D–E, E–F, F–H, negative stall line back to 0."""
        vp = np.linspace(0.0, self.v_a, samples)
        vn = np.linspace(self.v_h, 0.0, samples)
        v = np.concatenate([vp, [self.v_d, self.v_d, self.v_c], vn])
        n = np.concatenate([self.n_stall_pos(vp), [self.n_pos, 0.0, self.n_neg], -((vn / self.vs1_neg) ** 2)])
        return v, n


def envelope(ctx, mass: float, altitude: float, cn_over_cl: float) -> VnEnvelope:
    """The envelope at ``mass`` (kg) and ``altitude`` (m), the stall lines from ``cn_over_cl`` × the declared clean
    C_Lmax and C_Lmin; memoised in the context (the loads rules ask for it at every condition of a weight and
    altitude, and with C_Lmax against Mach its corners are root searches)."""
    key = ("vn_envelope", float(mass), float(altitude), float(cn_over_cl))
    return ctx.memo(key, lambda: _envelope(ctx, mass, altitude, cn_over_cl))


def _envelope(ctx, mass: float, altitude: float, cn_over_cl: float) -> VnEnvelope:
    a = ctx.aircraft
    clean = a.configurations["clean"]
    lf = a.envelope.limit_load_factors
    vs_pos = float(stall_speed_eas(mass, a.reference.area, cn_over_cl * clean.CLmax))
    vs_neg = float(stall_speed_eas(mass, a.reference.area, cn_over_cl * clean.CLmin))
    vc, _ = ctx.design_speed_eas("VC", altitude)
    vd, _ = ctx.design_speed_eas("VD", altitude)
    stall_pos = None
    v_a = vs_pos * np.sqrt(lf.positive)
    if clean.CLmax_by_mach is not None:
        k = 0.5 * RHO0 * a.reference.area / (mass * G0)

        def stall_pos(v):
            mach = convert_speed(np.asarray(v, dtype=float), "EAS", "MACH", altitude)
            return k * np.asarray(v, dtype=float) ** 2 * cn_over_cl * clean.clmax_at(mach)

        vs_pos = stall_line_speed(stall_pos, 1.0, vs_pos)
        v_a = stall_line_speed(stall_pos, lf.positive, v_a)
    return VnEnvelope(
        vs_pos,
        vs_neg,
        lf.positive,
        lf.negative,
        v_a,
        float(vc),
        float(vd),
        vs_neg * np.sqrt(abs(lf.negative)),
        stall_pos,
    )


def stall_line_speed(stall_n: Callable[[np.ndarray], np.ndarray], n: float, start: float) -> float:
    """The lowest EAS (m/s) at which the stall line ``stall_n`` reaches ``n``, searched upward from ``start`` (the
    speed at the low-speed C_N,max, which a C_N,max falling with Mach can only raise) to four times it; inf when the
    line does not reach ``n`` there (the envelope has no such point)."""
    grid = start * np.linspace(1.0, 4.0, 301)
    values = stall_n(grid) - n
    above = np.flatnonzero(values >= 0.0)
    if above.size == 0:
        return float("inf")
    j = int(above[0])
    if j == 0:
        return float(start)
    return float(brentq(lambda v: float(stall_n(np.array([v]))[0]) - n, grid[j - 1], grid[j], xtol=1e-9))
