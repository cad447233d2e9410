"""Run one rule on the baseline or on an edited copy of it."""

from certkit.aircraft import load_aircraft
from certkit.context import Context
from certkit.registry import discover, select
from certkit.scheduler import evaluate_rule

from ..conftest import BASELINE


def edited_baseline(tmp_path, edits):
    """The baseline with each (old, new) text replacement applied, written to tmp_path/edited.yaml."""
    text = BASELINE.read_text()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "edited.yaml"
    path.write_text(text)
    return path


def run_rule(rule_id, tmp_path=None, edits=()):
    path = edited_baseline(tmp_path, edits) if edits else BASELINE
    (rule,) = [r for r in select(discover(), (rule_id,)) if r.id == rule_id]
    return evaluate_rule(rule, Context(load_aircraft(path)))


def finding_by(result, loading, check_prefix):
    """The finding of ``result`` at the loading named ``loading`` whose check starts with ``check_prefix``."""
    return next(f for f in result.findings if f.condition.loading == loading and f.check.startswith(check_prefix))
