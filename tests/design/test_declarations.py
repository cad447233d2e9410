"""Rules tell the design layer what they produce (``Rule.produces``) and offer (``Rule.offers``): a rule written
outside certkit joins the horizontal-tail sizing loop, and its mode responses reach the design record, by its
declarations alone (no edit of certkit/design)."""

import numpy as np
import pytest

from certkit.design import evaluate
from certkit.design.sizing_loop import sizing_rules
from certkit.engine.conditions import CgCorners, ConditionSpace
from certkit.engine.registry import (
    DiscoveryOptions,
    Loads,
    ModeResponses,
    PluginError,
    Rule,
    SimulationRule,
    discover,
    rule,
)
from certkit.engine.results import Condition, Finding, LoadsRun
from certkit.models.loads.model import QUANTITIES, airplane_loads
from certkit.models.loads.response import LoadEnvelope

#: the plugin's limit torsion at the tail's 75 %-span station, N·m (the baseline's own loads reach 86.5 kN·m there)
BUFFET_TORSION = 150e3


@rule
class TailBuffetLoads(SimulationRule):
    """A plugin's tail load case: a fixed torsion at the 75 %-span station at every CG corner."""

    id = "25.251(b)"
    symbol = "tail-buffet-loads"
    title = "Tail buffet loads (test plugin)"
    amendment = "25-0"
    requirement = "A test rule."
    margin = "Declared allowable − torsion."
    criteria = {}
    conditions = ConditionSpace(loading=CgCorners(), configurations=("clean",))
    produces = (Loads("horizontal_tail"),)

    def simulate(self, ctx, conditions, crit):
        tail = airplane_loads(ctx)["horizontal_tail"]
        stations = tuple(tail.station_names)
        peaks = np.zeros((len(conditions), 2, len(QUANTITIES), len(stations)))
        peaks[:, 0, QUANTITIES.index("torsion"), stations.index("75% span")] = -BUFFET_TORSION
        peaks[:, 1, QUANTITIES.index("torsion"), stations.index("75% span")] = BUFFET_TORSION
        env = LoadEnvelope(
            {"horizontal_tail": stations},
            {"horizontal_tail": peaks},
            {"horizontal_tail": np.zeros_like(peaks)},
            [c.label() for c in conditions],
            keys=list(conditions),
        )
        findings = [
            Finding.compare(c, "buffet torsion", BUFFET_TORSION, 1e9, at_least=False, unit="N·m") for c in conditions
        ]
        return LoadsRun(findings, list(conditions), envelope=env)


@rule
class PitchDamperModes(Rule):
    """A plugin's mode response: the short period of a fictitious loading, Level 3."""

    id = "25.672(c)"
    symbol = "pitch-damper-modes"
    title = "Pitch damper off (test plugin)"
    amendment = "25-0"
    requirement = "A test rule."
    margin = "ζ − 0.15."
    criteria = {}
    conditions = ConditionSpace(loading=CgCorners(), configurations=("clean",))
    offers = (ModeResponses(("short_period",), key="damper_off_modes"),)

    def evaluate(self, ctx, conditions, crit):
        c = Condition(loading="damper_off", configuration="clean")
        row = {"short_period": {"zeta": 0.16, "wn_rad_s": 1.2, "level_B": 3}}
        return [
            Finding.compare(c, "short period damper off", 0.16, 0.15, at_least=True, unit="ζ", damper_off_modes=row)
        ]


def test_declarations_choose_the_sizing_rules():
    rules = discover(DiscoveryOptions()) + [TailBuffetLoads, PitchDamperModes]
    chosen = sizing_rules(rules)
    assert TailBuffetLoads in chosen.rules and PitchDamperModes not in chosen.rules
    # the built-in rules that declare tail station loads, and the pitch manoeuvres' elevator hinge moments
    assert {r.id for r in chosen.rules} == {
        "25.331(b)",
        "25.331(c)(1)",
        "25.331(c)(2)",
        "25.341(a)",
        "25.345(a)(2)",
        "25.349(a)",
        "25.251(b)",
    }
    assert chosen.hinge == {"25.331(c)(1)", "25.331(c)(2)"}


def test_a_wrong_declaration_is_refused_when_declared():
    with pytest.raises(PluginError, match="field 'produces'"):
        rule(type("BadLoads", (TailBuffetLoads,), {"produces": (Loads("horizontal_tail", "pressure"),)}))
    with pytest.raises(PluginError, match="field 'offers'"):
        rule(type("BadOffer", (PitchDamperModes,), {"offers": ("level.*",)}))


@pytest.fixture(scope="module")
def record():
    """The baseline with the two plugins registered beside the built-in rules."""
    rules = evaluate._rules() + [TailBuffetLoads, PitchDamperModes]
    saved = list(evaluate._RULES)
    evaluate._RULES[:] = rules
    try:
        yield evaluate.evaluate_design("aircraft/lta.yaml", {}, responses=["sizing.*", "level.*.damper_off.*"])
    finally:
        evaluate._RULES[:] = saved


def test_a_plugin_tail_load_sizes_the_tail(record):
    """The plugin's torsion exceeds every built-in rule's at 75 % span, so the box is sized for it there: the
    envelope the loop sized names the plugin's rule at that station and carries its load."""
    env = record["details"]["sizing"]["envelope"]
    assert "25.251(b)" in env["rules"]
    k = env["stations"].index("75% span")
    assert env["limit_loads"]["torsion"][k] == pytest.approx(BUFFET_TORSION)
    crit = [c for c in env["critical"] if c["station"] == "75% span" and c["quantity"] == "torsion"]
    assert [c["rule"] for c in crit] == ["25.251(b)"]


def test_a_plugin_mode_response_reaches_the_record(record):
    assert record["responses"]["level.short_period.damper_off.clean"] == 3
