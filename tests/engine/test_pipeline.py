"""The check pipeline: results.json, determinism, --jobs, --rules folders, plugins, isolation, escaping."""

import json
import re
import textwrap

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.registry import PluginError, discover, folder_rules, select
from certkit.engine.results_json import stable_lines
from certkit.engine.scheduler import run, work_units
from certkit.errors import UserError

from ..conftest import BASELINE
from ..rules.helpers import VB_SCHEDULE

USER_RULE = textwrap.dedent("""
    from certkit.engine.conditions import CgCorners, ConditionSpace
    from certkit.engine.registry import Criterion, Rule, rule
    from certkit.engine.results import Finding

    @rule
    class CornerMassCheck(Rule):
        id = "25.901"
        symbol = "user-corner-mass"
        title = "User rule: corner mass below MRW"
        amendment = "none"
        requirement = "Every corner of the envelope is below the maximum ramp weight."
        margin = "MRW minus corner mass."
        criteria = {"scale": Criterion(1.0, "", "user test", "factor on MRW")}
        conditions = ConditionSpace(loading=CgCorners())

        def evaluate(self, ctx, conditions, crit):
            out = []
            for c in conditions:
                if c.loading == "{explode}":
                    raise RuntimeError("solver diverged at this corner")
                limit = crit.scale * ctx.aircraft.mass.MRW
                out.append(Finding.compare(c, "mass", c.mass, limit, at_least=False, unit="kg"))
            return out
""")


def write_rule(folder, explode="none"):
    folder.mkdir(exist_ok=True)
    (folder / "corner_mass.py").write_text(USER_RULE.replace("{explode}", explode))
    return folder


def test_check_writes_results_json_with_stable_keys(cli, tmp_path):
    out = cli("check", BASELINE, "--out", tmp_path)
    data = json.loads((tmp_path / "results.json").read_text())
    assert set(data) >= {"certkit_version", "aircraft", "summary", "rules"}
    assert set(data["aircraft"]) >= {"name", "source_sha256"}
    assert set(data["summary"]) == {"rules", "complies", "complies_partial", "fails", "not_evaluated"}
    ids = [r["id"] for r in data["rules"]]
    assert {"25.333", "25.335(c)", "25.337"} <= set(ids)
    for r in data["rules"]:
        assert set(r) >= {
            "id",
            "symbol",
            "title",
            "status",
            "min_margin",
            "unit",
            "critical_condition",
            "findings",
            "implementation",
            "limitations",
            "unevaluated",
        }
        assert (r["implementation"] == "partial") == bool(r["unevaluated"])
        for f in r["findings"]:
            assert set(f) >= {"condition", "value", "limit", "margin", "normalized_margin", "unit", "status", "reason"}
            if f["margin"] is not None:
                assert (f["margin"] >= -1e-9 * max(1, abs(f["limit"]))) == (f["status"] == "complies")
    # the three first rules are evaluated over the CG-envelope weights
    r337 = next(r for r in data["rules"] if r["id"] == "25.337")
    masses = {round(f["condition"]["mass_kg"]) for f in r337["findings"]}
    assert len(masses) == 4  # 310,000 / 460,000 / 560,000 / 657,000 lb
    s = data["summary"]
    assert out.exit_code == (1 if s["fails"] else 3 if s["not_evaluated"] or s["complies_partial"] else 0)
    html = (tmp_path / "index.html").read_text()
    assert html.count("<svg") >= 1
    ids = re.findall(r'\bid="([^"]+)"', html)
    assert len(ids) == len(set(ids))  # no SVG or page id twice (each figure's ids carry its own prefix)
    assert set(re.findall(r'(?:url\(#|href="#)([^")]+)', html)) <= set(ids)


