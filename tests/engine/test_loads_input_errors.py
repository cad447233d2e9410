"""Bad loads input: stops inside the design limits, a flap limit factor above the clean one, a capability
at a station no load is computed at — each reported with its YAML path and line, all together, exit code 2."""

from ..conftest import BASELINE
from ..rules.helpers import edited_baseline

ELEVATOR_TRAVEL = "        travel: {min: -30 deg, max: 25 deg}              # [given] trailing edge up negative"
FLAPS_FACTOR = "    flaps_extended: 2.0"
SOB_SHEAR = "    - {station: side_of_body, quantity: shear, limit: 6775 kN"


def _edited(tmp_path, edits):
    path = edited_baseline(tmp_path, edits)
    return path, path.read_text().splitlines()


def _line_of(lines, needle):
    return next(i for i, line in enumerate(lines, 1) if needle in line)


def test_stop_inside_design_limit_and_flap_factor(cli, tmp_path):
    """The elevator stop at −20° inside its −21.8° design limit; flaps-extended 2.8 g above the clean 2.5 g."""
    path, lines = _edited(
        tmp_path,
        [(ELEVATOR_TRAVEL, ELEVATOR_TRAVEL.replace("-30 deg", "-20 deg")), (FLAPS_FACTOR, "    flaps_extended: 2.8")],
    )
    out = cli("check", path, "--select", "25.337", "--out", tmp_path / "rep")
    assert out.exit_code == 2 and "Traceback" not in out.output
    assert "2 problems" in out.output
    elevator = next(line for line in out.output.splitlines() if "controls.elevator" in line)
    assert "-21.8° to 16.8°" in elevator and "-20.0° to 25.0°" in elevator and "stop inside a design limit" in elevator
    reported = int(elevator.split("edited.yaml:")[1].split(":")[0])  # the elevator's mapping, at or after its key
    assert _line_of(lines, "elevator:") <= reported <= _line_of(lines, "travel: {min: -20 deg")
    flaps = next(line for line in out.output.splitlines() if "flaps_extended" in line)
    assert f"edited.yaml:{_line_of(lines, 'flaps_extended: 2.8')}:" in flaps and "(got 2.8)" in flaps


def test_capability_without_its_station(cli, tmp_path):
    """A wing capability at the tip (station 1.0) has no load to be compared with: an error, not a silent skip."""
    path, lines = _edited(tmp_path, [(SOB_SHEAR, SOB_SHEAR.replace("side_of_body", "1.0"))])
    out = cli("check", path, "--select", "25.337", "--out", tmp_path / "rep")
    assert out.exit_code == 2
    (msg,) = [line for line in out.output.splitlines() if "structure.wing" in line]
    assert "structure.wing.3.station" in msg and "inboard" in msg and "(got 1.0)" in msg
    assert f"edited.yaml:{_line_of(lines, '{station: 1.0, quantity: shear')}:" in msg


def test_side_of_body_outside_a_small_tail(cli, tmp_path):
    """A horizontal tail of 60 ft² and aspect ratio 4.62 has an 8.3 ft semispan, inside the fuselage half width
    (20.23/2 ft): its side-of-body capability has no station."""
    text = BASELINE.read_text()
    start = text.index("  horizontal_tail:\n", text.index("geometry:"))
    area_line = next(line for line in text[start:].splitlines() if line.strip().startswith("area:"))
    path, _ = _edited(tmp_path, [(area_line, "    area: 60 ft^2")])
    out = cli("check", path, "--select", "25.337", "--out", tmp_path / "rep")
    assert out.exit_code == 2
    assert "structure.horizontal_tail." in out.output and "outside the horizontal tail semispan" in out.output


AILERON_LIMITS = "        design_limits: {min: -25 deg, max: 25 deg}  # estimate: 5 deg short of travel"


def test_overlapping_control_segments(cli, tmp_path):
    """A flaperon segment declared over the aileron's own span: one problem naming the control's YAML path and both
    spans, exit 2, no traceback."""
    segment = "\n        segments: [{name: flaperon, span_start: 0.70, span_end: 0.80, chord_ratio: 0.25, gain: 0.6}]"
    path, lines = _edited(tmp_path, [(AILERON_LIMITS, AILERON_LIMITS + segment)])
    out = cli("check", path, "--select", "25.337", "--out", tmp_path / "rep")
    assert out.exit_code == 2 and "Traceback" not in out.output
    problem = next(line for line in out.output.splitlines() if "controls.aileron" in line)
    assert "the control (from 0.78) overlaps or abuts segment 'flaperon' (to 0.8)" in problem
