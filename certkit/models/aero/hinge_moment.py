"""Control-surface hinge moments from the vortex lattice.

Method (the hinge moment AVL 3.x computes, Drela & Youngren, routine SFFORC): every bound-leg force F_i of the
lattice (per unit q∞) acts at its bound-leg midpoint r_i; the part of element i that lies on the control (its
chordwise fraction aft of the hinge line times the control gain, d_i) contributes the moment of F_i about the
hinge line of its strip, through the point p_j where the hinge line crosses the strip's centre and along the
unit hinge vector h_j:

    H / q∞ = Σ_i d_i [(r_i − p_j) × F_i] · h_j

(both halves of a mirrored surface: for the elevator, the whole elevator). H is positive in the sense of a
positive deflection (a right-handed rotation about the hinge vector; trailing edge down for an elevator, see
:mod:`certkit.conventions`): a restoring surface has Ch_δ < 0. The coefficient is referred to the control's own
area S_c (aft of the hinge line, all its strips) and mean chord c_c = S_c / (its span), the reference of
:mod:`certkit.models.control_force`:  C_h = H / (q∞ S_c c_c),  C_h = Ch_0 + Ch_α α + Ch_δ δ, per radian, with α
the lattice's angle of attack (in a whole-airplane lattice the tailplane's local angle is α (1 − dε/dα): the
derivative includes the downwash the lattice computes) and δ the control variable.

Limits: thin-airfoil, inviscid, attached flow. A thin-airfoil lattice puts the control's load near its hinge
line's leading edge as potential flow does, and overestimates the magnitude of hinge moments of real (thick,
viscous, gapped) sections — thickness and the boundary layer at the trailing edge reduce Ch_α and Ch_δ, often by
a factor of 1.5–3 (Abbott & von Doenhoff, *Theory of Wing Sections*, §8.7; USAF DATCOM §6.1.3 corrects the
thin-airfoil values for trailing-edge angle and thickness). No such correction is applied here: the values are
the lattice's, and a design hinge moment from them is conservative for the actuators.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

EPS = 1e-3


@dataclass(frozen=True)
class HingeMomentDerivatives:
    """Hinge-moment coefficients of one control, per radian, at one Mach number and state; ``area`` and ``chord``
    the reference S_c (m²) and c_c (m). ``moment`` gives H (N·m) at a dynamic pressure, α and δ."""

    control: str
    mach: float
    area: float
    chord: float
    Ch_0: float
    Ch_alpha: float
    Ch_delta: float

    def moment(self, qbar, alpha, delta):
        """Hinge moment (N·m) at dynamic pressure ``qbar`` (Pa), angle of attack and deflection (rad)."""
        return (
            qbar
            * self.area
            * self.chord
            * (self.Ch_0 + self.Ch_alpha * np.asarray(alpha) + self.Ch_delta * np.asarray(delta))
        )


def control_reference(lattice, control: str) -> tuple[float, float]:
    """Area aft of the hinge line (m², every strip carrying ``control``) and mean chord (area / span) of a
    trailing-edge control."""
    k = list(lattice.control_names).index(control)
    strips = np.flatnonzero(np.linalg.norm(lattice.hinge_axis[k], axis=-1) > 0)
    if strips.size == 0:
        raise ValueError(f"no strip of the lattice carries the control {control!r}")
    aft = lattice.rle[strips, 0] + lattice.chord[strips] - lattice.hinge_point[k, strips, 0]
    area = float(np.sum(aft * lattice.width[strips]))
    return area, area / float(np.sum(lattice.width[strips]))


def hinge_moment_over_q(vl, control: str, alpha: float = 0.0, controls=None) -> float:
    """H / q∞ (m³) of ``control`` at the state (α, control deflections ``controls``) of the lattice ``vl``."""
    lat = vl.lattice
    if control not in lat.control_names:
        raise KeyError(f"unknown control {control!r}; the lattice has {list(lat.control_names)}")
    k = list(lat.control_names).index(control)
    force = vl.vortex_forces(alpha=alpha, controls=controls)
    strip = lat.vortex_strip
    arm = lat.rv - lat.hinge_point[k, strip]
    moment = np.cross(arm, force)
    return float(np.sum(lat.control_fraction[k] * np.einsum("ij,ij->i", moment, lat.hinge_axis[k, strip])))


def hinge_moment_derivatives(vl, control: str, alpha: float = 0.0, controls=None) -> HingeMomentDerivatives:
    """Ch_0, Ch_α, Ch_δ of ``control`` at the lattice's Mach number about the state (α, ``controls``); the
    derivatives by central differences of ±1e-3 rad (exact for the lattice's quadratic forces)."""
    base = dict(controls or {})
    delta0 = base.get(control, 0.0)
    area, chord = control_reference(vl.lattice, control)
    ref = area * chord

    def h(a=alpha, d=delta0):
        return hinge_moment_over_q(vl, control, a, {**base, control: d}) / ref

    ch_alpha = (h(a=alpha + EPS) - h(a=alpha - EPS)) / (2 * EPS)
    ch_delta = (h(d=delta0 + EPS) - h(d=delta0 - EPS)) / (2 * EPS)
    ch_0 = h() - ch_alpha * alpha - ch_delta * delta0
    return HingeMomentDerivatives(control, vl.mach, area, chord, ch_0, ch_alpha, ch_delta)
