"""Command line: ``certkit check | diff | rules | explain | schema | derivatives | trim | modes | mission | evaluate |
import jsbsim | study ... | new-rule``.

Exit codes: 0 every rule complies, 1 a rule fails, 2 input or usage error (no traceback),
3 nothing fails but something was not evaluated, 70 internal error (a bug: the message asks for a report; the
traceback with ``certkit --debug``), 130 interrupted (Ctrl-C; previous outputs are left as they were).
"""

from __future__ import annotations

import functools
import gc
import importlib
import json
import math
import os
import platform
import sys
import time
import traceback
import warnings
from contextlib import contextmanager
from pathlib import Path

import click

from certkit import __version__, interrupts
from certkit.engine.worker_processes import one_blas_thread
from certkit.errors import UserError
from certkit.user_cache import cache_folder

EXIT_USAGE = 2
EXIT_INTERNAL = 70  # EX_SOFTWARE of sysexits(3)
EXIT_INTERRUPTED = 130  # 128 + SIGINT, as shells report it
_DEBUG = {"on": False}


class _Group(click.Group):
    """The one error boundary: a :class:`UserError` anywhere below is a message and exit code 2; Ctrl-C exits 130;
    anything else is an internal error (exit 70) with a bug-report hint, its traceback only with ``--debug``.
    Command groups of their own package (``study``) are imported when named, not at every start."""

    lazy_commands = {"study": ("certkit.cli.study", "study")}

    def list_commands(self, ctx):
        return sorted({*super().list_commands(ctx), *self.lazy_commands})

    def get_command(self, ctx, name):
        if name in self.lazy_commands and name not in self.commands:
            module, attr = self.lazy_commands[name]
            self.add_command(getattr(importlib.import_module(module), attr), name)
        return super().get_command(ctx, name)

    def invoke(self, ctx):
        try:
            return super().invoke(ctx)
        except UserError as exc:
            click.echo(f"error: {exc}", err=True)
            sys.exit(EXIT_USAGE)
        except BrokenPipeError:  # the reader went away (`certkit ... | head`): stop quietly, as Unix tools do
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            sys.exit(1)
        except KeyboardInterrupt:
            click.echo("interrupted: nothing was written (previous reports are left as they were)", err=True)
            sys.exit(EXIT_INTERRUPTED)
        except (click.exceptions.ClickException, click.exceptions.Exit, click.exceptions.Abort):
            raise
        except Exception as exc:  # noqa: BLE001 - the boundary: every other exception is a bug of certkit
            if _DEBUG["on"]:
                traceback.print_exc()
            detail = str(exc).splitlines()[0][:300] if str(exc) else ""
            click.echo(
                f"internal error: {exc.__class__.__name__}{': ' + detail if detail else ''}\n"
                f"This is a bug in certkit {__version__}, not a mistake in your input. Please report it to the "
                "certkit developers with the command, the input files and this message"
                f"{'' if _DEBUG['on'] else ' (run `certkit --debug ...` for the traceback)'}.",
                err=True,
            )
            sys.exit(EXIT_INTERNAL)


def _discovery(rules_dirs):
    from certkit.engine.registry import (  # deferred: CLI start-up: the registry loads importlib.metadata
        DiscoveryOptions,
        discover,
    )

    options = DiscoveryOptions(rules_dirs=tuple(rules_dirs))
    return options, discover(options)


@contextmanager
def _long_lived_objects():
    """Start-up of a check (imports, the aircraft, the rules) makes only objects that live as long as the process:
    the cyclic garbage collector is off while they are made, and they are frozen afterwards (never scanned again,
    here nor in the worker processes that fork from here) until the check ends. About 0.1 s less per process."""
    gc.disable()
    try:
        yield
        gc.freeze()
    finally:
        gc.enable()


#: the report's missions on the scale of the rules' :attr:`~certkit.engine.registry.Rule.cost` (the baseline's fly in
#: about the time of §25.349(a)'s rolling conditions, cost 5): where the workers take them among the rules
MISSION_COST = 5.0
#: the check's output formats written from the findings themselves (the others from the results' text and summary)
FINDINGS_FORMATS = ("junit", "sarif", "github")


def _mission_for_report(aircraft, ctx) -> dict | None:
    """The aircraft file's missions (design range, payload–range, nominal mission, cruise drag) for the report, or
    why they could not be flown, on the clean aerodynamic model of ``ctx`` (a Context on ``aircraft``: the rules' in
    that process); None without a ``mission:`` section."""
    if aircraft.mission is None:
        return None
    from certkit.models.performance.mission import (  # deferred: CLI start-up: the mission models load with the check
        fly_missions,
    )
    from certkit.report.mission_plots import (  # deferred: CLI start-up: the report layer loads with the check
        payload_range_svg,
    )

    try:
        m = fly_missions(aircraft, ctx.aero("clean"))
    except UserError as exc:
        return {"error": str(exc)}
    out = m.as_dict()
    out.pop("timings", None)  # results.json is the same for identical runs
    out["svg"] = payload_range_svg(m.payload_range, m.range_requirement_m)
    return out


