"""Imports belong at the top of a module. An import inside a function or method is kept only where something needs
it there, and its first line says what: ``# deferred: <reason>`` — the start-up of the CLI or of the worker processes
(a heavy library, or a layer a command loads only when it runs), an import cycle, or an optional dependency that may
be absent. The scan reads every module of certkit and of the rules (``ast`` for the imports, ``tokenize`` for the
comments) and lists each function-level import without a reason."""

from __future__ import annotations

import ast
import io
import tokenize

import pytest

from ..conftest import ROOT

#: the source folders scanned
SOURCES = (ROOT / "certkit", ROOT / "rules")
MARK = "# deferred:"


def _comments(source: str) -> dict[int, str]:
    """Line number → the comment on that line."""
    return {
        tok.start[0]: tok.string
        for tok in tokenize.generate_tokens(io.StringIO(source).readline)
        if tok.type == tokenize.COMMENT
    }


def _function_imports(tree: ast.AST):
    """Every import statement inside a function or method body (nested ones included)."""
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for inner in ast.walk(node):
                if isinstance(inner, (ast.Import, ast.ImportFrom)):
                    yield inner


def unexplained_imports(sources=SOURCES) -> list[str]:
    """``file:line: import`` of each function-level import whose first line has no ``# deferred: <reason>``."""
    found = set()
    for folder in sources:
        for path in sorted(folder.rglob("*.py")):
            source = path.read_text(encoding="utf-8")
            comments = _comments(source)
            for node in _function_imports(ast.parse(source, str(path))):
                comment = comments.get(node.lineno, "")
                reason = comment.partition(MARK)[2].strip() if comment.startswith(MARK) else ""
                if not reason:
                    found.add((str(path.relative_to(folder.parent)), node.lineno, ast.unparse(node)))
    return [f"{file}:{line}: {text}" for file, line, text in sorted(found)]


def test_every_function_level_import_names_its_reason():
    assert unexplained_imports() == []


@pytest.mark.parametrize(
    "source, expected",
    [
        ("def f():\n    import math\n", ["certkit/bad.py:2: import math"]),
        ("def f():\n    import math  # deferred:\n", ["certkit/bad.py:2: import math"]),
        ("def f():\n    import math  # deferred:   \n", ["certkit/bad.py:2: import math"]),
        ("def f():\n    import math  # start-up\n", ["certkit/bad.py:2: import math"]),
        ("def f():\n    x = 1  # deferred: not an import\n    import math\n", ["certkit/bad.py:3: import math"]),
        ("class A:\n    def f(self):\n        from os import path\n", ["certkit/bad.py:3: from os import path"]),
        ("def f():\n    def g():\n        import json\n", ["certkit/bad.py:3: import json"]),
        ("def f():\n    if True:\n        import json\n", ["certkit/bad.py:3: import json"]),
        ("def f():\n    from os import (  # deferred: a reason\n        path,\n    )\n", []),
        ("def f():\n    from os import (\n        path,  # deferred: on a later line\n    )\n", ["certkit/bad.py:2: "]),
        ("def f():\n    import math  # deferred: CLI start-up\n", []),
        ("import math\n\n\ndef f():\n    return math.pi\n", []),
    ],
)
def test_a_function_level_import_without_a_reason_is_found(tmp_path, source, expected):
    """The scan itself: bare, empty-reason and misplaced comments are reported, in functions, methods, nested
    functions and blocks; a reason on the first line, or an import at the top, passes."""
    folder = tmp_path / "certkit"
    folder.mkdir()
    (folder / "bad.py").write_text(source)
    found = unexplained_imports((folder,))
    assert len(found) == len(expected) and all(f.startswith(e) for f, e in zip(found, expected)), found
