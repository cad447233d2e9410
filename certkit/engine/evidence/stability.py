"""Evidence data of the stability and controllability rules (§§25.147–25.181): a matrix of margins over CG corners
× configurations, and the damping–frequency chart of the rigid-body modes with the MIL-F-8785C level boundaries."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from certkit.engine.evidence.data import Axis, Chart, Column, Heatmap, Limit, Panel, Series, Table
from certkit.engine.results import Evidence, Finding, margin_key


def margin_matrix(findings: Iterable[Finding]) -> tuple[list[str], list[str], np.ndarray, dict[tuple[str, str], str]]:
    """(corners, configurations, matrix of the smallest normalised margin, critical check per cell).
    NaN where nothing was evaluated."""
    corners: list[str] = []
    configs: list[str] = []
    cells: dict[tuple[str, str], tuple[float, str]] = {}
    for f in findings:
        loading = f.condition.loading
        if f.margin is None or loading is None:
            continue
        cfg = f.condition.configuration or "—"
        if loading not in corners:
            corners.append(loading)
        if cfg not in configs:
            configs.append(cfg)
        m = margin_key(f)
        key = (loading, cfg)
        if key not in cells or m < cells[key][0]:
            cells[key] = (m, f.check)
    mat = np.full((len(corners), len(configs)), np.nan)
    for (ld, cfg), (m, _) in cells.items():
        mat[corners.index(ld), configs.index(cfg)] = m
    return corners, configs, mat, {k: v[1] for k, v in cells.items()}


def margin_matrix_evidence(findings: Iterable[Finding], title: str) -> list[Evidence]:
    corners, configs, mat, checks = margin_matrix(findings)
    if not corners:
        return []
    rows = [
        [ld, cfg, float(mat[i, j]) if math.isfinite(mat[i, j]) else None, checks.get((ld, cfg), "")]
        for i, ld in enumerate(corners)
        for j, cfg in enumerate(configs)
    ]
    table = Table(
        [
            Column("corner", "CG corner", kind="text"),
            Column("configuration", "configuration", kind="text"),
            Column("margin", "smallest normalised margin"),
            Column("check", "critical check", kind="text"),
        ],
        rows,
    )
    heatmap = Heatmap(
        corners, configs, mat, Axis("smallest normalised margin"), row_label="CG corner", column_label="configuration"
    )
    return [
        Evidence(
            title,
            heatmap,
            caption=(
                "Smallest normalised margin (margin / |limit|, or the margin itself where the limit is zero) of every "
                "check "
                "at each CG corner and configuration, over the speeds and altitudes evaluated; ≥ 0 complies. Failing "
                "cells "
                "are vermillion and hatched; grey cells were not evaluated."
            ),
            table=table,
        )
    ]


_MARKERS = {"short_period": "o", "phugoid": "s", "dutch_roll": "^"}
_LEVEL_COLOUR = {1: 0, 2: 1, 3: 3, 4: 5}  # palette entries: blue, orange, purple, vermillion


def damping_frequency_chart(points: list[dict[str, Any]], boundaries: list[tuple[str, float, str]]) -> Chart:
    """(damping ratio, natural frequency) of the oscillatory modes, one colour per Level and one marker per mode,
    with the damping-ratio boundaries (label, ζ, mode) as labelled limits and ζ = 0 (unstable left of it)."""
    groups: dict[tuple[str, int], list[tuple[float, float]]] = {}
    for p in points:
        if p["mode"] in _MARKERS:
            groups.setdefault((p["mode"], p["level"]), []).append((p["zeta"], p["wn"]))
    series = []
    for (mode, level), xy in sorted(groups.items()):
        z, w = np.array(xy).T
        series.append(
            Series(
                f"{mode.replace('_', ' ')} — Level {level if level < 4 else '>3'}",
                z,
                w,
                style="none",
                marker=_MARKERS[mode],
                colour=_LEVEL_COLOUR[level],
            )
        )
    limits = [Limit(zeta, label, axis="x", kind="reference") for label, zeta, _ in boundaries]
    limits.append(Limit(0.0, "ζ = 0", axis="x", kind="limit"))
    return Chart(
        Axis("damping ratio ζ"), [Panel(Axis("natural frequency ωn", "rad/s", "rad/s", log=True), series, limits)]
    )
