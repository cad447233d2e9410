"""The check report carries the aircraft file's missions (the payload–range diagram drawn in the report)."""

import json
import subprocess
import sys

import pytest

from certkit.aircraft import load_aircraft
from certkit.models.performance.mission import fly_missions


def test_check_report_has_the_mission_and_payload_range(tmp_path):
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "certkit.cli",
            "check",
            "aircraft/lta.yaml",
            "--select",
            "25.103",
            "--out",
            str(tmp_path),
        ],
        capture_output=True,
        text=True,
    )
    assert proc.returncode in (0, 1, 3), proc.stderr
    data = json.loads((tmp_path / "results.json").read_text())
    m = data["models"]["mission"]
    expected = fly_missions(load_aircraft("aircraft/lta.yaml").model)
    # results.json rounds to 9 significant digits (certkit.engine.results_json): within half a unit of the 9th digit
    assert m["design_range_m"] == pytest.approx(expected.design_range_m, rel=5e-9)
    assert "svg" not in m  # the drawing is in the HTML only
    html = (tmp_path / "index.html").read_text()
    assert 'id="mission"' in html and "Payload–range diagram" in html
    assert f"{expected.design_range_m / 1852:,.0f} nmi" in html
