"""``certkit study report STUDY.yaml``: the study report from the study's store (see :mod:`.report`)."""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

import click

from certkit.errors import UserError

EXIT_USAGE = 2


def _samples(ctx, param, value) -> int:
    try:
        n = float(value)
    except ValueError:
        raise click.BadParameter(f"expected a number of samples such as 1e6, got {value!r}") from None
    if not (n >= 1000 and n == int(n)):
        raise click.BadParameter(f"expected a whole number of at least 1000, got {value!r}")
    return int(n)


#: the study store of a command (default: the study's own)
_store_path_option = click.option(
    "--store",
    "store_path",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="The study store (default: the study's own store).",
)


def executor_options(command):
    """--executor, --workers and --scheduler: where the commands that evaluate true-model cases run them."""
    command = click.option(
        "--scheduler", default=None, help="Address of a running dask scheduler (tcp://host:8786), with --executor dask."
    )(command)
    command = click.option(
        "--workers", type=int, default=None, help="Worker processes (default: the cores available)."
    )(command)
    return click.option(
        "--executor", type=click.Choice(["local", "dask", "serial"]), default="local", show_default=True
    )(command)


def case_runner(executor: str, workers: int | None, scheduler: str | None):
    """The study runner with the command's executor, showing its progress on stderr."""
    from certkit.study.runner import run_study_cases  # deferred: CLI start-up: `certkit --help` loads this module

    if scheduler and executor != "dask":
        raise UserError("--scheduler is for --executor dask")
    if workers is not None and workers < 1:
        raise UserError(f"--workers must be 1 or more (got {workers})")

    def run_cases(study, store, points, *, block, role):
        return run_study_cases(
            study,
            store,
            points,
            block=block,
            role=role,
            executor=executor,
            workers=workers,
            scheduler=scheduler,
            progress=sys.stderr,
        )

    return run_cases


def open_study(study_path: Path, store_path: Path | None):
    """(study definition, store, store frame) for ``study_path``.

    The definition is the study file as it is now (objectives, constraints and analysis options may change after a
    run without changing a case); its variables must be those the store was run with."""

    from certkit.study.spec import load_study  # deferred: CLI start-up: `certkit --help` loads this module
    from certkit.study.store import Store  # deferred: CLI start-up: `certkit --help` loads this module

    study = load_study(
        study_path
    )  # the file as it is now: objectives, constraints and options may be edited after a run
    if store_path is None:
        default = getattr(Store, "default_path", None)
        store_path = Path(default(study_path)) if default else study_path.with_suffix(".sqlite")
    if not store_path.exists():
        raise UserError(
            f"{study_path}: no study store at {store_path}; run `certkit study run {study_path}` first or give --store"
        )
    store = Store.open(store_path)
    stored = {v.path for v in store.study().variables}
    if {v.path for v in study.variables} != stored:
        raise UserError(
            f"{study_path}: its variables differ from those the store {store_path} was run with "
            f"({', '.join(sorted(stored))}); run the study again or give --store"
        )
    return study, store, store.frame()


