"""Run one rule on the baseline or on an edited copy of it."""

from certkit.aircraft import load_aircraft
from certkit.context import Context
from certkit.registry import discover, select
from certkit.scheduler import evaluate_rule

from ..conftest import BASELINE


def run_rule(rule_id, tmp_path=None, edits=()):
    path = BASELINE
    if edits:
        text = BASELINE.read_text()
        for old, new in edits:
            assert old in text, old
            text = text.replace(old, new)
        path = tmp_path / "edited.yaml"
        path.write_text(text)
    (rule,) = [r for r in select(discover(), (rule_id,)) if r.id == rule_id]
    return evaluate_rule(rule, Context(load_aircraft(path)))