def _compile_kernels(jobs: int, announce: bool) -> None:
    """At the first run after an install (numba's cache cold), compile certkit's kernels ahead in ``jobs`` processes
    (:mod:`certkit.models.kernel_warmup`), saying so when ``announce``."""
    from certkit.models.kernel_warmup import (  # deferred: CLI start-up: the kernels are compiled by a check only
        compile_if_cold,
    )

    def say() -> None:
        click.echo("compiling certkit's numba kernels (once after an install; cached for later runs)…", err=True)

    seconds = compile_if_cold(jobs, starting=say if announce else None)
    if announce and seconds:
        click.echo(f"kernels compiled in {seconds:.0f} s", err=True)


def _default_jobs(jobs: int | None) -> int:
    """The processes to use (default: the cores available, at most 4). Every process gets one BLAS/OpenMP thread (set
    before numpy loads; a user's own setting is kept): threaded BLAS in several processes oversubscribes the cores and
    slows the lattice several times, and a threaded BLAS sums in another order, which changes the last digits of a
    result with the number of threads — results.json would then depend on --jobs."""
    if jobs is None:
        jobs = min(4, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)
    if jobs < 1:
        raise UserError(f"--jobs must be at least 1 (got {jobs})")
    one_blas_thread()
    return jobs


class _Number(click.ParamType):
    """A finite number (NaN and infinities are refused), optionally at least ``minimum``."""

    name = "number"

    def __init__(self, minimum: float | None = None):
        self.minimum = minimum

    def convert(self, value, param, ctx):
        if isinstance(value, float):
            number = value
        else:
            try:
                number = float(value)
            except (TypeError, ValueError):
                self.fail(f"{value!r} is not a number", param, ctx)
        if not math.isfinite(number):
            self.fail(f"{value!r}: a finite number is needed", param, ctx)
        if self.minimum is not None and number < self.minimum:
            self.fail(f"{value!r}: must be at least {self.minimum:g}", param, ctx)
        return number


FINITE = _Number()
NON_NEGATIVE = _Number(minimum=0.0)


def _patterns(option: str, values: tuple[str, ...]) -> tuple[str, ...]:
    """Rule patterns of a repeatable, comma-separated option; a value naming no pattern (``--select ""``) is refused
    rather than read as "no selection" (every rule)."""
    found = []
    for value in values:
        parts = [p.strip() for p in value.split(",") if p.strip()]
        if not parts:
            raise UserError(
                f"{option} {value!r}: names no rule (give a rule id prefix or a symbol, e.g. {option} 25.3; "
                "see `certkit rules`)"
            )
        found += parts
    return tuple(found)


def _check_output_file(output_file: str | None) -> None:
    """``--output-file`` checked before the evaluation: its folder must exist and be writable, the path not a folder."""
    if not output_file:
        return
    path = Path(output_file)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise UserError(f"--output-file {output_file!r}: the folder {str(folder)!r} does not exist (create it first)")
    if path.is_dir():
        raise UserError(f"--output-file {output_file!r}: is a folder; give a file name")
    if not os.access(folder, os.W_OK | os.X_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise UserError(f"--output-file {output_file!r}: not writable (permission denied)")


_rules_option = click.option(
    "--rules",
    "rules_dirs",
    multiple=True,
    type=click.Path(file_okay=False),
    help="Folder of your own rule modules (repeatable).",
)


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="certkit")
@click.option(
    "--debug",
    is_flag=True,
    envvar="CERTKIT_DEBUG",
    help="Show the traceback of an internal error and numerical warnings.",
)
def main(debug):
    """certkit — compliance engine for transport aircraft against 14 CFR Part 25."""
    _DEBUG["on"] = debug
    if not debug:  # numerical warnings (overflow in a trial step...) are handled where they matter, not printed
        warnings.simplefilter("ignore", RuntimeWarning)
        os.environ.setdefault("PYTHONWARNINGS", "ignore::RuntimeWarning")  # for processes that do not fork


