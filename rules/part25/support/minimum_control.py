"""The §25.149 minimum control speeds VMCA and VMCL as the regulation's conditions define them, shared by §25.149, by
§25.107 (which needs VMC when the aircraft file declares none) and by §25.125 (VREF ≥ VMCL): the criteria, the
condition spaces and the search of :func:`certkit_rules.part25.support.control_speeds.vmc_rows` with them
(regulation content, no rule here).

VMCL (§25.149(f); text read from a JAR/FAR quotation and CS 25 AMC 25.149(f), docs/regulation-notes.md): the same
static search as VMCA — straight flight with at most 5° of bank, the critical engine inoperative, the rudder or the
aileron at its design limit — in each approach and landing configuration declared, at the most unfavourable (aft) CG
at the maximum landing weight, with go-around thrust on the operating engine (taken as the VMCA search's maximum
takeoff thrust: certkit has no separate go-around rating), each speed trimmed as it is flown (the stabiliser solved
with the elevator at its trim setting, as for VMCA).
"""

from __future__ import annotations

from types import SimpleNamespace

from certkit_rules.part25.support.control_speeds import condition_vmc, vmc_rows

from certkit.engine.conditions import Altitudes, ConditionSpace, DesignWeight
from certkit.engine.registry import Criterion
from certkit.engine.scheduler import criteria_for

#: the paragraph whose criteria (and aircraft-file overrides, ``criteria."25.149"``) the search uses
VMCA_RULE_ID = "25.149"
SOURCE = "14 CFR 25.149 (Amdt. 25-108; (a)-(e) verified, docs/regulation-notes.md)"
#: what the VMCA search needs from the aircraft file
VMCA_REQUIRES = ("configurations.takeoff.CLmax",)
VMCA_CRITERIA = {
    "vmc_over_vsr_max": Criterion(1.13, "", SOURCE + " (c)", "largest VMC / VSR"),
    "bank_deg": Criterion(5.0, "deg", SOURCE + " (b)", "bank toward the operating engine"),
    "throttle": Criterion(
        0.99,
        "",
        "project choice: 99 % of the throttle range stands for maximum takeoff thrust "
        "(the trim cannot converge on the throttle stop itself)",
        "throttle of the operating engine",
    ),
    "grid_low": Criterion(0.6, "", "project choice: search from 0.6 VSR", "lowest speed searched, multiple of VSR"),
    "grid_high": Criterion(1.4, "", "project choice: search to 1.4 VSR", "highest speed searched, multiple of VSR"),
    "speed_tolerance_kn": Criterion(
        0.05,
        "kn",
        "project choice: secant step at which the search stops (VMCA to 0.1 kn)",
        "speed step of the VMCA search",
    ),
    "rudder_force_lbf": Criterion(150.0, "lbf", SOURCE + " (d)", "largest rudder force to maintain control at VMC"),
}
VMCA_CONDITIONS = ConditionSpace(
    loading=DesignWeight("MTOW", cgs=("aft",)),
    configurations=("takeoff",),
    altitudes=Altitudes((0.0,)),
    extra=(("inoperative", ("left", "right")),),
    note="Operating engine at full throttle; bank toward it; sea level, standard day.",
)


def vmca_rows(ctx, conditions, crit):
    """The VMCA search of the rule's conditions with its criteria
    (:func:`certkit_rules.part25.support.control_speeds.vmc_rows`)."""
    return vmc_rows(
        ctx,
        conditions,
        bank_deg=crit.bank_deg,
        throttle=crit.throttle,
        low=crit.grid_low,
        high=crit.grid_high,
        tolerance_kn=crit.speed_tolerance_kn,
    )


def condition_vmca(rows, k: int, crit) -> tuple[float, int, bool]:
    """VMCA (m/s CAS) of scheduled condition ``k``
    (:func:`certkit_rules.part25.support.control_speeds.condition_vmc`)."""
    return condition_vmc(rows, k, crit.grid_low)


def computed_vmca(ctx):
    """The airplane's VMCA (m/s CAS) as §25.149 computes it with its criteria (and the aircraft file's overrides):
    the highest over its conditions (each engine inoperative, most unfavourable CG); None when the rule's inputs
    are missing. For the rules that need VMC when the aircraft file declares none (§25.107)."""
    if ctx.missing(VMCA_REQUIRES):
        return None
    crit, _ = criteria_for(SimpleNamespace(id=VMCA_RULE_ID, criteria=VMCA_CRITERIA), ctx)  # with the file's overrides
    conds = VMCA_CONDITIONS.expand(ctx.aircraft)
    rows = vmca_rows(ctx, conds, crit)
    return max(condition_vmca(rows, k, crit)[0] for k in range(len(conds)))


#: the conditions of VMCL (§25.149(f)): each approach and landing configuration, the aft CG at MLW (as a function of
#: weight, the option (f)(4) gives: the weight §25.125 checks VREF at), each engine inoperative
VMCL_CONDITIONS = ConditionSpace(
    loading=DesignWeight("MLW", cgs=("aft",)),
    configurations=("approach", "landing"),
    altitudes=Altitudes((0.0,)),
    extra=(("inoperative", ("left", "right")),),
    note="Operating engine at go-around (maximum) thrust; bank toward it; sea level, standard day.",
)


def computed_vmcl(ctx, configuration: str = "landing"):
    """(VMCL in m/s CAS, how it is limited) of ``configuration`` as §25.149 computes it with its criteria: the highest
    over the inoperative engines at the aft CG and MLW; None when the configuration or MLW is not declared, or when a
    trim failed above the stall (not determined)."""
    if ctx.missing(VMCA_REQUIRES + ("mass.MLW",)) or configuration not in ctx.aircraft.configurations:
        return None
    crit, _ = criteria_for(SimpleNamespace(id=VMCA_RULE_ID, criteria=VMCA_CRITERIA), ctx)
    conds = [c for c in VMCL_CONDITIONS.expand(ctx.aircraft) if c.configuration == configuration]
    rows = vmca_rows(ctx, conds, crit)
    found = [condition_vmca(rows, k, crit) for k in range(len(conds))]
    if any(rows["limited_by"][j] == "trim failure" for j in range(len(rows["limited_by"]))):
        return None
    speed, best, _ = max(found, key=lambda f: f[0])
    return speed, rows["limited_by"][best]
