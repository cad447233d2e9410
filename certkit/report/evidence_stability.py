"""Evidence for the stability and controllability rules (§§25.147–25.181): a matrix of margins over
CG corners × configurations, and the damping–frequency chart of the rigid-body modes with the
MIL-F-8785C level boundaries."""

from __future__ import annotations

import math

import numpy as np

from certkit.report.plots import figure_to_svg, subplots, text_width
from certkit.results import Evidence


def margin_matrix(findings) -> tuple[list[str], list[str], np.ndarray, dict]:
    """(corners, configurations, matrix of the smallest normalised margin, critical check per cell).
    NaN where nothing was evaluated."""
    corners, configs = [], []
    cells: dict[tuple[str, str], tuple[float, str]] = {}
    for f in findings:
        if f.margin is None or f.condition.loading is None:
            continue
        c = f.condition
        cfg = c.configuration or "—"
        if c.loading not in corners:
            corners.append(c.loading)
        if cfg not in configs:
            configs.append(cfg)
        m = f.normalized_margin if f.normalized_margin is not None else f.margin
        key = (c.loading, cfg)
        if key not in cells or m < cells[key][0]:
            cells[key] = (m, f.check)
    mat = np.full((len(corners), len(configs)), np.nan)
    for (ld, cfg), (m, _) in cells.items():
        mat[corners.index(ld), configs.index(cfg)] = m
    return corners, configs, mat, {k: v[1] for k, v in cells.items()}


def margin_matrix_svg(corners, configs, mat, title="") -> str:
    fig, ax = subplots(figsize=(1.6 + 1.3 * len(configs), 0.9 + 0.36 * len(corners)), left=text_width(corners, 9) + 0.25,
                       top=0.35 if title else 0.15)
    finite = mat[np.isfinite(mat)]
    span = max(1e-9, float(np.max(np.abs(finite)))) if finite.size else 1.0
    ax.imshow(np.clip(mat, -span, span), cmap="RdYlGn", vmin=-span, vmax=span, aspect="auto")
    for i in range(len(corners)):
        for j in range(len(configs)):
            v = mat[i, j]
            ax.text(j, i, "—" if not math.isfinite(v) else f"{v:+.2f}", ha="center", va="center", fontsize=8)
    ax.set_xticks(range(len(configs)), configs)
    ax.set_yticks(range(len(corners)), corners)
    ax.set_xlabel("configuration")
    if title:
        ax.set_title(title, fontsize=9)
    return figure_to_svg(fig)


def margin_matrix_evidence(findings, title: str) -> list[Evidence]:
    corners, configs, mat, checks = margin_matrix(findings)
    if not corners:
        return []
    rows = [{"corner": ld, "configuration": cfg, "smallest normalised margin": None if not math.isfinite(mat[i, j]) else round(float(mat[i, j]), 4),
             "critical check": checks.get((ld, cfg), "")} for i, ld in enumerate(corners) for j, cfg in enumerate(configs)]
    return [Evidence(title, margin_matrix_svg(corners, configs, mat), caption=(
        "Smallest normalised margin (margin / |limit|, or the margin itself where the limit is zero) of every check "
        "at each CG corner and configuration, over the speeds and altitudes evaluated; ≥ 0 complies."), table=rows)]


_MARKERS = {"short_period": "o", "phugoid": "s", "dutch_roll": "^", "roll": "v", "spiral": "D"}


def damping_frequency_svg(points: list[dict], boundaries: list[tuple[str, float, str]]) -> str:
    """Scatter of (damping ratio, natural frequency) of the oscillatory modes, one colour per Level, with
    vertical lines at the damping-ratio boundaries (label, ζ, mode)."""
    fig, ax = subplots(figsize=(6.6, 4.0))
    colours = {1: "#2e7d32", 2: "#f9a825", 3: "#ef6c00", 4: "#c0392b"}
    groups: dict[tuple[str, int], list[tuple[float, float]]] = {}
    for p in points:
        if p["mode"] in ("short_period", "phugoid", "dutch_roll"):
            groups.setdefault((p["mode"], p["level"]), []).append((p["zeta"], p["wn"]))
    for (mode, level), xy in sorted(groups.items()):
        z, w = np.array(xy).T
        ax.scatter(z, w, marker=_MARKERS[mode], color=colours[level], s=22, edgecolors="0.2", linewidths=0.3,
                   label=f"{mode.replace('_', ' ')} — Level {level if level < 4 else '>3'}")
    for label, zeta, mode in boundaries:
        ax.axvline(zeta, color="0.4", ls=":", lw=0.8)
        ax.annotate(label, (zeta, 0.012), rotation=90, fontsize=6.5, color="0.3", textcoords="offset points", xytext=(2, 0))
    ax.axvline(0.0, color="#c0392b", lw=0.9)
    ax.set_yscale("log")
    ax.set_xlabel("damping ratio ζ")
    ax.set_ylabel("natural frequency ωn (rad/s)")
    ax.grid(True, alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper right", ncol=1)
    return figure_to_svg(fig)
