"""The aircraft file's optional ``structure`` section: SI conversion by quantity, every problem with its
path, and the loads rules' comparison with the declared capabilities (§25.303: ultimate = 1.5 × limit;
§25.305: limit load without permanent deformation, ultimate without failure).
"""

import textwrap

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.errors import InputError
from certkit.models.loads.capability import declared_capabilities
from certkit.units import FT, LB

from ..conftest import BASELINE
from ..rules.helpers import NO_STRUCTURE, own

STRUCTURE = textwrap.dedent("""\
    structure:
      horizontal_tail:
        - {station: root, quantity: shear, limit: 250 kN, ultimate: 400 kN, source: "test allowable"}
        - {station: 0.6, quantity: bending, limit: "300000 lbf*ft", ultimate: {negative: 700 kN*m, positive: 500 kN*m},
           source: "test allowable"}
      vertical_tail:
        - {station: root, quantity: shear, limit: {negative: 1 MN, positive: 1.2 MN}, ultimate: 1.8 MN, source: "test"}
    sources:
    """)


def with_structure(tmp_path, structure=STRUCTURE):
    """The baseline with its own structure section replaced by ``structure``."""
    text = BASELINE.read_text().replace(NO_STRUCTURE[0], "", 1).replace("\nsources:\n", "\n" + structure, 1)
    path = tmp_path / "structure.yaml"
    path.write_text(text)
    return path


def test_values_in_si_and_capabilities(tmp_path):
    a = load_aircraft(with_structure(tmp_path)).model
    ht = a.structure.horizontal_tail
    assert ht[0].limit == pytest.approx(250e3) and ht[0].ultimate == pytest.approx(400e3)
    assert ht[1].station == 0.6 and ht[1].limit == pytest.approx(300000 * LB * 9.80665 * FT)
    assert ht[1].ultimate.negative == pytest.approx(700e3) and ht[1].ultimate.positive == pytest.approx(500e3)
    caps = declared_capabilities(Context(load_aircraft(with_structure(tmp_path))), "horizontal_tail")
    assert [(c.station, c.quantity) for c in caps] == [("root", "shear"), ("60% span", "bending")]
    assert caps[1].allowable("ultimate", "min") == pytest.approx(700e3)  # negative sense: download
    assert caps[1].allowable("ultimate", "max") == pytest.approx(500e3)
    fin = declared_capabilities(Context(load_aircraft(with_structure(tmp_path))), "vertical_tail")
    assert fin[0].limit == (pytest.approx(1e6), pytest.approx(1.2e6))
    bare = tmp_path / "bare.yaml"
    bare.write_text(BASELINE.read_text().replace(NO_STRUCTURE[0], "", 1))
    assert load_aircraft(bare).model.structure is None
    assert declared_capabilities(Context(load_aircraft(bare)), "wing") == ()
    assert {c.station for c in declared_capabilities(Context(load_aircraft(BASELINE)), "wing")} == {
        "root",
        "side of body",
    }


def test_problems_reported_with_paths(tmp_path):
    bad = textwrap.dedent("""\
        structure:
          wing:
            - {station: root, quantity: bending, limit: 100 kN, ultimate: 200 kN, source: "wrong unit"}
            - {station: 1.5, quantity: shear, limit: 100 kN, ultimate: 200 kN, source: "beyond the tip"}
          horizontal_tail:
            - {station: root, quantity: shear, limit: 300 kN, ultimate: 200 kN, source: "ultimate below limit"}
            - {station: 0.0, quantity: shear, limit: 100 kN, ultimate: 200 kN, source: "root again"}
          vertical_tail:
            - {station: side_of_body, quantity: torsion, limit: 1 MN*m, ultimate: 2 MN*m, source: "no such"}
        sources:
        """)
    with pytest.raises(InputError) as info:
        load_aircraft(with_structure(tmp_path, bad))
    paths = {p.path: p.message for p in info.value.problems}
    assert "not a moment" in paths["structure.wing.0.limit"]
    assert any(p.startswith("structure.wing.1.station") for p in paths)
    # relations between fields need the section valid on its own: fix the wing and ask again
    fixed = bad.replace(
        'limit: 100 kN, ultimate: 200 kN, source: "wrong unit"', 'limit: 1 MN*m, ultimate: 2 MN*m, source: "fixed"'
    )
    fixed = fixed.replace("station: 1.5", "station: 0.5")
    with pytest.raises(InputError) as info:
        load_aircraft(with_structure(tmp_path, fixed))
    paths = {p.path: p.message for p in info.value.problems}
    assert "below the limit allowable" in paths.get("structure.horizontal_tail.0.ultimate", ""), paths
    assert "already declared" in paths["structure.horizontal_tail.1"]
    assert "no side-of-body" in paths["structure.vertical_tail.0.station"]


