"""Runs rules over their conditions; isolates failures; deterministic with any number of jobs.

For each rule: check the inputs it needs (missing → ``not_evaluated`` before any computation),
apply the aircraft file's criteria overrides, expand the condition space, evaluate the whole batch,
and if the batch raises, evaluate condition by condition so that one bad condition is recorded
as ``not_evaluated`` with its reason while the others still run. ``jobs > 1`` spreads rules over
processes; results are put back in rule order, so they equal those of ``jobs = 1``.
"""

from __future__ import annotations

import datetime as _dt
import inspect
import traceback
from concurrent.futures import ProcessPoolExecutor

from certkit import __version__
from certkit.aircraft import LoadedAircraft
from certkit.context import Context
from certkit.errors import UserError
from certkit.registry import Criteria, DiscoveryOptions, Rule, discover
from certkit.results import Condition, Finding, RuleResult, RunResult


def criteria_for(rule: type[Rule], ctx: Context) -> tuple[Criteria, dict]:
    """The rule's criteria with the aircraft file's overrides; unknown names are a user error."""
    values = Criteria({name: c.value for name, c in rule.criteria.items()})
    override = ctx.aircraft.criteria.get(rule.id)
    applied: dict = {}
    if override is not None:
        for name, value in override.values.items():
            if name not in rule.criteria:
                known = ", ".join(rule.criteria) or "none"
                raise UserError(f"criteria.{rule.id}.values.{name}: rule {rule.id} has no criterion {name!r} (known: {known})")
            default = rule.criteria[name].value
            if isinstance(default, (int, float)) and not isinstance(default, bool) and not isinstance(value, (int, float)):
                raise UserError(f"criteria.{rule.id}.values.{name}: expected a number like {default!r}, got {value!r}")
            applied[name] = {"default": default, "value": value, "justification": override.justification}
            values[name] = value
    return values, applied


def _describe_exception(exc: BaseException) -> str:
    return f"{exc.__class__.__name__}: {exc}"


def evaluate_rule(rule: type[Rule], ctx: Context, *, evidence: bool = True, keep_loads: bool = False) -> RuleResult:
    """Evaluate one rule on the context's aircraft; ``evidence=False`` skips the plots and tables (a design
    evaluation reads only the findings); ``keep_loads`` keeps the rule's load envelopes on the result. After the
    rule's own findings come one ``not_evaluated`` finding per sub-paragraph it does not evaluate
    (:attr:`Rule.unevaluated`)."""
    result = _evaluate_own(rule, ctx, evidence, keep_loads)
    result.findings += [Finding.outside_scope(para, why) for para, why in rule.unevaluated]
    return result


def _evaluate_own(rule: type[Rule], ctx: Context, evidence: bool, keep_loads: bool) -> RuleResult:
    instance = rule()
    criteria, overrides = criteria_for(rule, ctx)
    result = RuleResult(rule.id, rule.symbol, rule.title, [], overrides=overrides, implementation=rule.implementation,
                        limitations=" ".join(inspect.cleandoc(rule.limitations).split()),
                        unevaluated=[list(u) for u in rule.unevaluated])
    missing = ctx.missing(rule.requires)
    if missing:
        result.findings.append(Finding.not_evaluated(
            Condition(), "inputs", "needs " + ", ".join(missing),
            hint=f"declare {', '.join(missing)} in the aircraft file"))
        return result
    try:
        conditions = rule.conditions.expand(ctx.aircraft)
    except Exception as exc:  # a condition space that cannot be built is reported, not raised
        result.findings.append(Finding.not_evaluated(Condition(), "conditions", _describe_exception(exc)))
        return result
    if not conditions:
        result.findings.append(Finding.not_evaluated(Condition(), "conditions", "no condition applies (configurations or speeds not declared)"))
        return result
    try:
        findings = instance.evaluate(ctx, conditions, criteria)
    except UserError:
        raise
    except Exception:
        findings = []
        for cond in conditions:
            try:
                findings += instance.evaluate(ctx, [cond], criteria)
            except UserError:
                raise
            except Exception as exc:
                findings.append(Finding.not_evaluated(cond, "computation", _describe_exception(exc),
                                                      traceback=traceback.format_exc(limit=3)))
    for cond in _uncovered(conditions, findings):
        findings.append(Finding.not_evaluated(cond, "computation", "the rule returned no finding for this condition"))
    result.findings = findings
    if keep_loads:
        result.load_envelopes = instance.load_envelopes()
        result.run = getattr(instance, "run", None)
    if not evidence:
        return result
    try:
        result.evidence = instance.evidence(ctx, findings, criteria)
    except Exception as exc:
        result.notes.append(f"evidence could not be drawn: {_describe_exception(exc)}")
    return result


