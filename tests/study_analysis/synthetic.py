"""Synthetic study stores in the documented frame format (INTERFACES.md), built directly as DataFrames.

The responses are made-up smooth functions of the eight horizontal-tail variables of the seed study (bounds
from the ``studies/ht-redesign.yaml`` description), with the shapes the analysis must handle: a
quadratic, a multiplicative (log-linear) response, a margin, integer handling-quality levels (one regressed, one with
its mode quantities, derived from them), failed cases.
"""

from __future__ import annotations

import hashlib
import math

import numpy as np
import pandas as pd
from certkit_rules.part25.support import handling_levels as hq

from certkit.study.spec import Study

FT2 = 0.09290304
DEG = math.pi / 180.0
HT = "geometry.horizontal_tail."
EL = HT + "controls.elevator."

VARIABLES = [
    {"path": HT + "aspect_ratio", "lower": 3.70, "upper": 5.54, "baseline": 4.62, "unit_label": ""},
    {"path": HT + "taper", "lower": 0.26, "upper": 0.40, "baseline": 0.33, "unit_label": ""},
    {"path": HT + "thickness_ratio", "lower": 0.071, "upper": 0.106, "baseline": 0.088, "unit_label": ""},
    {
        "path": HT + "sweep_quarter_chord",
        "lower": 27.86 * DEG,
        "upper": 41.78 * DEG,
        "baseline": 34.82 * DEG,
        "unit_label": "rad",
    },
    {"path": HT + "area", "lower": 895.4 * FT2, "upper": 1343.0 * FT2, "baseline": 1119.0 * FT2, "unit_label": "m^2"},
    {"path": EL + "span_start", "lower": 0.0, "upper": 0.20, "baseline": 0.0, "unit_label": ""},
    {"path": EL + "span_end", "lower": 0.80, "upper": 1.00, "baseline": 0.93, "unit_label": ""},
    {"path": EL + "chord_ratio", "lower": 0.233, "upper": 0.350, "baseline": 0.291, "unit_label": ""},
]


def study_dict(**analysis) -> dict:
    """The study file's data (before validation); the aircraft file is never read by the analysis."""
    return {
        "name": "synthetic-ht",
        "aircraft": "lta.yaml",
        "variables": [
            {
                "path": v["path"],
                "baseline": v["baseline"],
                "bounds": [v["lower"], v["upper"]],
                "unit_label": v["unit_label"],
            }
            for v in VARIABLES
        ],
        "designs": [{"name": "lhs", "generator": "lhs", "n": 10, "seed": 1}],
        "objectives": [
            {"response": "objective.cruise_CD"},
            {"response": "objective.OEW_kg"},
            {"response": "objective.block_fuel_kg"},
        ],
        "constraints": [
            {"name": "range", "response": "constraint.range_margin_m", "min": 0.0},
            {"name": "elevator travel", "response": "subcheck.25.111.elevator_fraction_of_travel.value", "max": 0.7},
            {"name": "short period fwd", "response": "level.short_period.fwd_mrw.clean", "max": 1},
            {"name": "short period cg2", "response": "level.short_period.cg2_mlw.landing", "max": 1},
        ],
        "analysis": analysis or None,
    }


def study_of(data: dict) -> Study:
    """The validated study model of ``data``."""
    return Study.model_validate(data)


def synthetic_study(**analysis) -> Study:
    return study_of(study_dict(**analysis))


def unit(x: np.ndarray) -> np.ndarray:
    b = np.array([[v["lower"], v["upper"]] for v in VARIABLES])
    return (x - b[:, 0]) / (b[:, 1] - b[:, 0]) * 2 - 1


