"""Run one rule on the baseline or on an edited copy of it."""

import re

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.registry import discover, select
from certkit.engine.scheduler import evaluate_rule

from ..conftest import BASELINE


def _structure_section(text: str) -> str:
    """The baseline's ``structure:`` section, from its key to the next top-level key (the sections after it — sizing,
    mission, calibration — stay), newline-terminated."""
    start = text.index("\nstructure:\n") + 1
    end = re.compile(r"^[a-z_]+:", re.M).search(text, start + 1).start()
    return text[start:end]


#: edit removing the baseline's declared structural capability (aircraft/lta.yaml ``structure:``)
NO_STRUCTURE = (_structure_section(BASELINE.read_text()), "")


def _control_forces_section(text: str) -> str:
    """The baseline's ``control_forces:`` section (its comment lines included), newline-terminated."""
    start = text.index("\ncontrol_forces:") + 1
    end = re.compile(r"^[a-z_]+:", re.M).search(text, start + 1).start()
    return text[start:end]


def control_forces_edit(section: str):
    """Edit replacing the baseline's ``control_forces:`` section by ``section`` (a whole section, from its key,
    newline-terminated; "" removes it)."""
    return (_control_forces_section(BASELINE.read_text()), section)


#: edit removing the baseline's declared control-force models
NO_CONTROL_FORCES = control_forces_edit("")


def _stabilizer_block(text: str) -> str:
    """The baseline's movable-stabiliser declaration (``geometry.horizontal_tail.stabilizer``), newline-terminated."""
    start = text.index("    stabilizer:")
    end = text.index("  vertical_tail:", start)
    return text[start:end]


#: edit removing the baseline's movable stabiliser: the airplane trims with the elevator, the stabiliser fixed at its
#: declared incidence (the behaviour without a movable stabiliser)
NO_STABILIZER = (_stabilizer_block(BASELINE.read_text()), "")


def _block(key: str, indent: str) -> str:
    """The baseline's text of the mapping ``key`` at ``indent`` (its line and the more indented lines under it)."""
    lines = BASELINE.read_text().splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if line.startswith(f"{indent}{key}:"))
    end = start + 1
    while end < len(lines) and lines[end].startswith(indent + " ") and lines[end][len(indent) + 1] == " ":
        end += 1
    return "".join(lines[start:end])


#: the baseline's C_Lmax-against-Mach table and its VA and VB schedules (docs/baseline-sources.md §6a, Q11)
CN_MAX_TABLE, VA_SCHEDULE, VB_SCHEDULE = _block("CLmax_by_mach", "    "), _block("VA", "  "), _block("VB", "  ")
#: the baseline with the low-speed C_N,max at every Mach number and the single VA and VB derived from it (266 and
#: 226 KEAS, §6a): the closed-form envelope of the hand calculations
CONSTANT_CN_MAX = [
    (CN_MAX_TABLE, ""),
    (VA_SCHEDULE, "  VA: 266 kn EAS\n"),
    (VB_SCHEDULE, "  VB: 226 kn EAS\n"),
]


def edited_baseline(tmp_path, edits):
    """The baseline with each (old, new) text replacement applied, written to tmp_path/edited.yaml."""
    text = BASELINE.read_text()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "edited.yaml"
    path.write_text(text)
    return path


def run_rule(rule_id, tmp_path=None, edits=(), keep_loads=False):
    path = edited_baseline(tmp_path, edits) if edits else BASELINE
    (rule,) = [r for r in select(discover(), (rule_id,)) if r.id == rule_id]
    return evaluate_rule(rule, Context(load_aircraft(path)), keep_loads=keep_loads)


#: the reason of a loads finding beyond the aerodynamic model's highest Mach breakpoint (not extrapolated)
MACH_RANGE = "beyond the aerodynamic and strip loads model's Mach range"


def in_mach_range(findings):
    """The findings not set aside as beyond the aerodynamic model's Mach range."""
    return [f for f in findings if MACH_RANGE not in (f.reason or "")]


