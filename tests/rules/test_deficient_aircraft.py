"""Every rule can fail: the baseline made deficient in one respect at a time — speeds below the §25.335
minima, a limit load factor below §25.337(b), half the thrust, a horizontal tail or a fin too small, control design
limits of ±2°, structure at 5 % of its declared capability — and each rule whose inputs the deficiency affects is run
(``--select`` style subsets) and must report "fails". The thresholds are the paragraphs' own (cited per case); the
deficiencies are gross so that the verdict does not hang on model detail.

Rules already failing on the baseline show their failure path there (§25.125, §25.143(h), §25.161, §25.181, see
`certkit check aircraft/lta.yaml`, and each rule's own deficient-airplane test); §25.107(e)(1)(iv) fails on the baseline
at the forward CG (its declared VR, docs/baseline-sources.md §14b) and tests/rules/test_r25_107_vlof.py fails it at
every CG with a lower tail-strike attitude; §25.107(c)(2) fails on the baseline (its declared V2 below the 35-ft
speed, §14b), and tests/rules/test_r25_107_v35.py fails its (e)(1)(iii) with a V2 the takeoff cannot reach;
§25.107(e)(3) complies on the baseline and tests/rules/test_r25_107_early_rotation.py fails it with less thrust and a
lower VR; §25.107(g)(2) fails on the baseline (its VFTO, the (g)(1) minimum, inside the stall warning of the 40°
turn), and tests/rules/test_r25_107_vfto_turn.py passes it with a higher VFTO;
§25.111 fails on the baseline (its rudder beyond the ±23.2° design limit, docs/baseline-sources.md §14a), and
tests/rules/test_r25_111.py fails it with a ±15° rudder too; §25.113 needs a declared takeoff field length, and
tests/rules/test_r25_113.py fails it with one and 30 % less thrust; §25.173(b)/(c) need a control-force model the
baseline does not declare (tests/rules/test_control_forces.py runs them with one).
"""

import re

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.registry import discover
from certkit.engine.scheduler import evaluate_rule

from .helpers import VA_SCHEDULE, VB_SCHEDULE, edited_baseline, own

TWO_ALTITUDES = ("altitude_points: 5", "altitude_points: 2")


def _scaled_structure(text: str, factor: float) -> str:
    """The baseline's ``structure:`` allowables (kN, kN*m) times ``factor``."""
    start = text.index("\nstructure:\n")
    end = text.index("\nsources:\n", start)
    section = re.sub(
        r"(\d+(?:\.\d+)?) (kN\*m|kN)\b", lambda m: f"{float(m.group(1)) * factor:.1f} {m.group(2)}", text[start:end]
    )
    return text[:start] + section + text[end:]


SPEEDS = [
    (VA_SCHEDULE, "  VA: 200 kn EAS\n"),
    (VB_SCHEDULE, "  VB: 180 kn EAS\n"),
    ("  VD: 340 kn EAS", "  VD: 330 kn EAS"),
    ("  V2: 161 kn CAS", "  V2: 155 kn CAS"),
    ("  VREF: 136 kn CAS", "  VREF: 136 kn CAS\n  VSR: {takeoff: 141 kn CAS}"),
]

