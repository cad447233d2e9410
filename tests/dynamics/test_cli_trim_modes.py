"""`certkit trim` and `certkit modes` on the baseline (CLI runner, --json parsed)."""

import json

import pytest

from ..conftest import BASELINE

CRUISE = ("--corner", "fwd_mrw", "--altitude", "31000 ft", "--speed", "M0.84")


def test_trim_at_a_corner_converges_within_limits(cli):
    """Cruise at the forward MRW corner, M 0.84, 31,000 ft: converged, throttle in (0, 1), elevator inside
    its design limits (−21.8°, +16.8°), wings level, no limit exceeded."""
    r = cli("trim", BASELINE, *CRUISE, "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    assert d["converged"] and d["condition"]["loading"] == "fwd_mrw"
    thr = [v for k, v in d["controls"].items() if k.startswith("throttle")]
    assert thr and all(0.0 < t < 1.0 for t in thr)
    assert -21.8 < d["controls"]["elevator"] < 16.8
    assert abs(d["phi_deg"]) < 1e-6 and not d["limits_exceeded"]
    assert d["condition"]["altitude_m"] == pytest.approx(31000 * 0.3048)


def test_trim_names_how_the_corner_was_built(cli):
    """The fwd_light corner cannot be reached with the declared empty airplane: the text output says it was built from
    the declared items with the empty airplane moved, and at what height; a reachable corner names its fuel and
    payload."""
    light = cli("trim", BASELINE, "--corner", "fwd_light", "--altitude", "10000 ft", "--speed", "250 kn CAS").output
    assert "loading built from declared items, empty airplane moved" in light and "height -1.06 m" in light
    mrw = cli("trim", BASELINE, *CRUISE).output
    assert "loading built from declared items: empty airplane (" in mrw and "kg fuel in its tanks" in mrw


def test_modes_present_with_the_expected_signs(cli):
    """All five modes; short period, phugoid and Dutch roll oscillatory (positive frequency) and stable (negative
    real part); the roll mode a stable real root; the short period faster than the phugoid."""
    r = cli("modes", BASELINE, *CRUISE, "--json")
    assert r.exit_code == 0, r.output
    m = json.loads(r.output)["modes"]
    assert set(m) >= {"short_period", "phugoid", "dutch_roll", "roll", "spiral"}
    for name in ("short_period", "phugoid", "dutch_roll"):
        re, im = m[name]["eigenvalue"]
        assert re < 0 and im > 0 and 0 < m[name]["damping_ratio"] < 1
    assert m["roll"]["eigenvalue"][0] < 0 and m["roll"]["eigenvalue"][1] == 0
    assert m["short_period"]["natural_frequency_rad_s"] > 10 * m["phugoid"]["natural_frequency_rad_s"]
    r = cli("modes", BASELINE, *CRUISE)  # text form too
    assert r.exit_code == 0 and "short" in r.output.lower()


@pytest.mark.parametrize(
    "args, words",
    [
        (("--corner", "nope"), ("nope", "fwd_mrw")),
        (("--corner", "fwd_mrw", "--altitude", "50000 ft"), ("ceiling",)),
        (
            ("--maneuver", "oei", "--inoperative", "middle", "--speed", "M0.5", "--altitude", "10000 ft"),
            ("left", "right"),
        ),
    ],
)
@pytest.mark.parametrize("command", ["trim", "modes"])
def test_bad_input_exits_2_with_a_clear_message(cli, command, args, words):
    if command == "modes" and "--maneuver" in args:
        pytest.skip("modes are about the straight-flight trim")
    r = cli(command, BASELINE, *args)
    assert r.exit_code == 2
    assert "Traceback" not in r.output and "error" in r.output.lower()
    for w in words:
        assert w in r.output
