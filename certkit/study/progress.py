"""Progress of a run: a live bar on a terminal (rich), plain periodic lines otherwise (logs, CI, pipes).

Both show the cases done out of the study's total, the failed ones, the rate of this run and the time left.
"""

from __future__ import annotations

import sys
import time
from typing import Any, TextIO


def _duration(seconds: float) -> str:
    seconds = int(round(seconds))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    return f"{h}h{m:02d}m{s:02d}s" if h else (f"{m}m{s:02d}s" if m else f"{s}s")


class _Counts:
    def __init__(self, total: int, done: int, failed: int):
        self.total, self.done, self.failed = total, done, failed
        self.run_done = 0
        self.start = time.monotonic()

    def add(self, status: str) -> None:
        self.done += 1
        self.run_done += 1
        self.failed += status == "failed"

    def rate(self) -> float:
        elapsed = time.monotonic() - self.start
        return self.run_done / elapsed if elapsed > 0 else 0.0

    def eta(self) -> str:
        rate = self.rate()
        return _duration((self.total - self.done) / rate) if rate > 0 else "?"

    def line(self) -> str:
        return f"{self.done}/{self.total} done, {self.failed} failed · {self.rate():.3g} cases/s · ETA {self.eta()}"


class PlainProgress:
    """A line at most every ``interval`` seconds (when a case finishes), and one at the end."""

    def __init__(
        self, total: int, done: int, failed: int, label: str, stream: TextIO | None = None, interval: float = 10.0
    ):
        self.counts = _Counts(total, done, failed)
        self.label, self.interval = label, interval
        self.stream = stream or sys.stdout
        self._last = time.monotonic()

    def __enter__(self) -> PlainProgress:
        return self

    def advance(self, status: str) -> None:
        self.counts.add(status)
        now = time.monotonic()
        if now - self._last >= self.interval:
            self._last = now
            self._print()

    def _print(self) -> None:
        print(f"[{time.strftime('%H:%M:%S')}] {self.label}: {self.counts.line()}", file=self.stream, flush=True)

    def __exit__(self, *exc: object) -> None:
        self._print()


class LiveProgress:
    """rich's live bar: done/total, failed, rate, ETA."""

    def __init__(self, total: int, done: int, failed: int, label: str, stream: TextIO | None = None):
        from rich.console import Console  # deferred: rich only for a live progress bar (a terminal)
        from rich.progress import (  # deferred: rich only for a live progress bar (a terminal)
            BarColumn,
            MofNCompleteColumn,
            Progress,
            TextColumn,
            TimeElapsedColumn,
        )

        self.counts = _Counts(total, done, failed)
        self._bar = Progress(
            TextColumn("[bold]{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TextColumn("{task.fields[detail]}"),
            TimeElapsedColumn(),
            console=Console(file=stream or sys.stdout),
            transient=False,
        )
        self._task = self._bar.add_task(label, total=total, completed=done, detail=self._detail())

    def _detail(self) -> str:
        c = self.counts
        return f"[red]{c.failed} failed[/] · {c.rate():.3g} cases/s · ETA {c.eta()}"

    def __enter__(self) -> LiveProgress:
        self._bar.__enter__()
        return self

    def advance(self, status: str) -> None:
        self.counts.add(status)
        self._bar.update(self._task, completed=self.counts.done, detail=self._detail())

    def __exit__(self, *exc: Any) -> None:
        self._bar.__exit__(*exc)


def make_progress(
    total: int, done: int, failed: int, label: str, stream: TextIO | None = None, interval: float = 10.0
) -> PlainProgress | LiveProgress:
    stream = stream or sys.stdout
    if getattr(stream, "isatty", lambda: False)():
        return LiveProgress(total, done, failed, label, stream)
    return PlainProgress(total, done, failed, label, stream, interval)
