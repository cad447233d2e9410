"""The study report page: well-formed, self-contained (no network reference), the required content; the CLI."""

from __future__ import annotations

import json
import re
from html.parser import HTMLParser

import numpy as np
import pytest
from click.testing import CliRunner

from certkit.cli import study_analysis as analysis_cli
from certkit.study.analysis.export import evaluate_export
from tests.study_analysis.report_fixture import small_report
from tests.study_analysis.synthetic import VARIABLES, sample, store_frame, synthetic_study

# the tests of the synthetic study's reports run on one pytest-xdist worker, which builds each once
pytestmark = pytest.mark.xdist_group("study-report")

VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}


class _Balance(HTMLParser):
    """Every non-void element closed in order (SVG's self-closing elements allowed)."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack, self.errors, self.ids = [], [], []

    def handle_starttag(self, tag, attrs):
        self.ids += [v for k, v in attrs if k == "id"]
        if tag not in VOID:
            self.stack.append((tag, self.getpos()))

    def handle_startendtag(self, tag, attrs):
        self.ids += [v for k, v in attrs if k == "id"]

    def handle_endtag(self, tag):
        if tag in VOID:
            return
        if not self.stack or self.stack[-1][0] != tag:
            self.errors.append(f"</{tag}> at {self.getpos()} closes {self.stack[-1] if self.stack else None}")
            return
        self.stack.pop()


def test_html_is_well_formed_and_self_contained():
    _, html = small_report()
    parser = _Balance()
    parser.feed(html)
    parser.close()
    assert parser.errors == []
    assert parser.stack == []
    assert len(parser.ids) == len(set(parser.ids))
    assert not re.search(r"https?:", html, re.I), "a network reference in the page"
    assert not re.search(r"""<(script|img|link|iframe)[^>]*\s(src|href)=["'](?!data:|#)""", html, re.I)
    assert '<meta name="viewport"' in html and "@media print" in html and "@media (max-width" in html


def test_report_content():
    analysis, html = small_report()
    assert analysis.sha256 in html
    assert "trim did not converge at 25.331(c)(2) condition 3" in html
    n_failed = int((store_frame(n_train=200, n_val=60)["status"] == "failed").sum())
    assert f"{n_failed} failed cases, excluded from fitting" in html
    for heading in (
        "Surrogates and goodness of fit",
        "Constraints ranked by activity",
        "Joint probability by stage",
        "Pareto fronts",
        "Optima",
        "Prediction profiler",
        "Global sensitivity",
        "Provenance",
    ):
        assert heading in html
    assert "Direct check not run (--no-check)" in html
    # every analysed response has a surrogate or, a level whose mode quantities are recorded, is derived from
    # theirs (and has none of its own); the ranking puts the least probable constraint first
    derived = "level.short_period.cg2_mlw.landing"
    assert set(analysis.levels) == {derived} and derived not in analysis.surrogates
    assert set(analysis.surrogates) | set(analysis.levels) >= set(analysis.view.analysed_responses())
    assert "mode.short_period.zeta.cg2_mlw.landing" in analysis.surrogates
    assert "Handling-quality levels from the mode quantities" in html
    d = analysis.levels[derived]
    assert f"{d.n_agree} / {d.n_validation}" in html and d.n_reproduced == d.n_recorded
    # the profiler shows the derived level as its quantities
    profiled = {r["name"] for r in analysis.profiler["responses"]}
    assert derived not in profiled and set(d.source.sources.values()) <= profiled
    ps = [o.p for o in analysis.mc.ranked()]
    assert ps == sorted(ps)
    # a flagged surrogate is named wherever it is used
    for name in [r for r, s in analysis.surrogates.items() if s.flagged]:
        assert html.count(name) >= 3


def test_profiler_data_reproduces_the_surrogates():
    analysis, html = small_report()
    data = json.loads(
        re.search(r'<script type="application/json" id="profiler-data">(.*?)</script>', html, re.S).group(1)
    )
    assert [v["path"] for v in data["variables"]] == [v["path"] for v in VARIABLES]
    x = sample(10, 9)
    for r in data["responses"]:
        # a near-interpolating Gaussian process sums weights α of ±3·10⁴ to values of 10⁵: the page's loop and
        # scikit-learn's matrix product, adding in other orders, agree to ~10⁻⁸ (1e-9 where no such cancellation)
        gp = r["model"]["kind"] == "gp"
        np.testing.assert_allclose(
            evaluate_export(r["model"], x),
            analysis.surrogates[r["name"]].predict(x),
            rtol=1e-7 if gp else 1e-9,
            atol=1e-12,
        )


