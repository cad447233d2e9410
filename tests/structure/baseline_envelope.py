"""The baseline's horizontal-tail LIMIT load envelope as the Subpart C loads rules compute it, stored as a small
data file so that the sizing tests need not run the rules (20 s).

Regenerate (after a change of the loads model or the baseline) with

    certkit check aircraft/lta.yaml --select 25.331,25.341,25.349,25.351 --out /tmp/ck -j 1
    python -m tests.structure.baseline_envelope /tmp/ck/results.json

It keeps, per station of the horizontal tail, the largest magnitude of shear (N), bending and torsion (N·m)
over every finding of the four rules that loads the tail (§25.331(c)(1) and (c)(2) all but the wing's; §25.341(a),
§25.349(a) and (b), §25.351 where the check names the horizontal tail), from the findings' "max/min" details.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

DATA = Path(__file__).parent / "data" / "baseline_ht_limit_envelope.json"
QUANTITIES = ("shear", "bending", "torsion")


def _magnitudes(value) -> list[float]:
    if isinstance(value, list):
        return [m for v in value for m in _magnitudes(v)]
    return [] if value is None else [abs(float(value))]


def extract(results: dict) -> dict:
    env: dict[str, dict[str, list]] = {}
    for rule in results["rules"]:
        for f in rule["findings"]:
            if not (rule["id"].startswith("25.331") or "horizontal tail" in f["check"]) or ", wing" in f["check"]:
                continue  # the wing's findings of §25.331 (its balanced and checked manoeuvres) load the wing
            for key, value in f["details"].items():
                if "max/min" not in key:
                    continue
                station = key.split(" ")[0] if key.startswith("root") else key.rsplit(" ", 3)[0]
                station = station.replace(" down-going/up-going side", "")
                quantity = next(q for q in QUANTITIES if q in key)
                mags = _magnitudes(value)
                if not mags:
                    continue
                best = env.setdefault(station, {}).get(quantity, [0.0, ""])
                if max(mags) > best[0]:
                    env[station][quantity] = [max(mags), f"{rule['id']} {f['check']}"]
    return env


def station_span(aircraft, station: str) -> float:
    """In-plane distance (m) from the tail root of a loads-model station name (root, side of body, NN% span)."""
    ht = aircraft.geometry.horizontal_tail
    cos = math.cos(ht.dihedral)
    tip = math.sqrt(ht.area * ht.aspect_ratio) / 2.0 / cos
    if station == "root":
        return 0.0
    if station == "side of body":
        return 0.5 * aircraft.geometry.fuselage.width / cos
    return float(station.rstrip("% span")) / 100.0 * tip


def main(path: str) -> None:
    env = extract(json.loads(Path(path).read_text()))
    out = {
        "source": "certkit check aircraft/lta.yaml --select 25.331,25.341,25.349,25.351 (limit loads, kN and kN·m "
        "in the findings, stored here in N and N·m)",
        "stations": {s: {q: [round(v[0] * 1e3, 1), v[1]] for q, v in qs.items()} for s, qs in env.items()},
    }
    DATA.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {DATA}")


if __name__ == "__main__":
    main(sys.argv[1])
