"""A design's rules over two forked processes give the same record as in one process."""

from certkit.design.evaluate import evaluate_design
from certkit.design.parallel import shares
from certkit.engine.registry import DiscoveryOptions, discover, producers
from certkit.study.worker import canonical_json


def test_two_processes_give_the_same_record():
    values = {"geometry.horizontal_tail.area": "1150 ft^2", "geometry.horizontal_tail.taper": 0.3}
    wanted = ["rule.25.331*", "rule.25.17*", "subcheck.25.341(a).*", "sizing.*", "objective.OEW_kg"]
    one = evaluate_design("aircraft/lta.yaml", values, wanted, jobs=1)
    two = evaluate_design("aircraft/lta.yaml", values, wanted, jobs=2)
    for rec in (one, two):
        rec.pop("timings")
    assert canonical_json(one) == canonical_json(two)


def test_shares_balance_the_declared_costs():
    """Longest-processing-time order: heaviest first into the lighter group (costs 8, 5, 5, 4, 3, 2: 8 + 4 + 2 and
    5 + 5 + 3)."""
    loads = producers(discover(DiscoveryOptions()), "horizontal_tail")
    groups = shares(loads, 2)
    sums = sorted(sum(r.cost for r in g) for g in groups)
    assert sorted(r.id for g in groups for r in g) == sorted(r.id for r in loads)
    assert sums == [13, 14]
