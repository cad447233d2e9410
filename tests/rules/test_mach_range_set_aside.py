"""Rolling (§25.349(a)), unsymmetrical gust (§25.349(b)) and yaw (§25.351) conditions beyond the Mach range of the
aerodynamic and strip-loads tables are set aside with the reason, never extrapolated: an airplane declaring MD 0.97
(beyond the highest breakpoint the lattice is solved at, 0.95, so its tables end at the default 0.90)."""

import pytest
from certkit_rules.part25.support.structural_checks import condition_mach

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.registry import discover
from certkit.engine.scheduler import evaluate_rule

from .helpers import MACH_RANGE, edited_baseline

EDITS = [("altitude_points: 5", "altitude_points: 2"), ("MD: 0.94", "MD: 0.97")]


@pytest.fixture(scope="module")
def ctx(tmp_path_factory):
    return Context(load_aircraft(edited_baseline(tmp_path_factory.mktemp("mach"), EDITS)))


@pytest.mark.parametrize("rule_id", ["25.349(a)", "25.349(b)", "25.351"])
def test_beyond_the_tables_is_set_aside(ctx, rule_id):
    (rule,) = [r for r in discover() if r.id == rule_id]
    findings = [f for f in evaluate_rule(rule, ctx).findings if f.condition.speed is not None]
    beyond = [f for f in findings if condition_mach(f.condition) > 0.90 + 1e-3]
    within = [f for f in findings if condition_mach(f.condition) <= 0.90 + 1e-3]
    assert beyond and within
    assert all(f.status == "not_evaluated" and MACH_RANGE in f.reason for f in beyond)
    assert not any(MACH_RANGE in (f.reason or "") for f in within)