@main.command()
@click.argument("aircraft_file", type=click.Path(dir_okay=False))
@click.option(
    "--out", "out_dir", type=click.Path(file_okay=False), help="Report folder (default reports/<aircraft name>/)."
)
@click.option("--select", multiple=True, help="Rule id prefix or symbol to run (repeatable, comma-separated).")
@click.option("--ignore", multiple=True, help="Rule id prefix or symbol to skip (repeatable, comma-separated).")
@click.option(
    "--jobs",
    "-j",
    default=None,
    type=int,
    help="Parallel processes (default: the CPU cores available, at most 4; results do not depend on it).",
)
@click.option(
    "--output-format",
    "output_format",
    default="text",
    show_default=True,
    type=click.Choice(["text", "json", "junit", "sarif", "github"]),
    help="What to print on standard output: the rule table, results.json, JUnit XML, SARIF 2.1.0 or GitHub "
    "Actions annotations.",
)
@click.option("--output-file", type=click.Path(dir_okay=False), help="Write that output to a file instead.")
@click.option("--json", "as_json", is_flag=True, help="Same as --output-format json.")
@click.option("--quiet", "-q", is_flag=True, help="No progress and no rule table: the summary line only.")
@_rules_option
def check(aircraft_file, out_dir, select, ignore, jobs, output_format, output_file, as_json, quiet, rules_dirs):
    """Evaluate every selected rule on AIRCRAFT_FILE and write results.json and an HTML report."""
    jobs = _default_jobs(jobs)
    output_format = "json" if as_json else output_format
    with _long_lived_objects():
        from certkit.aircraft import load_aircraft  # deferred: CLI start-up: the check's layers load when it runs
        from certkit.engine.registry import (  # deferred: CLI start-up: the check's layers load when it runs
            select as select_rules,
        )
        from certkit.engine.scheduler import (  # deferred: CLI start-up: the check's layers load when it runs
            check_overrides,
            run,
        )
        from certkit.models.aero.lattice_store import (  # deferred: CLI start-up: the check's layers load when it runs
            LatticeStore,
        )
        from certkit.report.html import (  # deferred: CLI start-up: the check's layers load when it runs
            ReportFinish,
            write_report,
        )
        from certkit.report.output import (  # deferred: CLI start-up: the check's layers load when it runs
            prepare_output,
            report_folder_name,
        )
        from certkit.report.terminal import Progress  # deferred: CLI start-up: the check's layers load when it runs

        start = time.perf_counter()
        loaded = load_aircraft(aircraft_file)
        options, rules = _discovery(rules_dirs)
        check_overrides(loaded, rules)
        select, ignore = _patterns("--select", select), _patterns("--ignore", ignore)
        chosen = select_rules(rules, select, ignore)
        out = Path(out_dir) if out_dir else Path("reports") / report_folder_name(loaded.name)
        prepare_output(out)  # an output that cannot be written is an error before the evaluation, not after
        _check_output_file(output_file)
    from certkit.models.mass.loading import (  # deferred: CLI start-up: the check's layers load when it runs
        inertia_comparison,
    )

    warning = inertia_comparison(loaded.model)
    if warning:
        click.echo(f"warning: {warning}", err=True)
    _compile_kernels(jobs, announce=not quiet and output_format == "text")
    progress = Progress(chosen, quiet=quiet or output_format != "text")
    try:
        # the missions are flown in this process while the workers evaluate the rules
        result = run(
            loaded,
            chosen,
            jobs=jobs,
            options=options,
            finish=ReportFinish(chosen),
            progress=progress,
            alongside={"mission": functools.partial(_mission_for_report, loaded.model)},
            alongside_cost={"mission": MISSION_COST},
            lattice_store=LatticeStore(cache_folder() / "lattices"),
            findings=output_format in FINDINGS_FORMATS,  # the other outputs read the summary and the encoded text
        )
        progress.close()
        result.selection = {
            "select": list(select),
            "ignore": list(ignore),
            "partial": len(chosen) < len(rules),
            "rules_selected": len(chosen),
            "rules_registered": len(rules),
        }
        result.options = {"rules_dirs": [str(d) for d in rules_dirs], "plugins": options.plugins}
        result.environment = _environment()
        result.jobs = jobs
        result.inputs = loaded.source.values_by_path()
        result.duration_s = round(time.perf_counter() - start, 1)
        json_path, html_path = write_report(result, chosen, out)
    finally:
        progress.close()
        gc.unfreeze()
    lines = None
    if output_format in FINDINGS_FORMATS:
        from certkit.report.ci_formats import (  # deferred: CLI start-up: the check's layers load when it runs
            datum_lines,
        )

        lines = datum_lines(loaded.source, chosen, result.rules)
    _print_check(result, output_format, output_file, quiet, json_path, html_path, time.perf_counter() - start, lines)
    sys.exit(result.exit_code())


def _environment() -> dict:
    return {"platform": platform.platform(), "python": platform.python_version()}


