"""Engine models: a tabulated deck, a parametric high-bypass turbofan, windmilling drag.

Every model offers ``thrust(throttle, h, mach) -> N`` and ``fuel_flow(throttle, h, mach) -> kg/s``
on arrays (the signature :class:`certkit.models.dynamics.eom.Engine` expects), throttle in [0, 1].

:class:`EngineDeck`
    Thrust and fuel flow tabulated on an (altitude, Mach, throttle) grid, interpolated linearly.
    A point outside the table raises :class:`DeckRangeError` naming the point and the table's
    range, unless the deck was built with ``allow_extrapolation=True`` (then the end values are
    extrapolated linearly) — never silently.

:class:`ParametricTurbofan`
    Without a deck: thrust lapse of a high-bypass turbofan after Mattingly (*Aircraft Engine
    Design*, 2nd ed., AIAA 2002, §2.3 installed-thrust lapse for high-bypass turbofans):
        δ0 = δ (1 + 0.2 M²)^3.5,  θ0 = θ (1 + 0.2 M²)     (total pressure / temperature ratios)
        lapse = δ0 (1 − 0.49 √M)                              for θ0 ≤ TR
        lapse = δ0 (1 − 0.49 √M − 3 (θ0 − TR) / (1.5 + M))    for θ0 > TR
    with TR the throttle ratio (1.0 by default: the engine is flat-rated to ISA sea level);
    thrust = T_SL · lapse · (idle + (1 − idle) · throttle);
    TSFC = (0.4 + 0.45 M) √θ  per hour (same source), fuel flow = TSFC · T / g0, TSFC taken
    independent of throttle (a simplification: part-power TSFC rises at low settings).

:func:`windmill_drag`
    Drag of a failed, windmilling turbofan as a momentum deficit through the fan plus nacelle
    spillage, of the form used by Torenbeek (*Synthesis of Subsonic Airplane Design*, App. G):
        D = q [0.0785 D_i² + 2/(1 + 0.16 M²) · (π/4) D_i² · (V_N/V)(1 − V_N/V)]
    with D_i the inlet diameter and V_N/V ≈ 0.42 for high-bypass fans (check these constants
    against the source before relying on the value in a VMC finding).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit
from scipy.interpolate import RegularGridInterpolator

from certkit import atmosphere as isa
from certkit.atmosphere import isa_scalar
from certkit.units import G0


class DeckRangeError(ValueError):
    """A point outside an engine deck's table."""


class EngineDeck:
    """Tabulated engine: ``altitude`` (m), ``mach``, ``throttle`` grids (increasing), ``thrust``
    (N) and ``fuel_flow`` (kg/s) arrays of shape (n_alt, n_mach, n_throttle)."""

    def __init__(
        self,
        altitude,
        mach,
        throttle,
        thrust,
        fuel_flow=None,
        allow_extrapolation: bool = False,
        name: str = "engine deck",
    ):
        self.grid = tuple(np.asarray(g, dtype=float) for g in (altitude, mach, throttle))
        shape = tuple(g.size for g in self.grid)
        for g, label in zip(self.grid, ("altitude", "Mach", "throttle")):
            if g.ndim != 1 or g.size < 2 or np.any(np.diff(g) <= 0):
                raise ValueError(f"{name}: the {label} breakpoints must be increasing (at least two)")
        thrust = np.asarray(thrust, dtype=float)
        if thrust.shape != shape:
            raise ValueError(f"{name}: thrust table has shape {thrust.shape}, the grid needs {shape}")
        self.name = name
        self.allow_extrapolation = allow_extrapolation
        self._thrust = RegularGridInterpolator(self.grid, thrust, bounds_error=False, fill_value=None)
        self._ff = None
        if fuel_flow is not None:
            ff = np.asarray(fuel_flow, dtype=float)
            if ff.shape != shape:
                raise ValueError(f"{name}: fuel-flow table has shape {ff.shape}, the grid needs {shape}")
            self._ff = RegularGridInterpolator(self.grid, ff, bounds_error=False, fill_value=None)

    def _points(self, throttle, h, mach):
        h, mach, throttle = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (h, mach, throttle)))
        pts = np.stack([h, mach, throttle], axis=-1)
        if not self.allow_extrapolation:
            lo = np.array([g[0] for g in self.grid])
            hi = np.array([g[-1] for g in self.grid])
            bad = np.any((pts < lo - 1e-9) | (pts > hi + 1e-9), axis=-1)
            if np.any(bad):
                b = pts[bad][0]
                raise DeckRangeError(
                    f"{self.name}: altitude {b[0]:.0f} m, Mach {b[1]:.3f}, throttle {b[2]:.3f} is outside the table "
                    f"(altitude {lo[0]:.0f}–{hi[0]:.0f} m, Mach {lo[1]:.2f}–{hi[1]:.2f}, throttle "
                    f"{lo[2]:.2f}–{hi[2]:.2f}); "
                    "extend the deck or build it with allow_extrapolation=True"
                )
        return pts

    def thrust(self, throttle, h, mach):
        return self._thrust(self._points(throttle, h, mach))

    def fuel_flow(self, throttle, h, mach):
        if self._ff is None:
            raise ValueError(f"{self.name}: no fuel-flow table")
        return self._ff(self._points(throttle, h, mach))


