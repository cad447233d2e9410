"""The horizontal-tail load envelope the structure is sized for, from the Subpart C rules' own runs.

Every rule that declares it produces station loads of the ``horizontal_tail`` (``Rule.produces``; the pitch
manoeuvres, discrete gusts and rolling conditions of the built-in rules) keeps the load envelopes of its conditions;
this module reduces them to the largest limit-load magnitude of each quantity (shear, bending, torsion) at each
station of the tail, with the rule and condition that set it (the loads engineer's critical-case list), and the factor
of safety those rules hold in force (ultimate = factor × limit).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from certkit.engine.results import Condition, RuleResult
from certkit.models.loads.model import QUANTITIES

SURFACE = "horizontal_tail"


@dataclass
class CriticalLoad:
    quantity: str
    station: str
    limit_load: float  # N or N·m, signed as the loads model signs it
    rule: str
    condition: str


#: the criterion by which a loads rule states its factor of safety (ultimate load / limit load)
ULTIMATE_FACTOR = "ultimate_factor"


@dataclass
class TailLoadEnvelope:
    """Largest limit-load magnitudes (3, n_stations) at the tail's stations over every loads rule's conditions."""

    stations: tuple[str, ...]
    limit: np.ndarray
    critical: list[CriticalLoad] = field(default_factory=list)
    rules: tuple[str, ...] = ()
    #: the factor of safety (ultimate / limit) the structure is sized with: the largest the rules that computed
    #: these loads hold in force (their ``ultimate_factor`` criterion, overridable in the aircraft file; a rule
    #: that declares none has its loads carried with the others')
    ultimate_factor: float | None = None

    def exceeds(self, other: "TailLoadEnvelope", rtol: float = 1e-9) -> bool:
        """True when any load of this envelope is larger than ``other``'s (same stations)."""
        return bool(np.any(self.limit > other.limit * (1.0 + rtol) + 1e-9))

    def union(self, other: "TailLoadEnvelope | None") -> "TailLoadEnvelope":
        """The larger of the two envelopes at every station and quantity (critical cases from whichever is larger)."""
        if other is None:
            return self
        take_self = self.limit >= other.limit
        crit = [c for c in self.critical if take_self[QUANTITIES.index(c.quantity), self.stations.index(c.station)]]
        crit += [
            c for c in other.critical if not take_self[QUANTITIES.index(c.quantity), other.stations.index(c.station)]
        ]
        return TailLoadEnvelope(
            self.stations,
            np.where(take_self, self.limit, other.limit),
            crit,
            tuple(sorted(set(self.rules) | set(other.rules))),
            max(self.ultimate_factor or 0.0, other.ultimate_factor or 0.0) or None,
        )

    def as_dict(self) -> dict[str, object]:
        return {
            "stations": list(self.stations),
            "limit_loads": {q: [float(v) for v in self.limit[i]] for i, q in enumerate(QUANTITIES)},
            "units": {"shear": "N", "bending": "N·m", "torsion": "N·m"},
            "critical": [vars(c) for c in self.critical],
            "rules": list(self.rules),
            "ultimate_factor": self.ultimate_factor,
        }


def tail_load_envelope(results: Iterable[RuleResult]) -> TailLoadEnvelope:
    """Reduce the kept envelopes of evaluated loads rules (:class:`certkit.engine.results.RuleResult` with
    ``load_envelopes``) to the tail's limit-load magnitudes. Raises ``ValueError`` when no rule computed tail loads
    (the structure cannot be sized: the caller reports why)."""
    stations: tuple[str, ...] | None = None
    best = np.zeros((0, 0))
    crit: dict[tuple[int, int], CriticalLoad] = {}
    rules: set[str] = set()
    factors: list[float] = []
    for res in results:
        for env in res.load_envelopes:
            if SURFACE not in env.peaks:
                continue
            factor = (res.criteria.get(ULTIMATE_FACTOR) or {}).get("value")
            if factor is not None:
                factors.append(float(factor))
            P = env.peaks[SURFACE]  # (n, 2, 3, S): min [0] / max [1] over time
            if stations is None:
                stations, best = tuple(env.stations[SURFACE]), np.zeros((len(QUANTITIES), P.shape[-1]))
            elif tuple(env.stations[SURFACE]) != stations:
                raise ValueError(f"rule {res.id}: tail stations {env.stations[SURFACE]} differ from {stations}")
            rules.add(res.id)
            mag = np.abs(np.nan_to_num(P, nan=0.0))  # (n, 2, 3, S)
            for q in range(len(QUANTITIES)):
                for s in range(len(stations)):
                    flat = mag[:, :, q, s]
                    i, sense = np.unravel_index(int(np.argmax(flat)), flat.shape)
                    if flat[i, sense] > best[q, s]:
                        best[q, s] = flat[i, sense]
                        crit[(q, s)] = CriticalLoad(
                            QUANTITIES[q],
                            stations[s],
                            float(P[i, sense, q, s]),
                            res.id,
                            env.labels[i] if i < len(env.labels) else str(i),
                        )
    if stations is None:
        raise ValueError(
            "no loads rule computed horizontal-tail loads (the rules that declare them were not "
            "evaluated or could not trim any condition)"
        )
    if not factors:
        raise ValueError(
            f"no rule computing horizontal-tail loads ({', '.join(sorted(rules))}) declares an {ULTIMATE_FACTOR!r} "
            "criterion: the factor of safety the structure is to carry them with is unknown"
        )
    return TailLoadEnvelope(stations, best, [crit[k] for k in sorted(crit)], tuple(sorted(rules)), max(factors))


def near_critical_conditions(
    results: list[RuleResult], fraction: float, own_fraction: float = 1.0
) -> dict[str, list[Condition] | None]:
    """Per loads rule id, the conditions whose tail load reaches ``fraction`` of the envelope over every rule
    (:func:`tail_load_envelope`), or ``own_fraction`` of the rule's own largest, at some station and quantity —
    as the rule's envelopes name them (their ``keys``); a rule whose envelopes do not name their conditions maps to
    None (all of them). The start of a design's sizing loop evaluates these points only
    (:mod:`certkit.design.sizing_loop`): each rule's own critical cases stay in, as a changed tail can make a
    case critical that was not for the declared one."""
    best = tail_load_envelope(results).limit[None, None]  # (1, 1, 3, S)
    out: dict[str, list[Condition] | None] = {}
    for res in results:
        envs = [e for e in res.load_envelopes if SURFACE in e.peaks]
        if not envs:
            continue
        if any(len(e.keys) != len(e.labels) for e in envs):
            out[res.id] = None
            continue
        mags = [np.abs(np.nan_to_num(e.peaks[SURFACE], nan=0.0)) for e in envs]  # each (n, 2, 3, S)
        own = np.max([m.max(axis=(0, 1)) for m in mags], axis=0)[None, None]
        chosen: list[Condition] = []
        out[res.id] = chosen
        for env, mag in zip(envs, mags):
            near = np.any((mag >= fraction * best) | (mag >= own_fraction * own), axis=(1, 2, 3))
            chosen += [env.keys[i] for i in np.flatnonzero(near) if env.keys[i] not in chosen]
    return out