def _print_check(result, output_format, output_file, quiet, json_path, html_path, seconds, lines=None) -> None:
    if output_format != "text":
        from certkit.report.ci_formats import render  # deferred: CLI start-up: the check's layers load when it runs

        text = (
            json_path.read_text(encoding="utf-8") if output_format == "json" else render(output_format, result, lines)
        )
        if output_file:
            try:
                Path(output_file).write_text(text, encoding="utf-8")
            except OSError as exc:
                raise UserError(
                    f"--output-file {output_file!r}: cannot write ({exc.strerror or exc}); the report was "
                    f"written to {json_path.parent}"
                ) from None
        else:
            click.echo(text, nl=False)
        return
    from certkit.report.terminal import rule_rows  # deferred: CLI start-up: the check's layers load when it runs

    if not quiet:
        for line in rule_rows(result.rules, colour=sys.stdout.isatty()):
            click.echo(line)
        click.echo()
    s = result.summary()
    scope = (
        f" (a partial selection: {s['rules']} of {result.selection['rules_registered']} registered rules)"
        if result.selection.get("partial")
        else ""
    )
    click.echo(
        f"{s['rules']} rules{scope}: {s['complies']} comply, {s['complies_partial']} comply in part "
        f"(sub-paragraphs not evaluated), {s['fails']} fail, {s['not_evaluated']} not evaluated "
        f"({seconds:.2f} s)"
    )
    if not quiet:
        click.echo(f"report: {html_path}\nresults: {json_path}")


@main.command(name="diff")
@click.argument("old", type=click.Path(dir_okay=False))
@click.argument("new", type=click.Path(dir_okay=False))
@click.option("--html", "html_file", type=click.Path(dir_okay=False), help="Also write the comparison as an HTML page.")
@click.option(
    "--tolerance",
    default=1e-6,
    show_default=True,
    type=NON_NEGATIVE,
    help="Margin changes below tolerance × max(1, |limit|) are not listed.",
)
def diff_command(old, new, html_file, tolerance):
    """Compare two results.json: status flips and margin changes per rule and condition. Exit 1 when a rule got
    worse (complies → fails or not evaluated...), else 0."""
    from certkit.report.diff import (  # deferred: CLI start-up: the diff's layers load when it runs
        compare,
        load,
        render_html,
        text_lines,
    )

    a, b = load(old), load(new)
    changes = compare(a, b, tolerance)
    for line in text_lines(changes, a, b):
        click.echo(line)
    if html_file:
        Path(html_file).write_text(render_html(changes, a, b, old, new), encoding="utf-8")
        click.echo(f"html: {html_file}")
    sys.exit(1 if any(c.regression for c in changes) else 0)


@main.command(name="rules")
@_rules_option
@click.option("--markdown", is_flag=True, help="Print a Markdown table (docs/rules.md holds it).")
def list_rules(rules_dirs, markdown):
    """List the registered rules: id, symbol, title, implementation status."""
    from certkit.engine.rule_index import rule_metadata  # deferred: CLI start-up: the rule index loads the registry

    rules = rule_metadata(tuple(rules_dirs))
    if markdown:
        click.echo("| Rule | Symbol | Title | Status |\n| --- | --- | --- | --- |")
        for r in rules:
            click.echo(f"| §{r['id']} | `{r['symbol']}` | {r['title']} | {r['implementation']} |")
        return
    for r in rules:
        click.echo(f"{r['id']:<14} {r['symbol']:<38} {r['implementation']:<12} {r['title']}")


@main.command()
@click.argument("rule")
@_rules_option
def explain(rule, rules_dirs):
    """Print a rule's documentation (id — with or without §, e.g. "§25.337" — id prefix or symbol): requirement,
    criterion, conditions, margin."""
    from certkit.engine.rule_index import (  # deferred: CLI start-up: the rule index loads the registry
        find,
        rule_metadata,
    )

    matches = find(rule_metadata(tuple(rules_dirs)), rule)
    if not matches:
        raise UserError(f"no rule {rule!r} (see `certkit rules`)")
    click.echo("\n\n".join(r["documentation"] for r in matches))


@main.command()
@click.option("--results", "of_results", is_flag=True, help="The JSON Schema of results.json instead.")
def schema(of_results):
    """Print the JSON Schema of the aircraft file (for editor autocompletion), or of results.json."""
    if of_results:
        from certkit.engine.results_json import (  # deferred: CLI start-up: results_json loads numpy
            schema as results_schema,
        )

        click.echo(json.dumps(results_schema(), indent=2, ensure_ascii=False))
        return
    from certkit.aircraft import json_schema  # deferred: CLI start-up: the aircraft model loads pydantic and pint

    click.echo(json.dumps(json_schema(), indent=2))


