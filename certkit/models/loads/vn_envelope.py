"""The manoeuvring envelope (V–n diagram) of §25.333(b) at one weight and altitude: the stall lines
n = ±(V / V_S1)², V_S1 = √(2 W / (ρ₀ S C_N)) EAS from ±C_N,max (the 1-g stall speed at that normal-force
coefficient, :func:`certkit.models.performance.stall.stall_speed_eas`), bounded by the limit load factors n₊ (A to D)
and n₋ (F to H), VD (D to E) and the line E–F.
Corners A (the +C_N,max line at n₊), D (VD, n₊), E (VD, 0), F (VC, n₋), H (the −C_N,max line at n₋); speeds in
m/s EAS, VC and VD Mach-limited at the altitude (:meth:`certkit.engine.context.Context.design_speed_eas`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.performance.stall import stall_speed_eas


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

    def corners(self) -> dict[str, tuple[float, float]]:
        return {
            "A": (self.v_a, self.n_pos),
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
        n = np.concatenate([(vp / self.vs1_pos) ** 2, [self.n_pos, 0.0, self.n_neg], -((vn / self.vs1_neg) ** 2)])
        return v, n


def envelope(ctx, mass: float, altitude: float, cn_over_cl: float) -> VnEnvelope:
    """The envelope at ``mass`` (kg) and ``altitude`` (m), the stall lines from ``cn_over_cl`` × the declared clean
    C_Lmax and C_Lmin."""
    a = ctx.aircraft
    clean = a.configurations["clean"]
    lf = a.envelope.limit_load_factors
    vs_pos = float(stall_speed_eas(mass, a.reference.area, cn_over_cl * clean.CLmax))
    vs_neg = float(stall_speed_eas(mass, a.reference.area, cn_over_cl * clean.CLmin))
    vc, _ = ctx.design_speed_eas("VC", altitude)
    vd, _ = ctx.design_speed_eas("VD", altitude)
    return VnEnvelope(
        vs_pos,
        vs_neg,
        lf.positive,
        lf.negative,
        vs_pos * np.sqrt(lf.positive),
        float(vc),
        float(vd),
        vs_neg * np.sqrt(abs(lf.negative)),
    )
