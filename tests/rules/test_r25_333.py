"""§25.333 V–n envelope corners against hand calculation (n W = ½ ρ₀ V² S C_N)."""

import math

import pytest

from certkit.units import KN

from .helpers import run_rule
from .test_r25_335 import CN_OVER_CL, KT_FT, RHO0_SLUG, S_FT2


def test_corners_hand_calculation():
    r = run_rule("25.333")
    f = next(f for f in r.findings if f.check.startswith("A") and f.condition.altitude == 0.0
             and abs(f.condition.mass / 0.45359237 - 310_000) < 1)
    vs_pos = math.sqrt(2 * 310_000 / (RHO0_SLUG * S_FT2 * CN_OVER_CL * 1.4)) / KT_FT
    vs_neg = math.sqrt(2 * 310_000 / (RHO0_SLUG * S_FT2 * CN_OVER_CL * 0.8)) / KT_FT
    corners = f.details["corners"]
    assert corners["A"][0] / KN == pytest.approx(vs_pos * math.sqrt(2.5), rel=1e-4)
    assert corners["H"][0] / KN == pytest.approx(vs_neg * 1.0, rel=1e-4)
    assert corners["D"] == [pytest.approx(340 * KN, rel=1e-4), 2.5]
    assert corners["E"][1] == 0.0 and corners["F"] == [pytest.approx(272 * KN, rel=1e-4), -1.0]
    assert r.status == "complies"


def test_evidence_is_an_inline_svg():
    r = run_rule("25.333")
    assert r.evidence and r.evidence[0].svg.startswith("<svg")


def test_negative_stall_beyond_vc_fails(tmp_path):
    """A very small |CLmin| moves H beyond VC: the envelope does not close and the rule fails."""
    r = run_rule("25.333", tmp_path, [("CLmin: -0.8 ", "CLmin: -0.15 ")])
    assert r.status == "fails"
    assert any(f.check.startswith("H") and f.margin < 0 for f in r.findings)


def test_not_evaluated_without_negative_stall(tmp_path):
    r = run_rule("25.333", tmp_path, [("    CLmin: -0.8 ", "    # ")])
    assert r.status == "not_evaluated" and "configurations.clean.CLmin" in r.findings[0].reason
