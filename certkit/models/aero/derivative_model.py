"""Aerodynamic model from a table of stability and control derivatives.

This is the model an aircraft file uses when it declares whole derivative tables (wind tunnel,
CFD or published data), and the model the flight-dynamics tests build from published data.

Inputs
    Derivatives per radian in **stability axes** (x along the relative wind projected on the plane
    of symmetry), as AVL and the textbooks give them; rate derivatives per unit p̂ = p b/2V,
    q̂ = q c/2V, r̂ = r b/2V, α̇-derivatives per unit α̇ c/2V. Values are floats or sequences with
    one entry per Mach breakpoint; every term is linearly interpolated in Mach and held at the end
    values outside the breakpoints (``mach_range`` says where the table ends).

Equations (δ_j: control deflections in radians, Etkin sign convention; p_s, r_s stability-axis
rates, p_s = p cos α + r sin α, r_s = r cos α − p sin α)

    CL_lin = CL0 + CL_alpha α + CL_q q̂ + Σ CL_δj δj
    CL     = stall(CL_lin)                       (see below; CL = CL_lin without a stall model)
    CD     = CD0 + CD_alpha α + CD_alpha2 α² + k (CL − CL_minD)² + Σ CD_δj δj
             (the parabolic polar CD0 + k (CL − CL_minD)² when only k is given, drag derivatives
             when CD_alpha/CD_alpha2 are given; both may be combined, e.g. a zero-lift drag
             varying with α plus induced drag)
    CY     = CY_beta β + CY_p p̂_s + CY_r r̂_s + Σ CY_δj δj
    Cl_s   = Cl_beta β + Cl_p p̂_s + Cl_r r̂_s + Σ Cl_δj δj
    Cm     = Cm0 + Cm_alpha α + Cm_q q̂ + Σ Cm_δj δj
    Cn_s   = Cn_beta β + Cn_p p̂_s + Cn_r r̂_s + Σ Cn_δj δj
    Cl     = Cl_s cos α − Cn_s sin α,   Cn = Cl_s sin α + Cn_s cos α   (body axes, as the
                                                                       AeroModel protocol asks)

    The α̇ terms (CL_alphadot, Cm_alphadot) cannot be carried by :class:`AeroState`; the equations
    of motion take them from :meth:`StabilityDerivativeModel.alpha_dot_derivatives` and solve the
    resulting implicit equation for α̇ exactly (Etkin's (m − Z_ẇ) form).

Stall model (optional, :class:`StallModel`)
    Below stall the lift is rounded onto CLmax with a smooth minimum of width w = ``rounding``:
        CL_att = CLmax − w ln(1 + exp((CLmax − CL_lin)/w)),
    which tends to CL_lin well below CLmax and to CLmax above it.
    Past the break angle α_b = α_s + ``break_delta`` (α_s: where CL_lin reaches CLmax) the flow is
    blended, with a logistic weight σ = 1/(1 + exp(−(α − α_b)/``break_width``)), into a
    separated flat-plate flow: CL_sep = CD90 sin α cos α, CD_sep = CD90 sin² α,
        CL = (1 − σ) CL_att + σ CL_sep,   CD = CD_attached + σ CD_sep.
    The result is smooth (continuous derivatives), so Newton trims and RK4 simulations near stall
    behave, and lift falls after the break as a real wing's does. The rounding and the blend's onset
    would keep the peak below the CLmax they are written with, so the CLmax used inside is calibrated
    at construction so that the lift curve's maximum (controls neutral) equals the declared CLmax at
    every Mach breakpoint: the declared value is the model's maximum lift coefficient.
    Controls named in ``after_stall`` (pseudo-controls such as a gust angle) add their lift after
    the stall model and outside the induced drag.

The equations are evaluated by compiled code (:mod:`certkit.models.aero.derivative_kernel`), the
same function the equations of motion call inside their integration step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from certkit.models.aero.derivative_kernel import BASE_TERMS, CONTROL_PREFIXES, coefficients_batch
from certkit.models.aero.interface import AeroReference, AeroState, Coefficients
from certkit.models.compiled import kernel_array

_BASE_TERMS = BASE_TERMS
_CONTROL_PREFIXES = CONTROL_PREFIXES


@dataclass(frozen=True)
class StallModel:
    """Smooth stall: CLmax (float or one per Mach breakpoint), rounding width in CL, break angle
    beyond the linear-lift stall angle and its width (radians), flat-plate normal-force
    coefficient CD90 of the separated flow."""

    CLmax: float | Sequence[float]
    rounding: float = 0.08
    break_delta: float = np.radians(2.0)
    break_width: float = np.radians(1.5)
    CD90: float = 1.8


class StabilityDerivativeModel:
    """AeroModel from stability and control derivatives (see the module docstring for equations).

    Parameters
    ----------
    reference : AeroReference
        S, b, c and the moment reference point the moment derivatives refer to.
    derivatives : mapping name → float or sequence (one value per Mach breakpoint)
        Names from ``CL0 CL_alpha CL_q CL_alphadot CD0 k CL_minD CD_alpha CD_alpha2 CY_beta CY_p
        CY_r Cl_beta Cl_p Cl_r Cm0 Cm_alpha Cm_q Cm_alphadot Cn_beta Cn_p Cn_r`` and control terms
        ``<coef>_<control>`` (e.g. ``Cm_elevator``, ``Cl_aileron``, ``CD_flap``). A missing term is
        zero. Unknown names raise ``KeyError`` (a misspelt derivative must not vanish silently).
    mach : sequence of Mach breakpoints (increasing), or None for a single Mach-independent table.
    control_names : the controls; by default those appearing in control terms, in order of
        appearance.
    stall : optional StallModel.
    tail_downwash : optional :class:`~certkit.models.aero.tail_downwash.FreeAirDownwash`, the free-air downwash at
        the horizontal tail the table's pitching moment holds; the equations of motion reduce it near the runway
        (:mod:`certkit.models.aero.tail_ground_effect`). None: no ground effect at the tail.
    calibrated_clmax : optional, the internal CLmax of a model with the same base terms and stall model, already
        calibrated (a copy with further control terms); None: calibrated here.
    flap_lift : optional, per Mach breakpoint, the lift coefficient increments of the configuration's flaps on the
        wing (tail off) and on the horizontal tail (its share from the change of downwash), shape (2, n_mach) — both
        already in CL0; kept apart for the strip loads model, which spreads them on the surfaces
        (:mod:`certkit.models.loads.response`). None: no flap lift to spread (flaps up, or not known).
    """

    def __init__(
        self,
        reference: AeroReference,
        derivatives: Mapping[str, float | Sequence[float]],
        mach: Sequence[float] | None = None,
        control_names: Sequence[str] | None = None,
        stall: StallModel | None = None,
        after_stall: Sequence[str] = (),
        alpha_drag: bool | None = None,
        tail_downwash=None,
        calibrated_clmax: np.ndarray | None = None,
        flap_lift: Sequence[float] | None = None,
    ) -> None:
        self.reference = reference
        self.tail_downwash = tail_downwash
        self.mach = np.atleast_1d(np.asarray(mach if mach is not None else [0.0], dtype=float))
        if self.mach.ndim != 1 or np.any(np.diff(self.mach) <= 0):
            raise ValueError("Mach breakpoints must be a strictly increasing 1-D sequence")
        nm = self.mach.size
        self.flap_lift = (
            None if flap_lift is None else np.broadcast_to(np.asarray(flap_lift, dtype=float), (2, nm)).copy()
        )
        found: list[str] = []
        for name in derivatives:
            if name in _BASE_TERMS:
                continue
            prefix, _, ctrl = name.partition("_")
            if prefix not in _CONTROL_PREFIXES or not ctrl or ctrl in ("alpha", "beta", "p", "q", "r"):
                raise KeyError(f"unknown derivative {name!r}")
            if ctrl not in found:
                found.append(ctrl)
        self.control_names: tuple[str, ...] = tuple(control_names) if control_names is not None else tuple(found)
        for name in derivatives:
            ctrl = name.partition("_")[2]
            if name not in _BASE_TERMS and ctrl not in self.control_names:
                raise KeyError(
                    f"unknown derivative {name!r}: neither a stability derivative nor a term of a "
                    f"control in {self.control_names}"
                )
        self.uses_alpha_drag = (
            alpha_drag if alpha_drag is not None else "CD_alpha" in derivatives or "CD_alpha2" in derivatives
        )
        unknown = [c for c in after_stall if c not in self.control_names]
        if unknown:
            raise KeyError(f"after_stall names unknown controls {unknown}")
        self.after_stall = tuple(after_stall)
        names = list(_BASE_TERMS) + [f"{p}_{c}" for c in self.control_names for p in _CONTROL_PREFIXES]
        self._index = {n: i for i, n in enumerate(names)}
        table = np.zeros((len(names), nm))
        for name, value in derivatives.items():
            v = np.asarray(value, dtype=float)
            if v.ndim == 0:
                table[self._index[name]] = v
            elif v.shape == (nm,):
                table[self._index[name]] = v
            else:
                raise ValueError(
                    f"{name}: expected a float or {nm} values (one per Mach breakpoint), got shape {v.shape}"
                )
        self._table = table
        self.stall = stall
        self._clmax = np.zeros(nm)
        stall_params = np.zeros(5)
        if stall is not None:
            clmax = np.asarray(stall.CLmax, dtype=float)
            if not (clmax.ndim == 0 or clmax.shape == (nm,)):
                raise ValueError(f"CLmax: expected a float or {nm} values")
            self._clmax = np.broadcast_to(clmax, (nm,)).copy()
            stall_params[:] = (1.0, stall.rounding, stall.break_delta, stall.break_width, stall.CD90)
        #: the compiled evaluator's arguments (table, Mach breakpoints, CLmax, stall parameters,
        #: α-drag flag, after-stall flags) — see :mod:`certkit.models.aero.derivative_kernel`
        self.kernel_data = (
            np.ascontiguousarray(table),
            self.mach,
            self._clmax,
            stall_params,
            bool(self.uses_alpha_drag),
            np.array([c in self.after_stall for c in self.control_names], dtype=np.bool_),
        )
        self._clmax_declared = self._clmax.copy()
        if stall is not None and calibrated_clmax is not None:  # a copy with other controls: the same calibration
            self._clmax[:] = calibrated_clmax
        elif stall is not None:
            self._calibrate_clmax()

    def _calibrate_clmax(self, iterations: int = 6) -> None:
        """Make the declared CLmax the largest lift coefficient the model reaches (controls neutral, at each Mach
        breakpoint): the rounding and the onset of the separated-flow blend keep the curve's peak below the
        CLmax they are written with (by about 15 % with the default widths), so that internal value is raised
        until the peak of the lift curve equals the declared one (a fixed-point iteration on the ratio). The
        breakpoints still iterating are evaluated in one batch: at a breakpoint the kernel reads that breakpoint's
        CLmax alone (interpolation weights 0 and 1), so each iterates as it would by itself."""
        internal = self._clmax
        points = 801
        cla = np.array([max(abs(float(self._table[self._index["CL_alpha"], k])), 1e-3) for k in range(self.mach.size)])
        cl0 = np.array([float(self._table[self._index["CL0"], k]) for k in range(self.mach.size)])
        going = list(range(self.mach.size))
        for _ in range(iterations):
            if not going:
                break
            starts = [(internal[k] - cl0[k]) / cla[k] for k in going]  # each breakpoint's stall angle
            alpha = np.concatenate(
                [np.linspace(a - 0.2, a + self.stall.break_delta + 4 * self.stall.break_width, points) for a in starts]
            )
            z = np.zeros_like(alpha)
            cl = coefficients_batch(
                *self.kernel_data,
                alpha,
                z,
                z,
                z,
                z,
                np.repeat(self.mach[going], points),
                np.zeros((alpha.size, len(self.control_names))),
            )[:, 0]
            left = []
            for b, k in enumerate(going):
                peak = float(cl[b * points : (b + 1) * points].max())
                if not abs(peak - self._clmax_declared[k]) < 1e-5:  # (a NaN peak goes on, as it would alone)
                    internal[k] *= self._clmax_declared[k] / peak
                    left.append(k)
            going = left

    # ------------------------------------------------------------------ helpers
    @property
    def mach_range(self) -> tuple[float, float]:
        return float(self.mach[0]), float(self.mach[-1])

    def _weights(self, mach: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        m = self.mach
        if m.size == 1:
            z = np.zeros(np.shape(mach), dtype=int)
            return z, np.zeros(np.shape(mach))
        x = np.minimum(np.maximum(mach, m[0]), m[-1])
        i = np.minimum(np.searchsorted(m, x, side="right") - 1, m.size - 2)
        w = (x - m[i]) / (m[i + 1] - m[i])
        return i, w

    def _interp_rows(self, rows: np.ndarray, i: np.ndarray, w: np.ndarray) -> np.ndarray:
        if self.mach.size == 1:
            r = rows[..., 0]
            return np.broadcast_to(r.reshape(r.shape + (1,) * np.ndim(w)), r.shape + np.shape(w))
        return rows[..., i] * (1.0 - w) + rows[..., np.minimum(i + 1, self.mach.size - 1)] * w

    def derivative(self, name: str, mach=0.0) -> np.ndarray:
        """One derivative interpolated at ``mach``."""
        i, w = self._weights(np.asarray(mach, dtype=float))
        return self._interp_rows(self._table[self._index[name]], i, w)

    def clmax(self, mach) -> np.ndarray | None:
        """The stall model's CLmax at ``mach`` (interpolated like the derivatives), None without a stall model."""
        if self.stall is None:
            return None
        i, w = self._weights(np.asarray(mach, dtype=float))
        return self._interp_rows(self._clmax_declared, i, w)

    def alpha_dot_derivatives(self, mach) -> tuple[np.ndarray, np.ndarray]:
        """(CL_alphadot, Cm_alphadot) at ``mach``, per unit α̇ c/2V (used by the equations of motion)."""
        i, w = self._weights(np.asarray(mach, dtype=float))
        rows = self._table[[self._index["CL_alphadot"], self._index["Cm_alphadot"]]]
        out = self._interp_rows(rows, i, w)
        return out[0], out[1]

    # ------------------------------------------------------------------ protocol
    def coefficients(self, state: AeroState) -> Coefficients:
        shape = np.broadcast_shapes(
            np.shape(state.alpha),
            np.shape(state.beta),
            np.shape(state.p_hat),
            np.shape(state.q_hat),
            np.shape(state.r_hat),
            np.shape(state.mach),
            *[np.shape(v) for v in state.controls.values()],
        )
        flat = [
            kernel_array(np.broadcast_to(np.asarray(a, dtype=float), shape)).reshape(-1)
            for a in (state.alpha, state.beta, state.p_hat, state.q_hat, state.r_hat, state.mach)
        ]
        ctrl = np.zeros((flat[0].size, len(self.control_names)))
        for j, name in enumerate(self.control_names):
            d = state.controls.get(name)
            if d is not None:
                ctrl[:, j] = np.broadcast_to(np.asarray(d, dtype=float), shape).reshape(-1)
        out = coefficients_batch(*self.kernel_data, *flat, ctrl)
        c = [out[:, k].reshape(shape) for k in range(6)]
        return Coefficients(CL=c[0], CD=c[1], CY=c[2], Cl=c[3], Cm=c[4], Cn=c[5])

    def _nonzero_terms(self) -> dict[str, np.ndarray]:
        """The table's non-zero terms by name (one value per Mach breakpoint)."""
        return {n: self._table[i] for n, i in self._index.items() if np.any(self._table[i] != 0.0)}

    def without_stall(self) -> "StabilityDerivativeModel":
        """A copy with linear lift (no stall model): for balanced load states on the V–n envelope's stall line,
        whose lift coefficient C_N,max the rounded stall model does not reach. Made once per model (the balanced
        manoeuvres and the stall-line test of every response ask for it)."""
        linear = self.__dict__.get("_linear")
        if linear is None:
            linear = self._linear = StabilityDerivativeModel(
                self.reference,
                self._nonzero_terms(),
                mach=self.mach,
                control_names=self.control_names,
                after_stall=self.after_stall,
                alpha_drag=self.uses_alpha_drag,
                tail_downwash=self.tail_downwash,
                flap_lift=self.flap_lift,
            )
        return linear

    def with_control_terms(
        self, terms: Mapping[str, float | Sequence[float]], after_stall: Sequence[str] = ()
    ) -> "StabilityDerivativeModel":
        """A copy with further control terms (``<coef>_<control>``, one value per Mach breakpoint
        or a float); controls named in ``after_stall`` add their lift after the stall model and
        outside the induced drag (pseudo-controls such as a gust angle). A base term (``CL_alpha`` …) is refused:
        it is not a control's, and the copy keeps this model's CLmax calibration, which only base terms change."""
        base = sorted(set(terms) & set(_BASE_TERMS))
        if base:
            raise KeyError(f"with_control_terms takes control terms only, not the stability derivatives {base}")
        names = list(self.control_names)
        for name in terms:
            ctrl = name.partition("_")[2]
            if ctrl not in names:
                names.append(ctrl)
        derivs = self._nonzero_terms()
        derivs.update(terms)
        # the CLmax calibration (controls neutral) sees only the base terms: unchanged, it is this model's
        return StabilityDerivativeModel(
            self.reference,
            derivs,
            mach=self.mach,
            control_names=names,
            stall=self.stall,
            after_stall=tuple(self.after_stall) + tuple(after_stall),
            alpha_drag=self.uses_alpha_drag,
            tail_downwash=self.tail_downwash,
            calibrated_clmax=self._clmax,
            flap_lift=self.flap_lift,
        )
