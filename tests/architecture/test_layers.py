"""The layers of the developers' guide, declared once (:data:`LAYERS`, bottom first) and checked on the source: a
module may import its own layer and the layers below it, never one above. Every import statement is read, at module
level and inside functions, so the check cannot pass because an import happens to be lazy.

Each exception in :data:`ALLOWED_UPWARD` names the importing module, the imported one and why the import is not a
dependency of the lower layer on the upper one."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: (layer name, the packages or modules it holds), bottom first. A module belongs to the longest prefix that names it.
LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    (
        "base",
        (
            "certkit.units",
            "certkit.atmosphere",
            "certkit.errors",
            "certkit.conventions",
            "certkit.interrupts",
            "certkit.user_cache",
            "certkit.lean_imports",
            "certkit",
        ),
    ),
    ("aircraft file", ("certkit.aircraft",)),
    ("models", ("certkit.models",)),
    ("engine", ("certkit.engine",)),
    ("rules", ("certkit_rules",)),
    ("design", ("certkit.design",)),
    ("study", ("certkit.study",)),
    ("report", ("certkit.report",)),
    ("cli", ("certkit.cli",)),
)

#: (importing module, imported module): why it is not an upward dependency.
ALLOWED_UPWARD: dict[tuple[str, str], str] = {
    (
        "certkit.engine.registry",
        "certkit_rules",
    ): "discovery: the registry loads the built-in rules package by name, as it loads plugins' entry points",
}

#: The source folders and the package each holds.
SOURCES = ((ROOT / "certkit", "certkit"), (ROOT / "rules", "certkit_rules"))


def layer_of(module: str) -> int | None:
    """Index in :data:`LAYERS` of a certkit module (None for third-party modules)."""
    best, best_len = None, -1
    for index, (_, prefixes) in enumerate(LAYERS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > best_len:
                best, best_len = index, len(prefix)
    return best


def module_name(path: Path, folder: Path, package: str) -> str:
    parts = list(path.relative_to(folder).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join([package, *parts])


def imports(path: Path, module: str):
    """(line, names) for every import statement of a file, relative ones resolved: ``from a import b`` names ``a.b``
    then ``a`` (``b`` may be a module or a name in ``a``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node.lineno, (alias.name,)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")
                anchor = anchor[: len(anchor) - (node.level - 1)]
                base = ".".join(anchor + ([base] if base else []))
            for alias in node.names:  # from certkit import report
                yield node.lineno, (f"{base}.{alias.name}", base)


def upward_imports(sources=SOURCES) -> list[str]:
    found = []
    for folder, package in sources:
        for path in sorted(folder.rglob("*.py")):
            module = module_name(path, folder, package)
            own = layer_of(module)
            for line, names in imports(path, module):
                name = names[0]
                target = layer_of(name)
                if target is None or own is None or target <= own:
                    continue
                if any(module == m and (name == a or name.startswith(a + ".")) for m, a in ALLOWED_UPWARD):
                    continue
                found.append(
                    f"{path.relative_to(path.parents[len(path.relative_to(folder).parts)])}:{line}: "
                    f"{module} ({LAYERS[own][0]}) imports {name} ({LAYERS[target][0]})"
                )
    return sorted(set(found))


def test_every_import_points_down_the_declared_layers():
    assert upward_imports() == []


def test_the_tree_shows_the_layers():
    """Every module of certkit sits in a declared layer's package (the root holds only the base modules)."""
    root_modules = {p.stem for p in (ROOT / "certkit").glob("*.py")} - {"__init__"}
    base = {m.rpartition(".")[2] for m in LAYERS[0][1] if m != "certkit"}
    assert root_modules <= base, f"modules at the package root outside the base layer: {sorted(root_modules - base)}"
    packages = {p.name for p in (ROOT / "certkit").iterdir() if (p / "__init__.py").exists()}
    declared = {m.split(".")[1] for _, prefixes in LAYERS[1:] for m in prefixes if m.startswith("certkit.")}
    assert packages <= declared, f"packages in no declared layer: {sorted(packages - declared)}"


@pytest.mark.parametrize(
    "source, expected",
    [
        ("from certkit.engine.results import Finding\n", "(models) imports certkit.engine.results.Finding (engine)"),
        ("def f():\n    from certkit.report import figures\n", "imports certkit.report.figures (report)"),
        ("from certkit import cli\n", "imports certkit.cli (cli)"),
        ("import certkit_rules.part25\n", "imports certkit_rules.part25 (rules)"),
    ],
)
def test_a_deliberately_wrong_import_is_found(tmp_path, source, expected):
    """The scan itself: a models module importing upward, lazily or not, in each import form, is reported."""
    folder = tmp_path / "certkit"
    (folder / "models").mkdir(parents=True)
    (folder / "models" / "__init__.py").write_text("")
    (folder / "models" / "bad.py").write_text(source)
    found = upward_imports(((folder, "certkit"),))
    assert len(found) == 1 and expected in found[0], found


def test_a_relative_import_is_resolved(tmp_path):
    folder = tmp_path / "certkit"
    (folder / "models" / "aero").mkdir(parents=True)
    (folder / "models" / "aero" / "bad.py").write_text("from ...engine import context\n")
    found = upward_imports(((folder, "certkit"),))
    assert len(found) == 1 and "certkit.engine" in found[0], found


def test_evidence_data_draws_nothing():
    """Rules return evidence as data; only the report draws: the evidence package imports no plotting library."""
    folder = ROOT / "certkit" / "engine" / "evidence"
    drawing = [
        f"{path.name}:{line}: {names[0]}"
        for path in sorted(folder.rglob("*.py"))
        for line, names in imports(path, module_name(path, ROOT / "certkit", "certkit"))
        if names[0].split(".")[0] == "matplotlib" or names[-1].split(".")[0] == "matplotlib"
    ]
    assert list(folder.rglob("*.py")) and drawing == []
