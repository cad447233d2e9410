"""``certkit new-rule``: scaffold a rule module and its test from the paragraph id.

The scaffold is a valid, registered rule marked ``implementation = "planned"`` whose findings are
``not_evaluated`` ("not implemented yet") until its author writes the computation: it can never pass.
"""

from __future__ import annotations

import re
from pathlib import Path

from certkit.engine.registry import RULE_ID, SYMBOL
from certkit.errors import UserError

#: Part 25 subparts by paragraph number range
SUBPARTS = (("b", 1, 255), ("c", 301, 581))

MODULE = '''"""§{rule_id} {title}.

TODO: quote the numeric criteria of the paragraph and their amendment.
"""

from __future__ import annotations

from certkit.engine.conditions import CgCorners, ConditionSpace
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding


@rule
class {class_name}(Rule):
    id = "{rule_id}"
    symbol = "{symbol}"
    title = "{title}"
    amendment = "TODO"
    implementation = "planned"
    requirement = """
        TODO: what the paragraph asks, in plain words.
    """
    margin = "TODO: how the margin is formed; >= 0 complies."
    references = ()
    requires = ()
    criteria = {{
        # "name": Criterion(value, "unit", "14 CFR {rule_id}", "meaning"),
    }}
    conditions = ConditionSpace(loading=CgCorners())

    def evaluate(self, ctx, conditions, crit):
        return [Finding.not_evaluated(c, "{rule_id}", "not implemented yet") for c in conditions]
'''

TEST = '''"""Tests of §{rule_id} ({symbol})."""

from pathlib import Path

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.scheduler import evaluate_rule
from {package} import {class_name}

BASELINE = Path(__file__).resolve().parents[2] / "aircraft" / "lta.yaml"


def test_{func}_never_passes_unimplemented():
    result = evaluate_rule({class_name}, Context(load_aircraft(BASELINE)))
    assert result.status in ("complies", "fails", "not_evaluated")
    if {class_name}.implementation == "planned":
        assert result.status == "not_evaluated"

# TODO: a hand-calculated case, a case on the limit, a sign check and a not-evaluated case.
'''


def subpart_of(rule_id: str) -> str:
    match = re.match(r"\d+\.(\d+)", rule_id)
    if match is None:
        raise ValueError(f"not a Part 25 paragraph id: {rule_id!r}")
    number = int(match.group(1))
    for name, lo, hi in SUBPARTS:
        if lo <= number <= hi:
            return name
    raise UserError(
        f"{rule_id}: built-in rules cover Subparts B (25.1-25.255) and C (25.301-25.581); "
        "put other paragraphs in a plugin or a --rules folder"
    )


def scaffold_rule(root: Path, rule_id: str, symbol: str, title: str, subpart: str | None = None) -> tuple[Path, Path]:
    if not RULE_ID.match(rule_id):
        raise UserError(f"{rule_id!r} is not a paragraph id such as '25.331(c)(2)'")
    if not SYMBOL.match(symbol):
        raise UserError(f"symbol {symbol!r} must be kebab-case, e.g. 'stall-speed'")
    subpart = subpart or subpart_of(rule_id)
    stem = "r" + re.sub(r"[^0-9a-z]+", "_", rule_id.lower()).strip("_")
    folder = root / "rules" / "part25" / f"subpart_{subpart}"
    if not (folder / "__init__.py").exists():
        raise UserError(f"{folder} is not a rules package (run new-rule from the repository root or pass --root)")
    module = folder / f"{stem}.py"
    test_dir = root / "tests" / "rules"
    test = test_dir / f"test_{stem}.py"
    for path in (module, test):
        if path.exists():
            raise UserError(f"{path} exists already; not overwritten")
    class_name = "".join(part.capitalize() for part in symbol.split("-"))
    fields = dict(
        rule_id=rule_id,
        title=title.replace('"', "'"),
        symbol=symbol,
        class_name=class_name,
        package=f"certkit_rules.part25.subpart_{subpart}.{stem}",
        func=symbol.replace("-", "_"),
    )
    module.write_text(MODULE.format(**fields), encoding="utf-8")
    test_dir.mkdir(parents=True, exist_ok=True)
    test.write_text(TEST.format(**fields), encoding="utf-8")
    return module, test
