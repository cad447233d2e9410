"""§25.341(a) lateral gusts on the fin in the rule: one finding per loading, altitude and speed point against the
declared fin capability, not evaluated without it, and a deficient fin fails."""

import pytest
from certkit_rules.part25.subpart_c.r25_341 import DiscreteGust

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.scheduler import evaluate_rule
from certkit.models.loads.capability import declared_capabilities

from .helpers import BASELINE, edited_baseline, hand_margin, in_mach_range, own

FAST = [
    ("altitude_points: 5", "altitude_points: 2"),
    (
        "\nsources:\n",
        '\ncriteria:\n  "25.341(a)":\n    justification: "two gradients keep the test fast"\n'
        '    values: {gradients: "30 350"}\nsources:\n',
    ),
]


def _fin_section(text: str) -> str:
    start = text.index("  vertical_tail:\n", text.index("\nstructure:\n"))
    end = text.index("\nsizing:\n", start) + 1
    return text[start:end]


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    ctx = Context(load_aircraft(edited_baseline(tmp_path_factory.mktemp("lat"), FAST)))
    return ctx, evaluate_rule(DiscreteGust, ctx)


def _lateral(res):
    return [f for f in res.findings if f.condition.get("gust") == "lateral"]


def test_one_lateral_finding_per_entry_with_margins_by_hand(result):
    ctx, res = result
    lateral = _lateral(res)
    entries = {
        (f.condition.loading, f.condition.altitude, f.condition.get("speed_point"))
        for f in res.findings
        if f.condition.get("gust") == "up"
    }
    assert len(lateral) == len(entries)
    assert {(f.condition.loading, f.condition.altitude, f.condition.get("speed_point")) for f in lateral} == entries
    caps = declared_capabilities(ctx, "vertical_tail")
    lateral = in_mach_range(lateral)
    for f in lateral:
        assert f.all_details()["root shear max/min (kN)"][0] == pytest.approx(
            -f.all_details()["root shear max/min (kN)"][1]
        )
        norm, margin, _ = hand_margin(f.all_details(), caps)
        assert f.normalized_margin == pytest.approx(norm, abs=5e-5)
    assert all(f.status == "complies" for f in lateral)  # the fin is sized by §25.351 on the baseline
    env = res.run.lateral_envelope if res.run else None
    assert env is None or set(env.peaks) == {"vertical_tail"}


def test_without_fin_capability_not_evaluated(tmp_path):
    text = BASELINE.read_text()
    ctx = Context(load_aircraft(edited_baseline(tmp_path, FAST + [(_fin_section(text), "")])))
    res = evaluate_rule(DiscreteGust, ctx)
    lateral = in_mach_range(_lateral(res))
    assert lateral and all(
        f.status == "not_evaluated" and "no structural capability declared" in f.reason for f in lateral
    )
    assert all("root shear max/min (kN)" in f.all_details() for f in lateral)
    assert all(f.status != "not_evaluated" for f in in_mach_range(own(res)) if f.condition.get("gust") != "lateral")


def test_a_weak_fin_fails(tmp_path):
    """Deficient airplane: the fin root shear allowable cut to 100 kN (the lateral gusts shear it by about 230 kN at
    VC): every lateral finding fails against exactly that allowable."""
    weak = FAST + [
        ("quantity: shear, limit: 5022 kN, ultimate: 5022 kN", "quantity: shear, limit: 100 kN, ultimate: 100 kN")
    ]
    ctx = Context(load_aircraft(edited_baseline(tmp_path, weak)))
    lateral = in_mach_range(_lateral(evaluate_rule(DiscreteGust, ctx)))
    assert lateral and all(
        f.status == "fails" and f.limit == pytest.approx(100e3) and "shear at root" in f.check for f in lateral
    )