def true_responses(x: np.ndarray) -> dict[str, np.ndarray]:
    """The synthetic 'true model'."""
    u = unit(x)
    ar, tap, tc, sw, area, e0, e1, cr = u.T
    cd = 0.0262 + 0.0004 * area - 0.00015 * ar + 0.0002 * tc + 0.0001 * sw**2 + 0.00005 * area * tc
    oew = 138_000 * np.exp(0.012 * area + 0.006 * ar - 0.004 * tc + 0.003 * sw)
    fuel = 61_000 + 900 * (cd - 0.0262) / 0.0004 + 0.15 * (oew - 138_000)
    rng_margin = 150_000 - 4.0e6 * (cd - 0.0262) - 3.0 * (oew - 138_000) + 20_000 * tap
    elev = 0.62 - 0.08 * area - 0.05 * cr - 0.03 * (e1 - e0) + 0.02 * sw + 0.01 * area**2
    sp = 1.0 + (0.6 * (-area) + 0.3 * sw + 0.9 > 1.2) + (0.6 * (-area) + 0.3 * sw > 0.7)
    # the landing short period at cg2 as a design record gives it: its quantities, and the level the rule's mode
    # table gives them (category C: ζ ≥ 0.35 Level 1, ≥ 0.25 Level 2, ≥ 0.15 Level 3; the CAP inside Level 1)
    zeta2, wn2, cap2 = 0.30 + 0.12 * area + 0.05 * ar, 1.2 + 0.2 * area, 0.5 + 0.2 * area
    sp2 = hq.configuration_level("short_period", "landing", zeta=zeta2, wn=wn2, cap=cap2)
    return {
        "objective.cruise_CD": cd,
        "objective.OEW_kg": oew,
        "objective.block_fuel_kg": fuel,
        "constraint.range_margin_m": rng_margin,
        "subcheck.25.111.elevator_fraction_of_travel.value": elev,
        "level.short_period.fwd_mrw.clean": sp.astype(float),
        "level.short_period.cg2_mlw.landing": sp2.astype(float),
        "mode.short_period.zeta.cg2_mlw.landing": zeta2,
        "mode.short_period.wn_rad_s.cg2_mlw.landing": wn2,
        "mode.short_period.cap.cg2_mlw.landing": cap2,
    }


def sample(n: int, seed: int) -> np.ndarray:
    b = np.array([[v["lower"], v["upper"]] for v in VARIABLES])
    return b[:, 0] + (b[:, 1] - b[:, 0]) * np.random.default_rng(seed).random((n, len(b)))


def frame_of(
    x: np.ndarray, block: str, role: str, *, fail_every: int = 0, noise: float = 0.0, seed: int = 0
) -> pd.DataFrame:
    """Cases in the store's format; every ``fail_every``-th case failed (no responses, an error text)."""
    rng = np.random.default_rng(seed)
    resp = true_responses(x)
    df = pd.DataFrame({f"var:{v['path']}": x[:, i] for i, v in enumerate(VARIABLES)})
    for name, vals in resp.items():
        vals = vals.copy()
        if noise and not name.startswith(("level.", "mode.")):
            vals = vals * (1.0 + noise * rng.standard_normal(len(vals)))
        df[f"resp:{name}"] = vals
    df.insert(0, "key", [hashlib.sha256(f"{block}{r.tobytes().hex()}".encode()).hexdigest() for r in x])
    df.insert(1, "block", block)
    df.insert(2, "role", role)
    df.insert(3, "status", "ok")
    df.insert(4, "error", None)
    df["wall_s"] = 2.0
    df["worker"] = "w0"
    if fail_every:
        bad = np.arange(len(df)) % fail_every == fail_every - 1
        df.loc[bad, "status"] = "failed"
        df.loc[bad, "error"] = "trim did not converge at 25.331(c)(2) condition 3"
        for name in resp:
            df.loc[bad, f"resp:{name}"] = np.nan
    return df


def store_frame(n_train: int = 300, n_val: int = 80, fail_every: int = 25) -> pd.DataFrame:
    return pd.concat(
        [
            frame_of(sample(n_train, 1), "lhs", "training", fail_every=fail_every),
            frame_of(sample(n_val, 2), "random", "validation", fail_every=fail_every),
        ],
        ignore_index=True,
    )
