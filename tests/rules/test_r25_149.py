"""§25.149 minimum control speed.

Hand calculation of the VMCA search on a grid (linear interpolation where the control usage
|δ|/δ_limit crosses 1), and the rule on the baseline: VMCA against 1.13 VSR, with VSR = √(2W/(ρ0 S CLmax))
in lb, ft, slug (656,000 lb, 4927.3 ft², takeoff CLmax of the model) to 0.1 %.
"""

import math

import numpy as np
import pytest

from certkit_rules.part25.subpart_b.r25_149 import vmca_from_grid

from .helpers import run_rule


@pytest.fixture(scope="module")
def result():
    return run_rule("25.149")


def test_grid_interpolation_hand_calculation():
    """Usage 1.4 at 100 kt and 0.8 at 110 kt: crossing at 100 + 0.4/0.6·10 = 106.67 kt."""
    assert vmca_from_grid([90, 100, 110, 120], [2.0, 1.4, 0.8, 0.5]) == pytest.approx(106.6667, abs=1e-3)
    assert vmca_from_grid([90, 100], [0.9, 0.5]) is None  # controllable everywhere: below the grid


def test_on_the_limit():
    """Usage exactly 1 at a grid speed: VMCA is that speed (margin 0 there)."""
    assert vmca_from_grid([90, 100, 110], [1.5, 1.0, 0.7]) == pytest.approx(100.0)


def test_sign_more_usage_raises_vmca():
    lo = vmca_from_grid([90, 100, 110], [1.5, 1.2, 0.7])
    hi = vmca_from_grid([90, 100, 110], [1.5, 1.2, 0.9])
    assert hi > lo


def test_baseline_vsr_and_vmc_not_declared(result, ctx):
    c = next(f for f in result.findings if f.check.startswith("(c)"))
    clmax = ctx.clmax("takeoff")
    vsr_kn = math.sqrt(2 * 656_000 / (0.0023769 * 4927.3 * clmax)) / 1.6878099
    assert c.details["VSR"] / 0.514444 == pytest.approx(vsr_kn, rel=1e-3)
    assert c.limit == pytest.approx(1.13 * c.details["VSR"], rel=1e-9)
    assert (c.margin >= 0) == (c.status == "complies") and np.isfinite(c.value)
    b = next(f for f in result.findings if f.check.startswith("(b)"))
    assert b.status == "not_evaluated" and b.reason == "needs speeds.VMC"


def test_not_evaluated_without_takeoff_clmax(tmp_path):
    r = run_rule("25.149", tmp_path, edits=[("    CLmax: 1.95 ", "    #CLmax: 1.95 ")])
    assert r.status == "not_evaluated" and "configurations.takeoff.CLmax" in r.findings[0].reason
