"""Condition spaces: §25.21(a) — each requirement must be met at each appropriate combination of
weight and centre of gravity within the range of loading conditions.

A rule declares a :class:`ConditionSpace`: a product of a loading axis (CG-envelope corners,
envelope weights, a design weight at its forward/reference/aft CG), configurations, altitudes,
speeds and named extra axes. The scheduler expands it against the aircraft, in a fixed order.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from certkit.aircraft.model import Aircraft, CgEnvelope
from certkit.atmosphere import from_tas, to_tas
from certkit.engine.results import Condition
from certkit.models.mass.loading import reference_cg

# --- CG envelope ---------------------------------------------------------------------------


def cg_limits_at(aircraft: Aircraft, mass: float) -> tuple[float, float]:
    """Forward and aft CG limits (m) of the envelope polygon at ``mass`` (kg)."""
    v = _envelope(aircraft).vertices
    xs, ms = np.array([p.x for p in v]), np.array([p.mass for p in v])
    crossings = []
    n = len(v)
    for i in range(n):
        x0, m0, x1, m1 = xs[i], ms[i], xs[(i + 1) % n], ms[(i + 1) % n]
        if m0 == m1:
            if abs(mass - m0) <= 1e-9 * max(1.0, m0):
                crossings += [x0, x1]
            continue
        t = (mass - m0) / (m1 - m0)
        if -1e-12 <= t <= 1 + 1e-12:
            crossings.append(x0 + t * (x1 - x0))
    if not crossings:
        raise ValueError(f"mass {mass:.0f} kg lies outside the CG envelope ({ms.min():.0f} to {ms.max():.0f} kg)")
    return min(crossings), max(crossings)


def _envelope(aircraft: Aircraft) -> CgEnvelope:
    """The declared weight–CG envelope (an input error names it where it is needed and absent)."""
    if aircraft.cg_envelope is None:
        raise ValueError("cg_envelope is not declared")
    return aircraft.cg_envelope


def inside_envelope(aircraft: Aircraft, mass: float, x_cg: float, tol: float = 1e-6) -> bool:
    try:
        fwd, aft = cg_limits_at(aircraft, mass)
    except ValueError:
        return False
    return fwd - tol <= x_cg <= aft + tol


# --- axes ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Loading:
    name: str
    mass: float
    x_cg: float


class LoadingAxis:
    def loadings(self, aircraft: Aircraft) -> list[Loading]:
        raise NotImplementedError

    def describe(self) -> str:
        raise NotImplementedError


@dataclass(frozen=True)
class CgCorners(LoadingAxis):
    """Every vertex of the weight–CG envelope polygon."""

    def loadings(self, aircraft: Aircraft) -> list[Loading]:
        vertices = _envelope(aircraft).vertices
        return [Loading(v.name or f"corner {i + 1}", v.mass, v.x) for i, v in enumerate(vertices)]

    def describe(self) -> str:
        return "every corner of the weight–CG envelope"


@dataclass(frozen=True)
class EnvelopeWeights(LoadingAxis):
    """Every distinct weight of the envelope, at the forward CG limit for that weight."""

    def loadings(self, aircraft: Aircraft) -> list[Loading]:
        vertices = _envelope(aircraft).vertices
        masses = sorted({v.mass for v in vertices})
        out: list[Loading] = []
        for m in masses:
            fwd, _ = cg_limits_at(aircraft, m)
            names = [v.name for v in vertices if v.mass == m and v.name]
            out.append(Loading(f"W{len(out) + 1}" + (f" ({'/'.join(names)})" if names else ""), m, fwd))
        return out

    def describe(self) -> str:
        return "every distinct weight of the weight–CG envelope (forward CG)"


_DESIGN_WEIGHTS = {"MTOW", "MLW", "MZFW", "MRW", "OEW"}


@dataclass(frozen=True)
class DesignWeight(LoadingAxis):
    """A design weight (MTOW, MLW, …) at chosen CG positions: forward limit, reference, aft limit."""

    weight: str = "MTOW"
    cgs: tuple[str, ...] = ("reference",)

    def loadings(self, aircraft: Aircraft) -> list[Loading]:
        mass = getattr(aircraft.mass, self.weight)
        if mass is None:
            raise ValueError(f"mass.{self.weight} is not declared")
        fwd, aft = cg_limits_at(aircraft, min(mass, max(v.mass for v in _envelope(aircraft).vertices)))
        where = {"forward": fwd, "aft": aft, "reference": min(max(reference_cg(aircraft), fwd), aft)}
        return [Loading(f"{self.weight} {c}", mass, where[c]) for c in self.cgs]

    def describe(self) -> str:
        return f"{self.weight} at the {', '.join(self.cgs)} CG"


@dataclass(frozen=True)
class EnvelopeAltitudes:
    """``n`` altitudes evenly from the envelope's minimum altitude to its ceiling (n from the file if None)."""

    n: int | None = None

    def values(self, aircraft: Aircraft) -> list[float]:
        env = aircraft.envelope
        if env is None:
            raise ValueError("envelope is not declared")
        return [float(h) for h in np.linspace(env.min_altitude, env.ceiling, self.n or env.altitude_points)]

    def describe(self) -> str:
        return "altitudes from the envelope minimum to the ceiling" + (f" ({self.n} points)" if self.n else "")