@main.command()
@click.argument("model_file", type=click.Path(dir_okay=False))
@click.option("--mach", type=FINITE, default=None, help="Mach number (default: the AVL file's, or 0.2).")
@click.option("--alpha", "alpha_deg", type=FINITE, default=0.0, show_default=True, help="Angle of attack, deg.")
@click.option("--beta", "beta_deg", type=FINITE, default=0.0, show_default=True, help="Sideslip angle, deg.")
@click.option("--config", "configuration", default="clean", show_default=True, help="Configuration (aircraft files).")
@click.option("--json", "as_json", is_flag=True, help="Machine-readable output.")
def derivatives(model_file, mach, alpha_deg, beta_deg, configuration, as_json):
    """Stability and control derivatives of an aircraft file or an AVL geometry (.avl) file.

    Per radian, stability axes, rates per p̂ = pb/2V, q̂ = qc̄/2V, r̂ = rb/2V (AVL's normalisation). Control signs:
    for an aircraft file certkit's (a positive deflection gives a negative moment); for an .avl file the file's
    own (AVL's). For an aircraft file the neutral point and static margin are the model's (lattice + fuselage
    term + overrides); the lattice's are printed beside them. Induced drag: Trefftz plane (AVL's CDff). Drag along
    the stability x axis (see certkit/conventions.py).
    """
    one_blas_thread()  # a threaded LU of a few thousand panels starts threads it cannot use (0.5-0.8 s -> 0.4 s)
    from certkit.cli.aero_report import derivative_report  # deferred: CLI start-up: the vortex lattice loads numpy

    report = derivative_report(model_file, mach, alpha_deg, beta_deg, configuration)
    if as_json:
        click.echo(json.dumps(report, indent=2, allow_nan=False))
        return
    ref, tot = report["reference"], report["totals"]
    click.echo(
        f"{report['source']}  Mach {report['mach']:.3f}  alpha {report['alpha_deg']:.3f} deg  beta "
        f"{report['beta_deg']:.3f} deg"
    )
    click.echo(f"Sref {ref['area']:.5g}  Cref {ref['chord']:.5g}  Bref {ref['span']:.5g}  Xref {ref['x_ref']:.5g}")
    if tot is not None:
        click.echo(
            f"CL {tot['CL']:.5f}  CDff (Trefftz plane) {tot['CD_induced_trefftz']:.6f}  e "
            f"{tot['span_efficiency']:.4f}  "
            f"Cm {tot['Cm']:.5f}"
        )
    if report["neutral_point"] is not None:
        click.echo(
            f"neutral point Xnp {report['neutral_point']:.5g}  static margin {report['static_margin']:+.4f} c  "
            f"({report['neutral_point_source']})"
        )
    if report.get("model") is not None and report["lattice"] is not None:
        click.echo(
            f"lattice alone: Xnp {report['lattice_neutral_point']:.5g}  static margin "
            f"{report['lattice_static_margin']:+.4f} c"
        )
    for key in ("controls", "drag"):
        click.echo(f"{key}: {report['conventions'][key]}")
    columns = [c for c in ("lattice", "model") if report.get(c) is not None]
    click.echo(f"\n{'derivative':<22}" + "".join(f"{c:>14}" for c in columns))
    for name in report[columns[0]]:
        row = "".join(f"{v:>14.6f}" if v is not None else f"{'—':>14}" for v in (report[c].get(name) for c in columns))
        click.echo(f"{name:<22}{row}")
    for note in report.get("notes", []):
        click.echo(f"note: {note}")


def _condition_options(f):
    options = [
        click.option(
            "--corner", help="Named CG-envelope corner (default: --weight/--cg, else MTOW at the reference CG)."
        ),
        click.option("--weight", help="Mass with unit, e.g. '600000 lb'."),
        click.option("--cg", help="CG station with unit, e.g. '97.25 ft'."),
        click.option("--config", "configuration", default="clean", show_default=True),
        click.option(
            "--altitude", default=None, help="Altitude with unit (default: the file's flight_condition, else 35000 ft)."
        ),
        click.option(
            "--speed",
            default=None,
            help="'250 kn EAS', '280 kn CAS', '490 kn TAS' or 'M0.84' (default: the "
            "file's flight_condition, else M0.84).",
        ),
        click.option(
            "--maneuver",
            "kind",
            default="straight",
            show_default=True,
            help="straight, climb (with --gamma), turn (--bank), oei (--inoperative, --bank), sideslip (--beta).",
        ),
        click.option(
            "--gamma", "gamma_deg", type=FINITE, default=0.0, show_default=True, help="Flight-path angle, deg."
        ),
        click.option("--bank", "bank_deg", type=FINITE, default=0.0, show_default=True, help="Bank angle, deg."),
        click.option("--beta", "beta_deg", type=FINITE, default=0.0, show_default=True, help="Sideslip, deg."),
        click.option("--inoperative", help="Failed engine name (oei)."),
        click.option("--json", "as_json", is_flag=True),
    ]
    for option in reversed(options):
        f = option(f)
    return f


def _flight(aircraft_file, **kw):
    from certkit.aircraft import load_aircraft  # deferred: CLI start-up: the physics loads with the command
    from certkit.cli.flight_report import (  # deferred: CLI start-up: the physics loads with the command
        condition_from_options,
    )
    from certkit.engine.context import Context  # deferred: CLI start-up: the physics loads with the command

    ctx = Context(load_aircraft(aircraft_file))
    as_json = kw.pop("as_json")
    return ctx, condition_from_options(ctx.aircraft, **kw), as_json, kw


