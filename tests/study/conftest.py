"""A small study on a stand-in aircraft file (the test evaluators do not read the aircraft)."""

from __future__ import annotations

from pathlib import Path

import pytest

EVALUATORS = "tests.study.evaluators"

STUDY = """\
name: small
aircraft: aircraft.yaml
variables:
  - {path: geometry.horizontal_tail.area, baseline: 1119.2 ft^2, bounds: [1000 ft^2, 1240 ft^2]}
  - {path: geometry.horizontal_tail.sweep_quarter_chord, baseline: 34.82 deg, bounds: ±10 %}
designs:
  - {name: ccd, generator: ccd}
  - {name: lhs, generator: lhs, n: LHS_N, seed: 3}
responses: [objective.*, constraint.*, subcheck.*]
objectives:
  - {response: objective.cruise_CD}
constraints:
  - {name: range, response: constraint.range_margin_m, min: 0}
"""


def write_study(folder: Path, lhs: int = 6, extra: str = "") -> Path:
    (folder / "aircraft.yaml").write_text("name: stand-in\n")
    path = folder / "small.yaml"
    path.write_text(STUDY.replace("LHS_N", str(lhs)) + extra)
    return path


@pytest.fixture
def small_study(tmp_path) -> Path:
    return write_study(tmp_path)