#: case: (edits, whether the structure is scaled to 5 %, the rules that must fail). Deficiencies that do not interact
#: share one aircraft (one aerodynamic model each) to keep the file affordable.
CASES = {
    # §25.335(c) VA ≥ VS1√n (265.2 KEAS at MRW), §25.333 corner A, §25.335(d) VB ≥ VS1√n_g (225.1 KEAS),
    # §25.335(b) VC ≤ 0.8 VD (272 > 0.8 × 330), §25.103 VSR ≥ 1-g stall speed (declared 141 < 142.0 kn takeoff),
    # §25.107(b)(1) V2 ≥ 1.13 VSR (155 < 1.13 × 141 = 159.3 kn); §25.337(b) n₊ ≥ 2.5 (2.3 declared);
    # §25.305 the structure at 5 % of its declared allowables, far below every limit load
    "speeds, load factor and structure below the paragraphs' minima": (
        SPEEDS + [("    positive: 2.5 ", "    positive: 2.3 ")],
        True,
        (
            "25.103",
            "25.107",
            "25.333",
            "25.335(b)",
            "25.335(c)",
            "25.335(d)",
            "25.337",
            "25.331(b)",
            "25.331(c)(1)",
            "25.331(c)(2)",
            "25.341(a)",
            "25.341(b)",
            "25.345(a)(2)",
            "25.349(a)",
            "25.349(b)",
            "25.351",
            "25.427(b)",
        ),
    ),
    # §25.335(a) VC ≥ VB + 1.32 U_ref: 272 < 240 + 43.8
    "VB too close to VC": ([(VB_SCHEDULE, "  VB: 240 kn EAS\n")], False, ("25.335(a)",)),
    # §25.121: half the thrust, one engine out, cannot hold the minimum gradients; a 450 ft² stabiliser (from
    # 1,119.2): the neutral point moves ahead of the aft CG limit (§25.171, §25.173(a))
    "half the thrust and a horizontal tail too small": (
        [
            ("  static_thrust: 97300 lbf", "  static_thrust: 48650 lbf"),
            ("    area: 1119.2 ft^2 ", "    area: 450 ft^2 "),
        ],
        False,
        ("25.121(a)", "25.121(b)", "25.121(c)", "25.121(d)", "25.171", "25.173(a)"),
    ),
    # a 150 ft² fin (from 527.84): directionally unstable (§25.177), VMCA above 1.13 VSR (§25.149); ±2° design
    # limits on elevator and rudder: the trims of §25.145(b) and §25.147 need more, and so do §25.255's 1.5 g pull-ups
    # and 0 g push-overs out of trim (the baseline's stabiliser trim rate, 0.25 deg/s)
    "a fin too small and control design limits of ±2°": (
        [
            ("    area: 527.84 ft^2 ", "    area: 150 ft^2 "),
            ("design_limits: {min: -21.8 deg, max: 16.8 deg}", "design_limits: {min: -2 deg, max: 2 deg}"),
            ("design_limits: {min: -23.2 deg, max: 23.2 deg}", "design_limits: {min: -2 deg, max: 2 deg}"),
        ],
        False,
        ("25.177", "25.149", "25.145(b)", "25.147(a)", "25.147(c)", "25.255"),
    ),
}

RULES = {r.id: r for r in discover()}


def test_every_rule_is_exercised_or_explained():
    """Each registered rule is in a deficient case, already fails on the baseline, or needs an absent model."""
    covered = {rid for *_, ids in CASES.values() for rid in ids}
    explained = {
        "25.107(c)(2)",
        "25.107(e)(1)(iv)",
        "25.107(e)(3)",
        "25.107(g)(2)",
        "25.111",
        "25.113",
        "25.125",
        "25.143(h)",
        "25.161",
        "25.181",
        "25.173(b)",
        "25.173(c)",
    }
    assert set(RULES) <= covered | explained, sorted(set(RULES) - covered - explained)


@pytest.mark.parametrize("case", list(CASES), ids=list(CASES))
def test_deficient_aircraft_fails(case, tmp_path):
    edits, scaled, rule_ids = CASES[case]
    path = edited_baseline(tmp_path, [TWO_ALTITUDES, *edits])
    if scaled:
        path.write_text(_scaled_structure(path.read_text(), 0.05))
    ctx = Context(load_aircraft(path))
    for rid in rule_ids:
        result = evaluate_rule(RULES[rid], ctx, evidence=False)
        assert result.status == "fails", (rid, [(f.check, f.status, f.reason) for f in own(result)][:5])
        assert all(f.margin < 0 for f in own(result) if f.status == "fails")
