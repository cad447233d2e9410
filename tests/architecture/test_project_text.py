"""Text speaks of the project only: README, docs, code, tests, benchmarks, the aircraft and study files describe
certkit, its sources and dates, never the project's development process ("issue 12", "session 6", "this session")."""

from __future__ import annotations

import re

from ..conftest import ROOT

#: wording of the development process
PATTERN = re.compile(r"\b(issue[- ]?#?\d+|session[- ]\d+|sessions? \d+|this session|earlier session)\b", re.I)
#: an external document's own issue number, kept as part of its citation
ALLOWED = ("EASA TCDS", "Issue 16 (30 Jul 2020)", "versioner API issue")
SCANNED = ("README.md", "docs", "certkit", "rules", "tests", "benchmarks", "aircraft", "studies")


def development_wording(root=ROOT) -> list[str]:
    found = []
    for name in SCANNED:
        base = root / name
        files = [base] if base.is_file() else [p for p in base.rglob("*") if p.suffix in (".py", ".md", ".yaml")]
        for path in sorted(files):
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if PATTERN.search(line) and not any(a in line for a in ALLOWED):
                    found.append(f"{path.relative_to(root)}:{number}: {line.strip()[:120]}")
    return [f for f in found if not f.startswith("tests/architecture/test_project_text.py")]


def test_no_development_history_in_the_project_text():
    assert development_wording() == []


def test_the_scan_finds_planted_wording(tmp_path):
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "a.md").write_text(
        "ok\nas measured in session 9\n(EASA TCDS IM.A.003, Issue 16 (30 Jul 2020))\n"
    )
    (tmp_path / "certkit").mkdir()
    (tmp_path / "certkit" / "b.py").write_text('"""The pipeline (issue 13)."""\n')
    assert development_wording(tmp_path) == [
        "docs/a.md:2: as measured in session 9",
        'certkit/b.py:1: """The pipeline (issue 13)."""',
    ]
