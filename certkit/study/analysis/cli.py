"""``certkit study report STUDY.yaml``: the study report from the study's store (see :mod:`.report`)."""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

import click

from certkit.errors import UserError
from certkit.study.spec import load_study
from certkit.study.store import Store

EXIT_USAGE = 2


def _samples(ctx, param, value) -> int:
    try:
        n = float(value)
    except ValueError:
        raise click.BadParameter(f"expected a number of samples such as 1e6, got {value!r}") from None
    if not (n >= 1000 and n == int(n)):
        raise click.BadParameter(f"expected a whole number of at least 1000, got {value!r}")
    return int(n)


def open_study(study_path: Path, store_path: Path | None):
    """(study definition, store, store frame) for ``study_path``.

    The definition is the study file as it is now (objectives, constraints and analysis options may change after a
    run without changing a case); its variables must be those the store was run with."""

    study = load_study(study_path)  # the file as it is now: objectives, constraints and options may be edited after a run
    if store_path is None:
        default = getattr(Store, "default_path", None)
        store_path = Path(default(study_path)) if default else study_path.with_suffix(".sqlite")
    if not store_path.exists():
        raise UserError(f"{study_path}: no study store at {store_path}; run `certkit study run {study_path}` first "
                        f"or give --store")
    store = Store.open(store_path)
    stored = {v.path for v in store.study().variables}
    if {v.path for v in study.variables} != stored:
        raise UserError(f"{study_path}: its variables differ from those the store {store_path} was run with "
                        f"({', '.join(sorted(stored))}); run the study again or give --store")
    return study, store, store.frame()


@click.command("report")
@click.argument("study_file", metavar="STUDY.yaml", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Folder for index.html (default: <study>-report next to the study file).")
@click.option("--store", "store_path", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="The study store (default: the study's own store).")
@click.option("--no-check", is_flag=True, help="Skip the true-model re-evaluations (direct check and optima).")
@click.option("--samples", default="1e6", callback=_samples, show_default=True,
              help="Monte Carlo samples over the design box.")
def report_command(study_file: Path, out_dir: Path | None, store_path: Path | None, no_check: bool, samples: int):
    """Analyse a finished study: surrogates, feasibility, Pareto fronts, optima, profiler, sensitivity."""
    from certkit.study.analysis.report import write_study_report

    try:
        study, store, frame = open_study(study_file, store_path)
        sha = hashlib.sha256(study_file.read_bytes()).hexdigest()
        out = out_dir or study_file.with_name(study_file.stem + "-report")
        path = write_study_report(study, frame, out, store=store, samples=samples, check=not no_check, sha256=sha,
                                  log=lambda msg: click.echo(msg, err=True))
    except UserError as exc:
        click.echo(f"error: {exc}", err=True)
        sys.exit(EXIT_USAGE)
    click.echo(str(path))
