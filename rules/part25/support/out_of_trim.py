"""The §25.255 out-of-trim condition as §25.331(a)(2) asks the manoeuvre loads to consider it (regulation content, no
rule here): "The in-trim and out-of-trim flight conditions specified in § 25.255 must be considered" (text from the
current eCFR via law.cornell.edu, docs/regulation-notes.md). From a trim at cruise speeds up to VMO/MMO, the
stabiliser moved nose up and nose down by three seconds of the trim system's normal rate, except as limited by the
trim system's stops (§25.255(a)(1)), and held. Shared by the balanced (§25.331(b)) and checked (§25.331(c)(2))
manoeuvres.
"""

from __future__ import annotations

from certkit.engine.registry import Criterion

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
    return float(ctx.design_speed_eas(name, h)[0])
