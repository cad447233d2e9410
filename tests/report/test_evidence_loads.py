"""The allowables a load envelope is drawn against (certkit/engine/evidence/loads.py): per sense, the smaller of the
declared
allowable limit load and the allowable ultimate load ÷ the §25.303 factor of safety — the load at which the first of
the two margins of certkit/models/loads/capability.py reaches zero. Reference: the baseline's declared wing and tail
capabilities (aircraft/lta.yaml `structure`, docs/baseline-sources.md §10) and 14 CFR 25.303 (factor 1.5)."""

import numpy as np
import pytest

from certkit.engine.evidence import Chart
from certkit.engine.evidence.loads import allowables, envelope_chart
from certkit.models.loads.capability import Capability, worst_margin


def test_governing_allowables_of_the_baseline(ctx):
    allow = allowables(ctx, 1.5)
    # wing root shear: limit 7,917 kN, ultimate 8,948 kN → 8,948 / 1.5 = 5,965.3 kN governs (both senses)
    assert allow["wing"][("root", "shear")] == pytest.approx((-8948e3 / 1.5, 8948e3 / 1.5), rel=1e-9)
    # horizontal-tail root bending: limit = ultimate = 7,366 kN·m → 7,366 / 1.5 = 4,910.7 kN·m
    assert allow["horizontal_tail"][("root", "bending")] == pytest.approx((-7366e3 / 1.5, 7366e3 / 1.5), rel=1e-9)
    # a factor of 1 leaves the limit allowable governing the wing root shear
    assert allowables(ctx, 1.0)["wing"][("root", "shear")] == pytest.approx((-7917e3, 7917e3), rel=1e-9)


def test_a_load_on_the_governing_allowable_has_zero_margin():
    """The drawn allowable is where worst_margin's smallest margin is zero (limit 100, ultimate 120, factor 1.5:
    the ultimate governs at 80)."""
    cap = Capability("wing", "root", "shear", 100.0, 120.0)
    peaks = np.zeros((2, 3, 1))
    peaks[1, 0, 0] = 80.0
    margin, _ = worst_margin([cap], "wing", ["root"], peaks, 1.5)
    assert margin.margin == pytest.approx(0.0, abs=1e-9) and margin.check == "ultimate"


def test_envelope_chart_draws_the_allowables_and_marks_the_critical_station():
    P = np.zeros((2, 2, 3, 2))  # conditions, sense, quantity, station
    P[:, 1, 0, :] = [[50.0, 40.0], [60.0, 30.0]]
    P[:, 0, 0, :] = [[-10.0, -5.0], [-20.0, -8.0]]
    chart = envelope_chart({"envelope": P}, ("root", "tip"), {("tip", "shear"): (-35.0, 35.0)})
    assert isinstance(chart, Chart) and chart.arrangement == "row"
    shear = chart.panels[0]
    labels = [s.label for s in shear.series]
    assert labels.count("allowable limit load") == 2
    assert shear.series[0].y.tolist() == [60.0, 40.0] and shear.series[1].y.tolist() == [-20.0, -8.0]
    # the tip's 40 against its allowable 35 is nearer than any other (the root has no allowable)
    (pt,) = shear.points
    assert (pt.x, pt.y) == (1.0, 40.0)


def test_a_zero_critical_load_names_no_condition():
    """Which of many exactly-zero loads is 'critical' is round-off (it differed between --jobs 1 and 2): not named."""
    from types import SimpleNamespace

    from certkit.engine.evidence.loads import case_table
    from certkit.models.loads.response import CriticalCase

    cases = [
        CriticalCase("vertical_tail", "root", "shear", "max", 0.0, "N", 1, 0.0),
        CriticalCase("vertical_tail", "root", "shear", "min", -131.1e3, "N", 0, 2.1),
    ]
    env = SimpleNamespace(critical_cases=lambda: cases, labels=["A", "B"], stations={"vertical_tail": ("root",)})
    rows = case_table(env, "vertical_tail").as_dicts()
    assert rows[0]["condition"].startswith("none") and rows[0]["time"] is None
    assert rows[1]["condition"] == "A" and rows[1]["load"] == pytest.approx(-131.1) and rows[1]["time"] == 2.1
