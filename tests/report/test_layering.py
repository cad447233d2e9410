"""The layering rule of the developers' guide for evidence: rules return evidence as data and never import the report
package (rules → report is forbidden); the evidence data package sits in the engine layer and imports nothing from the
report or the CLI either. Checked on the source (every import statement, at any depth), so it cannot pass by luck."""

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _imports(folder: Path):
    for path in sorted(folder.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    yield path, node.lineno, alias.name
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                yield path, node.lineno, node.module
                for alias in node.names:  # from certkit import report
                    yield path, node.lineno, f"{node.module}.{alias.name}"


def _offending(folder: Path, forbidden: tuple[str, ...]) -> list[str]:
    found = {(path, line): name for path, line, name in _imports(folder)
             if any(name == f or name.startswith(f + ".") for f in forbidden)}
    return [f"{path.relative_to(ROOT)}:{line}: {name}" for (path, line), name in found.items()]


def test_no_rule_imports_the_report_package():
    assert list((ROOT / "rules").rglob("*.py")), "the rules folder was not found"
    assert _offending(ROOT / "rules", ("certkit.report", "certkit.cli")) == []


def test_evidence_data_sits_below_the_report():
    assert _offending(ROOT / "certkit" / "evidence", ("certkit.report", "certkit.cli", "certkit_rules", "matplotlib")) == []


def test_the_scan_finds_a_forbidden_import(tmp_path):
    """The scan itself: a module importing the report, in either form, is reported."""
    (tmp_path / "a.py").write_text("def f():\n    from certkit.report.figures import render\n")
    (tmp_path / "b.py").write_text("from certkit import report\n")
    global ROOT
    saved, ROOT = ROOT, tmp_path
    try:
        assert len(_offending(tmp_path, ("certkit.report",))) == 2
    finally:
        ROOT = saved
