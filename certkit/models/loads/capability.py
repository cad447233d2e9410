"""Structural capability and the comparison of loads with it.

A capability is what the structure of one surface can carry at one station, for one load quantity:
the allowable **limit** load (no detrimental permanent deformation) and the allowable **ultimate**
load (no failure), each as a magnitude (the same in both senses) or as a (negative, positive) pair.
The comparison forms two margins, each ≥ 0 when the structure is adequate:

    limit margin    = allowable_limit − |limit load|
    ultimate margin = allowable_ultimate − factor × |limit load|

``factor`` is the factor of safety the rule passes in (the regulation's number lives in the rule).
:func:`declared_capabilities` reads them from the aircraft file's optional ``structure`` section
(:class:`certkit.aircraft.model.StructuralCapability`); the loads model adds the declared span
fractions to its load stations, so a declared station is always one the loads are computed at.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
import numpy.typing as npt
from numba import njit

from certkit.models.loads.model import QUANTITIES, station_label


@dataclass(frozen=True)
class Capability:
    surface: str
    station: str
    quantity: str  # shear, bending, torsion
    limit: float | tuple[float, float]  # N or N·m; (negative sense, positive sense) magnitudes if a pair
    ultimate: float | tuple[float, float]
    source: str = ""

    def allowable(self, which: str, sense: str) -> float:
        value = getattr(self, which)
        if isinstance(value, tuple):
            return float(value[1] if sense == "max" else value[0])
        return float(value)


@dataclass(frozen=True)
class LoadMargin:
    check: str  # "limit" or "ultimate"
    sense: str  # "max" or "min"
    load: float  # the design load compared (limit load, or factor × limit load), magnitude
    allowable: float
    margin: float


#: a surface's capabilities as arrays (:func:`_table`): rows, quantity and station indices, allowables, 1/|allowable|
CapabilityTable = tuple[
    tuple["Capability", ...],
    npt.NDArray[np.int64],
    npt.NDArray[np.int64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]


@lru_cache(maxsize=256)
def _table(capabilities: tuple[Capability, ...], surface: str, stations: tuple[str, ...]) -> CapabilityTable | None:
    """The capabilities of ``surface`` at ``stations`` as arrays: the rows, their station and quantity indices and the
    allowables (R, 4) in the order max limit, max ultimate, min limit, min ultimate (one table per capability set)."""
    rows = [
        (cap, stations.index(cap.station), QUANTITIES.index(cap.quantity))
        for cap in capabilities
        if cap.surface == surface and cap.station in stations
    ]
    if not rows:
        return None
    s = np.array([r[1] for r in rows])
    q = np.array([r[2] for r in rows])
    allow = np.array(
        [
            [cap.allowable(check, sense) for sense in ("max", "min") for check in ("limit", "ultimate")]
            for cap, *_ in rows
        ]
    )
    return tuple(r[0] for r in rows), q, s, allow, 1.0 / np.maximum(np.abs(allow), 1e-9)


#: tables of capability tuples by identity (each entry holds its tuple, so the identity stays its own): a rule passes
#: the same declared capabilities to each of its thousands of findings, and the table cache's key would hash every
#: capability of the tuple at each one
_BY_IDENTITY: dict[tuple[int, str, tuple[str, ...]], tuple[tuple[Capability, ...], CapabilityTable | None]] = {}


def _table_of(capabilities: Iterable[Capability], surface: str, stations: Sequence[str]) -> CapabilityTable | None:
    """:func:`_table` of the capabilities, looked up by identity for a tuple (immutable: the same object holds the
    same capabilities)."""
    stations = tuple(stations)
    if not isinstance(capabilities, tuple):
        return _table(tuple(capabilities), surface, stations)
    key = (id(capabilities), surface, stations)
    hit = _BY_IDENTITY.get(key)
    if hit is not None and hit[0] is capabilities:
        return hit[1]
    table = _table(capabilities, surface, stations)
    if len(_BY_IDENTITY) >= 256:
        _BY_IDENTITY.clear()
    _BY_IDENTITY[key] = (capabilities, table)
    return table


def worst_margin(
    capabilities: Iterable[Capability],
    surface: str,
    stations: Sequence[str],
    peaks: npt.ArrayLike,
    ultimate_factor: float,
) -> tuple[LoadMargin, Capability] | None:
    """The smallest normalised margin (margin / |allowable|) over the ``capabilities`` of ``surface`` at ``stations``
    for the loads ``peaks`` (2, 3, S: min and max), as (LoadMargin, Capability), or None when no capability applies.
    Each capability is compared in each loaded sense (max when the largest load is not ≤ 0, min when the smallest is
    not ≥ 0; a NaN load counts as loaded) at limit (|load|) and ultimate (factor × |load|), in that order; the first
    smallest wins (a NaN margin first in that order stays)."""
    table = _table_of(capabilities, surface, stations)
    if table is None:
        return None
    caps, q, s, allow, inv_scale = table
    i, j, load = _worst(np.ascontiguousarray(peaks, dtype=float), q, s, allow, inv_scale, float(ultimate_factor))
    return _margin(table, i, j, load)


def _margin(table: CapabilityTable, i: int, j: int, load: float) -> tuple[LoadMargin, Capability] | None:
    """The (LoadMargin, Capability) of row ``i``, column ``j`` of ``table`` (:func:`_worst`'s result; None: i < 0)."""
    if i < 0:
        return None
    a = float(table[3][i, j])
    return LoadMargin(("limit", "ultimate")[j % 2], ("max", "min")[j // 2], load, a, a - load), table[0][i]


def worst_state(
    capabilities: Iterable[Capability],
    surface: str,
    stations: Sequence[str],
    peaks_by_state: npt.ArrayLike,
    ultimate_factor: float,
) -> tuple[int, tuple[LoadMargin, Capability]] | None:
    """The state of ``peaks_by_state`` (M, 2, 3, S) whose :func:`worst_margin` is the smallest margin / max(|allowable|,
    10⁻⁹) — the first such, or the first whose normalised margin is NaN — and that margin; None when no state loads a
    capability. One compiled pass over the states (a fuel-state finding compares a handful per condition)."""
    table = _table_of(capabilities, surface, stations)
    if table is None:
        return None
    _, q, s, allow, inv_scale = table
    m, i, j, load = _worst_of_states(
        np.ascontiguousarray(peaks_by_state, dtype=float), q, s, allow, inv_scale, float(ultimate_factor)
    )
    found = _margin(table, i, j, load)
    return None if m < 0 or found is None else (m, found)


@njit(cache=True)
def _worst_of_states(peaks_by_state, q, s, allow, inv_scale, ultimate_factor):  # type: ignore[no-untyped-def]
    """:func:`worst_state`'s search: the state, row, column and load of the smallest margin / max(|allowable|, 10⁻⁹)
    over the states' :func:`_worst` margins (a NaN stops the search at its state), or (−1, −1, −1, 0)."""
    best_m, best_i, best_j, best_load, smallest = -1, -1, -1, 0.0, np.inf
    for m in range(peaks_by_state.shape[0]):
        i, j, load = _worst(peaks_by_state[m], q, s, allow, inv_scale, ultimate_factor)
        if i < 0:
            continue
        a = allow[i, j]
        norm = (a - load) / max(abs(a), 1e-9)
        if np.isnan(norm):
            return m, i, j, load
        if norm < smallest:
            best_m, best_i, best_j, best_load, smallest = m, i, j, load, norm
    return best_m, best_i, best_j, best_load


@njit(cache=True)
def _worst(peaks, q, s, allow, inv_scale, ultimate_factor):  # type: ignore[no-untyped-def]
    """:func:`worst_margin`'s search in compiled code (a design study makes thousands per design): the row and column
    (max limit, max ultimate, min limit, min ultimate) of the first smallest normalised margin and its load, or
    (−1, −1, 0) when no capability is loaded."""
    first_i = first_j = best_i = best_j = -1
    best, first_load, best_load = np.inf, 0.0, 0.0
    for i in range(q.shape[0]):
        hi, lo = peaks[1, q[i], s[i]], peaks[0, q[i], s[i]]
        for j in range(4):
            value = hi if j < 2 else lo
            if (j < 2 and value <= 0.0) or (j >= 2 and value >= 0.0):
                continue  # not loaded in that sense (a NaN load counts as loaded)
            load = abs(value) * ultimate_factor if j % 2 else abs(value)
            norm = (allow[i, j] - load) * inv_scale[i, j]
            if first_i < 0:
                first_i, first_j, first_load = i, j, load
                if np.isnan(norm):  # a NaN first in the order stays
                    return i, j, load
            if norm < best:  # the first smallest; a NaN after a number never wins
                best, best_i, best_j, best_load = norm, i, j, load
    if best_i < 0:  # none loaded (−1, −1, 0), or every margin infinite: the first stays
        return first_i, first_j, first_load
    return best_i, best_j, best_load


def declared_capabilities(ctx: Any, surface: str) -> tuple[Capability, ...]:
    """The capabilities of ``surface`` declared in the aircraft file (empty when none are)."""
    st = getattr(ctx.aircraft, "structure", None)
    out = []
    for c in getattr(st, surface) if st is not None else ():

        def value(v: Any) -> float | tuple[float, float]:
            return (float(v.negative), float(v.positive)) if hasattr(v, "negative") else float(v)

        out.append(
            Capability(surface, station_label(c.station), c.quantity, value(c.limit), value(c.ultimate), c.source)
        )
    return tuple(out)
