"""The §25.255 out-of-trim condition as §25.331(a)(2) asks the manoeuvre loads to consider it (regulation content, no
rule here): "The in-trim and out-of-trim flight conditions specified in § 25.255 must be considered" (text from the
current eCFR via law.cornell.edu, docs/regulation-notes.md). From a trim at cruise speeds up to VMO/MMO, the
stabiliser moved nose up and nose down by three seconds of the trim system's normal rate, except as limited by the
trim system's stops (§25.255(a)(1)), and held. Shared by the balanced (§25.331(b)) and checked (§25.331(c)(2))
manoeuvres.
"""

from __future__ import annotations

import math

from certkit.engine.registry import Criterion
from certkit.models.flight import control_limits
from certkit.units import KN

#: the out-of-trim senses: the sign of the stabiliser's movement (leading edge up positive) — nose up is leading edge
#: down; the same words as the checked manoeuvres' directions
MISTRIMS = {"nose up": -1.0, "nose down": 1.0}

MISTRIM_SECONDS = Criterion(
    3.0,
    "s",
    "14 CFR 25.331(a)(2) (the out-of-trim conditions of §25.255), 25.255(a)(1) ([CFR 2003] GPO text)",
    "out-of-trim stabiliser movement: this many seconds at the trim system's normal rate, within its trim limits",
)


def mistrim_rate(aircraft) -> float | None:
    """The movable stabiliser's declared trim rate (rad/s), None without one (no out-of-trim conditions)."""
    g = aircraft.geometry
    st = g.horizontal_tail.stabilizer if g is not None else None
    return None if st is None or st.rate is None else float(st.rate)


def no_mistrim(what: str) -> str:
    """The not-evaluated reason of ``what`` out of trim without a declared trim rate."""
    return (
        f"the out-of-trim {what} (§25.331(a)(2), the §25.255 mistrim) are not evaluated: they need a movable "
        "stabiliser with its trim rate (geometry.horizontal_tail.stabilizer.rate)"
    )


def out_of_trim_speed(ctx, h: float) -> float:
    """EAS (m/s) up to which §25.255(a) trims the airplane at ``h``: VMO/MMO, else VC/MC where VMO is not declared
    (VMO may not exceed VC, §25.1505)."""
    name = "VMO" if ctx.aircraft.speeds.VMO is not None else "VC"
    return ctx.design_speed_eas_at(name, h)


def mistrim(ctx, reference_stabilizer: float, sense: str, configuration: str, crit) -> tuple[float, bool]:
    """(the held stabiliser deflection in rad, whether the trim limit stopped it): the reference trim's setting moved
    by ``mistrim_seconds`` of the declared rate in the sense ``sense``, within ``configuration``'s trim limits."""
    lo, hi = control_limits(ctx.aircraft, configuration=configuration)["stabilizer"]
    wanted = reference_stabilizer + MISTRIMS[sense] * float(crit.mistrim_seconds) * float(
        mistrim_rate(ctx.aircraft) or 0.0
    )
    return float(min(max(wanted, lo), hi)), not lo <= wanted <= hi


def mistrim_note(sense: str, trim_speed_eas: float, moved: float, limited: bool, then: str) -> str:
    """The finding's account of an out-of-trim condition: where the stabiliser was trimmed, how far it moved, and
    ``then`` (what the elevator does)."""
    return (
        f"out of trim {sense}: the stabiliser of the 1 g trim at {trim_speed_eas / KN:.1f} kn EAS moved "
        f"{math.degrees(moved):+.2f}° (§25.255(a)(1)"
        + (", stopped by the trim limit)" if limited else ")")
        + f", held; {then}"
    )