def test_report_command(tmp_path, monkeypatch):
    study = tmp_path / "study.yaml"
    study.write_text("name: synthetic-ht\n")
    frame = store_frame(n_train=80, n_val=20)
    seen = {}

    def write_study_report(study_def, frame_, out, **kw):  # the analysis itself is tested above
        seen.update(kw, study=study_def, frame=frame_, out=out)
        return out / "index.html"

    monkeypatch.setattr(analysis_cli, "open_study", lambda path, store_path: (synthetic_study(), "STORE", frame))
    monkeypatch.setattr("certkit.report.study_report.write_study_report", write_study_report)
    result = CliRunner().invoke(
        analysis_cli.report_command, [str(study), "--out", str(tmp_path / "out"), "--samples", "2e4", "--no-check"]
    )
    assert result.exit_code == 0, result.output
    assert seen["samples"] == 20_000 and seen["check"] is False and seen["store"] == "STORE"
    assert seen["out"] == tmp_path / "out" and seen["frame"] is frame
    assert len(seen["sha256"]) == 64
    result = CliRunner().invoke(analysis_cli.report_command, [str(study)])
    assert seen["samples"] == 1_000_000 and seen["check"] is True and seen["out"] == tmp_path / "study-report"
    bad = CliRunner().invoke(analysis_cli.report_command, [str(study), "--samples", "12.5"])
    assert bad.exit_code == 2 and "whole number" in bad.output


def test_bad_analysis_options_are_errors_with_their_lines(tmp_path, cli):
    """An analysis option out of range, and an uncertainty or relaxation entry that matches no constraint (it
    would silently do nothing), are errors of the study file: YAML path and line, exit 2, no traceback."""
    from tests.study.conftest import write_study

    options = """\
  - {name: sp, response: level.short_period.fwd_mrw.clean, max: 1}
analysis:
  level_relaxation:
    - {responses: "level.*", max_level: LEVEL}
    - {responses: "level.phugoid.*", max_level: 2}
  uncertainty:
    - {responses: "rule.25.331*", percent: 10}
    - {responses: "constraint.*", percent: 5, distribution: normal}
"""
    path = write_study(tmp_path, extra=options.replace("LEVEL", "5"))
    path.write_text(path.read_text().replace("subcheck.*]", "subcheck.*, level.*]"))
    result = cli("study", "report", path, "--out", tmp_path / "o")
    assert result.exit_code == 2, result.output
    assert "small.yaml:17: analysis.level_relaxation.0.max_level" in result.output, result.output
    path = write_study(tmp_path, extra=options.replace("LEVEL", "2"))
    path.write_text(path.read_text().replace("subcheck.*]", "subcheck.*, level.*]"))
    result = cli("study", "report", path, "--out", tmp_path / "o")
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    found = dict(re.findall(r"small\.yaml:(\d+): (\S+): ", result.output))
    assert found.get("18") == "analysis.level_relaxation.1.responses", result.output
    assert "matches no level constraint" in result.output
    assert found.get("20") == "analysis.uncertainty.0.responses", result.output
    assert "matches no constraint's response" in result.output and "rule.25.331*" in result.output
    assert "analysis.uncertainty.1" not in result.output  # constraint.* matches the range constraint
    assert "analysis.level_relaxation.0" not in result.output


def test_summary_ranks_every_constraint_with_its_interval():
    """summary.json's data (:func:`study_summary`) on the small synthetic study: every constraint once, least
    probable first, each probability the Monte Carlo's count over its samples and inside its own 95 % interval; the
    stages' joint probabilities likewise; JSON without NaN."""
    import json

    from certkit.study.analysis.summary import study_summary

    analysis, _ = small_report()
    s = study_summary(analysis)
    json.dumps(s, allow_nan=False)
    mc = analysis.mc
    names = [c["name"] for c in s["constraints"]]
    assert sorted(names) == sorted(c.name for c in analysis.view.constraints)
    ps = [c["p"] for c in s["constraints"]]
    assert ps == sorted(ps)
    by_name = {o.constraint.name: o for o in mc.constraints}
    for c in s["constraints"]:
        o = by_name[c["name"]]
        assert c["p"] == pytest.approx(o.successes / mc.n, rel=1e-5)
        lo, hi = c["interval95"]
        assert lo <= c["p"] <= hi
    for stage, row in s["stages"].items():
        assert row["p"] == pytest.approx(mc.stage_counts[stage] / mc.n, rel=1e-5)
    assert s["cases"]["total"] == 260 and s["monte_carlo"]["samples"] == mc.n
    (level,) = s["levels"]
    assert level["response"] == "level.short_period.cg2_mlw.landing" and level["validation_agreement"] > 0.9
    assert set(level["derived_from"]) == {"zeta", "wn", "cap"}


def test_conflicting_constraints_are_shown_with_the_stage_none_meets():
    """Where no design meets every constraint, the page names the stage and the constraints that fail at the
    design of least violation (the analysis' ``conflicts``)."""
    import dataclasses

    from certkit.report.study_report import render
    from certkit.study.analysis.optimise import LEAST_VIOLATION

    analysis, _ = small_report()
    first = analysis.optima[0]
    nearest = dataclasses.replace(
        first, optimum=dataclasses.replace(first.optimum, stage="constrained", method=LEAST_VIOLATION)
    )
    html = render(dataclasses.replace(analysis, optima=[nearest], conflicts={"range": ["constrained (-1.2e+04)"]}))
    assert "No design meets every constraint of constrained on the surrogates" in html
    assert "<b>range</b> (constrained (-1.2e+04))" in html