def test_deterministic_and_jobs_equal(baseline):
    rules = discover()
    a = run(baseline, rules)
    b = run(baseline, rules)
    c = run(baseline, rules, jobs=2)
    # results.json: the rules the workers encoded, stitched into the rest, read as encoding the whole at once
    assert all(r.encoded is not None for r in c.rules)
    worker_text = c.to_json()
    for r in c.rules:
        r.encoded = None
    assert c.to_json() == worker_text
    # byte-identical apart from the one line of what varies between runs (time stamp, duration, processes)
    texts = [stable_lines(x.to_json()) for x in (a, b, c)]
    assert texts[0] == texts[1] == texts[2]
    assert json.loads(worker_text)["rules"] == json.loads(a.to_json())["rules"]


def test_user_rules_folder_appears_in_report(cli, tmp_path):
    folder = write_rule(tmp_path / "my_rules")
    out = cli("check", BASELINE, "--rules", folder, "--out", tmp_path / "rep", "--select", "25.9")
    data = json.loads((tmp_path / "rep" / "results.json").read_text())
    assert [r["id"] for r in data["rules"]] == ["25.901"]
    assert data["rules"][0]["status"] == "complies"
    assert out.exit_code == 0
    assert "User rule: corner mass below MRW" in (tmp_path / "rep" / "index.html").read_text()


def test_exception_at_one_condition_is_isolated(baseline, tmp_path):
    rules = folder_rules(write_rule(tmp_path / "r", explode="fwd_mid"))
    result = run(baseline, rules).rules[0]
    bad = [f for f in result.findings if f.status == "not_evaluated"]
    assert [f.condition.loading for f in bad] == ["fwd_mid"]
    assert "solver diverged" in bad[0].reason
    assert len(result.findings) == 8
    assert result.status == "not_evaluated"
    assert run(baseline, rules).exit_code() == 3


def test_invalid_plugin_metadata_names_plugin_and_field(tmp_path):
    folder = tmp_path / "broken"
    folder.mkdir()
    (folder / "bad_rule.py").write_text(USER_RULE.replace('id = "25.901"', 'id = "twenty-five"'))
    with pytest.raises(PluginError, match=r"bad_rule\.py.*CornerMassCheck.*field 'id'"):
        folder_rules(folder)
    (folder / "bad_rule.py").write_text(USER_RULE.replace('id = "25.901"', 'id = "25.901"\n    cost = -1'))
    with pytest.raises(PluginError, match=r"bad_rule\.py.*CornerMassCheck.*field 'cost' = -1 must be a positive"):
        folder_rules(folder)
    (folder / "bad_rule.py").write_text(USER_RULE.replace('id = "25.901"', 'id = "25.901"\n    run_with = 3'))
    with pytest.raises(PluginError, match=r"bad_rule\.py.*CornerMassCheck.*field 'run_with' = 3 must be a string"):
        folder_rules(folder)


def test_rules_that_share_work_form_one_unit():
    """§25.341(a) and §25.349(b) share the gust runs, §25.331(b) and §25.427(b) the balanced states, §25.331(c)(1)
    and (c)(2) and §25.427(b) the pitch manoeuvres, §25.427(b) the gust runs too (run_with): one process evaluates
    the six, in registry order; every rule is in exactly one unit; units go heaviest first."""
    rules = discover()
    units = work_units(rules)
    (gust,) = [u for u in units if any(r.id == "25.341(a)" for r in u)]
    assert [r.id for r in gust] == ["25.331(b)", "25.331(c)(1)", "25.331(c)(2)", "25.341(a)", "25.349(b)", "25.427(b)"]
    assert sorted(r.id for u in units for r in u) == sorted(r.id for r in rules)
    costs = [sum(r.cost for r in u) for u in units]
    assert costs == sorted(costs, reverse=True)


def test_cli_plugin_error_exit_2(cli, tmp_path):
    import subprocess
    import sys

    folder = tmp_path / "broken"
    folder.mkdir()
    (folder / "bad_rule.py").write_text(USER_RULE.replace('symbol = "user-corner-mass"', 'symbol = "Bad Symbol"'))
    proc = subprocess.run(
        [sys.executable, "-m", "certkit.cli", "rules", "--rules", str(folder)], capture_output=True, text=True
    )
    assert proc.returncode == 2 and "field 'symbol'" in proc.stderr and "Traceback" not in proc.stderr


