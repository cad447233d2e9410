"""MIL-F-8785C (5 Nov 1980) flying-qualities levels for Class III airplanes, as data.

Part 25 states no numeric damping or time-constant requirement; certkit reports the military
specification's Level (1 best, 3 worst; 4 = worse than Level 3) of each rigid-body mode as a
reference reading, and uses one of its numbers (short-period ζ ≥ 0.35, Level 1 category A/C) as the
numeric reading of §25.181(a)'s "heavily damped" (overridable in the aircraft file).

Every limit carries its paragraph number. ``verified`` is False for every row: the values come from
docs/regulation-notes.md §6 — R. C. Nelson, *Flight Stability and Automatic Control* (2nd ed.),
Tables 10.1–10.3, as reproduced secondarily, and from memory of the specification (marked ``mem``
in the note) — and have not been checked against the specification's text.

Flight-phase categories (MIL-F-8785C 1.3): A non-terminal phases needing rapid manoeuvring or precise
tracking (cruise manoeuvring), B gradual non-terminal phases (climb, cruise, descent), C terminal
phases (takeoff, approach, landing).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

SOURCE = (
    "MIL-F-8785C (1980), Class III, as reproduced in Nelson, Flight Stability and Automatic Control, "
    "Tables 10.1-10.3, and docs/regulation-notes.md §6 (UNVERIFIED against the specification)"
)

#: flight-phase category of each certkit configuration
CATEGORY = {"takeoff": "C", "approach": "C", "landing": "C", "clean": "B"}


@dataclass(frozen=True)
class Limit:
    """One boundary of one Level: ``quantity`` of ``mode`` must be ≥ (``bound`` "min") or ≤ ("max") ``value``."""

    mode: str
    quantity: str  # zeta, zeta_wn (rad/s), wn (rad/s), tau (s), t_double (s), cap ((rad/s²)/g)
    categories: str  # the categories it applies to, e.g. "AC"
    level: int
    bound: str  # "min" or "max"
    value: float
    unit: str
    paragraph: str
    verified: bool = False
    note: str = ""


_T4 = "3.2.2.1.2 Table IV"
_T6 = "3.3.1.1 Table VI"
_T7 = "3.3.1.2 Table VII"
_T8 = "3.3.1.3 Table VIII"
_PH = "3.2.1.2"
_CAP = "3.2.2.1.1 (Figs. 1-3, lines of constant ω²/(n/α))"
#: the unit of the control anticipation parameter ω_sp²/(n/α)
CAP_UNIT = "(rad/s²)/g"

LIMITS: tuple[Limit, ...] = (
    # short-period damping ratio, Table IV (mem)
    Limit("short_period", "zeta", "AC", 1, "min", 0.35, "", _T4, note="mem"),
    Limit("short_period", "zeta", "AC", 1, "max", 1.30, "", _T4, note="mem"),
    Limit("short_period", "zeta", "B", 1, "min", 0.30, "", _T4, note="mem"),
    Limit("short_period", "zeta", "B", 1, "max", 2.00, "", _T4, note="mem"),
    Limit("short_period", "zeta", "AC", 2, "min", 0.25, "", _T4, note="mem"),
    Limit("short_period", "zeta", "B", 2, "min", 0.20, "", _T4, note="mem"),
    Limit("short_period", "zeta", "ABC", 2, "max", 2.00, "", _T4, note="mem"),
    Limit("short_period", "zeta", "ABC", 3, "min", 0.15, "", _T4, note="mem"),
    # short-period frequency as the control anticipation parameter, 3.2.2.1.1 (mem); read only where the condition's
    # n/α is known (the rule's trim), never from a surrogate of ω alone
    Limit("short_period", "cap", "A", 1, "min", 0.28, CAP_UNIT, _CAP, note="mem"),
    Limit("short_period", "cap", "B", 1, "min", 0.085, CAP_UNIT, _CAP, note="mem"),
    Limit("short_period", "cap", "C", 1, "min", 0.16, CAP_UNIT, _CAP, note="mem"),
    Limit("short_period", "cap", "ABC", 1, "max", 3.6, CAP_UNIT, _CAP, note="mem"),
    Limit("short_period", "cap", "A", 2, "min", 0.16, CAP_UNIT, _CAP, note="mem"),
    Limit("short_period", "cap", "B", 2, "min", 0.038, CAP_UNIT, _CAP, note="mem"),
    Limit("short_period", "cap", "C", 2, "min", 0.096, CAP_UNIT, _CAP, note="mem"),
    Limit("short_period", "cap", "ABC", 2, "max", 10.0, CAP_UNIT, _CAP, note="mem"),
    # phugoid, 3.2.1.2 (mem)
    Limit("phugoid", "zeta", "ABC", 1, "min", 0.04, "", _PH, note="mem"),
    Limit("phugoid", "zeta", "ABC", 2, "min", 0.0, "", _PH, note="mem"),
    Limit("phugoid", "t_double", "ABC", 3, "min", 55.0, "s", _PH, note="mem; time to double of an unstable phugoid"),
    # Dutch roll, Table VI (Nelson Table 10.2)
    Limit("dutch_roll", "zeta", "A", 1, "min", 0.19, "", _T6),
    Limit("dutch_roll", "zeta_wn", "A", 1, "min", 0.35, "rad/s", _T6),
    Limit("dutch_roll", "zeta", "BC", 1, "min", 0.08, "", _T6),
    Limit("dutch_roll", "zeta_wn", "BC", 1, "min", 0.15, "rad/s", _T6),
    Limit("dutch_roll", "wn", "ABC", 1, "min", 0.4, "rad/s", _T6),
    Limit("dutch_roll", "zeta", "ABC", 2, "min", 0.02, "", _T6),
    Limit("dutch_roll", "zeta_wn", "ABC", 2, "min", 0.05, "rad/s", _T6),
    Limit("dutch_roll", "wn", "ABC", 2, "min", 0.4, "rad/s", _T6),
    Limit(
        "dutch_roll",
        "zeta",
        "ABC",
        3,
        "min",
        0.0,
        "",
        _T6,
        note="mem; Nelson's reproduction is ambiguous (may read 0.02)",
    ),
    Limit("dutch_roll", "wn", "ABC", 3, "min", 0.4, "rad/s", _T6),
    # roll-mode time constant, Table VII (Nelson Table 10.1)
    Limit("roll", "tau", "ABC", 1, "max", 1.4, "s", _T7),
    Limit("roll", "tau", "ABC", 2, "max", 3.0, "s", _T7),
    Limit("roll", "tau", "ABC", 3, "max", 10.0, "s", _T7),
    # spiral, minimum time to double amplitude, Table VIII (Nelson Table 10.3); a convergent spiral meets every level
    Limit("spiral", "t_double", "ABC", 1, "min", 20.0, "s", _T8),
    Limit("spiral", "t_double", "ABC", 2, "min", 12.0, "s", _T8),
    Limit("spiral", "t_double", "ABC", 3, "min", 4.0, "s", _T8),
)


@lru_cache(maxsize=None)
def limits_for(mode: str, category: str, level: int) -> tuple[Limit, ...]:
    """The boundaries a mode must meet for ``level`` in ``category`` (one scan of the table per combination)."""
    return tuple(lim for lim in LIMITS if lim.mode == mode and category in lim.categories and lim.level == level)


def quantities(mode, n_alpha: float | None = None) -> dict[str, float]:
    """The quantities the tables bound, from a :class:`certkit.models.dynamics.modes.Mode` (and, for the control
    anticipation parameter ω²/(n/α), the condition's ``n_alpha`` in g/rad; without it the CAP is not read).

    An unstable (divergent) mode has an infinite time constant and a finite time to double; a
    convergent one an infinite time to double."""
    sigma = mode.eigenvalue.real
    out = {
        "zeta": mode.damping_ratio,
        "wn": mode.natural_frequency,
        "zeta_wn": mode.damping_ratio * mode.natural_frequency,
        "tau": 1.0 / -sigma if sigma < 0 else np.inf,
        "t_double": mode.time_to_double if mode.time_to_double is not None else np.inf,
    }
    if n_alpha is not None and n_alpha > 0:
        out["cap"] = mode.natural_frequency**2 / n_alpha
    return out


def _meets(lim: Limit, q: dict):
    """Whether the quantities ``q`` (scalars or arrays) meet the boundary ``lim`` (boolean, or an array of them);
    a quantity ``q`` does not hold (the CAP without n/α) bounds nothing."""
    if lim.quantity not in q:
        return True
    value = q[lim.quantity]
    return value >= lim.value if lim.bound == "min" else value <= lim.value


def categories_of(configuration: str) -> tuple[str, ...]:
    """MIL-F-8785C flight-phase categories read for a configuration: clean is both cruise manoeuvring (A) and
    cruise (B); flaps or gear extended are terminal phases (C)."""
    return ("A", "B") if CATEGORY.get(configuration, "B") == "B" else ("C",)


def _time(value) -> np.ndarray:
    """A time to half or double amplitude as an array: None or NaN (the mode does not converge, or diverge) → ∞."""
    out = np.asarray(np.nan if value is None else value, dtype=float)
    return np.where(np.isfinite(out), out, np.inf)


def level_from_quantities(mode_name: str, category: str, *, zeta, wn, t_half=None, t_double=None, cap=None):
    """The MIL-F-8785C Level (1 best, 3 worst, 4 worse than Level 3) of a mode from its quantities — the damping
    ratio ``zeta``, undamped natural frequency ``wn`` (rad/s), time to half amplitude ``t_half`` (s; None, NaN or
    ∞ when the mode does not converge) and time to double ``t_double`` (s; likewise when it does not diverge) —
    in flight-phase ``category``: the best Level whose every boundary of :data:`LIMITS` they meet (the roll-mode
    time constant is t_half / ln 2) and, given, the short period's control anticipation parameter ``cap``
    ((rad/s²)/g; None: not read). Scalars give an int; arrays (e.g. surrogate predictions of the quantities)
    an int array of their broadcast shape."""
    zeta, wn = np.asarray(zeta, dtype=float), np.asarray(wn, dtype=float)
    q = {"zeta": zeta, "wn": wn, "zeta_wn": zeta * wn, "tau": _time(t_half) / np.log(2.0), "t_double": _time(t_double)}
    if cap is not None:
        q["cap"] = np.asarray(cap, dtype=float)
    shape = np.broadcast_shapes(*(np.shape(v) for v in q.values()))
    level = np.full(shape, 4)
    for lv in (3, 2, 1):
        met = np.ones(shape, dtype=bool)
        for lim in limits_for(mode_name, category, lv):
            met &= np.asarray(_meets(lim, q), dtype=bool)
        level = np.where(met, lv, level)
    return int(level) if level.ndim == 0 else level


def configuration_level(mode_name: str, configuration: str, **quantities):
    """The worst of :func:`level_from_quantities` over the flight-phase categories a configuration is read in
    (:func:`categories_of`): the level a design record gives for ``level.<mode>.<corner>.<configuration>``."""
    levels = [level_from_quantities(mode_name, cat, **quantities) for cat in categories_of(configuration)]
    out = np.maximum.reduce([np.asarray(v) for v in levels])
    return int(out) if np.ndim(out) == 0 else out


def _times(zeta, wn) -> dict[str, np.ndarray]:
    """Times to half and to double amplitude from the damping ratio and natural frequency: the root's real part is
    σ = −ζ·ω_n for an oscillatory and a real root alike (:mod:`certkit.models.dynamics.modes`), so
    t_half = ln 2/(ζω_n) when it converges, t_double = ln 2/(−ζω_n) when it diverges (∞ otherwise)."""
    sigma = -np.asarray(zeta, dtype=float) * np.asarray(wn, dtype=float)
    with np.errstate(divide="ignore"):
        return {
            "t_half": np.where(sigma < 0, np.log(2.0) / -sigma, np.inf),
            "t_double": np.where(sigma > 0, np.log(2.0) / sigma, np.inf),
        }


def damping_level(mode_name: str, configuration: str, *, zeta, wn, cap=None):
    """:func:`configuration_level` from the damping ratio ``zeta``, natural frequency ``wn`` (rad/s) and, for the
    short period, the control anticipation parameter ``cap`` alone (the times to half and double follow from ζω_n):
    the level a design record gives, from surrogates of the quantities it also records."""
    return configuration_level(mode_name, configuration, zeta=zeta, wn=wn, cap=cap, **_times(zeta, wn))


def damping_level_margin(mode_name: str, configuration: str, level: int, *, zeta, wn, cap=None) -> np.ndarray:
    """How far a mode lies inside ``level`` in ``configuration``: over the configuration's flight-phase categories
    the least, over the levels up to ``level`` the greatest, of the least relative distance to that level's
    boundaries ((q − v)/|v| for a minimum, (v − q)/|v| for a maximum; the distance itself at v = 0). It is ≥ 0
    exactly where :func:`damping_level` ≤ ``level`` and continuous in the quantities, so an optimiser can hold a
    handling-quality level as an inequality (±∞ where a quantity is unbounded, e.g. no divergence)."""
    zeta, wn = np.asarray(zeta, dtype=float), np.asarray(wn, dtype=float)
    q = {"zeta": zeta, "wn": wn, "zeta_wn": zeta * wn}
    times = _times(zeta, wn)
    q["tau"], q["t_double"] = times["t_half"] / np.log(2.0), times["t_double"]
    if cap is not None:
        q["cap"] = np.asarray(cap, dtype=float)
    shape = np.broadcast_shapes(*(np.shape(v) for v in q.values()))
    out = np.full(shape, np.inf)
    for category in categories_of(configuration):
        best = np.full(shape, -np.inf)
        for lv in range(1, min(level, 3) + 1):
            inside = np.full(shape, np.inf)
            for lim in limits_for(mode_name, category, lv):
                if lim.quantity not in q:
                    continue
                scale = abs(lim.value) or 1.0
                d = q[lim.quantity] - lim.value if lim.bound == "min" else lim.value - q[lim.quantity]
                inside = np.minimum(inside, d / scale)
            best = np.maximum(best, inside)
        if level >= 4:
            best = np.full(shape, np.inf)
        out = np.minimum(out, best)
    return out


def level_of(mode_name: str, mode, category: str, n_alpha: float | None = None) -> tuple[int, str]:
    """(level, reason): the best Level whose every boundary the mode meets (4 = worse than Level 3),
    and the first boundary it misses at the next better Level (the CAP read with the condition's ``n_alpha``)."""
    q = quantities(mode, n_alpha)
    missed = ""
    for level in (1, 2, 3):
        bounds = limits_for(mode_name, category, level)
        failed = [lim for lim in bounds if not _meets(lim, q)]
        if not failed:
            return level, missed
        if not missed:
            lim = failed[0]
            missed = (
                f"Level {level} needs {lim.quantity} {'≥' if lim.bound == 'min' else '≤'} {lim.value:g}"
                f"{' ' + lim.unit if lim.unit else ''} (MIL-F-8785C {lim.paragraph}), has {q[lim.quantity]:.3g}"
            )
    return 4, missed


def table_rows() -> list[dict]:
    """The limits as report rows."""
    return [
        {
            "mode": lim.mode,
            "quantity": lim.quantity,
            "categories": lim.categories,
            "level": lim.level,
            "bound": lim.bound,
            "value": lim.value,
            "unit": lim.unit,
            "paragraph": f"MIL-F-8785C {lim.paragraph}",
            "verified": lim.verified,
            "note": lim.note,
        }
        for lim in LIMITS
    ]
