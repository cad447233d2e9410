"""The kernels a baseline check and a redesigned tail's evaluation compile, as the lines of
``certkit/models/kernel_signatures.txt``.

Run to rewrite the list:  python tests/hardening/kernel_usage.py > certkit/models/kernel_signatures.txt
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HEADER = (
    "# certkit's numba kernels compiled ahead at a first run (certkit/models/kernel_warmup.py): module, function,\n"
    "# argument types. Written by `python tests/hardening/kernel_usage.py`; tests/hardening/test_kernel_warmup.py\n"
    "# compares it with what a check and a design evaluation compile.\n"
)
#: a design whose tail differs from the baseline's (the design layer's own code paths)
DESIGN = {"geometry.horizontal_tail.area": "1000 ft^2", "geometry.horizontal_tail.aspect_ratio": 4.2}


def kernel_lines() -> str:
    from certkit.aircraft import load_aircraft
    from certkit.design.evaluate import evaluate_design
    from certkit.engine.registry import discover
    from certkit.engine.scheduler import run
    from certkit.models.kernel_warmup import used_signatures

    baseline = ROOT / "aircraft" / "lta.yaml"
    run(load_aircraft(baseline), discover(), jobs=1)
    evaluate_design(baseline, DESIGN)
    return HEADER + "".join(f"{m} {f} {t}\n" for m, f, t in used_signatures())


if __name__ == "__main__":
    print(kernel_lines(), end="")