def _uncovered(conditions, findings) -> list:
    """The scheduled conditions no finding names, itself or refined (a finding's condition with more fields set).
    Findings are grouped by loading and configuration, which a refinement keeps, so each condition is compared with
    its own group only."""
    covered = {f.condition for f in findings}
    groups: dict = {}
    for c in covered:
        groups.setdefault((c.loading, c.configuration), []).append(c)
    out = []
    for cond in conditions:
        if cond in covered:
            continue
        if cond.loading is not None and cond.configuration is not None:
            candidates = groups.get((cond.loading, cond.configuration), ())
        else:
            candidates = covered
        if not any(c.refines(cond) for c in candidates):
            out.append(cond)
    return out


def _evaluate_many(loaded: LoadedAircraft, rules: list[type[Rule]]) -> tuple[list[RuleResult], dict]:
    ctx = Context(loaded)
    return [evaluate_rule(r, ctx) for r in rules], ctx.provenance()


def _merge_provenance(parts: list[dict]) -> dict:
    """One provenance from several workers' (same inputs give the same entries; keep one of each)."""
    merged = {"aerodynamics": {}, "loadings": [], "components": parts[0]["components"] if parts else [],
              "component_notes": parts[0]["component_notes"] if parts else []}
    seen: dict = {}
    for p in parts:
        merged["aerodynamics"].update(p["aerodynamics"])
        for row in p["loadings"]:
            key = (round(row["mass_kg"], 3), round(row["x_cg_m"], 6))
            if key not in seen:
                seen[key] = dict(row)
                merged["loadings"].append(seen[key])
            else:  # the same loading named differently by different workers' rules: keep every name
                names = set(seen[key]["name"].split(" / ")) | set(row["name"].split(" / "))
                seen[key]["name"] = " / ".join(sorted(names))
    merged["aerodynamics"] = dict(sorted(merged["aerodynamics"].items()))
    merged["loadings"].sort(key=lambda r: (r["mass_kg"], r["x_cg_m"]))
    return merged


_WORKER: dict = {}


def _worker_init(loaded: LoadedAircraft, options: DiscoveryOptions) -> None:
    """A worker's Context on the aircraft the parent loaded (inherited when processes fork, pickled otherwise)."""
    import matplotlib

    matplotlib.use("Agg")
    _WORKER["ctx"] = Context(loaded)
    _WORKER["rules"] = {r.id: r for r in discover(options)}


def _worker_run(rule_ids: tuple[str, ...]) -> list[tuple[RuleResult, dict]]:
    """Rules in a worker process, one after the other on the worker's own Context (its models are reused by the
    next rules the worker takes), each encoded for ``results.json`` here, while other rules still run."""
    ctx = _WORKER["ctx"]
    out = []
    for rid in rule_ids:
        result = evaluate_rule(_WORKER["rules"][rid], ctx)
        result.encoded = result.to_json()
        out.append((result, ctx.provenance()))
    return out


def work_units(rules: list[type[Rule]]) -> list[tuple[type[Rule], ...]]:
    """The rules grouped for the worker processes: rules sharing a :attr:`Rule.run_with` key form one unit (in
    registry order), every other rule its own; the heaviest units (summed :attr:`Rule.cost`) first."""
    units: dict = {}
    for r in rules:
        units.setdefault(r.run_with or ("", r.id), []).append(r)
    return sorted((tuple(u) for u in units.values()), key=lambda u: -sum(r.cost for r in u))  # stable on ties


def run(loaded: LoadedAircraft, rules: list[type[Rule]], *, jobs: int = 1,
        options: DiscoveryOptions = DiscoveryOptions(), now: _dt.datetime | None = None) -> RunResult:
    """Evaluate ``rules`` on ``loaded`` in ``jobs`` processes: each process takes the next unit of work
    (:func:`work_units`) when it is free, the heaviest first."""
    if jobs < 1:
        raise UserError(f"--jobs must be at least 1 (got {jobs})")
    if jobs == 1 or len(rules) <= 1:
        results, provenance = _evaluate_many(loaded, rules)
        provenance = _merge_provenance([provenance])
    else:
        units = work_units(rules)
        with ProcessPoolExecutor(max_workers=min(jobs, len(units)), initializer=_worker_init,
                                 initargs=(loaded, options)) as pool:
            parts = [part for done in pool.map(_worker_run, [tuple(r.id for r in u) for u in units]) for part in done]
        by_id = {res.id: res for res, _ in parts}
        results = [by_id[r.id] for r in rules]
        provenance = _merge_provenance([p for _, p in parts])
    created = (now or _dt.datetime.now(_dt.timezone.utc)).isoformat(timespec="seconds")
    return RunResult(__version__, loaded.name, loaded.sha256, loaded.path, created, results, provenance)
