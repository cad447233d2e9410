"""Small deterministic evaluators for the study runner's tests (named with the hidden --evaluator option).

Each returns a record of the design-record contract (certkit.design-record/2) computed from the variables
alone, so that two runs, two executors or an interrupted and resumed run must give the same bytes.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time

from certkit.errors import UserError

AREA = "geometry.horizontal_tail.area"
SWEEP = "geometry.horizontal_tail.sweep_quarter_chord"
CALLS = []  # (pid, values) of the calls made in this process (serial executor)


def analytic(aircraft_path, values, responses):
    """A cheap smooth function of the variables; timings vary from call to call like a real evaluator's."""
    CALLS.append((os.getpid(), dict(values)))
    start = time.perf_counter()
    area, sweep = values.get(AREA, 100.0), values.get(SWEEP, 0.6)
    cd = 0.02 + 1e-5 * area + 0.01 * (sweep - 0.6) ** 2
    with open(aircraft_path, "rb") as f:
        sha = hashlib.sha256(f.read()).hexdigest()
    return {
        "schema": "certkit.design-record/2",
        "certkit_version": "0.1.0",
        "aircraft": {"name": "test", "sha256": sha},
        "variables": dict(values),
        "responses": {
            "objective.cruise_CD": cd,
            "objective.OEW_kg": 1.4e5 + 30.0 * area,
            "constraint.range_margin_m": 1.0e5 - 900.0 * area,
            "subcheck.25.111.elevator_fraction_of_travel.value": 0.5 + math.cos(sweep) / 10,
            "level.short_period.fwd_mrw.clean": None,
        },
        "statuses": {},
        "details": {"responses_requested": responses},
        "timings": {"total_s": time.perf_counter() - start + 1e-9 * os.getpid()},
    }


def flaky(aircraft_path, values, responses):
    """Fails (a trim that does not converge) for the larger tails."""
    if values[AREA] > 104.0:
        raise RuntimeError(f"trim did not converge at area {values[AREA]:.3f} m^2")
    return analytic(aircraft_path, values, responses)


def sleepy(aircraft_path, values, responses):
    """The analytic record after 0.1–0.4 s (a duration fixed by the values), to leave time to kill a run."""
    digest = hashlib.sha256(json.dumps(sorted(values.items())).encode()).digest()
    time.sleep(0.1 + 0.3 * digest[0] / 255)
    return analytic(aircraft_path, values, responses)


def slow(aircraft_path, values, responses):
    time.sleep(float(os.environ.get("CERTKIT_TEST_SLEEP", "2")))
    return analytic(aircraft_path, values, responses)


def crashing(aircraft_path, values, responses):
    """Kills its own process for the larger tails (a segfault, the OOM killer)."""
    if values[AREA] > 104.0:
        os._exit(9)
    return analytic(aircraft_path, values, responses)


def mistaken(aircraft_path, values, responses):
    raise UserError("geometry.horizontal_tail.aera: no such aircraft-file path")