@main.command(name="trim")
@click.argument("aircraft_file", type=click.Path(dir_okay=False))
@_condition_options
def trim_command(aircraft_file, **kw):
    """Trim one condition: angles, controls, thrust, and any control beyond its design limit."""
    from certkit.cli.flight_report import trim_report  # deferred: CLI start-up: the physics loads with the command

    ctx, fc, as_json, given = _flight(aircraft_file, **kw)
    report = trim_report(ctx, fc)
    if as_json:
        click.echo(json.dumps(report, indent=2, default=float))
        return
    _print_trim(report, given)


def _beside(given: str | None, aviation: str) -> str:
    """A value as the user gave it, with its aviation-unit value beside it unless given in that unit (not given: the
    value used, in the aviation unit)."""
    if not given:
        return aviation
    return (
        given
        if given.strip().endswith(aviation.rsplit(" ", 1)[-1]) and given[:1].isdigit()
        else f"{given} ({aviation})"
    )


def _print_trim(r, given: dict):
    """The trimmed state; the condition echoed in the units the user gave (with aviation units beside SI)."""
    from certkit.units import FT, KN, LB, LBF  # deferred: CLI start-up: pint loads when the command runs

    c = r["condition"]
    cg = f" · CG {given['cg']}" if given.get("cg") else f" · CG {c['x_cg_m'] / FT:.2f} ft"
    manoeuvre = c["kind"] + "".join(
        f" {k} {given[v]:g} deg" for k, v in (("γ", "gamma_deg"), ("bank", "bank_deg"), ("β", "beta_deg")) if given[v]
    )
    if c.get("inoperative"):
        manoeuvre += f", {c['inoperative']} engine inoperative"
    mass = _beside(given["corner"] or given["weight"], f"{c['mass_kg'] / LB:,.0f} lb")
    altitude = _beside(given["altitude"], f"{c['altitude_m'] / FT:,.0f} ft")
    speed = (
        f"{given['speed']} (TAS {c['tas_m_s'] / KN:.1f} kn)"
        if given.get("speed")
        else f"TAS {c['tas_m_s'] / KN:.1f} kn"
    )
    click.echo(f"{mass}{cg} · {c['configuration']} · {altitude} · {speed} · {manoeuvre}")
    click.echo(
        f"{'converged' if r['converged'] else 'NOT CONVERGED'} (residual {r['residual_norm']:.1e}, {r['iterations']} "
        "iterations)"
    )
    click.echo(
        f"alpha {r['alpha_deg']:.3f} deg  beta {r['beta_deg']:.3f} deg  theta {r['theta_deg']:.3f} deg  phi "
        f"{r['phi_deg']:.3f} deg"
    )
    st = r.get("stabilizer")
    for name, value in r["controls"].items():
        if name == "stabilizer" and st:  # the incidence, not the model's deflection from the datum
            stop = (
                f" (at its {st['at_stop']} stop; needs {st['required_deg']:.2f} deg; limits "
                f"{st['limits_deg'][0]:.2f} to {st['limits_deg'][1]:.2f} deg, {st['limits']})"
                if st["at_stop"]
                else ""
            )
            click.echo(f"  {'stabilizer':<18} {st['incidence_deg']:10.4f} deg incidence{stop}")
            continue
        click.echo(f"  {name:<18} {value:10.4f} {'' if name.startswith('throttle') else 'deg'}")
    thrust = r.get("thrust_N") or {}
    for name, value in thrust.items():
        click.echo(f"  thrust {name:<11} {value / LBF:10,.0f} lbf ({value / 1e3:,.1f} kN)")
    if len(thrust) > 1:
        total = sum(thrust.values())
        click.echo(f"  thrust total      {total / LBF:10,.0f} lbf ({total / 1e3:,.1f} kN)")
    for lim in r["limits_exceeded"]:
        click.echo(f"LIMIT: {lim['message']} — {lim['hint']}")
    if r.get("loading_built"):
        click.echo(f"loading built from {r['loading_built']}")
    for note in r["loading_notes"]:
        click.echo(f"note: {note}")
    for warning in r["warnings"]:
        click.echo(f"warning: {warning}", err=True)


