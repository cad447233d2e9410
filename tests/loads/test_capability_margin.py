"""The smallest normalised margin against declared capabilities (:func:`certkit.models.loads.capability.worst_margin`),
hand-checked: margin = allowable − load at limit (|load|) and ultimate (factor × |load|), normalised by |allowable|;
and its table lookup: a tuple of capabilities is looked up by identity (the same tuple object, the same table), a
list afresh at each call, so a changed list or another tuple with other allowables gives its own margin."""

import numpy as np
import pytest

from certkit.models.loads.capability import Capability, worst_margin

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
