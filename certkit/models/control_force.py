"""Cockpit control forces: reversible (hinge-moment) controls and artificial-feel units, vectorised.

Signs (:mod:`certkit.conventions`): a surface deflection δ is positive trailing edge down (elevator, each
aileron in the right-aileron sense) or trailing edge left (rudder). The cockpit displacement x is measured
in the sense that gives positive δ, through the gearing G = dδ/dx (rad per metre at the grip; a wheel's
gearing dδ/dθ over its radius D/2, so that the force is the one at the rim). A force F here is the force
the pilot applies *in the sense of positive δ*: a pull on the column (trailing edge up) is −F, a push on
the left pedal (rudder trailing edge left, nose left) is +F. Rules convert to pull/push or left/right.

Reversible control (Nelson, *Flight Stability and Automatic Control*, 2nd ed., ch. 2: hinge moments,
stick forces, stick-force gradient, stick-free neutral point; Etkin & Reid, *Dynamics of Flight*, 3rd ed.,
ch. 2: control hinge moments, stick force, stick-free static stability; Perkins & Hage, *Airplane
Performance, Stability and Control*, 1949, ch. 6). The hinge moment of the surface is

    H = C_h q_s S c,   C_h = Ch_0 + Ch_α α_s + Ch_δ δ,   q_s = η q̄,

with S, c the area and mean chord aft of the hinge line and α_s the local angle of attack of the surface
ahead of the hinge. Virtual work on a massless, frictionless linkage, F dx + H dδ = 0, gives the stick force

    F = −G f H = −G f η q̄ S c C_h                                   (Nelson's F = G q S_e c_e C_he)

with f the share of the hinge moment the pilot carries (1 unboosted; 1/(1 + B) with a boost ratio B).
The tailplane's local angle of attack is α_t = α (1 − dε/dα) + i_t − ε₀ (downwash ε = ε₀ + dε/dα α;
default dε/dα = 2 a_w / (π A) from the wing's lift slope, the elliptic-wing estimate of both books);
the fin's is α_f = −β (1 − dσ/dβ) (positive in the sense in which positive rudder lifts the fin).
An aileron pair (right δ, left −δ) sees the same α on both sides, so Ch_0 and Ch_α cancel and the wheel
holds −G f η q̄ S c · 2 Ch_δ δ (S, c of one aileron).

Trim. A trimmed control holds zero force at its trim state (δ₀, α₀). For a reversible control the trim
device (tab or trim bias) adds a hinge-moment coefficient ΔC_h = −C_h(δ₀, α₀) that stays fixed when the
speed changes (it acts through the same dynamic pressure), so

    F = −G f η q̄ S c [C_h(δ, α) − C_h(δ₀, α₀)].

In 1-g flight, C_h is linear in C_L = W/(q̄ S_w), so F = A (1 − q̄/q̄₀) with A ∝ (x_np′ − x_cg): the stick
force is zero at the trim speed, a pull below it (stable), and the gradient dF/dV = −2A/V₀ vanishes at the
stick-free neutral point x_np′ (:func:`stick_free_neutral_point`).

Artificial feel (fully powered controls): the feel unit returns F = F_b sign(x) + K s x with x = (δ − δ₀)/G
the cockpit displacement from the feel neutral (moved by trim to the trim deflection δ₀, or 0 untrimmed),
F_b the breakout (preload), K the spring gradient and s = q̄ / q_ref for a q-feel unit (else 1).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.atmosphere import density, speed_of_sound
from certkit.models.aero.planform import lift_curve_slope, sweep_at


@dataclass(frozen=True)
class ControlForceModel:
    """Force model of one cockpit control (built from the aircraft file by :func:`control_force_model`)."""

    name: str
    kind: str  # "reversible" | "artificial_feel"
    gearing: float  # rad of surface per metre at the grip (or rim)
    friction: float | None = None  # N
    # reversible
    Ch_0: float = 0.0
    Ch_alpha: float = 0.0
    Ch_delta: float = -1.0
    area: float = 0.0
    chord: float = 0.0
    fraction: float = 1.0
    eta: float = 1.0
    pair: bool = False  # an aileron pair: only Ch_delta acts, twice
    # artificial feel
    preload: float = 0.0
    gradient: float = 0.0  # N/m
    q_reference: float | None = None

    @property
    def reversible(self) -> bool:
        return self.kind == "reversible"

    def hinge_coefficient(self, alpha_local, delta):
        """C_h of the surface (of the aileron pair: C_h,right − C_h,left = 2 Ch_δ δ)."""
        alpha, delta = np.asarray(alpha_local, dtype=float), np.asarray(delta, dtype=float)
        if self.pair:  # the same α on both sides: it cancels (kept in the shape of the result)
            return 2.0 * self.Ch_delta * delta + 0.0 * alpha
        return self.Ch_0 + self.Ch_alpha * alpha + self.Ch_delta * delta

    def _scale(self, qbar):
        """N per unit C_h (reversible) or per unit of K·x (feel)."""
        q = np.asarray(qbar, dtype=float)
        if self.reversible:
            return self.gearing * self.fraction * self.eta * q * self.area * self.chord
        return q / self.q_reference if self.q_reference else np.ones_like(q)

    def force(self, qbar, alpha_local, delta, *, trim=None):
        """Pilot force (N, in the sense of positive δ) holding deflection δ at dynamic pressure q̄ and local
        angle of attack α_s. ``trim`` = (δ₀, α₀): the control trimmed to zero force there; None: untrimmed
        (reversible: the whole hinge moment; feel: neutral at δ = 0)."""
        delta = np.asarray(delta, dtype=float)
        if self.reversible:
            ch = self.hinge_coefficient(alpha_local, delta)
            if trim is not None:
                ch = ch - self.hinge_coefficient(trim[1], trim[0])
            return -self._scale(qbar) * ch
        x = (delta - (0.0 if trim is None else np.asarray(trim[0], dtype=float))) / self.gearing
        return self.preload * np.sign(x) + self.gradient * self._scale(qbar) * x

    def deflection_at_force(self, force, qbar, alpha_local, *, trim=None):
        """The deflection δ that force F (N, in the sense of positive δ) holds — the inverse of :meth:`force`
        (both models are monotonic in δ). A force inside the breakout band holds the feel neutral."""
        f = np.asarray(force, dtype=float)
        if self.reversible:
            ch = -f / self._scale(qbar)
            if trim is not None:
                ch = ch + self.hinge_coefficient(trim[1], trim[0])
            if self.pair:
                return ch / (2.0 * self.Ch_delta)
            return (ch - self.Ch_0 - self.Ch_alpha * np.asarray(alpha_local, dtype=float)) / self.Ch_delta
        x = np.sign(f) * np.maximum(np.abs(f) - self.preload, 0.0) / (self.gradient * self._scale(qbar))
        return (0.0 if trim is None else np.asarray(trim[0], dtype=float)) + x * self.gearing


def control_force_model(aircraft, name: str) -> ControlForceModel | None:
    """The force model of control ``name`` (elevator, aileron, rudder) declared in ``control_forces``, or None."""
    section = getattr(aircraft, "control_forces", None)
    decl = None if section is None else getattr(section, name, None)
    if decl is None:
        return None
    gearing = decl.gearing if decl.gearing is not None else decl.wheel_gearing / (0.5 * decl.wheel_diameter)
    common = dict(name=name, kind=decl.type, gearing=float(gearing), friction=decl.friction)
    if decl.type == "reversible":
        h = decl.hinge_moment
        return ControlForceModel(
            **common,
            Ch_0=h.Ch_0,
            Ch_alpha=h.Ch_alpha,
            Ch_delta=h.Ch_delta,
            area=decl.surface_area,
            chord=decl.chord,
            fraction=decl.hinge_moment_fraction,
            eta=decl.dynamic_pressure_ratio,
            pair=(name == "aileron"),
        )
    return ControlForceModel(**common, preload=decl.preload, gradient=decl.gradient, q_reference=decl.q_feel_reference)


def dynamic_pressure(tas, h):
    """q̄ = ½ ρ(h) V² (Pa) from true airspeed and geometric altitude."""
    return 0.5 * density(np.asarray(h, dtype=float)) * np.asarray(tas, dtype=float) ** 2


def downwash_gradient(aircraft, mach) -> np.ndarray:
    """dε/dα at the tailplane: the declared value, else 2 a_w/(π A) with the wing's DATCOM lift slope a_w
    (the elliptic-wing estimate ε = 2 C_Lw/(π A) of Nelson and Etkin & Reid, ch. 2)."""
    decl = getattr(getattr(aircraft, "control_forces", None), "elevator", None)
    mach = np.asarray(mach, dtype=float)
    if decl is not None and decl.type == "reversible" and decl.downwash_gradient is not None:
        return np.full(mach.shape, decl.downwash_gradient)
    w = aircraft.geometry.wing
    a_w = lift_curve_slope(w.aspect_ratio, sweep_at(0.5, w.sweep_quarter_chord, w.aspect_ratio, w.taper), mach)
    return 2.0 * a_w / (np.pi * w.aspect_ratio)


def local_angle(aircraft, name: str, alpha, beta, mach) -> np.ndarray:
    """Local angle of attack (rad) of the surface carrying control ``name``: the tailplane's
    α (1 − dε/dα) + i_t − ε₀ for the elevator, the fin's −β (1 − dσ/dβ) for the rudder, the wing's
    α + i_w for an aileron (which cancels in the pair)."""
    alpha, beta = np.asarray(alpha, dtype=float), np.asarray(beta, dtype=float)
    decl = getattr(getattr(aircraft, "control_forces", None), name, None)
    declared = decl is not None and decl.type == "reversible"
    g = aircraft.geometry
    if name == "elevator":
        eps0 = decl.downwash_at_zero_alpha if declared else 0.0
        return alpha * (1.0 - downwash_gradient(aircraft, mach)) + (g.horizontal_tail.incidence if g else 0.0) - eps0
    if name == "rudder":
        sigma = decl.downwash_gradient if declared and decl.downwash_gradient is not None else 0.0
        return -beta * (1.0 - sigma)
    return alpha + (g.wing.incidence if g else 0.0)


def trim_state(aircraft, name: str, results):
    """(q̄, α_s, δ) arrays of control ``name`` at each :class:`TrimResult` (NaN where not converged)."""
    V = np.array([r.V for r in results], dtype=float)
    h = np.array([r.h for r in results], dtype=float)
    ok = np.array([r.converged for r in results])
    alpha = np.array([r.alpha for r in results], dtype=float)
    beta = np.array([r.beta for r in results], dtype=float)
    delta = np.array([r.controls.get(name, np.nan) for r in results], dtype=float)
    mach = V / speed_of_sound(h)
    q = np.where(ok, dynamic_pressure(V, h), np.nan)
    return q, local_angle(aircraft, name, alpha, beta, mach), np.where(ok, delta, np.nan)


def stick_free_neutral_point(aero_model, elevator: ControlForceModel, mach, downwash) -> np.ndarray:
    """Stick-free neutral point x_np′ (airplane frame, m aft of the nose) of a reversible elevator: the
    elevator floats at C_h = 0, dδ/dα = −Ch_α (1 − dε/dα)/Ch_δ, so with the model's derivatives
    Cm_α′ = Cm_α + Cm_δ dδ/dα, CL_α′ = CL_α + CL_δ dδ/dα and x_np′ = x_ref − c̄ Cm_α′/CL_α′
    (the free-elevator factor 1 − τ Ch_α/Ch_δ of Nelson and Etkin & Reid, ch. 2)."""
    d = lambda n: np.asarray(aero_model.derivative(n, mach), dtype=float)  # noqa: E731
    float_rate = -elevator.Ch_alpha * (1.0 - np.asarray(downwash, dtype=float)) / elevator.Ch_delta
    cm = d("Cm_alpha") + d("Cm_elevator") * float_rate
    cl = d("CL_alpha") + d("CL_elevator") * float_rate
    ref = aero_model.reference
    return ref.x_ref - ref.chord * cm / cl
