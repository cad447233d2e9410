"""What ``certkit check`` prints: live progress on standard error, one row per rule fitted to the terminal width.

Progress: on a terminal a rich progress bar (rules done, the rule running, elapsed time and ETA); piped, one plain
line per finished rule (``[ 3/34] §25.337  complies  0.4 s  ETA 12 s``); nothing with ``--quiet``. The ETA scales
the elapsed time by the declared relative cost (:attr:`certkit.engine.registry.Rule.cost`) of the rules still to run.
Margins are shown in aviation units (:mod:`certkit.report.display`); results.json keeps SI.
"""

from __future__ import annotations

import os
import shutil
import sys
import time

import click

from certkit.engine.results import STATUS_LABEL
from certkit.report.reasons import margin_text

_COLOURS = {"complies": "green", "complies_partial": "cyan", "fails": "red", "not_evaluated": "yellow"}


def rule_rows(results, width: int | None = None, colour: bool = False) -> list[str]:
    """One line per rule, at most ``width`` characters (default: the terminal's; not cut when piped): status, §, title,
    critical margin, and the critical
    condition or, for a rule without a margin (not evaluated), its reason."""
    if width is None and (sys.stdout.isatty() or os.environ.get("COLUMNS")):
        width = shutil.get_terminal_size().columns
    lines = []
    for r in results:
        crit = r.critical
        margin = margin_text(crit.margin, crit.unit) if crit else "—"
        if r.status == "not_evaluated" or not crit:
            where = "reason: " + r.not_evaluated_reason
        else:
            where = f"{crit.condition.label()} — {crit.check}"
        status = STATUS_LABEL[r.status]
        head = f"{status:>17}  §{r.id:<13} "
        title = f"[override] {r.title}" if r.overrides else r.title
        if width:
            room = width - len(head) - 16  # the margin column and its spaces
            title_w = min(40, max(8, room // 2))
            title = _fit(title, title_w)
            row = f"{head}{title:<{title_w}} {margin:>14}  "
            row = (row + _fit(where, max(1, width - len(row))))[:width]
        else:
            row = f"{head}{title:<44} {margin:>14}  {where}"
        if colour:
            row = click.style(status.rjust(17), fg=_COLOURS[r.status], bold=r.status == "fails") + row[17:]
        lines.append(row)
    return lines


def _fit(text: str, width: int) -> str:
    return text if len(text) <= width else text[: max(0, width - 1)] + "…"


class Progress:
    """Tells the user which rules run and how long is left (see the module docstring)."""

    def __init__(self, rules, *, quiet: bool = False, stream=None):
        self.stream = stream or sys.stderr
        self.cost = {r.id: float(r.cost) for r in rules}
        self.total = sum(self.cost.values()) or 1.0
        self.n = len(rules)
        self.done_cost = 0.0
        self.done = 0
        self.running: list[str] = []
        self.start = time.perf_counter()
        self.quiet = quiet
        self.live = not quiet and hasattr(self.stream, "isatty") and self.stream.isatty()
        self._bar = None
        if self.live:
            from rich.console import Console  # deferred: rich only for a live progress bar (a terminal)
            from rich.progress import (  # deferred: rich only for a live progress bar (a terminal)
                BarColumn,
                MofNCompleteColumn,
                TextColumn,
                TimeElapsedColumn,
            )
            from rich.progress import Progress as Bar  # deferred: rich only for a live progress bar (a terminal)

            self._bar = Bar(
                TextColumn("checking"),
                BarColumn(),
                MofNCompleteColumn(),
                TimeElapsedColumn(),
                TextColumn("{task.fields[eta]}"),
                TextColumn("{task.fields[running]}"),
                console=Console(file=self.stream),
                transient=True,
            )
            self._task = self._bar.add_task("check", total=self.n, eta="", running="")
            self._bar.start()

    def eta(self) -> float | None:
        elapsed = time.perf_counter() - self.start
        if self.done_cost <= 0:
            return None
        return elapsed * (self.total - self.done_cost) / self.done_cost

    def started(self, rule_ids) -> None:
        self.running += list(rule_ids)
        self._refresh()

    def finished(self, results) -> None:
        for r in results:
            if r.id in self.running:
                self.running.remove(r.id)
            self.done += 1
            self.done_cost += self.cost.get(r.id, 1.0)
            if self.quiet:
                continue
            eta = self.eta()
            line = (
                f"[{self.done:>{len(str(self.n))}}/{self.n}] §{r.id:<13} {STATUS_LABEL[r.status]:<17} "
                f"{r.seconds or 0.0:6.1f} s" + (f"  ETA {eta:.0f} s" if eta is not None and self.done < self.n else "")
            )
            if self._bar is not None:
                self._bar.console.print(
                    line, highlight=False, style=_COLOURS[r.status] if r.status == "fails" else None
                )
            else:
                print(line, file=self.stream, flush=True)
        self._refresh()

    def _refresh(self) -> None:
        if self._bar is None:
            return
        eta = self.eta()
        self._bar.update(
            self._task,
            completed=self.done,
            eta=f"ETA {eta:.0f} s" if eta is not None else "",
            running=", ".join("§" + i for i in self.running[:3]),
        )

    def close(self) -> None:
        if self._bar is not None:
            self._bar.stop()
