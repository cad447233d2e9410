"""``certkit study run | status | export | schema`` (imports stay inside the commands: `certkit --help` is fast)."""

from __future__ import annotations

import json
import signal
import sys
from collections import Counter
from pathlib import Path

import click

from certkit import interrupts
from certkit.cli.study_analysis import export_surrogates, predict_command, refine_command, report_command
from certkit.errors import UserError

EXIT_INTERRUPTED = 130


def default_store(study_file: str | Path) -> Path:
    """``studies/ht-redesign.yaml`` → ``studies/ht-redesign.sqlite``."""
    return Path(study_file).with_suffix(".sqlite")


def _is_study_file(path: str) -> bool:
    return Path(path).suffix.lower() in (".yaml", ".yml")


def _store_of(target: str, store: str | None) -> Path:
    return Path(store) if store else (default_store(target) if _is_study_file(target) else Path(target))


_store_option = click.option(
    "--store", type=click.Path(dir_okay=False), help="Store file (default: the study file with the suffix .sqlite)."
)


class _StudyGroup(click.Group):
    """A store found damaged while it is read (after :meth:`Store.open` checked it) is a message, not a bug."""

    def invoke(self, ctx):
        import sqlite3  # deferred: CLI start-up: `certkit --help` loads this module; sqlite3 loads with a study command

        try:
            return super().invoke(ctx)
        except sqlite3.DatabaseError as exc:
            raise UserError(
                f"the study store could not be read (SQLite: {exc}): a damaged file; restore it from a "
                "copy, or delete it and run the study again"
            ) from None


@click.group(name="study", cls=_StudyGroup)
def study():
    """Design studies: designs of experiments over many designs, resumable, on this machine or a Dask cluster."""


@study.command()
@click.argument("study_file", type=click.Path(dir_okay=False))
@click.option(
    "--executor",
    type=click.Choice(["local", "dask", "serial"]),
    default="local",
    show_default=True,
    help="local: worker processes on this machine; dask: dask.distributed; serial: in this process.",
)
@click.option("--workers", type=int, default=None, help="Worker processes (default: the cores available).")
@click.option("--scheduler", default=None, help="Address of a running dask scheduler (tcp://host:8786).")
@_store_option
@click.option("--retry-failed", is_flag=True, help="Evaluate the failed cases again.")
@click.option("--evaluator", default=None, hidden=True, help="Dotted name of the evaluator (tests).")
@click.option(
    "--progress-interval",
    type=float,
    default=10.0,
    hidden=True,
    help="Seconds between progress lines when the output is not a terminal.",
)
def run(study_file, executor, workers, scheduler, store, retry_failed, evaluator, progress_interval):
    """Evaluate every case of STUDY_FILE without a result yet (run it again to resume)."""
    from certkit.study.plan import DEFAULT_EVALUATOR  # deferred: CLI start-up: `certkit --help` loads this module
    from certkit.study.runner import run_study  # deferred: CLI start-up: `certkit --help` loads this module
    from certkit.study.spec import load_study  # deferred: CLI start-up: `certkit --help` loads this module
    from certkit.study.store import Store  # deferred: CLI start-up: `certkit --help` loads this module

    spec = load_study(study_file)
    path = _store_of(study_file, store)
    signal.signal(signal.SIGTERM, interrupts.on_interrupt)  # `kill` stops as Ctrl-C does: workers first
    try:
        with Store.open(path, create=True) as db:
            summary = run_study(
                spec,
                db,
                executor,
                workers,
                scheduler,
                evaluator or DEFAULT_EVALUATOR,
                retry_failed,
                progress=sys.stdout,
                interval=progress_interval,
            )
            counts = Counter()
            for _block, _role, status, n in db.counts():
                counts[status] += n
    except KeyboardInterrupt:
        click.echo(f"\ninterrupted: every finished case is saved in {path}; run the same command to resume", err=True)
        sys.exit(EXIT_INTERRUPTED)
    rate = (
        f", {summary.elapsed_s * summary.workers / summary.submitted:.3g} s per case per worker"
        if summary.submitted
        else ""
    )
    click.echo(
        f"{spec.name}: {summary.total} cases — {counts['ok']} ok, {counts['failed']} failed, "
        f"{counts['pending']} pending; this run evaluated {summary.submitted} "
        f"in {summary.elapsed_s:.1f} s on {summary.workers} worker{'s' if summary.workers != 1 else ''}{rate}"
    )
    if summary.duplicates:
        click.echo(f"({summary.duplicates} points repeated an earlier block's and were evaluated once)")
    click.echo(f"store: {path}")


