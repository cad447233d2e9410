"""Wing fuel on the strips of the loads model: where each declared tank's fuel lies along the span.

A wing tank fills the wing box between the |y| of its bay's inboard and outboard ends. Its fuel per unit span
follows the box's cross-section, which at a constant thickness ratio scales as the square of the local chord
(box area ∝ width × depth ∝ c · (t/c) c); each strip gets the fuel of its part of the bay, in proportion to
c_j² × (the strip's width inside the bay). Without declared ends the bay runs from the side of body outboard to
the station where the fuel's centroid is the tank's declared centroid (|y| of ``cg``) — or, when even a bay to the
tip has its centroid inboard of the declared one, from the station that puts it there to the tip (a main tank
outboard of a centre tank that takes the inboard wing, as on the 777) — so that the tank's moment about any
station inboard of it is exactly its declared mass × arm. A tank whose centroid is on the plane of
symmetry (a centre tank) lies inboard of the side of body, half on each side. A partly filled tank keeps the
shape of the full one (its fuel scaled), and the fuel's X is the strips' reference axis (the box's middle).

The strips are those of one half of a mirrored surface (the right half, +y): a tank on the left (y < 0) is the
mirror of one on the right and loads the left half only.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from certkit.aircraft.model import Aircraft

Floats = npt.NDArray[np.float64]


def _weights(y1: Floats, y2: Floats, chord: Floats, a: float, b: float) -> tuple[Floats, Floats]:
    """Each strip's volume weight (chord² × its span inside [a, b]) and the centre of that part."""
    lo, hi = np.minimum(y1, y2), np.maximum(y1, y2)
    overlap = np.clip(np.minimum(hi, b) - np.maximum(lo, a), 0.0, None)
    w = chord**2 * overlap
    centre = 0.5 * (np.clip(lo, a, b) + np.clip(hi, a, b))
    return w, centre


def _centroid(y1: Floats, y2: Floats, chord: Floats, a: float, b: float) -> float:
    w, centre = _weights(y1, y2, chord, a, b)
    return float(np.sum(w * centre) / np.sum(w)) if np.sum(w) > 0 else a


def tank_strip_shares(
    y1: npt.ArrayLike,
    y2: npt.ArrayLike,
    chord: npt.ArrayLike,
    tank_y: float,
    side_of_body: float,
    y_inboard: float | None = None,
    y_outboard: float | None = None,
) -> tuple[Floats, str | None]:
    """Fraction of one tank's fuel on each strip of the right half of the wing (strips between |y| ``y1`` and ``y2``,
    chord ``chord``), and a note when the declared centroid cannot be honoured. The fractions sum to 1 for a tank
    on the right, ½ for a centre tank, 0 for a tank on the left."""
    y1, y2, chord = (np.asarray(v, dtype=np.float64) for v in (y1, y2, chord))
    tip = float(np.max(np.maximum(y1, y2)))
    if tank_y < -1e-6:
        return np.zeros_like(chord), None
    if abs(tank_y) <= 1e-6:
        a = 0.0 if y_inboard is None else y_inboard
        b = side_of_body if y_outboard is None else y_outboard
        w, _ = _weights(y1, y2, chord, a, b)
        return 0.5 * w / w.sum(), None
    a = y_inboard if y_inboard is not None else (side_of_body if side_of_body < tank_y else 0.0)
    note = None
    if y_outboard is not None:
        b = y_outboard
    elif _centroid(y1, y2, chord, a, tip) < tank_y:
        b = tip
        if y_inboard is None:  # the bay from the side of body is too far inboard: it starts further out
            lo, hi = a, tank_y
            for _ in range(60):  # the centroid grows with the inboard end: bisection
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if _centroid(y1, y2, chord, mid, tip) < tank_y else (lo, mid)
            note = (
                f"a bay from the side of body ({a:.2f} m) to the tip has its centroid at "
                f"{_centroid(y1, y2, chord, a, tip):.2f} m, inboard of the declared {tank_y:.2f} m: the bay is "
                f"taken from {0.5 * (lo + hi):.2f} m to the tip"
            )
            a = 0.5 * (lo + hi)
        else:
            note = (
                f"the declared centroid |y| {tank_y:.2f} m is outboard of the bay from {a:.2f} m to the tip "
                f"(centroid {_centroid(y1, y2, chord, a, tip):.2f} m): the tank fills the bay to the tip"
            )
    else:
        lo, hi = tank_y, tip
        for _ in range(60):  # the centroid grows with the outboard end: bisection
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if _centroid(y1, y2, chord, a, mid) < tank_y else (lo, mid)
        b = 0.5 * (lo + hi)
    w, _ = _weights(y1, y2, chord, a, b)
    return w / w.sum(), note


def wing_tank_shares(
    aircraft: Aircraft, y1: npt.ArrayLike, y2: npt.ArrayLike, chord: npt.ArrayLike, side_of_body: float
) -> tuple[tuple[str, ...], Floats, list[str]]:
    """Every declared tank's strip fractions (:func:`tank_strip_shares`): names, (K, J) array, notes."""
    names, rows, notes = [], [], []
    for t in aircraft.mass.fuel_tanks:
        share, note = tank_strip_shares(y1, y2, chord, float(t.cg.y), side_of_body, t.y_inboard, t.y_outboard)
        names.append(t.name)
        rows.append(share)
        if note:
            notes.append(f"fuel tank {t.name}: {note}")
    return tuple(names), np.array(rows).reshape(len(rows), np.size(chord)), notes
