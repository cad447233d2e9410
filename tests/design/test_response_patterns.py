"""The response patterns of a study (``evaluate_design(…, responses=…)``) select what :func:`fnmatch.fnmatchcase`
selects with each pattern's brackets taken literally — a rule id's "(c)(2)" is text, "[x]" too — now that the
patterns are translated once into one expression."""

import fnmatch

from certkit.design.evaluate import _matcher

NAMES = [
    "rule.25.331(c)(2).margin",
    "rule.25.331(c)(1).margin",
    "subcheck.25.143(h).h_takeoff_v2_rudder_within_design_limit.margin",
    "subcheck.x[1].margin",
    "subcheck.x1.margin",
    "level.dutch_roll.fwd_mrw.clean",
    "Level.dutch_roll.fwd_mrw.clean",
    "mission.design_range_m",
    "objective.OEW_kg",
    "travel.elevator",
    "travel.elevatorx",
    "sizing.iterations",
    "",
]
PATTERNS = [
    ("objective.*", "rule.*.margin", "level.*", "sizing.*"),
    ("rule.25.331(c)(2).margin",),
    ("subcheck.x[1].margin",),
    ("travel.?levator", "mission.design_range_m"),
    ("*",),
    ("level.*.fwd_*.clean", "*.margin"),
]


def test_the_patterns_select_what_fnmatch_selects():
    for patterns in PATTERNS:
        wanted = _matcher(patterns)
        expected = [n for n in NAMES if any(fnmatch.fnmatchcase(n, p.replace("[", "[[]")) for p in patterns)]
        assert [n for n in NAMES if wanted(n)] == expected, patterns
    assert not _matcher(("subcheck.x[1].margin",))("subcheck.x1.margin")  # the bracket is text, not a set
    assert not _matcher(("level.*",))("Level.dutch_roll.fwd_mrw.clean")  # case matters