def test_missing_input_is_not_evaluated_before_computation(tmp_path):
    text = BASELINE.read_text().replace(VB_SCHEDULE, "  # VB removed\n")
    f = tmp_path / "a.yaml"
    f.write_text(text)
    result = run(load_aircraft(f), select(discover(), ("25.335(d)",))).rules[0]
    assert result.status == "not_evaluated"
    assert result.findings[0].reason == "needs speeds.VB"


def test_select_and_ignore():
    rules = discover()
    assert [r.id for r in select(rules, ("25.335",), ("25.335(b)",))] == ["25.335(a)", "25.335(c)", "25.335(d)"]
    assert [r.id for r in select(rules, ("limit-maneuvering-load-factors",))] == ["25.337"]
    with pytest.raises(UserError, match="no rule matches"):
        select(rules, ("25.999",))


def test_html_escapes_every_input_string(cli, tmp_path):
    evil = "<script>alert('x')</script>"
    text = BASELINE.read_text().replace("name: LTA-300 large twin-aisle", f'name: "{evil}"')
    text = text.replace("name: fwd_light", 'name: "<b>fwd&light</b>"')
    f = tmp_path / "evil.yaml"
    f.write_text(text)
    cli("check", f, "--out", tmp_path / "out")
    html = (tmp_path / "out" / "index.html").read_text()
    assert "<script>alert" not in html and "<b>fwd" not in html
    # the report's own script (filters, print) and its compressed table blocks (inert data), none from the input
    assert html.count("<script") == html.count("<script>") + html.count('<script type="application/x-certkit-table">')
    assert html.count("<script>") == 1
    assert "&lt;script&gt;" in html and "&lt;b&gt;fwd&amp;light&lt;/b&gt;" in html


def test_criteria_override_is_applied_and_reported(tmp_path, cli):
    text = BASELINE.read_text() + textwrap.dedent("""
        criteria:
          "25.335(b)":
            justification: rational analysis including the automatic overspeed protection (test)
            values: {mach_margin: 0.05}
    """)
    f = tmp_path / "o.yaml"
    f.write_text(text)
    cli("check", f, "--out", tmp_path / "o", "--select", "25.335(b)")
    data = json.loads((tmp_path / "o" / "results.json").read_text())
    assert data["rules"][0]["overrides"]["mach_margin"]["value"] == 0.05
    assert "automatic overspeed protection" in (tmp_path / "o" / "index.html").read_text()
    bad = text.replace("mach_margin: 0.05", "mach_margn: 0.05")
    f.write_text(bad)
    with pytest.raises(UserError, match=r"criteria\.25\.335\(b\)\.values\.mach_margn"):
        run(load_aircraft(f), select(discover(), ("25.335(b)",)))


def test_rules_explain_and_new_rule(cli, tmp_path):
    listing = cli("rules").output
    assert "25.337" in listing and "limit-maneuvering-load-factors" in listing
    doc = cli("explain", "25.337").output
    for heading in ("Requirement", "Criterion", "Conditions", "Margin", "Cross-references"):
        assert heading in doc
    assert "24000" in doc and "14 CFR 25.337" in doc
    root = tmp_path / "repo"
    (root / "rules" / "part25" / "subpart_b").mkdir(parents=True)
    (root / "rules" / "part25" / "subpart_b" / "__init__.py").write_text("")
    out = cli("new-rule", "25.171", "--symbol", "static-stability", "--title", "Stability: general", "--root", root)
    assert out.exit_code == 0
    module = root / "rules" / "part25" / "subpart_b" / "r25_171.py"
    assert module.exists() and (root / "tests" / "rules" / "test_r25_171.py").exists()
    (rule_cls,) = folder_rules(module.parent)
    assert rule_cls.id == "25.171" and rule_cls.implementation == "planned"


