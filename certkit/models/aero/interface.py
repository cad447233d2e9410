"""What every aerodynamic model gives the flight dynamics and the rules.

An aerodynamic model is built once per aircraft and configuration and evaluated on arrays of
states in one call (a batch of 500 conditions is one numpy evaluation). Conventions are those of
:mod:`certkit.conventions`: forces CL, CD in stability axes, CY along +y, moments Cl, Cm, Cn in
**body axes** about the model's moment reference point, Etkin control-sign convention, angles in
radians, rates non-dimensional (p b/2V, q c/2V, r b/2V).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Protocol

import numpy as np


@dataclass(frozen=True)
class AeroReference:
    """Reference area S (m²), span b (m), mean aerodynamic chord c (m) and moment reference point
    (airplane frame: X aft of the nose, Z up, metres)."""

    area: float
    span: float
    chord: float
    x_ref: float
    z_ref: float = 0.0


@dataclass
class AeroState:
    """A batch of aerodynamic states; every array broadcasts to a common shape.

    ``controls`` maps a control-surface name (``elevator``, ``aileron``, ``rudder``, ``flap``, …)
    to its deflection in radians; an absent control is undeflected.
    """

    alpha: np.ndarray
    beta: np.ndarray | float = 0.0
    p_hat: np.ndarray | float = 0.0
    q_hat: np.ndarray | float = 0.0
    r_hat: np.ndarray | float = 0.0
    mach: np.ndarray | float = 0.0
    controls: Mapping[str, np.ndarray | float] = field(default_factory=dict)
    reynolds_per_metre: np.ndarray | float | None = None


@dataclass
class Coefficients:
    """Force and moment coefficients for a batch of states (arrays of the batch's shape)."""

    CL: np.ndarray
    CD: np.ndarray
    CY: np.ndarray
    Cl: np.ndarray
    Cm: np.ndarray
    Cn: np.ndarray

    def body_forces(
        self, alpha: np.ndarray, beta: np.ndarray | float = 0.0
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Body-axis force coefficients (CX forward, CY right, CZ down) from lift, drag and side
        force, rotating stability axes by alpha (beta enters through CY, drag along the wind in
        the plane of symmetry: the small-sideslip form used by AVL's CX/CZ output)."""
        ca, sa = np.cos(alpha), np.sin(alpha)
        cx = -self.CD * ca + self.CL * sa
        cz = -self.CD * sa - self.CL * ca
        return cx, np.broadcast_to(self.CY, np.shape(cx)), cz


class AeroModel(Protocol):
    """The protocol the dynamics, performance and loads models use."""

    reference: AeroReference
    control_names: tuple[str, ...]

    def coefficients(self, state: AeroState) -> Coefficients:
        """Coefficients for every state of the batch, moments about ``reference`` (x_ref, z_ref)."""
        ...