@study.command()
@click.argument("target", type=click.Path(dir_okay=False))
@_store_option
def status(target, store):
    """Cases per block (ok, failed, pending, new) of a study file or a store, wall times and failure reasons."""
    from certkit.study.plan import (  # deferred: CLI start-up: `certkit --help` loads this module
        DEFAULT_EVALUATOR,
        CaseContext,
        plan_study,
    )
    from certkit.study.spec import load_study  # deferred: CLI start-up: `certkit --help` loads this module
    from certkit.study.store import Store  # deferred: CLI start-up: `certkit --help` loads this module

    path = _store_of(target, store)
    new: Counter = Counter()
    with Store.open(path) as db:
        rows = db.rows()
        if _is_study_file(target):
            spec = load_study(target)
            known = {row["key"] for row in db.rows(include_stale=True)}
            plan = plan_study(spec, CaseContext.of(spec, db.meta("evaluator") or DEFAULT_EVALUATOR))
            new.update(c.block for c in plan.cases if c.key not in known)
        else:
            spec = db.study()
        click.echo(f"study {spec.name}  store {path}\naircraft {spec.aircraft}  evaluator {db.meta('evaluator')}")
        table: dict[tuple[str, str], Counter] = {}
        for block, role, state, n in db.counts():
            table.setdefault((block, role), Counter())[state] += n
        for block, n in new.items():
            role = next(b.role for b in spec.designs if b.name == block)
            table.setdefault((block, role), Counter())["new"] += n
        click.echo(f"\n{'block':<16}{'role':<12}{'cases':>7}{'ok':>7}{'failed':>8}{'pending':>9}{'new':>6}")
        total = Counter()
        for (block, role), c in table.items():
            c["cases"] = sum(c.values())
            total.update(c)
            click.echo(
                f"{block:<16}{role:<12}{c['cases']:>7}{c['ok']:>7}{c['failed']:>8}{c['pending']:>9}{c['new']:>6}"
            )
        click.echo(
            f"{'total':<28}{total['cases']:>7}{total['ok']:>7}{total['failed']:>8}{total['pending']:>9}"
            f"{total['new']:>6}"
        )
        walls = sorted(row["wall_s"] for row in rows if row["status"] == "ok")
        if walls:
            workers = {row["worker"] for row in rows if row["worker"]}
            click.echo(
                f"\nwall time per ok case: mean {sum(walls) / len(walls):.3g} s, median {walls[len(walls) // 2]:.3g} "
                "s, "
                f"max {walls[-1]:.3g} s; {len(workers)} worker process{'es' if len(workers) != 1 else ''}"
            )
        reasons = Counter(row["error"] for row in rows if row["status"] == "failed")
        if reasons:
            click.echo("\nfailures:")
            for reason, n in reasons.most_common(8):
                click.echo(f"  {n:>5} × {reason}")
        if db.stale():
            click.echo(
                f"\n{db.stale()} rows kept from earlier plans, aircraft files, versions or responses "
                "(not part of the study)"
            )


@study.command()
@click.argument("target", type=click.Path(dir_okay=False))
@_store_option
@click.option("--format", "fmt", type=click.Choice(["csv", "parquet"]), default="csv", show_default=True)
@click.option("--out", type=click.Path(dir_okay=False), help="Output file (default: the store's name, .csv/.parquet).")
@click.option(
    "--surrogates",
    "surrogates_out",
    type=click.Path(dir_okay=False),
    default=None,
    help="Instead of the cases: fit the study's surrogates and write them to this JSON file "
    "(read by `certkit study predict` and certkit.study.load_surrogates; TARGET: the study file).",
)
def export(target, store, fmt, out, surrogates_out):
    """Write one row per case (variables in SI, responses, status, error, wall time, worker) as CSV or Parquet,
    or (--surrogates) the study's fitted surrogates."""
    from certkit.study.store import Store  # deferred: CLI start-up: `certkit --help` loads this module
    from certkit.study.store import export as write  # deferred: CLI start-up: `certkit --help` loads this module

    if surrogates_out:
        if not _is_study_file(target):
            raise UserError(f"{target}: --surrogates needs the study file (its objectives and constraints)")
        written = export_surrogates(
            Path(target),
            Path(store) if store else None,
            Path(surrogates_out),
            log=lambda msg: click.echo(msg, err=True),
        )
        click.echo(f"exported: {written}")
        return
    path = _store_of(target, store)
    with Store.open(path) as db:
        written = write(db, Path(out) if out else path.with_suffix(f".{fmt}"), fmt)
    click.echo(f"exported: {written}")


@study.command()
def schema():
    """Print the JSON Schema of the study file."""
    from certkit.study.spec import json_schema  # deferred: CLI start-up: `certkit --help` loads this module

    click.echo(json.dumps(json_schema(), indent=2))


def _register_report() -> None:
    for command in (report_command, refine_command, predict_command):
        study.add_command(command)


_register_report()
