"""The vortex-lattice solver: one influence matrix, one LU factorisation, all unit solutions.

Method (Katz & Plotkin, *Low-Speed Aerodynamics*, ch. 12; Drela & Youngren, AVL 3.x):

* flow tangency at every control point, (V∞ + Ω×r + Σ Γ_j w_j)·n = 0, with the normals rotated by
  camber, incidence and (linearised) control deflection; strips of NOWAKE surfaces replace their
  trailing-edge equation by ΣΓ = 0 over the strip;
* the circulation is linear in the 6 freestream/rotation components u and in the products δ_d·u
  (a control deflection δ_d tilts the normals, so its right-hand side is −(V∞+Ω×r)·∂n/∂δ_d): the
  matrix is factorised once (LAPACK gesv through ``numpy.linalg.solve``) and solved for these
  6 + 6·n_controls unit right-hand sides at once;
* forces by Kutta–Joukowski on every bound leg, F = ρ Γ (V∞ + Ω×r + v_induced) × l, plus AVL's force
  on the chordwise parts of the trailing legs lying on the surface (freestream and rotation only);
  moments about the reference point. Forces are bilinear in the unit inputs, so every total
  coefficient is a quadratic form C = ũᵀ T ũ of the input vector ũ = (u, δ_1 u, …): evaluating a
  batch of states, and every derivative, is a small tensor contraction;
* induced drag, lift, side force and span efficiency from the Trefftz plane (2-D vortex wake).

All velocities are normalised by V∞, circulations by V∞ (metres); coefficients use the reference
area, span and chord of the configuration.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from certkit.models.aero.interface import AeroState, Coefficients

from .biot_savart import horseshoe_velocity
from .geometry import Configuration, GeometryError
from .lattice import Lattice, build_lattice


class SingularLatticeError(GeometryError):
    """The influence matrix cannot be factorised (coincident or degenerate panels)."""


#: AVL's vortex-core factors: same component 1e-4 × strip width; otherwise max(0·chord, 2·width)
CORE_SAME_COMPONENT = 1.0e-4
CORE_OTHER_COMPONENT_WIDTH = 2.0
CORE_OTHER_COMPONENT_CHORD = 0.0

#: condition-number estimate above which the influence matrix counts as singular (a pivot ratio of about 1e-12)
SINGULAR_CONDITION = 1.0e12

COEFFICIENTS = ("CL", "CD", "CY", "Cl", "Cm", "Cn")
VARIABLES = ("alpha", "beta", "p", "q", "r")


# ----------------------------------------------------------------------------------------------
# Results
# ----------------------------------------------------------------------------------------------


@dataclass
class StripLoads:
    """Spanwise loading, one entry per strip (all surfaces, mirrored halves included).

    ``surface`` name, ``y``/``z`` of the strip centre leading edge, ``chord``, ``width``, ``area``,
    ``c_cn`` chord × normal-force coefficient (AVL's c·cl span loading), ``cl`` strip lift
    coefficient (perpendicular to the stream in the plane normal to the strip), ``cn`` normal-force
    coefficient, ``force_over_q`` strip force / dynamic pressure (m², geometry axes X aft, Z up:
    multiply by q∞ for newtons), ``circulation`` ΣΓ/V∞ of the strip (m)."""

    surface: np.ndarray
    y: np.ndarray
    z: np.ndarray
    chord: np.ndarray
    width: np.ndarray
    area: np.ndarray
    c_cn: np.ndarray
    cl: np.ndarray
    cn: np.ndarray
    force_over_q: np.ndarray
    circulation: np.ndarray

    def for_surface(self, name: str) -> "StripLoads":
        """The strips of one surface (its mirror image is named ``name + ' (YDUP)'``)."""
        m = self.surface == name
        if not np.any(m):
            raise KeyError(f"no surface {name!r}; have {sorted(set(self.surface))}")
        return StripLoads(*(getattr(self, f)[m] for f in self.__dataclass_fields__))


@dataclass
class FlowSolution:
    """Coefficients at one flight state. Forces CL, CD (near-field, + cd0), CY; moments in stability
    axes ``Cl``, ``Cm``, ``Cn`` (AVL's Cl', Cm, Cn') and body axes ``Cl_body``, ``Cn_body`` (x forward,
    z down; Cm is common); body forces ``CX`` (forward), ``CZ`` (down). Trefftz plane: ``CL_trefftz``,
    ``CY_trefftz``, ``CD_induced``, ``span_efficiency``."""

    alpha: float
    beta: float
    mach: float
    CL: float
    CD: float
    CY: float
    Cl: float
    Cm: float
    Cn: float
    Cl_body: float
    Cn_body: float
    CX: float
    CZ: float
    CL_trefftz: float
    CY_trefftz: float
    CD_induced: float
    span_efficiency: float
    strips: StripLoads
    circulation: np.ndarray = field(repr=False)


class StabilityDerivatives(Mapping[str, float]):
    """Derivatives per radian (rates per unit p̂ = pb/2V, q̂ = qc/2V, r̂ = rb/2V), keyed
    ``"<coefficient>_<variable>"``: coefficients CL, CD, CY, Cl, Cm, Cn; variables alpha, beta, p, q,
    r and ``delta_<control>``. Read as ``d["Cm_q"]`` or ``d.Cm_q``. ``axes`` says whether rates and
    rolling/yawing moments are stability-axis (AVL's p', r', Cl', Cn') or body-axis ones.
    ``neutral_point`` is X_np = X_ref − c·Cm_α/CL_α (geometry frame, m)."""

    def __init__(self, values: dict[str, float], axes: str, neutral_point: float, solution: FlowSolution):
        self._values = values
        self.axes = axes
        self.neutral_point = neutral_point
        self.solution = solution

    def __getitem__(self, key: str) -> float:
        return self._values[key]

    def __iter__(self):
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def __getattr__(self, key: str) -> float:
        try:
            return self.__dict__["_values"][key]
        except KeyError:
            raise AttributeError(key) from None

    def __repr__(self) -> str:
        body = ", ".join(f"{k}={v:.6g}" for k, v in self._values.items())
        return f"StabilityDerivatives(axes={self.axes!r}, Xnp={self.neutral_point:.6g}, {body})"


# ----------------------------------------------------------------------------------------------
# Solver
# ----------------------------------------------------------------------------------------------


def _cross(a, b):
    return np.stack(
        [
            a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
            a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
            a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0],
        ],
        axis=-1,
    )


def _unit_velocities(points: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """(M, 6, 3) velocity at points per unit freestream component (3) and unit rotation (3): the
    air moves at −Ω×r relative to a body rotating at Ω (AVL: r × Ω)."""
    r = points - ref
    out = np.zeros((points.shape[0], 6, 3))
    out[:, 0, 0] = out[:, 1, 1] = out[:, 2, 2] = 1.0
    eye = np.eye(3)
    out[:, 3:, :] = _cross(r[:, None, :], eye[None, :, :])
    return out


class VortexLattice:
    """A paneled, factorised vortex lattice at one Mach number: build once, evaluate many times.

    >>> vl = VortexLattice(config, mach=0.7)
    >>> sol = vl.solve(alpha=0.05, controls={"elevator": -0.01})
    >>> der = vl.stability_derivatives(alpha=0.05)
    >>> der["Cm_alpha"], der.neutral_point

    ``coefficients(AeroState)`` implements :class:`certkit.models.aero.interface.AeroModel` (body-axis
    rates and moments), evaluating a batch of states as one tensor contraction; states at another
    Mach number get their own lattice, built on first use and cached.
    """

    def __init__(
        self,
        config: Configuration,
        mach: float | None = None,
        *,
        lattice: Lattice | None = None,
        trailing_leg_forces: bool = False,
    ):
        self.config = config
        self.trailing_leg_forces = trailing_leg_forces
        self.mach = float(config.mach if mach is None else mach)
        if not 0.0 <= self.mach < 1.0:
            raise ValueError(f"Mach {self.mach} outside the Prandtl–Glauert range [0, 1)")
        self.reference = config.reference
        self.lattice = lattice if lattice is not None else build_lattice(config)
        self.control_names = self.lattice.control_names
        self._ref_point = np.array([config.reference.x_ref, config.y_ref, config.reference.z_ref])
        self._others: dict[float, VortexLattice] = {self.mach: self}
        self._solve_unit_problems()

    # -- setup ---------------------------------------------------------------------------------

    def _core4(self, target_component: np.ndarray) -> np.ndarray:
        """Fourth powers of the vortex core radii seen from targets of the given components: (M, N), or
        (1, N) when every target lies on one component."""
        lat = self.lattice
        vortex_comp = lat.component[lat.vortex_strip]
        width = np.hypot(lat.rv2[:, 1] - lat.rv1[:, 1], lat.rv2[:, 2] - lat.rv1[:, 2])
        same = (CORE_SAME_COMPONENT * width) ** 4
        other = (
            np.maximum(CORE_OTHER_COMPONENT_CHORD * lat.chord[lat.vortex_strip], CORE_OTHER_COMPONENT_WIDTH * width)
            ** 4
        )
        if target_component.size and np.all(target_component == target_component[0]):
            return np.where(vortex_comp == target_component[0], same, other)[None, :]
        return np.where(target_component[:, None] == vortex_comp[None, :], same[None, :], other[None, :])

    def _solve_unit_problems(self) -> None:
        lat = self.lattice
        n, m = lat.n_vortices, len(self.control_names)
        beta = math.sqrt(1.0 - self.mach**2)
        vortex_comp = lat.component[lat.vortex_strip]
        # mirror symmetry: compute influences at one half (and the plane of symmetry) only; the
        # image point i' of i sees vortex j as i sees the image of j, reflected (y → −y)
        if lat.mirror is not None:
            rows = np.flatnonzero(lat.mirror >= np.arange(n))
            images = rows[lat.mirror[rows] != rows]
        else:
            rows, images = np.arange(n), np.arange(0)
        core = self._core4(vortex_comp[rows])
        aic = horseshoe_velocity(lat.rc[rows], lat.rv1, lat.rv2, core, beta, normals=lat.normal[rows])  # rows only
        # right-hand sides: 6 unit freestream/rotation components, then 6 per control
        unit_c = _unit_velocities(lat.rc, self._ref_point)  # (N, 6, 3)
        rhs = np.empty((n, 6 + 6 * m))
        rhs[:, :6] = -np.einsum("ikc,ic->ik", unit_c, lat.normal)
        for d in range(m):
            rhs[:, 6 + 6 * d : 12 + 6 * d] = -np.einsum("ikc,ic->ik", unit_c, lat.normal_control[d])
        rhs[~lat.alpha_beta[lat.vortex_strip]] = 0.0
        row_of = np.full(n, -1)
        row_of[rows] = np.arange(rows.size)
        for j in np.flatnonzero(~lat.wake):  # NOWAKE strips: zero net circulation replaces the TE equation
            te = lat.first[j] + lat.count[j] - 1
            rhs[te] = 0.0
            if row_of[te] >= 0:
                aic[row_of[te]] = 0.0
                aic[row_of[te], lat.first[j] : te + 1] = 1.0
        if not np.all(np.isfinite(aic)):
            raise SingularLatticeError("influence matrix has non-finite entries (coincident vortex and control point)")
        if images.size:
            gam = self._solve_symmetric(aic, rows, rhs)
        else:
            gam = self._solve_checked(aic, rhs)  # (N, K)
        if not np.all(np.isfinite(gam)):
            raise SingularLatticeError("vortex strengths are not finite: the influence matrix is singular")
        self.unit_circulation = gam
        # velocity at bound-leg midpoints for every unit solution (induced part never stored N×N)
        if images.size:
            flipped = gam[lat.mirror] * lat.mirror_sign[:, None]
            both = horseshoe_velocity(
                lat.rv[rows], lat.rv1, lat.rv2, core, beta, own_vortex=rows, out_rhs=np.hstack([gam, flipped])
            )
            induced = np.empty((3, n, gam.shape[1]))
            induced[:, rows] = both[:, :, : gam.shape[1]]
            pos = np.searchsorted(rows, images)
            induced[:, lat.mirror[images]] = both[:, pos, gam.shape[1] :] * np.array([1.0, -1.0, 1.0])[:, None, None]
        else:
            induced = horseshoe_velocity(
                lat.rv, lat.rv1, lat.rv2, core, beta, own_vortex=rows, out_rhs=gam
            )  # (3, N, K)
        vel = np.moveaxis(induced, 0, -1).copy()  # (N, K, 3)
        vel[:, :6, :] += _unit_velocities(lat.rv, self._ref_point)
        self.unit_bound_velocity = vel
        self._build_force_tensor()

    def _solve_checked(self, matrix: np.ndarray, rhs: np.ndarray, index: np.ndarray | None = None) -> np.ndarray:
        """Solve ``matrix · x = rhs`` (LAPACK gesv through numpy: LU with partial pivoting), raising
        SingularLatticeError if the system is singular or nearly so.

        The check costs one more right-hand side: a fixed pseudo-random vector b, whose solution gives
        ‖A‖₁‖x‖₁/‖b‖₁, a lower bound of the condition number κ₁(A) and, for a b with no special alignment,
        close to it (Dixon 1983, *SIAM J. Numer. Anal.* 20: within about √n with high probability for a
        random b). Coincident or degenerate panels give κ of order 1/ε; sound lattices of order 10²–10⁴
        (lta-clean: estimate 165 and 199 for its two half systems, κ₁ 1.5e3 and 1.4e3).
        Above ``SINGULAR_CONDITION`` (or on an exactly zero pivot or a non-finite result) the system is
        factorised again with scipy.linalg, imported only then, to name the vortex at the smallest pivot."""
        n = matrix.shape[0]
        probe = 2.0 * np.modf(np.arange(1, n + 1) * 0.6180339887498949)[0] - 1.0  # golden-ratio sequence in (−1, 1)
        try:
            sol = np.linalg.solve(matrix, np.column_stack([rhs, probe]))
        except np.linalg.LinAlgError:
            self._raise_singular(matrix, index)
        x = sol[:, -1]
        estimate = np.abs(matrix).sum(axis=0).max() * np.abs(x).sum() / np.abs(probe).sum()
        if not (np.all(np.isfinite(sol)) and estimate < SINGULAR_CONDITION):
            self._raise_singular(matrix, index)
        return sol[:, :-1]

    def _raise_singular(self, matrix: np.ndarray, index: np.ndarray | None):
        """Name the vortex at the smallest pivot of the LU factors of a singular (sub)system."""
        import scipy.linalg  # deferred: scipy.linalg only for a singular lattice: its import outlasts a derivatives run

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)  # an exactly zero pivot: named below
            lu, _ = scipy.linalg.lu_factor(matrix, check_finite=False)
        worst = int(np.argmin(np.abs(np.diag(lu))))
        vortex = int(index[worst]) if index is not None else worst
        strip = self.lattice.vortex_strip[min(vortex, self.lattice.n_vortices - 1)]
        raise SingularLatticeError(
            f"influence matrix is singular near vortex {vortex} (surface {self._surface_of_strip(strip)!r})"
        )

    def _solve_symmetric(self, aic_rows: np.ndarray, rows: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """Solve a mirror-symmetric system from its rows at one half (R) and the symmetry plane (Z).

        With images L = mirror(R), the rows at L repeat those at R with the columns of R and L
        swapped and those of Z negated; Z rows see L as the negative of R. Writing Γ_R = a + b,
        Γ_L = a − b gives two independent systems, (A_RR + A_RL) a = (r_R + r_L)/2 for the
        symmetric part and [[A_RR − A_RL, A_RZ], [2 A_ZR, A_ZZ]] [b; Γ_Z] = [(r_R − r_L)/2; r_Z] for
        the antisymmetric part: two factorisations of about half the size."""
        lat = self.lattice
        pair = lat.mirror[rows] != rows
        r_idx, z_idx = rows[pair], rows[~pair]
        l_idx = lat.mirror[r_idx]
        a_r, a_z = aic_rows[pair], aic_rows[~pair]
        a_rr, a_rl, a_rz = a_r[:, r_idx], a_r[:, l_idx], a_r[:, z_idx]
        a = self._solve_checked(a_rr + a_rl, 0.5 * (rhs[r_idx] + rhs[l_idx]), r_idx)
        anti = np.block([[a_rr - a_rl, a_rz], [2.0 * a_z[:, r_idx], a_z[:, z_idx]]])
        bz = self._solve_checked(
            anti, np.vstack([0.5 * (rhs[r_idx] - rhs[l_idx]), rhs[z_idx]]), np.concatenate([r_idx, z_idx])
        )
        b = bz[: r_idx.size]
        gam = np.empty_like(rhs)
        gam[r_idx] = a + b
        gam[l_idx] = a - b
        gam[z_idx] = bz[r_idx.size :]
        return gam

    def _surface_of_strip(self, j: int) -> str:
        for p in self.lattice.patches:
            if p.strips.start <= j < p.strips.stop:
                return p.name
        return "?"

    def _build_force_tensor(self) -> None:
        lat = self.lattice
        s = self.reference.area
        k = self.unit_circulation.shape[1]
        load = lat.load[lat.vortex_strip].astype(float)
        g = self.unit_circulation * load[:, None]
        bound = lat.rv2 - lat.rv1
        r = lat.rv - self._ref_point
        fx = _cross(self.unit_bound_velocity, bound[:, None, :])  # (N, K, 3)
        z = np.concatenate([fx, _cross(r[:, None, :], fx)], axis=-1)  # (N, K, 6)
        t = 2.0 * np.tensordot(g, z, axes=(0, 0))  # (K, K, 6)
        # chordwise parts of the trailing legs lying on the surface: freestream + rotation only
        for pts, leg in self._leg_geometry() if self.trailing_leg_forces else ():
            fl = _cross(_unit_velocities(pts, self._ref_point), leg[:, None, :])  # (N, 6, 3)
            zl = np.concatenate([fl, _cross((pts - self._ref_point)[:, None, :], fl)], axis=-1)
            t[:, :6, :] += 2.0 * np.tensordot(g, zl, axes=(0, 0))
        self.force_tensor = (
            np.ascontiguousarray(np.moveaxis(t, -1, 0)) / s
        )  # (6, K, K): FX, FY, FZ, MX, MY, MZ (geometry)
        self._n_inputs = k

    def _leg_geometry(self):
        lat = self.lattice
        j = lat.vortex_strip
        xte1 = lat.rle1[j, 0] + lat.chord1[j]
        xte2 = lat.rle2[j, 0] + lat.chord2[j]
        zeros = np.zeros_like(xte1)
        p1 = lat.rv1.copy()
        p1[:, 0] = 0.5 * (lat.rv1[:, 0] + xte1)
        p2 = lat.rv2.copy()
        p2[:, 0] = 0.5 * (lat.rv2[:, 0] + xte2)
        yield p1, np.stack([lat.rv1[:, 0] - xte1, zeros, zeros], axis=-1)
        yield p2, np.stack([xte2 - lat.rv2[:, 0], zeros, zeros], axis=-1)

    # -- inputs --------------------------------------------------------------------------------

    def _inputs(self, alpha, beta, p, q, r, deltas, axes: str):
        """Input vector ũ (K, B) and its derivatives dũ/dx (K, 5 + m, B) for x = (α, β, p̂, q̂, r̂, δ…)."""
        alpha, beta, p, q, r = np.broadcast_arrays(
            *(np.atleast_1d(np.asarray(v, float)) for v in (alpha, beta, p, q, r))
        )
        b = alpha.shape[0]
        m = len(self.control_names)
        dl = np.zeros((m, b)) if deltas is None else np.broadcast_to(deltas, (m, b)).astype(float)
        ca, sa, cb, sb = np.cos(alpha), np.sin(alpha), np.cos(beta), np.sin(beta)
        span, chord = self.reference.span, self.reference.chord
        nx = 5 + m
        u = np.zeros((6, b))
        du = np.zeros((6, nx, b))
        u[0], u[1], u[2] = ca * cb, -sb, sa * cb
        du[0, 0], du[0, 1] = -sa * cb, -ca * sb
        du[1, 1] = -cb
        du[2, 0], du[2, 1] = ca * cb, -sa * sb
        if axes == "stability":
            pb, rb = p * ca - r * sa, p * sa + r * ca
            dpb = (-p * sa - r * ca, ca, -sa)  # d/d(alpha, p, r)
            drb = (p * ca - r * sa, sa, ca)
        elif axes == "body":
            pb, rb = p, r
            dpb = (0.0 * p, 1.0, 0.0)
            drb = (0.0 * r, 0.0, 1.0)
        else:
            raise ValueError(f"axes must be 'stability' or 'body', not {axes!r}")
        # geometry axes (X aft, Z up): Ω = (−p, q, −r)
        u[3], u[4], u[5] = -pb * 2.0 / span, q * 2.0 / chord, -rb * 2.0 / span
        for row, der, fac in ((3, dpb, -2.0 / span), (5, drb, -2.0 / span)):
            du[row, 0] = fac * der[0]
            du[row, 2] = fac * der[1]
            du[row, 4] = fac * der[2]
        du[4, 3] = 2.0 / chord
        ut = np.empty((6 + 6 * m, b))
        dut = np.zeros((6 + 6 * m, nx, b))
        ut[:6], dut[:6] = u, du
        for d in range(m):
            ut[6 + 6 * d : 12 + 6 * d] = dl[d] * u
            dut[6 + 6 * d : 12 + 6 * d] = dl[d] * du
            dut[6 + 6 * d : 12 + 6 * d, 5 + d] += u
        return ut, dut, alpha

    def _deltas(self, controls: Mapping[str, float] | None, shape=None):
        m = len(self.control_names)
        if not controls:
            return None
        unknown = set(controls) - set(self.control_names)
        if unknown:
            raise KeyError(f"unknown control(s) {sorted(unknown)}; this lattice has {list(self.control_names)}")
        return np.array(
            [np.asarray(controls.get(n, 0.0), float) * np.ones(shape or ()) for n in self.control_names]
        ).reshape(m, -1)

    def _outputs(self, c6: np.ndarray, alpha: np.ndarray):
        """Stability/body coefficients from geometry-axis totals c6 (6, …) at angle of attack alpha."""
        ref = self.reference
        fx, fy, fz, mx, my, mz = c6
        ca, sa = np.cos(alpha), np.sin(alpha)
        cl_body, cm, cn_body = -mx / ref.span, my / ref.chord, -mz / ref.span
        return {
            "CL": -fx * sa + fz * ca,
            "CD": fx * ca + fz * sa,
            "CY": fy,
            "Cl": cl_body * ca + cn_body * sa,
            "Cm": cm,
            "Cn": cn_body * ca - cl_body * sa,
            "Cl_body": cl_body,
            "Cn_body": cn_body,
            "CX": -fx,
            "CZ": -fz,
        }

    # -- public evaluation ---------------------------------------------------------------------

    def at_mach(self, mach: float) -> "VortexLattice":
        """The lattice at another Mach number (same paneling), cached."""
        key = round(float(mach), 6)
        if key not in self._others:
            self._others[key] = VortexLattice(
                self.config, key, lattice=self.lattice, trailing_leg_forces=self.trailing_leg_forces
            )
            self._others[key]._others = self._others
        return self._others[key]

    def solve(
        self,
        alpha: float = 0.0,
        beta: float = 0.0,
        p_hat: float = 0.0,
        q_hat: float = 0.0,
        r_hat: float = 0.0,
        controls: Mapping[str, float] | None = None,
        *,
        rate_axes: str = "stability",
    ) -> FlowSolution:
        """Full solution at one state: coefficients, Trefftz-plane values and spanwise loads.
        Angles and deflections in radians; rates p̂, r̂ about stability axes unless
        ``rate_axes="body"``."""
        ut, _, _ = self._inputs(alpha, beta, p_hat, q_hat, r_hat, self._deltas(controls), rate_axes)
        ut = ut[:, 0]
        lat = self.lattice
        gam, fparts, rpts = self._vortex_forces(ut)
        load = lat.load[lat.vortex_strip][:, None]
        force = sum(fparts) * load
        moment = sum(_cross(rp - self._ref_point, fp) for rp, fp in zip(rpts, fparts)) * load
        s = self.reference.area
        c6 = np.concatenate([force.sum(0), moment.sum(0)]) / s
        out = self._outputs(c6, float(alpha))
        out["CD"] = out["CD"] + self.config.cd0
        strips = self._strip_loads(gam, sum(fparts), float(alpha))
        cl_ff, cy_ff, cd_ff = self._trefftz(gam)
        ar = self.reference.span**2 / s
        e = (cl_ff**2 + cy_ff**2) / (math.pi * ar * cd_ff) if cd_ff > 0 else float("nan")
        return FlowSolution(
            float(alpha),
            float(beta),
            self.mach,
            *(float(out[k]) for k in ("CL", "CD", "CY", "Cl", "Cm", "Cn", "Cl_body", "Cn_body", "CX", "CZ")),
            cl_ff,
            cy_ff,
            cd_ff,
            e,
            strips,
            gam,
        )

    def _vortex_forces(self, ut: np.ndarray):
        """Circulation (per unit V∞) and the force parts of each vortex (bound legs, then the trailing legs when
        they carry force) for the unit-input vector ``ut``, with their points of action."""
        lat = self.lattice
        gam = self.unit_circulation @ ut
        # the contraction over the inputs set only (a unit solution sets one or two of the 6 + 6 m): those of zero add
        # nothing, and reading their velocities (N × K × 3, a few hundred kB per Mach number) was most of the cost
        nz = np.flatnonzero(ut)
        vel = np.einsum("ikc,k->ic", self.unit_bound_velocity[:, nz, :], ut[nz])
        fparts = [2.0 * gam[:, None] * _cross(vel, lat.rv2 - lat.rv1)]
        rpts = [lat.rv]
        for pts, leg in self._leg_geometry() if self.trailing_leg_forces else ():
            v = np.einsum("ikc,k->ic", _unit_velocities(pts, self._ref_point), ut[:6])
            fparts.append(2.0 * gam[:, None] * _cross(v, leg))
            rpts.append(pts)
        return gam, fparts, rpts

    def strip_forces(
        self,
        alpha: float = 0.0,
        beta: float = 0.0,
        p_hat: float = 0.0,
        q_hat: float = 0.0,
        r_hat: float = 0.0,
        controls: Mapping[str, float] | None = None,
        *,
        rate_axes: str = "stability",
    ) -> tuple[np.ndarray, np.ndarray]:
        """Only the spanwise loading of :meth:`solve` (for the loads model, which needs no coefficients or
        Trefftz-plane values): each strip's force per unit q∞ (J, 3; as ``StripLoads.force_over_q``) and the
        circulation of every vortex (per unit V∞)."""
        ut, _, _ = self._inputs(alpha, beta, p_hat, q_hat, r_hat, self._deltas(controls), rate_axes)
        gam, fparts, _ = self._vortex_forces(ut[:, 0])
        return np.add.reduceat(sum(fparts), self.lattice.first, axis=0), gam

    def vortex_forces(
        self,
        alpha: float = 0.0,
        beta: float = 0.0,
        p_hat: float = 0.0,
        q_hat: float = 0.0,
        r_hat: float = 0.0,
        controls: Mapping[str, float] | None = None,
        *,
        rate_axes: str = "stability",
    ) -> np.ndarray:
        """Kutta–Joukowski force of every bound leg per unit q∞ (N, 3; geometry axes), the forces AVL sums for
        control hinge moments."""
        ut, _, _ = self._inputs(alpha, beta, p_hat, q_hat, r_hat, self._deltas(controls), rate_axes)
        _, fparts, _ = self._vortex_forces(ut[:, 0])
        return fparts[0] * self.lattice.load[self.lattice.vortex_strip][:, None]

    def _strip_loads(self, gam: np.ndarray, force: np.ndarray, alpha: float) -> StripLoads:
        lat = self.lattice
        fs = np.add.reduceat(force, lat.first, axis=0)  # (J, 3), per unit q∞ after scaling below
        area = lat.chord * lat.width
        cf = fs / area[:, None]
        cn = lat.ensy * cf[:, 1] + lat.ensz * cf[:, 2]
        spn = np.stack([np.zeros_like(lat.ensy), lat.ensz, -lat.ensy], axis=-1)
        udrag = np.array([math.cos(alpha), 0.0, math.sin(alpha)])
        ulift = _cross(np.broadcast_to(udrag, spn.shape), spn)
        ulift /= np.maximum(np.linalg.norm(ulift, axis=-1, keepdims=True), 1e-300)
        cl = np.sum(ulift * cf, axis=-1)
        names = np.empty(lat.n_strips, dtype=object)
        for p in lat.patches:
            names[p.strips] = p.name
        return StripLoads(
            names,
            lat.rle[:, 1].copy(),
            lat.rle[:, 2].copy(),
            lat.chord.copy(),
            lat.width.copy(),
            area,
            lat.chord * cn,
            cl,
            cn,
            fs,
            np.add.reduceat(gam, lat.first),
        )

    def _trefftz(self, gam: np.ndarray) -> tuple[float, float, float]:
        """Lift, side force and induced drag coefficients from the far wake (Trefftz plane): the
        trailing vortices leave the strip edges parallel to X and induce a 2-D cross-flow, evaluated
        at each strip's trailing-edge control point (AVL TPFORC); D = −ρ/2 Σ Γ (v·n) Δs."""
        lat = self.lattice
        keep = lat.load
        last = (lat.first + lat.count - 1)[keep]
        g = np.add.reduceat(gam, lat.first)[keep]
        p1, p2, pc = lat.rv1[last, 1:], lat.rv2[last, 1:], lat.rc[last, 1:]
        d = p2 - p1

        def vel(src):
            r = pc[:, None, :] - src[None, :, :]
            r2 = r[..., 0] ** 2 + r[..., 1] ** 2
            return np.stack([-r[..., 1], r[..., 0]], axis=-1) / (2.0 * math.pi * r2[..., None])

        v = np.einsum("ijc,j->ic", vel(p2) - vel(p1), g)  # (J, 2): (v, w) in the Trefftz plane
        s = self.reference.area
        cl = 2.0 * float(np.sum(g * d[:, 0])) / s
        cy = -2.0 * float(np.sum(g * d[:, 1])) / s
        cd = float(np.sum(g * (d[:, 1] * v[:, 0] - d[:, 0] * v[:, 1]))) / s
        return cl, cy, cd

    def stability_derivatives(
        self,
        alpha: float = 0.0,
        beta: float = 0.0,
        p_hat: float = 0.0,
        q_hat: float = 0.0,
        r_hat: float = 0.0,
        controls: Mapping[str, float] | None = None,
        *,
        axes: str = "stability",
    ) -> StabilityDerivatives:
        """Every derivative of CL, CD, CY, Cl, Cm, Cn w.r.t. α, β, p̂, q̂, r̂ and each control, per
        radian, at the given state. ``axes="stability"`` (AVL's stability-axis table: rates p', r'
        and moments Cl', Cn' about stability axes) or ``"body"`` (body rates and moments)."""
        ut, dut, a = self._inputs(alpha, beta, p_hat, q_hat, r_hat, self._deltas(controls), axes)
        ut, dut = ut[:, 0], dut[:, :, 0]
        t = self.force_tensor
        c6 = np.einsum("cab,a,b->c", t, ut, ut)
        grad = np.einsum("cab,b->ca", t + np.swapaxes(t, 1, 2), ut)  # (6, K)
        dc6 = grad @ dut  # (6, nx)
        dout = self._outputs(dc6, a[0])
        # the stability axes turn with alpha: add ∂/∂α at fixed geometry-axis totals
        ca, sa = math.cos(a[0]), math.sin(a[0])
        fx, fy, fz, mx, my, mz = c6
        clb, cnb = -mx / self.reference.span, -mz / self.reference.span
        extra = {
            "CL": -fx * ca - fz * sa,
            "CD": -fx * sa + fz * ca,
            "Cl": -clb * sa + cnb * ca,
            "Cn": -cnb * sa - clb * ca,
        }
        names = list(VARIABLES) + [f"delta_{n}" for n in self.control_names]
        values: dict[str, float] = {}
        for coef in COEFFICIENTS:
            key = f"{coef}_body" if (axes == "body" and coef in ("Cl", "Cn")) else coef
            for i, var in enumerate(names):
                values[f"{coef}_{var}"] = float(dout[key][i]) + (
                    float(extra[key]) if var == "alpha" and key in extra else 0.0
                )
        xnp = self.reference.x_ref - self.reference.chord * values["Cm_alpha"] / values["CL_alpha"]
        sol = self.solve(alpha, beta, p_hat, q_hat, r_hat, controls, rate_axes=axes)
        return StabilityDerivatives(values, axes, xnp, sol)

    def coefficients(self, state: AeroState) -> Coefficients:
        """AeroModel protocol: coefficients for a batch of states (body rates p̂, q̂, r̂; moments in
        body axes about the reference point; CL, CD in stability axes, CD near-field + cd0)."""
        shape = np.broadcast_shapes(
            *(np.shape(x) for x in (state.alpha, state.beta, state.p_hat, state.q_hat, state.r_hat, state.mach)),
            *(np.shape(v) for v in state.controls.values()),
        )
        bc = lambda x: np.broadcast_to(np.asarray(x, float), shape).ravel()  # noqa: E731
        mach = bc(state.mach)
        res = {k: np.empty(mach.size) for k in ("CL", "CD", "CY", "Cl_body", "Cm", "Cn_body")}
        controls = {n: bc(v) for n, v in state.controls.items()}
        for m in np.unique(mach):
            sel = mach == m
            vl = self if m == self.mach else self.at_mach(m)
            deltas = vl._deltas({n: v[sel] for n, v in controls.items()}, shape=(int(sel.sum()),))
            ut, _, a = vl._inputs(
                bc(state.alpha)[sel],
                bc(state.beta)[sel],
                bc(state.p_hat)[sel],
                bc(state.q_hat)[sel],
                bc(state.r_hat)[sel],
                deltas,
                "body",
            )
            c6 = np.einsum("can,an->cn", vl.force_tensor @ ut, ut)
            out = vl._outputs(c6, a)
            for k in res:
                res[k][sel] = out[k]
        res["CD"] += self.config.cd0
        r = {k: v.reshape(shape) for k, v in res.items()}
        return Coefficients(CL=r["CL"], CD=r["CD"], CY=r["CY"], Cl=r["Cl_body"], Cm=r["Cm"], Cn=r["Cn_body"])

    @property
    def control_derivative_names(self) -> tuple[str, ...]:
        return tuple(f"delta_{n}" for n in self.control_names)
