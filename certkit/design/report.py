"""A design record for people: the terminal form of ``certkit evaluate`` (aviation units first, SI beside)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from certkit.units import FT, LB, NMI

_LB = ("_kg", LB, "lb")
_NMI = ("_m", NMI, "nmi")


def _fmt(name: str, value: float | None) -> str:
    if value is None:
        return "—"
    if name.endswith("_kg"):
        return f"{value / LB:,.0f} lb ({value:,.0f} kg)"
    if name.endswith("range_m") or name.endswith("margin_m"):
        return f"{value / NMI:,.0f} nmi"
    if name.endswith("_s") and value > 600:
        return f"{value / 3600:.2f} h"
    if name.endswith("altitude_m"):
        return f"{value / FT:,.0f} ft"
    return f"{value:.4g}"


def print_record(record: dict[str, Any], echo: Callable[[str], object]) -> None:
    r = record["responses"]
    st = record["statuses"]
    echo(f"{record['aircraft']['name']}  (certkit {record['certkit_version']})")
    if record["variables"]:
        echo("\nDesign variables (SI)")
        for path, v in record["variables"].items():
            echo(f"  {path:<58} {v:.6g}")
    groups = [
        ("Objectives", "objective."),
        ("Mission", "mission."),
        ("Constraints", "constraint."),
        ("Sizing", "sizing."),
    ]
    for title, prefix in groups:
        rows = [(k, v) for k, v in r.items() if k.startswith(prefix)]
        if rows:
            echo(f"\n{title}")
            for k, v in rows:
                echo(f"  {k[len(prefix) :]:<40} {_fmt(k, v)}")
    rules = [(k[5:-7], v) for k, v in r.items() if k.startswith("rule.") and k.endswith(".margin")]
    if rules:
        echo("\nRules (normalised minimum margin, ≥ 0 complies)")
        for rid, v in rules:
            echo(f"  §{rid:<14} {st.get('rule.' + rid, ''):>13}  {_fmt('', v)}")
    travel = [(k, v) for k, v in r.items() if k.startswith("travel.") and k.count(".") == 1]
    if travel:
        echo("\nLargest fraction of control travel used (any rule)")
        for k, v in travel:
            echo(f"  {k[7:]:<14} {v:.1%}")
    levels = [(k, v) for k, v in r.items() if k.startswith("level.")]
    if levels:
        worst: dict[str, int] = {}
        for k, v in levels:
            mode = k.split(".")[1]
            worst[mode] = max(worst.get(mode, 0), int(v))
        echo("\nMIL-F-8785C levels (worst over CG corners and configurations; --json has each)")
        echo("  " + ", ".join(f"{m} {lv}" for m, lv in worst.items()))
    n_sub = sum(1 for k in r if k.startswith("subcheck.") and k.endswith(".margin"))
    failing = [k for k, s in st.items() if k.startswith("subcheck.") and s == "fails"]
    echo(
        f"\n{n_sub} named sub-checks ({len(failing)} failing{': ' + ', '.join(failing[:6]) if failing else ''}"
        f"{' …' if len(failing) > 6 else ''}); --json lists them all"
    )
    t = record["timings"]
    echo(
        "Timings: "
        + ", ".join(f"{k[:-2]} {v:.2f} s" for k, v in t.items() if k.endswith("_s") and isinstance(v, float))
    )