@click.command("report")
@click.argument("study_file", metavar="STUDY.yaml", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option(
    "--out",
    "out_dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="Folder for index.html (default: <study>-report next to the study file).",
)
@_store_path_option
@click.option("--no-check", is_flag=True, help="Skip the true-model re-evaluations (direct check and optima).")
@click.option(
    "--samples", default="1e6", callback=_samples, show_default=True, help="Monte Carlo samples over the design box."
)
@executor_options
def report_command(
    study_file: Path,
    out_dir: Path | None,
    store_path: Path | None,
    no_check: bool,
    samples: int,
    executor: str,
    workers: int | None,
    scheduler: str | None,
):
    """Analyse a finished study: surrogates, feasibility, Pareto fronts, optima, profiler, sensitivity. The
    true-model checks run on the given executor, with their progress on stderr; designs already in the store
    (a report made before) are not evaluated again."""
    from certkit.report.study_report import (  # deferred: CLI start-up: the study report loads pandas, scikit-learn
        write_study_report,
    )

    try:
        study, store, frame = open_study(study_file, store_path)
        sha = hashlib.sha256(study_file.read_bytes()).hexdigest()
        out = out_dir or study_file.with_name(study_file.stem + "-report")
        path = write_study_report(
            study,
            frame,
            out,
            store=store,
            samples=samples,
            check=not no_check,
            sha256=sha,
            log=lambda msg: click.echo(msg, err=True),
            run_cases=case_runner(executor, workers, scheduler),
        )
    except UserError as exc:
        click.echo(f"error: {exc}", err=True)
        sys.exit(EXIT_USAGE)
    click.echo(str(path))


def export_surrogates(study_path: Path, store_path: Path | None, out: Path, log=lambda msg: None) -> Path:
    """Fit the study's surrogates (and the possible-design classifier) from its store and write them as JSON."""
    from certkit.study.analysis.cases import cases  # deferred: CLI start-up: the surrogates load scikit-learn
    from certkit.study.analysis.derived_levels import (  # deferred: CLI start-up: the surrogates load scikit-learn
        fit_predictors,
    )
    from certkit.study.analysis.surrogate_file import (  # deferred: CLI start-up: the surrogates load scikit-learn
        surrogates_document,
        write_surrogates,
    )
    from certkit.study.analysis.validity import fit_validity  # deferred: CLI start-up: the surrogates load scikit-learn

    study, store, frame = open_study(study_path, store_path)
    surrogates, levels, not_fitted = fit_predictors(study, cases(frame, study), log)
    for name, why in not_fitted.items():
        log(f"no surrogate for {name}: {why}")
    sha = hashlib.sha256(study_path.read_bytes()).hexdigest()
    return write_surrogates(out, surrogates_document(study, surrogates, fit_validity(frame, study), sha, levels))


@click.command("refine")
@click.argument("study_file", metavar="STUDY.yaml", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option(
    "--cases",
    "n",
    type=click.IntRange(1, 10_000),
    default=20,
    show_default=True,
    help="New training cases to add where constraint boundaries and fronts are least certain.",
)
@_store_path_option
@click.option(
    "--samples",
    default="2e5",
    callback=_samples,
    show_default=True,
    help="Monte Carlo samples for the probabilities before and after.",
)
@executor_options
def refine_command(
    study_file: Path,
    n: int,
    store_path: Path | None,
    samples: int,
    executor: str,
    workers: int | None,
    scheduler: str | None,
):
    """Add cases where the surrogates are least sure, evaluate them, refit, and show how the probabilities moved."""
    from certkit.study.analysis.refine import refine  # deferred: CLI start-up: the surrogates load scikit-learn

    study, store, _ = open_study(study_file, store_path)
    run_cases = case_runner(executor, workers, scheduler)
    result = refine(study, store, n, samples=samples, run_cases=run_cases, log=lambda msg: click.echo(msg, err=True))
    click.echo(
        f"{result.added} cases added in block {result.block} ({result.ok} ok); probability of success "
        f"(95 % Wilson interval), before → after:"
    )
    width = max([len(m.name) for m in result.movements + [result.joint]])
    for m in result.movements + [result.joint]:
        click.echo(
            f"  {m.name:<{width}}  {100 * m.p_before:6.2f} % [{100 * m.interval_before[0]:.2f}, "
            f"{100 * m.interval_before[1]:.2f}] → {100 * m.p_after:6.2f} % [{100 * m.interval_after[0]:.2f}, "
            f"{100 * m.interval_after[1]:.2f}]  ({100 * (m.p_after - m.p_before):+.2f} points)"
        )


@click.command("predict")
@click.argument(
    "surrogates_file", metavar="SURROGATES.json", type=click.Path(exists=True, dir_okay=False, path_type=Path)
)
@click.option(
    "--set",
    "settings",
    multiple=True,
    metavar="PATH=VALUE",
    help="A variable's value (SI, or a quantity with a unit); the others take their baseline.",
)
@click.option(
    "--points",
    "points_csv",
    type=click.Path(exists=True, dir_okay=False, path_type=Path),
    default=None,
    help="A CSV of designs, one column per variable path (SI values); one output row per design.",
)
@click.option("--response", "responses", multiple=True, help="Responses to predict (default: every one).")
def predict_command(
    surrogates_file: Path, settings: tuple[str, ...], points_csv: Path | None, responses: tuple[str, ...]
):
    """Predict responses with exported surrogates, as CSV: the variables, each response, and `possible`."""
    import csv  # deferred: CLI start-up: `certkit --help` loads this module

    import numpy as np  # deferred: CLI start-up: `certkit --help` loads this module

    from certkit.study.analysis.surrogate_file import (  # deferred: CLI start-up: the surrogates load scikit-learn
        load_surrogates,
    )
    from certkit.study.spec import parse_quantity  # deferred: CLI start-up: `certkit --help` loads this module

    model = load_surrogates(surrogates_file)
    if points_csv is not None:
        if settings:
            raise UserError("give either --points or --set, not both")
        with points_csv.open(newline="") as fh:
            points = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(fh)]
    else:
        point = {}
        for text in settings:
            path, sep, raw = text.partition("=")
            if not sep:
                raise UserError(f"--set {text!r}: expected PATH=VALUE")
            try:
                point[path.strip()] = parse_quantity(raw.strip())[0]
            except ValueError as exc:
                raise UserError(f"--set {text!r}: {exc}") from None
        points = [point]
    x = model.inputs(points)
    values = model.predict(x, list(responses) or None)
    possible = model.possible(x)
    writer = csv.writer(sys.stdout, lineterminator="\n")
    writer.writerow(model.variables + list(values) + ["possible"])
    for i in range(len(x)):
        writer.writerow(
            [repr(float(v)) for v in x[i]]
            + [repr(float(values[r][i])) for r in values]
            + [str(bool(np.asarray(possible)[i])).lower()]
        )
