"""The developers' guide: "rules return findings and evidence data; physics procedures live in models, not in rule
modules; rules do not import each other". Every module of the built-in rules package is read (its import statements,
at module level and inside functions) and must not name a module that declares a rule (other than itself): what rules
share lives in modules that declare none (``rules/part25/support/gust.py``, ``support/structural_checks.py`` …), and
those
depend on no rule either."""

from __future__ import annotations

import ast
import importlib
import pkgutil
from pathlib import Path

import certkit_rules

from certkit.engine.registry import _rules_in_module


def _modules() -> dict[str, object]:
    return {
        info.name: importlib.import_module(info.name)
        for info in pkgutil.walk_packages(certkit_rules.__path__, prefix="certkit_rules.")
    }


def _rule_modules(modules) -> set[str]:
    return {name for name, module in modules.items() if _rules_in_module(module, "built-in")}


def _imports(module) -> list[tuple[str, set[str]]]:
    """(module name, names imported from it) of every import statement of ``module``'s source; for
    ``from package import name`` both the package and ``package.name`` (a submodule) are listed."""
    tree = ast.parse(Path(module.__file__).read_text(encoding="utf-8"))
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(a.name, set()) for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names = {a.name for a in node.names}
            out.append((node.module, names))
            out += [(f"{node.module}.{n}", set()) for n in names]
    return out


def _rule_imports(modules) -> list[tuple[str, str, set[str]]]:
    """(importer, imported rule module, names) for every module of the package importing a rule module."""
    rules = _rule_modules(modules)
    return [
        (name, target, names)
        for name in sorted(modules)
        for target, names in _imports(modules[name])
        if target in rules and target != name
    ]


def test_rule_modules_are_found():
    """The check reads the modules the registry discovers (a test that finds no rule module could not fail)."""
    rules = _rule_modules(_modules())
    assert {"certkit_rules.part25.subpart_c.r25_331", "certkit_rules.part25.subpart_b.r25_171"} <= rules
    assert len(rules) >= 20  # 25 modules declare the 37 rules today


def test_shared_modules_declare_no_rule():
    """Rule modules are named for their paragraph (``r25_331``); the shared ones (named for what they hold) declare
    no rule, so the registry finds every rule once, in its own module."""
    modules = _modules()
    rules = _rule_modules(modules)
    assert all(name.rsplit(".", 1)[1].startswith("r25_") for name in rules)
    shared = {name for name, m in modules.items() if not hasattr(m, "__path__")} - rules
    assert {
        "certkit_rules.part25.support.structural_checks",
        "certkit_rules.part25.support.gust_runs",
        "certkit_rules.part25.support.climb_checks",
        "certkit_rules.part25.support.control_checks",
    } <= shared


def test_no_module_imports_a_rule_module():
    """No module of the rules package imports a rule module (§25.121's included: what it shares lives in
    ``support/climb_checks.py``, ``support/control_checks.py`` and ``rules/part25/support/thrust_trims.py``)."""
    found = _rule_imports(_modules())
    assert not found, "modules importing rule modules (move what they share to a module without rules):\n" + "\n".join(
        f"  {who} imports {target} {sorted(names)}" for who, target, names in found
    )