@dataclass(frozen=True)
class Altitudes:
    values_m: tuple[float, ...]

    def values(self, aircraft: Aircraft) -> list[float]:
        return list(self.values_m)

    def describe(self) -> str:
        return "altitudes " + ", ".join(f"{h:.0f} m" for h in self.values_m)


@dataclass(frozen=True)
class DeclaredSpeeds:
    """Declared speeds by name (``speeds.VC``, …), kept in the kind they were declared in."""

    names: tuple[str, ...]

    def values(self, aircraft: Aircraft) -> list[tuple[str, float, str]]:
        out = []
        for name in self.names:
            s = getattr(aircraft.speeds, name)
            if s is not None:
                out.append((name, s.value, s.kind))
        return out

    def describe(self) -> str:
        return "declared speeds " + ", ".join(self.names)


@dataclass(frozen=True)
class ConditionSpace:
    """The product of a loading axis, configurations, altitudes, speeds and named extra axes."""

    loading: LoadingAxis | None = None
    configurations: tuple[str, ...] | None = None
    altitudes: EnvelopeAltitudes | Altitudes | None = None
    speeds: DeclaredSpeeds | None = None
    extra: tuple[tuple[str, tuple[object, ...]], ...] = field(default=())
    note: str = ""

    def expand(self, aircraft: Aircraft) -> list[Condition]:
        loadings: list[Loading | None] = [*self.loading.loadings(aircraft)] if self.loading else [None]
        configs: list[str | None] = (
            [c for c in self.configurations if c in aircraft.configurations] if self.configurations else [None]
        )
        alts: list[float | None] = [*self.altitudes.values(aircraft)] if self.altitudes else [None]
        speeds: list[tuple[str, float, str] | None] = [*self.speeds.values(aircraft)] if self.speeds else [None]
        extra_names = [name for name, _ in self.extra]
        extra_values = [values for _, values in self.extra]
        out = []
        for ld, cfg, h, sp in itertools.product(loadings, configs, alts, speeds):
            for ex in itertools.product(*extra_values):
                out.append(
                    Condition.from_fields(
                        {
                            "loading": ld.name if ld else None,
                            "mass": ld.mass if ld else None,
                            "x_cg": ld.x_cg if ld else None,
                            "configuration": cfg,
                            "altitude": None if h is None else float(h),
                            "speed": sp[1] if sp else None,
                            "speed_kind": sp[2] if sp else None,
                            "speed_name": sp[0] if sp else None,
                            "extra": tuple(zip(extra_names, ex)),
                        }
                    )
                )
        return out

    def describe(self) -> str:
        parts = []
        if self.loading:
            parts.append(self.loading.describe())
        if self.configurations:
            parts.append("configurations " + ", ".join(self.configurations))
        if self.altitudes:
            parts.append(self.altitudes.describe())
        if self.speeds:
            parts.append(self.speeds.describe())
        for name, values in self.extra:
            parts.append(f"{name}: " + ", ".join(map(str, values)))
        text = "; ".join(parts) if parts else "the whole airplane (one condition)"
        return text + (f". {self.note}" if self.note else "")


def speed_as(condition: Condition, kind: str) -> float:
    """The condition's speed converted to ``kind`` at the condition's altitude (sea level if none)."""
    if condition.speed is None or condition.speed_kind is None:
        raise ValueError(f"the condition {condition.label()} has no speed")
    return _converted(float(condition.speed), condition.speed_kind, float(condition.altitude or 0.0), kind)


@lru_cache(maxsize=16384)
def _converted(speed: float, from_kind: str, h: float, kind: str) -> float:
    """One speed conversion, remembered: the rules convert the same few hundred speeds thousands of times per
    evaluation (a pure function of its arguments, so the cache returns exactly what the conversion would)."""
    return float(from_tas(to_tas(speed, from_kind, h), kind, h))
