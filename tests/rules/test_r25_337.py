"""§25.337 against hand calculation of 2.1 + 24,000/(W + 10,000) bounded to [2.5, 3.8]."""

import pytest
from certkit_rules.part25.subpart_c.r25_337 import required_positive_load_factor

from certkit.units import LB

from .helpers import run_rule


@pytest.mark.parametrize(
    "w_lb,expected",
    [
        (656_000, 2.5),  # 2.1 + 24000/666000 = 2.136 -> floor 2.5
        (5_000, 2.1 + 24000 / 15000),  # 3.7, inside the bounds
        (3_000, 3.8),  # 3.946 -> cap 3.8
        (50_000, 2.5),  # exactly 2.5 at 50,000 lb
    ],
)
def test_formula_hand_values(w_lb, expected):
    assert required_positive_load_factor(w_lb * LB, 2.1, 24000, 10000, 2.5, 3.8) == pytest.approx(expected, rel=1e-12)


def test_baseline_on_the_limit():
    """Baseline declares n+ = 2.5 and n- = -1.0: both margins are exactly 0 and comply."""
    r = run_rule("25.337")
    assert r.status == "complies"
    assert {round(f.margin, 12) for f in r.findings} == {0.0}
    assert len(r.findings) == 2 * 4  # two checks at each of the 4 envelope weights


def test_sign_lower_factors_fail(tmp_path):
    r = run_rule("25.337", tmp_path, [("positive: 2.5 ", "positive: 2.4 "), ("negative: -1.0", "negative: -0.9")])
    assert r.status == "fails"
    margins = {f.check: f.margin for f in r.findings}
    assert margins["(b) positive limit load factor"] == pytest.approx(-0.1)
    assert margins["(c)(1) negative limit load factor up to VC"] == pytest.approx(-0.1)


def test_not_evaluated_without_load_factors(tmp_path):
    r = run_rule(
        "25.337",
        tmp_path,
        [
            (
                "  limit_load_factors:\n    positive: 2.5              # [given]\n    negative: -1.0\n    "
                "flaps_extended: 2.0\n",
                "",
            )
        ],
    )
    assert r.status == "not_evaluated" and "envelope.limit_load_factors" in r.findings[0].reason