@dataclass
class ParametricTurbofan:
    """High-bypass turbofan scaled to its sea-level static thrust (N); see the module docstring."""

    static_thrust: float
    throttle_ratio: float = 1.0
    idle_fraction: float = 0.05

    def lapse(self, h, mach):
        return self.thrust(1.0, h, mach) / self.static_thrust  # full throttle: static thrust × lapse

    def thrust(self, throttle, h, mach):
        thr, h, mach = (np.asarray(a, dtype=float) for a in (throttle, h, mach))
        if not thr.shape == h.shape == mach.shape:  # (the simulations call this at every step with equal shapes)
            thr, h, mach = np.broadcast_arrays(thr, h, mach)
        isa._check_range(h)
        flat = [np.ascontiguousarray(a).reshape(-1) for a in (thr, h, mach)]
        return _turbofan_thrust(*flat, self.static_thrust, self.throttle_ratio, self.idle_fraction).reshape(h.shape)

    def kernel_parameters(self) -> np.ndarray:
        """(static thrust, throttle ratio, idle fraction): what compiled integrations need to give the thrust as
        :meth:`thrust_rows` does (:func:`certkit.models.dynamics.kernel.integrate_open_loop`)."""
        return np.array([self.static_thrust, self.throttle_ratio, self.idle_fraction], dtype=float)

    def thrust_rows(self, throttle, h, mach) -> np.ndarray:
        """Thrust (N) of several engines of this model at once: ``throttle`` (n, n_engines), ``h`` and ``mach`` (n,)
        per condition (the flight simulations call this at every step)."""
        thr = np.ascontiguousarray(throttle, dtype=float)
        h = np.ascontiguousarray(h, dtype=float)
        out = np.empty(thr.shape)
        if (
            _turbofan_thrust_rows(
                thr,
                h,
                np.ascontiguousarray(mach, dtype=float),
                self.static_thrust,
                self.throttle_ratio,
                self.idle_fraction,
                out,
            )
            >= 0
        ):
            isa._check_range(h)  # raises, naming the altitude
        return out

    def tsfc(self, h, mach):
        """Thrust-specific fuel consumption, kg/(N s)."""
        theta = isa.temperature(h) / isa.T0
        return (0.4 + 0.45 * np.asarray(mach, dtype=float)) * np.sqrt(theta) / 3600.0 / G0

    def fuel_flow(self, throttle, h, mach):
        return self.tsfc(h, mach) * self.thrust(throttle, h, mach)


@njit(cache=True, inline="always")
def _mattingly_lapse(d0, t0, m, throttle_ratio):
    """Mattingly's high-bypass installed-thrust lapse from δ0, θ0 and Mach (module docstring)."""
    base = 1.0 - 0.49 * math.sqrt(m)
    if t0 <= throttle_ratio:
        return d0 * base
    return d0 * (base - 3.0 * (t0 - throttle_ratio) / (1.5 + m))


@njit(cache=True, inline="always")
def _lapse_scalar(h, mach, throttle_ratio):
    m = max(mach, 0.0)
    t_air, p_air = isa_scalar(h)
    k = 1.0 + 0.2 * m * m
    return _mattingly_lapse(p_air / isa.P0 * k**3.5, t_air / isa.T0 * k, m, throttle_ratio)


@njit(cache=True)
def _hot_day_ratio(h, mach, delta_isa, throttle_ratio):
    out = np.empty(h.shape[0])
    for i in range(h.shape[0]):
        m = max(mach[i], 0.0)
        t_air, p_air = isa_scalar(h[i])
        k = 1.0 + 0.2 * m * m
        d0 = p_air / isa.P0 * k**3.5
        standard = _mattingly_lapse(d0, t_air / isa.T0 * k, m, throttle_ratio)
        hot = _mattingly_lapse(d0, (t_air + delta_isa[i]) / isa.T0 * k, m, throttle_ratio)
        out[i] = max(hot, 0.0) / standard if standard > 0.0 else 0.0
    return out


