"""Command line interface (typer), thin: parse, call the library, print.

Every command takes ``--json`` and then prints exactly one JSON object on stdout (SI units,
snake_case keys with unit suffixes; NaN and inf become ``null``). Input errors (bad config, bad
value, unknown preset, unreadable file) print one line ``error: <message>`` on stderr and exit
with code 2, never a traceback. A simulation whose status is not ``"ok"`` exits with code 1.

One module per task: :mod:`.machine` (presets, show, demo), :mod:`.simulate`, :mod:`.response`,
:mod:`.sweep`, :mod:`.analyze`, :mod:`.liquid`,
:mod:`.reproduce`; :mod:`.common` holds the options, the error guard, the JSON printer and the
checks they share. The physics modules are imported inside the commands so that ``presets`` and
``show`` stay fast.
"""
from __future__ import annotations

import sys
from typing import Optional

import typer

from . import analyze, liquid, machine, reproduce, response, simulate, study, sweep
from . import (liquid_check, study_design, study_liquid, study_maps,  # noqa: F401  (register their commands)
               study_runup, study_tsr)
from .common import ERRORS_PRINTED, USER_ERRORS, error_text, forget_written, one_line, print_error
from .vocabulary import rewrite_deprecated

__all__ = ["app", "main"]

app = typer.Typer(name="autobalance", no_args_is_help=True, add_completion=False,
                  rich_markup_mode=None,     # help as written: no rich markup or :emoji: codes
                  pretty_exceptions_enable=False,
                  help="Simulate and design passive automatic balancers: presets, show, simulate, "
                       "response, sweep, study, design, analyze, liquid, reproduce, demo.")


def _print_version(value: bool) -> None:
    if value:
        from .. import __version__

        typer.echo(f"autobalance {__version__}")
        raise typer.Exit()


@app.callback()
def _root(version: bool = typer.Option(False, "--version", is_eager=True,
                                       callback=_print_version,
                                       help="Print the version and exit.")) -> None:
    """The program's own options (its help is the app's)."""


app.command()(machine.presets)
app.command()(machine.show)
app.command("simulate")(simulate.simulate_cmd)
app.command()(response.response)
app.command("sweep")(sweep.sweep_cmd)
app.command()(machine.demo)
app.add_typer(analyze.app, name="analyze",
              help="Washer analysis (seed 000): vibratory forces, equilibria, error bounds, "
                   "kinetic-static model, the washer's studies.")
app.add_typer(study.app, name="study",
              help="Design studies of any machine: speed map, start positions, unbalance "
                   "range, TSR plateau, immobility, tolerances, sensitivity, run-up.")
app.command("design")(study_design.design)
app.command("reproduce")(reproduce.reproduce)
app.add_typer(liquid.app, name="liquid",
              help="Liquid (Leblanc) balancers (seeds 001, 003): free surface, motion modes, "
                   "entrainment speeds, kinetostatics, spin-up, stability.")


def main(argv: Optional[list[str]] = None) -> None:
    """Console entry point ``autobalance`` (also ``python -m autobalance``).

    Input errors, usage errors included (a bad option value, a missing argument, an unknown
    command), exit 2 with one line on stderr; Ctrl-C exits 130 with one line; never a traceback
    for either.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after the program name; default ``sys.argv[1:]``.

    Raises
    ------
    SystemExit
        Always, with the command's exit code.
    """
    try:                          # typer vendors click as typer._click (pyproject: typer>=0.29)
        from typer._click.exceptions import NoArgsIsHelpError, UsageError
    except ImportError:           # pragma: no cover - a typer that uses click itself
        from click.exceptions import NoArgsIsHelpError, UsageError

    forget_written()
    printed = ERRORS_PRINTED[0]
    argv, warnings = rewrite_deprecated(sys.argv[1:] if argv is None else list(argv))
    for w in warnings:
        print(w, file=sys.stderr)
    try:
        rv = app(args=argv, prog_name="autobalance", standalone_mode=False)
    except NoArgsIsHelpError:           # the help was printed
        sys.exit(0)
    except UsageError as exc:
        cmd = exc.ctx.command_path if exc.ctx is not None else "autobalance"
        print_error(f"{' '.join(exc.format_message().split())} (see {cmd} --help)")
        sys.exit(2)
    except USER_ERRORS as exc:
        print_error(error_text(exc))
        sys.exit(2)
    except KeyboardInterrupt as exc:    # a SweepInterrupted says what was kept
        print_error(one_line(exc) if str(exc) else "interrupted")
        sys.exit(128 + int(getattr(exc, "signal", 2)))
    code = rv if isinstance(rv, int) else 0
    if code == 130 and ERRORS_PRINTED[0] == printed:   # typer's own exit for a Ctrl-C
        print_error("interrupted")
    sys.exit(code)
