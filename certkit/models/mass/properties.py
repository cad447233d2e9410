"""Mass, CG and inertia tensor of an airplane from its components.

Positions are in the airplane frame (X aft of the nose, Y right, Z up, m); inertia tensors are in
body axes (x forward, y right, z down) as the equations of motion use them, J = [[Ixx, −Ixy, −Ixz],
[−Ixy, Iyy, −Iyz], [−Ixz, −Iyz, Izz]] with products Ixz = ∫ x z dm.

Parallel-axis theorem: J_cg = Σ_i [J_i + m_i (|d_i|² 1 − d_i d_iᵀ)], d_i the component's CG
relative to the total CG in body axes.

Without a component breakdown, :func:`inertia_from_radii` uses non-dimensional radii of gyration
in the form of Roskam (*Airplane Design* Part V, ch. 4):
    Ixx = m (b R̄x / 2)²,  Iyy = m (L R̄y / 2)²,  Izz = m ((b + L)/2 · R̄z / 2)²
(b span, L fuselage length). The default radii R̄x = 0.31, R̄y = 0.35, R̄z = 0.47 are those of
the Boeing 747 inertias of Etkin & Reid's example (40 000 ft cruise, 2.88e5 kg); an aircraft file
should state the radii for its own class (Roskam Part V tabulates them by airplane type).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from certkit.models.dynamics.eom import airplane_to_body, inertia_tensor


class InertiaError(ValueError):
    """An inertia tensor that no physical mass distribution can have."""


@dataclass(frozen=True)
class MassComponent:
    name: str
    mass: float
    cg: Sequence[float]  # airplane frame
    inertia: np.ndarray | None = None  # about its own CG, body axes (None: a point mass)


@dataclass(frozen=True)
class MassProperties:
    mass: float
    cg: np.ndarray  # airplane frame
    inertia: np.ndarray  # body axes about the CG

    @property
    def Ixx(self) -> float:
        return float(self.inertia[0, 0])

    @property
    def Iyy(self) -> float:
        return float(self.inertia[1, 1])

    @property
    def Izz(self) -> float:
        return float(self.inertia[2, 2])

    @property
    def Ixz(self) -> float:
        return float(-self.inertia[0, 2])


def body_axis_tensor(t) -> np.ndarray:
    """The inertia tensor J (body axes) of a declared :class:`certkit.aircraft.model.InertiaTensor`: its moments and
    products in its own axes (body, stability or principal, x ``axes_angle`` above the body x axis) turned about y,
    J_body = C J C^T with C's columns the declared axes in body axes: x = (cos ε, 0, −sin ε), z = (sin ε, 0, cos ε)."""
    J = np.array([[t.Ixx, -t.Ixy, -t.Ixz], [-t.Ixy, t.Iyy, -t.Iyz], [-t.Ixz, -t.Iyz, t.Izz]], dtype=float)
    eps = getattr(t, "axes_angle", 0.0)
    if eps == 0.0:
        return J
    c, s = np.cos(eps), np.sin(eps)
    C = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    return C @ J @ C.T


def combine(components: Sequence[MassComponent]) -> MassProperties:
    """Total mass, CG and inertia about the total CG (parallel-axis theorem)."""
    if not components:
        raise ValueError("no mass components")
    m = np.array([c.mass for c in components], dtype=float)
    if np.any(m < 0):
        bad = [c.name for c in components if c.mass < 0]
        raise ValueError(f"negative component mass: {', '.join(bad)}")
    own = [None if c.inertia is None else np.asarray(c.inertia, dtype=float) for c in components]
    return combine_arrays(m, np.array([c.cg for c in components], dtype=float), own)


def combine_arrays(m: np.ndarray, pos: np.ndarray, own: Sequence[np.ndarray | None] | np.ndarray) -> MassProperties:
    """:func:`combine` of components given as arrays: masses (N,) (none negative), CGs (N, 3) and each one's own
    inertia tensor ((N, 3, 3), or a sequence with None for a point mass)."""
    total = m.sum()
    if total <= 0:
        raise ValueError("total mass is zero")
    cg = (m[:, None] * pos).sum(axis=0) / total
    d = airplane_to_body(pos, cg)
    # parallel-axis terms m (|d|² I − d dᵀ), formed for all at once, then added one after another from zero with the
    # components' own tensors in the components' order (a cumulative sum: the additions of a loop, without its cost)
    dd = np.array([np.dot(di, di) for di in d])
    terms = m[:, None, None] * (dd[:, None, None] * np.eye(3) - d[:, :, None] * d[:, None, :])
    if isinstance(own, np.ndarray):  # every component with its own tensor: own and term interleaved
        addends = np.empty((2 * len(m) + 1, 3, 3))
        addends[0] = 0.0
        addends[1::2], addends[2::2] = own, terms
    else:
        listed = [np.zeros((3, 3))]
        for inertia, term in zip(own, terms):
            if inertia is not None:
                listed.append(inertia)
            listed.append(term)
        addends = np.array(listed)
    J = np.cumsum(addends, axis=0)[-1]
    check_inertia(J)
    return MassProperties(mass=float(total), cg=cg, inertia=J)


def inertia_from_radii(
    mass: float, span: float, length: float, Rx: float = 0.31, Ry: float = 0.35, Rz: float = 0.47, Ixz: float = 0.0
) -> np.ndarray:
    """Body-axis inertia tensor from non-dimensional radii of gyration (module docstring)."""
    J = inertia_tensor(
        mass * (span * Rx / 2) ** 2, mass * (length * Ry / 2) ** 2, mass * ((span + length) / 2 * Rz / 2) ** 2, Ixz
    )
    check_inertia(J)
    return J


def check_inertia(J, name: str = "inertia tensor") -> np.ndarray:
    """Raise :class:`InertiaError` unless J is symmetric, positive definite and its principal
    moments satisfy the triangle inequalities (I1 + I2 ≥ I3 for every permutation)."""
    J = np.asarray(J, dtype=float)
    if J.shape != (3, 3):
        raise InertiaError(f"{name}: expected a 3×3 tensor, got shape {J.shape}")
    if not np.allclose(J, J.T, rtol=1e-9, atol=1e-9 * max(np.abs(J).max(), 1.0)):
        raise InertiaError(f"{name} is not symmetric")
    eig = np.linalg.eigvalsh(J)
    if eig[0] <= 0:
        raise InertiaError(
            f"{name} is not positive definite (principal moments {', '.join(f'{e:.4g}' for e in eig)} kg m²): "
            "check the signs of the products of inertia and the units"
        )
    tol = 1e-9 * eig.sum()
    if eig[0] + eig[1] < eig[2] - tol:
        raise InertiaError(
            f"{name} violates the triangle inequality: principal moments {eig[0]:.4g} + {eig[1]:.4g} < "
            f"{eig[2]:.4g} kg m², which no mass distribution can produce"
        )
    return J


__all__ = [
    "MassComponent",
    "MassProperties",
    "combine",
    "combine_arrays",
    "inertia_from_radii",
    "check_inertia",
    "InertiaError",
]