def test_refined_conditions_cover_their_origin():
    from certkit.engine.results import Condition

    base = Condition(loading="fwd_mlw", mass=2e5, x_cg=28.0, configuration="landing")
    assert base.with_(speed=70.0, speed_kind="EAS", thrust="idle").refines(base)
    assert not base.with_(mass=1e5).refines(base)
    assert not Condition(loading="aft_mlw", mass=2e5, x_cg=28.0).refines(base)


def test_a_condition_without_an_extra_item_is_the_condition_built_without_it():
    from certkit.engine.results import Condition

    tagged = Condition(loading="fwd_mlw", altitude=3000.0, extra=(("source", "25.331(b)"), ("gust", "up")))
    plain = Condition(loading="fwd_mlw", altitude=3000.0, extra=(("gust", "up"),))
    assert tagged.without("source") == plain and hash(tagged.without("source")) == hash(plain)
    assert tagged.without("source", "gust") == Condition(loading="fwd_mlw", altitude=3000.0)
    assert tagged.without("speed") == tagged and tagged.get("source") == "25.331(b)"  # the original unchanged


def test_a_margin_without_a_unit_is_refused():
    """Every margin carries a unit word: a dimensionless comparison names its quantity (ratio, g, C_L, ζ)."""
    from certkit.engine.results import Condition, Finding

    with pytest.raises(ValueError, match="needs the unit"):
        Finding.compare(Condition(), "x ≥ 1", 2.0, 1.0, at_least=True, unit="")
    with pytest.raises(ValueError, match="needs the unit"):
        Finding.compare(Condition(), "x ≥ 1", 2.0, 1.0, at_least=True, unit="1")
    assert Finding.compare(Condition(), "x ≥ 1", 2.0, 1.0, at_least=True, unit="g").unit == "g"


def _process_id(ctx) -> tuple[int, str, int]:
    import os

    return os.getpid(), type(ctx).__name__, id(ctx)


def test_work_alongside_the_rules_runs_in_a_worker_and_lands_in_the_models(baseline, monkeypatch):
    """``alongside`` (the report's missions): with several processes a worker runs it once the rules are handed out
    (its result under ``models``); with one, this process. It is given the Context of the process's rules (whose
    models it reuses)."""
    import os

    from certkit.engine import scheduler

    rules = [r for r in discover() if r.id in ("25.333", "25.335(a)", "25.335(b)")]
    two = run(baseline, rules, jobs=2, alongside={"pid": _process_id})
    contexts = []

    def context(loaded, lattice_store=None, made=scheduler.Context):
        contexts.append(made(loaded, lattice_store))
        return contexts[-1]

    monkeypatch.setattr(scheduler, "Context", context)
    one = run(baseline, rules, jobs=1, alongside={"pid": _process_id})
    assert two.models["pid"][0] != os.getpid() and two.models["pid"][1] == "Context"
    assert len(contexts) == 1 and one.models["pid"] == (os.getpid(), "Context", id(contexts[0]))
    assert [r.id for r in two.rules] == [r.id for r in one.rules]


def test_work_alongside_is_handed_out_among_the_units_by_its_cost():
    """Longest processing time first: the report's missions (cost 5) go after the units at least as heavy and before
    the lighter ones, so that the light units fill both processes' ends; work without a cost goes last."""
    from types import SimpleNamespace

    from certkit.engine.scheduler import _queue

    units = [(SimpleNamespace(cost=c, id=f"u{c}"),) for c in (8, 5, 4, 1)]
    work = {"missions": lambda: None, "uncosted": lambda: None, "heavy": lambda: None}
    order = _queue(units, work, {"missions": 5.0, "heavy": 100.0})
    names = [item if kind == "work" else item[0].id for kind, item in order]
    assert names == ["heavy", "u8", "u5", "missions", "u4", "u1", "uncosted"]