@main.command(name="modes")
@click.argument("aircraft_file", type=click.Path(dir_okay=False))
@_condition_options
@click.option(
    "--no-density-gradient",
    is_flag=True,
    help="Leave the altitude out of the linear model: the textbook four longitudinal equations (Etkin & "
    "Reid eq. 4.9,18), whose phugoid lacks the density gradient's stiffening.",
)
def modes_command(aircraft_file, no_density_gradient, **kw):
    """Dynamic modes about one trimmed condition: eigenvalue, frequency, damping, period, time to half/double.
    The linear model includes the altitude (the density gradient and the thrust lapse with height, which raise the
    phugoid frequency) unless --no-density-gradient."""
    from certkit.cli.flight_report import modes_report  # deferred: CLI start-up: the physics loads with the command

    ctx, fc, as_json, given = _flight(aircraft_file, **kw)
    report = modes_report(ctx, fc, density_gradient=not no_density_gradient)
    if as_json:
        click.echo(json.dumps(report, indent=2, default=float))
        return
    _print_trim(report, given)
    click.echo(
        f"\n{'mode':<14}{'eigenvalue':>26}{'omega_n rad/s':>15}{'zeta':>9}"
        f"{'period s':>10}{'T_half s':>10}{'T_double s':>11}"
    )
    fmt = lambda v: "—" if v is None else f"{v:.3f}"  # noqa: E731
    for name, m in report["modes"].items():
        re, im = m["eigenvalue"]
        click.echo(
            f"{name:<14}{re:>12.5f} {im:+11.5f}j{m['natural_frequency_rad_s']:>15.4f}{m['damping_ratio']:>9.4f}"
            f"{fmt(m['period_s']):>10}{fmt(m['time_to_half_s']):>10}{fmt(m['time_to_double_s']):>11}"
        )


@main.command(name="mission")
@click.argument("aircraft_file", type=click.Path(dir_okay=False))
@click.option("--oew", help="Operating empty weight replacing the declared one, with unit ('306000 lb').")
@click.option("--svg", "svg_path", type=click.Path(dir_okay=False), help="Write the payload-range diagram (SVG) here.")
@click.option("--json", "as_json", is_flag=True, help="Machine-readable output (SI).")
def mission_command(aircraft_file, oew, svg_path, as_json):
    """Design range, payload-range, block fuel and time of the nominal mission, cruise drag (the mission: section)."""
    from certkit.aircraft import load_aircraft  # deferred: CLI start-up: the physics loads with the command
    from certkit.cli.flight_report import _quantity  # deferred: CLI start-up: the physics loads with the command
    from certkit.models.performance.mission import (  # deferred: CLI start-up: the physics loads with the command
        fly_missions,
    )
    from certkit.models.performance.mission_report import (  # deferred: CLI start-up: the physics loads with it
        mission_json,
        mission_table,
    )

    loaded = load_aircraft(aircraft_file)
    result = fly_missions(loaded.model, oew_kg=_quantity(oew, "mass", "--oew") if oew else None)
    if svg_path:
        from certkit.report.mission_plots import (  # deferred: CLI start-up: the report loads with the command
            payload_range_svg,
        )

        try:
            Path(svg_path).write_text(
                payload_range_svg(result.payload_range, result.range_requirement_m), encoding="utf-8"
            )
        except OSError as exc:
            raise UserError(f"--svg {svg_path!r}: cannot write ({exc.strerror or exc})") from None
    click.echo(json.dumps(mission_json(result), indent=2) if as_json else mission_table(result))


@main.command(name="new-rule")
@click.argument("rule_id")
@click.option("--symbol", required=True, help="Kebab-case symbol, e.g. 'stall-speed'.")
@click.option("--title", required=True, help="Short title.")
@click.option(
    "--subpart", type=click.Choice(["b", "c", "d"]), default=None, help="Subpart (default from the paragraph number)."
)
@click.option("--root", type=click.Path(file_okay=False), default=".", show_default=True, help="Repository root.")
def new_rule(rule_id, symbol, title, subpart, root):
    """Scaffold a rule module under rules/part25/subpart_X/ and its test under tests/rules/."""
    from certkit.engine.scaffold import scaffold_rule  # deferred: CLI start-up: the scaffold loads the registry

    module, test = scaffold_rule(Path(root), rule_id, symbol, title, subpart)
    click.echo(f"created {module}\ncreated {test}")


@main.command(name="evaluate")
@click.argument("aircraft_file", type=click.Path(dir_okay=False))
@click.option(
    "--set",
    "settings",
    multiple=True,
    metavar="PATH=VALUE",
    help='Design variable, e.g. --set geometry.horizontal_tail.area="1250 ft^2" (repeatable).',
)
@click.option(
    "--response",
    "responses",
    multiple=True,
    metavar="NAME",
    help="Response name or glob pattern to compute (repeatable; default: all).",
)
@click.option(
    "--jobs",
    "-j",
    default=None,
    type=int,
    help="Processes sharing the rules (default: the CPU cores available, at most 4; the record does not depend on it).",
)
@click.option("--json", "as_json", is_flag=True, help="Print the whole record as JSON.")
def evaluate_command(aircraft_file, settings, responses, jobs, as_json):
    """Evaluate one design: size the horizontal tail from its loads, run every rule and the mission, print one
    record (design variables, objectives, rule margins, sub-checks, handling levels, sizing, timings)."""
    jobs = _default_jobs(jobs)
    _compile_kernels(jobs, announce=not as_json)
    from certkit.design.evaluate import (  # deferred: CLI start-up: the design layer loads with the command
        evaluate_design,
    )
    from certkit.design.report import print_record  # deferred: CLI start-up: the design layer loads with the command
    from certkit.design.sizing_loop import (  # deferred: CLI start-up: the design layer loads with the command
        SizingNotConverged,
    )
    from certkit.design.variables import (  # deferred: CLI start-up: the design layer loads with the command
        parse_setting,
    )
    from certkit.models.structure.box import (  # deferred: CLI start-up: the design layer loads with the command
        StructuralSizingError,
    )

    try:
        record = evaluate_design(
            aircraft_file, [parse_setting(s) for s in settings], list(responses) or None, jobs=jobs
        )
    except (SizingNotConverged, StructuralSizingError) as exc:  # the design is possible but cannot be sized
        click.echo(f"error: the design could not be evaluated: {exc}", err=True)
        sys.exit(1)
    if as_json:
        click.echo(json.dumps(record, indent=2, allow_nan=False))
    else:
        print_record(record, click.echo)