def own(result):
    """The rule's own findings: without those standing for the sub-paragraphs it does not evaluate."""
    from certkit.engine.results import SCOPE_KEY

    return [f for f in result.findings if SCOPE_KEY not in f.all_details()]


def finding_by(result, loading, check_prefix):
    """The finding of ``result`` at the loading named ``loading`` whose check starts with ``check_prefix``."""
    return next(f for f in result.findings if f.condition.loading == loading and f.check.startswith(check_prefix))


def hand_margin(details, capabilities, ultimate_factor=1.5):
    """The smallest normalised margin of a loads finding recomputed by hand from its reported station loads
    (details "<station> <quantity> max/min (kN…)", rounded to 0.1 kN / kN·m) and the declared capabilities
    (§25.305: allowable limit − |limit load|; allowable ultimate − 1.5 |limit load|, §25.303), each sense
    against its own allowable. Returns (normalised margin, margin in N or N·m, "<limit|ultimate> <quantity> at
    <station>"); where two checks tie within rounding either may be the rule's."""
    checks = _hand_checks(details, capabilities, ultimate_factor)
    if not checks:
        return None
    normalised, margin, label, _ = min(checks, key=lambda c: c[0])  # the first smallest, in the checks' order
    return normalised, margin, label


def _hand_checks(details, capabilities, ultimate_factor):
    """Every (normalised margin, margin, "<limit|ultimate> <quantity> at <station>", load rounding over the allowable)
    of the reported station loads against the capabilities, in capability, sense, limit-then-ultimate order."""
    out = []
    for cap in capabilities:
        key = f"{cap.station} {cap.quantity} max/min (kN{'·m' if cap.quantity != 'shear' else ''})"
        if key not in details:
            continue
        hi, lo = (1e3 * v for v in details[key])
        for sense, load in (("max", hi), ("min", lo)):
            if (sense == "max" and load <= 0) or (sense == "min" and load >= 0):
                continue
            for which, factor in (("limit", 1.0), ("ultimate", ultimate_factor)):
                allowable = cap.allowable(which, sense)
                margin = allowable - factor * abs(load)
                label = f"{which} {cap.quantity} at {cap.station}"
                out.append((margin / allowable, margin, label, 0.1e3 * factor / abs(allowable)))
    return out


def assert_margins_by_hand(findings, capabilities_by_surface):
    """Every evaluated loads finding's margin equals :func:`hand_margin` of its reported loads against the declared
    capabilities of its surface (the surface named at the end of the check before ":"), within the 0.1 kN rounding
    of the reported loads: 0.2 kN (kN·m) plus 0.1 % of the allowable. Where two checks tie in normalised margin within
    that rounding (a tailplane whose station allowables and loads scale alike), the finding's margin may be either's."""
    for f in findings:
        if f.status in ("complies", "fails") and f.margin is not None:
            named = f.check.split(":")[0]
            surface = next(s for s in capabilities_by_surface if named.endswith(s.replace("_", " ")))
            tied = tied_hand_margins(f.all_details(), capabilities_by_surface[surface])
            assert any(f.margin == pytest.approx(m, abs=0.2e3 + 1e-3 * abs(f.limit)) for m in tied), (f.margin, tied)


def tied_hand_margins(details, capabilities, ultimate_factor=1.5):
    """The margins (N or N·m) of every check whose normalised margin lies within the reported loads' rounding (0.1 kN,
    kN·m, times the factor, over the allowable) of :func:`hand_margin`'s smallest."""
    checks = _hand_checks(details, capabilities, ultimate_factor)
    if not checks:
        return []
    worst = min(c[0] for c in checks)
    return [margin for normalised, margin, _, rounding in checks if normalised <= worst + rounding + 1e-12]


def failures_with(tmp_path, rule, edits, check_part):
    """The failing findings of ``rule`` on the baseline edited by ``edits`` (a deficient airplane) whose check
    contains ``check_part``."""
    result = evaluate_rule(rule, Context(load_aircraft(edited_baseline(tmp_path, edits))))
    return [f for f in result.findings if f.status == "fails" and check_part in f.check]