def test_pitch_rule_compares_with_declared_tail_capability(tmp_path):
    """§25.331(c)(1) on the baseline (sea level and ceiling) with a declared tailplane capability: each
    finding's margin is the smaller normalised of (limit allowable − |limit load|) and (ultimate allowable
    − 1.5 × |limit load|) over the declared root shear (250/400 kN) and 60 %-span bending items, formed
    here by hand from the loads the finding reports (rounded to 0.1 kN, tolerance 0.2 kN(·m) × 1.5)."""
    text = with_structure(tmp_path).read_text().replace("altitude_points: 5", "altitude_points: 2")
    path = tmp_path / "two.yaml"
    path.write_text(text)
    from certkit.engine.registry import discover, select
    from certkit.engine.scheduler import evaluate_rule

    (rule,) = [r for r in select(discover(), ("25.331(c)(1)",)) if r.id == "25.331(c)(1)"]
    result = evaluate_rule(rule, Context(load_aircraft(path)))
    tail = [f for f in own(result) if ", wing" not in f.check]  # the wing's findings: tests/rules/test_r25_331_wing.py
    assert tail and all(f.status in ("complies", "fails") for f in tail)
    bend_lim = 300000 * LB * 9.80665 * FT
    for f in tail:
        d = f.all_details()
        assert "60% span bending max/min (kN·m)" in d
        candidates = []
        for key, lim, ult, unit in (
            ("root shear max/min (kN)", (250e3, 250e3), (400e3, 400e3), "shear at root"),
            ("60% span bending max/min (kN·m)", (bend_lim, bend_lim), (700e3, 500e3), "bending at 60% span"),
        ):
            hi, lo = d[key]
            for sense, load, k in (("max", hi * 1e3, 1), ("min", lo * 1e3, 0)):
                if (sense == "max" and load <= 0) or (sense == "min" and load >= 0):
                    continue
                candidates.append(((lim[k] - abs(load)) / lim[k], lim[k] - abs(load), f"limit {unit} ({sense})"))
                candidates.append(
                    ((ult[k] - 1.5 * abs(load)) / ult[k], ult[k] - 1.5 * abs(load), f"ultimate {unit} ({sense})")
                )
        _, margin, check = min(candidates)
        assert f.margin == pytest.approx(margin, abs=300.0)
        assert check in f.check
        assert (f.status == "complies") == (f.margin >= 0)


def test_not_evaluated_without_capability_for_the_surface(tmp_path):
    """A capability declared for the fin only leaves the tailplane findings not evaluated, with the reason
    (the rule path without any ``structure`` section is tests/rules/test_r25_331.py)."""
    import numpy as np
    from certkit_rules.part25.support.structural_checks import NO_CAPABILITY, capability_finding

    from certkit.engine.results import Condition

    structure = "structure:\n  vertical_tail:" + STRUCTURE.split("  vertical_tail:")[1]
    ctx = Context(load_aircraft(with_structure(tmp_path, structure)))
    caps = declared_capabilities(ctx, "horizontal_tail")
    assert caps == () and len(declared_capabilities(ctx, "vertical_tail")) == 1
    f = capability_finding(Condition(loading="x"), "test", "horizontal_tail", np.ones((2, 3, 1)), ("root",), caps, 1.5)
    assert f.status == "not_evaluated" and f.reason == NO_CAPABILITY