@main.command(name="calibrate")
@click.argument("aircraft_file", type=click.Path(dir_okay=False))
@click.option(
    "--tail",
    is_flag=True,
    help="Solve the horizontal tail's non-optimum factor (the declared tail group "
    "from today's loads) instead of the performance calibration.",
)
def calibrate_command(aircraft_file, tail):
    """Solve the declared calibration factors from their targets and print them for the aircraft file: the drag
    factor that flies calibration.target (fuel-flow factor as declared), or with --tail the non-optimum factor whose
    sized tail group equals the declared 'horizontal tail' component."""
    from certkit.aircraft import load_aircraft  # deferred: CLI start-up: the design layer loads with the command
    from certkit.design.calibration import (  # deferred: CLI start-up: the design layer loads with the command
        calibration_text,
        solve_drag_factor,
        solve_tail_factor,
    )

    loaded = load_aircraft(aircraft_file)

    def progress(f, v):
        click.echo(f"  factor {f:.5f}: {'%.1f kg' % v if tail else '%.1f nmi' % (v / 1852.0)}", err=True)

    result = (
        solve_tail_factor(aircraft_file, loaded.model, progress=progress)
        if tail
        else solve_drag_factor(loaded.model, progress=progress)
    )
    click.echo(calibration_text(result))


@main.group(name="import")
def import_group():
    """Write a certkit aircraft file from another tool's model."""


@import_group.command(name="jsbsim")
@click.argument("fdm_file", type=click.Path(dir_okay=False))
@click.option(
    "--out", "out_path", type=click.Path(dir_okay=False), help="Aircraft file to write (default: standard output)."
)
@click.option("--mach", type=FINITE, default=0.8, show_default=True, help="Mach number the α tables are linearised at.")
@click.option("--altitude", default="35000 ft", show_default=True, help="Altitude of that point, with unit.")
def import_jsbsim_command(fdm_file, out_path, mach, altitude):
    """A certkit aircraft file from a JSBSim FDM (AIRCRAFT.xml): mass, inertia, engines and thrust deck, and the
    aerodynamic functions as a derivative table linearised at level flight at --mach/--altitude; what could not
    be mapped is listed in the file's header and on standard error."""
    from certkit.aircraft.jsbsim_import.importer import (  # deferred: CLI start-up: the JSBSim reader loads with it
        import_jsbsim,
        to_yaml,
    )
    from certkit.cli.flight_report import _quantity  # deferred: CLI start-up: the physics loads with the command

    result = import_jsbsim(fdm_file, mach=mach, altitude=_quantity(altitude, "length", "--altitude"))
    text = to_yaml(result)
    from certkit.aircraft import (  # deferred: CLI start-up: the aircraft model loads with the command
        validate_aircraft_data,
    )

    validate_aircraft_data(result.data)  # what is written must load
    for line in result.unmapped:
        click.echo(f"not mapped: {line}", err=True)
    if out_path:
        try:
            Path(out_path).write_text(text, encoding="utf-8")
        except OSError as exc:
            raise UserError(f"--out {out_path!r}: cannot write ({exc.strerror or exc})") from None
        click.echo(f"wrote {out_path} ({len(result.unmapped)} items not mapped, listed in its header)", err=True)
    else:
        click.echo(text)


def entry() -> None:
    """The ``certkit`` program: :func:`main` with Ctrl-C recorded (:mod:`certkit.interrupts`); an interrupted run ends
    with exit code 130 at once, without the interpreter's shutdown. Every object left is frozen before the shutdown
    (``gc.freeze``): the interpreter's last collection would otherwise scan them all only to free memory that the
    process hands back as it ends (about 0.2 s after a check)."""
    interrupts.install()
    try:
        main()
    except SystemExit as exc:
        if interrupts.requested() and exc.code == EXIT_INTERRUPTED:
            interrupts.leave(EXIT_INTERRUPTED)
        gc.freeze()
        raise
