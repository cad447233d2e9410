"""The smallest normalised margin against declared capabilities (:func:`certkit.models.loads.capability.worst_margin`),
hand-checked: margin = allowable − load at limit (|load|) and ultimate (factor × |load|), normalised by |allowable|;
and its table lookup: a tuple of capabilities is looked up by identity (the same tuple object, the same table), a
list afresh at each call, so a changed list or another tuple with other allowables gives its own margin; and the
state of several (fuel states) with the smallest margin, found in one compiled pass (:func:`worst_state`)."""

import numpy as np
import pytest

from certkit.models.loads.capability import Capability, worst_margin, worst_state

STATIONS = ("root", "mid")


def _peaks(root_shear: float) -> np.ndarray:
    peaks = np.zeros((2, 3, len(STATIONS)))
    peaks[1, 0, 0] = root_shear  # max shear at the root; every other load zero (not loaded)
    return peaks


def test_margin_by_hand():
    caps = (Capability("wing", "root", "shear", 100.0, 120.0), Capability("wing", "mid", "shear", 50.0, 60.0))
    m, cap = worst_margin(caps, "wing", STATIONS, _peaks(90.0), 1.5)
    # limit: (100 − 90)/100 = 0.10; ultimate: (120 − 135)/120 = −0.125 → the ultimate check governs
    assert cap is caps[0] and (m.check, m.sense) == ("ultimate", "max")
    assert (m.load, m.allowable, m.margin) == pytest.approx((135.0, 120.0, -15.0))


def test_tables_follow_the_capabilities_not_a_stale_cache():
    strong = (Capability("wing", "root", "shear", 200.0, 300.0),)
    weak = (Capability("wing", "root", "shear", 80.0, 300.0),)
    assert worst_margin(strong, "wing", STATIONS, _peaks(90.0), 1.5)[0].margin == pytest.approx(110.0)
    assert worst_margin(weak, "wing", STATIONS, _peaks(90.0), 1.5)[0].margin == pytest.approx(-10.0)
    assert worst_margin(strong, "wing", STATIONS, _peaks(90.0), 1.5)[0].margin == pytest.approx(110.0)
    listed = [Capability("wing", "root", "shear", 200.0, 300.0)]
    assert worst_margin(listed, "wing", STATIONS, _peaks(90.0), 1.5)[0].margin == pytest.approx(110.0)
    listed[0] = Capability("wing", "root", "shear", 80.0, 300.0)  # the same list, changed
    assert worst_margin(listed, "wing", STATIONS, _peaks(90.0), 1.5)[0].margin == pytest.approx(-10.0)
    # the same tuple with the stations in another order: its own table (the loads are read at their own stations)
    both = (Capability("wing", "root", "shear", 200.0, 300.0), Capability("wing", "mid", "shear", 50.0, 300.0))
    assert worst_margin(both, "wing", ("root", "mid"), _peaks(90.0), 1.5)[0].margin == pytest.approx(110.0)
    m, cap = worst_margin(both, "wing", ("mid", "root"), _peaks(90.0), 1.5)  # now the 90 is the mid station's shear
    assert cap is both[1] and m.margin == pytest.approx(-40.0)


def _state_by_state(caps, peaks_by_state):
    """The state a search over the states one by one picks (smallest margin / max(|allowable|, 1e-9), the first NaN)."""
    best, smallest = None, np.inf
    for j, peaks in enumerate(peaks_by_state):
        w = worst_margin(caps, "wing", STATIONS, peaks, 1.5)
        if w is None:
            continue
        norm = w[0].margin / max(abs(w[0].allowable), 1e-9)
        if np.isnan(norm):
            return j, w
        if norm < smallest:
            best, smallest = (j, w), norm
    return best


@pytest.mark.parametrize("seed", range(40))
def test_the_critical_state_is_the_one_a_state_by_state_search_picks(seed):
    """:func:`worst_state` (one compiled pass) against the states' :func:`worst_margin` one by one: the same state, the
    same margin and capability, bit for bit — with unloaded states, NaN loads and ties among them."""
    rng = np.random.default_rng(seed)
    caps = (
        Capability("wing", "root", "shear", 100.0, 150.0),
        Capability("wing", "root", "bending", (80.0, 120.0), (120.0, 180.0)),
        Capability("wing", "mid", "torsion", 40.0, 60.0),
    )
    states = rng.normal(0.0, 60.0, (int(rng.integers(1, 7)), 2, 3, len(STATIONS)))
    states[:, 0] = -np.abs(states[:, 0])  # the min below the max
    states[:, 1] = np.abs(states[:, 1])
    if seed % 4 == 1:
        states[rng.integers(len(states))] = 0.0  # a state that loads nothing
    if seed % 4 == 2:
        states[rng.integers(len(states)), 1, 0, 0] = np.nan
    if seed % 4 == 3:
        states[-1] = states[0]  # a tie: the first stays
    if seed % 8 == 0:
        states[:] = 0.0  # nothing loaded anywhere: no state
    want = _state_by_state(caps, states)
    got = worst_state(caps, "wing", STATIONS, states, 1.5)
    if want is None:
        assert got is None
        return
    assert got is not None and got[0] == want[0] and got[1][1] is want[1][1]
    assert got[1][0] == want[1][0] or (np.isnan(got[1][0].margin) and np.isnan(want[1][0].margin))