def temperature_thrust_ratio(h, mach, delta_isa, flat_rating_temperature: float) -> np.ndarray:
    """Full thrust on a day ISA + ``delta_isa`` (K) over the standard day's at the same pressure altitude ``h`` (m)
    and Mach number, for an engine flat-rated to the ambient ``flat_rating_temperature`` (K) at sea level static.

    Mattingly's lapse (module docstring) with the throttle ratio that puts its break there, TR = T_flat / T0 (θ0 =
    θ at M = 0, h = 0): 1 while the total temperature stays below the break (flat rating), then about 0.7 %/K
    static and 0.8 %/K at M 0.3 less. δ0 depends on pressure and Mach only, so it is the same on both days; the
    ratio multiplies the standard-day thrust of any engine model (a deck tabulated for ISA included)."""
    h, mach, dt = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (h, mach, delta_isa)))
    isa._check_range(h)
    flat = [np.ascontiguousarray(a).reshape(-1) for a in (h, mach, dt)]
    return _hot_day_ratio(*flat, flat_rating_temperature / isa.T0).reshape(h.shape)


@njit(cache=True)
def _turbofan_thrust(throttle, h, mach, static_thrust, throttle_ratio, idle_fraction):
    out = np.empty(h.shape[0])
    for i in range(h.shape[0]):
        thr = min(max(throttle[i], 0.0), 1.0)
        out[i] = (
            static_thrust * _lapse_scalar(h[i], mach[i], throttle_ratio) * (idle_fraction + (1.0 - idle_fraction) * thr)
        )
    return out


@njit(cache=True)
def _turbofan_thrust_rows(throttle, h, mach, static_thrust, throttle_ratio, idle_fraction, out):
    """:func:`_turbofan_thrust` for engines in columns, the lapse computed once per condition; returns the first
    condition whose altitude lies outside the modelled atmosphere (−1: none)."""
    for i in range(h.shape[0]):
        if h[i] < isa.H_MIN or h[i] > isa.H_MAX:
            return i
        turbofan_row_thrust(h[i], mach[i], throttle[i], static_thrust, throttle_ratio, idle_fraction, out[i])
    return -1


@njit(cache=True, inline="always")
def turbofan_row_thrust(h, mach, throttle, static_thrust, throttle_ratio, idle_fraction, out):
    """The parametric turbofan's thrust (N) of each engine of one condition into ``out``, ``throttle`` one entry
    per engine (clipped to 0–1): static thrust × lapse(h, M) × (idle + (1 − idle) × throttle). Compiled callers
    (:func:`_turbofan_thrust_rows`, the open-loop integration) share it."""
    lapse = static_thrust * _lapse_scalar(h, mach, throttle_ratio)
    for j in range(out.shape[0]):
        thr = min(max(throttle[j], 0.0), 1.0)
        out[j] = lapse * (idle_fraction + (1.0 - idle_fraction) * thr)


@dataclass(frozen=True)
class WindmillDrag:
    """``drag(qbar, mach) -> N`` of a failed turbofan of inlet diameter ``inlet_diameter`` (m) (module docstring)."""

    inlet_diameter: float
    velocity_ratio: float = 0.42

    def kernel_parameters(self) -> np.ndarray:
        """(0.0785 D_i², π/4 D_i², V_N/V): the arguments of :func:`windmill_drag_one` in compiled code."""
        d = self.inlet_diameter
        return np.array([0.0785 * d**2, np.pi / 4 * d**2, self.velocity_ratio], dtype=float)

    def __call__(self, qbar, mach):
        qbar, mach = np.broadcast_arrays(np.asarray(qbar, dtype=float), np.asarray(mach, dtype=float))
        flat = [np.ascontiguousarray(a).reshape(-1) for a in (qbar, mach)]
        return _windmill_drag_rows(*flat, self.kernel_parameters()).reshape(qbar.shape)


@njit(cache=True, inline="always")
def windmill_drag_one(qbar, mach, params):
    """Windmilling drag (N) at one condition; ``params`` from :meth:`WindmillDrag.kernel_parameters`."""
    r = params[2]
    return qbar * (params[0] + 2.0 / (1.0 + 0.16 * mach * mach) * params[1] * r * (1.0 - r))


@njit(cache=True, fastmath=False)  # explicit: not inherited from a fastmath caller
def _windmill_drag_rows(qbar, mach, params):
    out = np.empty(qbar.shape[0])
    for i in range(qbar.shape[0]):
        out[i] = windmill_drag_one(qbar[i], mach[i], params)
    return out


def windmill_drag(inlet_diameter: float, velocity_ratio: float = 0.42) -> WindmillDrag:
    """A ``windmill_drag(qbar, mach) -> N`` callable for a failed turbofan (module docstring)."""
    return WindmillDrag(float(inlet_diameter), float(velocity_ratio))


__all__ = [
    "EngineDeck",
    "DeckRangeError",
    "ParametricTurbofan",
    "temperature_thrust_ratio",
    "windmill_drag",
    "WindmillDrag",
]
