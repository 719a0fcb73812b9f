"""What every command of the command line shares: the option types, the error guard, the JSON
printer and the checks made before any work.

* Options (the commands' parameter names in brackets): :data:`SourceArg` (``source``: a preset
  name or a .toml file), :data:`SetOpt` (``set_``: ``--set PATH=VALUE`` overrides, values with
  units), :data:`ProfileOpt` (``profile``: switch the speed profile kind), :data:`JsonOpt`
  (``json_``: print one JSON object instead of text), :data:`PlotOpt` (``plot``: a figure
  file), :data:`WorkersOpt`, :data:`ExecutorOpt`, :data:`SchedulerOpt` (``workers``,
  ``executor``, ``scheduler``: where sweeps run), :data:`GradeOpt` (``grade``: the target ISO
  1940 grade G, default 16, checked with :func:`check_grade` and shown with :func:`grade_text`)
  and :data:`UnitsOpt` (``units``: the units of terminal text and figures,
  :func:`autobalance.config.display.display_units`; JSON stays SI).
* Errors: the user's input errors (:data:`USER_ERRORS`) become one line ``error: <message>`` on
  stderr and exit code 2 (:func:`guard`, :func:`fail`); never a traceback.
* Output: :func:`print_json` prints exactly one strict JSON object (SI units, NaN and inf as
  ``null``; :func:`autobalance.jsonable.to_jsonable`).
* Checks before the work: :func:`check_output_file` / :func:`check_plot` (files written at the
  end, atomically: :mod:`autobalance.atomic`), :func:`check_distinct` (no output is an input or
  another output), :func:`check_grade`, :func:`check_workers`, :func:`check_executor`.
"""
from __future__ import annotations

import json
import math
import os
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path
from typing import Annotated, Iterator, NoReturn, Optional

import typer

from ..config import ConfigError, load_config
from ..config.display import as_written
from ..jsonable import to_jsonable
from ..limits import ResourceError
from ..models import ParameterError

__all__ = ["DEFAULT_GRADE", "USER_ERRORS", "ExecutorOpt", "GradeOpt", "JsonOpt", "PlotOpt",
           "ProfileOpt", "as_options", "SchedulerOpt", "SetOpt", "SourceArg", "UnitsOpt",
           "WORKER_BYTES", "WorkersOpt", "check_distinct", "check_executor", "check_grade",
           "check_output_file", "check_plot", "check_workers", "class_text", "fail",
           "grade_text", "guard", "load_machine", "one_line", "print_error", "print_json",
           "quiet_dask_logs"]

# -- the shared options -------------------------------------------------------------------------
SourceArg = Annotated[str, typer.Argument(metavar="PRESET|CONFIG",
                                          help="Preset name or path of a .toml file.")]
SetOpt = Annotated[Optional[list[str]], typer.Option(
    "--set", "-s", metavar="PATH=VALUE",
    help="Override a value, e.g. --set suspension.kx='25 N/mm' (repeatable).")]
ProfileOpt = Annotated[Optional[str], typer.Option(
    "--profile", help="Switch the speed profile kind (constant, ramp, table, std, tsr, motor); "
                      "profile keys from the file that the new kind does not take are dropped.")]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON object (SI) on stdout.")]
#: A figure file; each command checks its suffix (:func:`check_plot`) before any work.
PlotOpt = Annotated[Optional[str], typer.Option(
    "--plot", metavar="FILE.png", help="Write a figure to this file (the suffix sets the format).")]
WorkersOpt = Annotated[Optional[int], typer.Option(
    "--workers", help="Local worker processes (default: all cores).")]
ExecutorOpt = Annotated[Optional[str], typer.Option(
    "--executor", help="Where the sweeps run: serial, local (processes on this machine) or dask.")]
SchedulerOpt = Annotated[Optional[str], typer.Option(
    "--scheduler", help="Dask scheduler address (default: $DASK_SCHEDULER_ADDRESS); the sweeps "
                        "run on that cluster.")]
#: The target ISO 1940 grade of every command that judges a result (004: G16).
DEFAULT_GRADE = 16.0
#: ``--grade G``: give it the default :data:`DEFAULT_GRADE` and check it with :func:`check_grade`.
GradeOpt = Annotated[float, typer.Option(
    "--grade", metavar="G", help="Target ISO 1940 balance grade G [mm/s] (default 16); shown "
                                 "with its ISO class.")]
#: ``--units``: None (the units written in the config), "si", or "speed=rpm,unbalance=g*mm".
UnitsOpt = Annotated[Optional[str], typer.Option(
    "--units", metavar="si|KIND=UNIT,...",
    help="Units of the text and figures (JSON stays SI): default the units written in the "
         "config; 'si'; or e.g. 'speed=rpm,unbalance=g*mm' (kinds: speed, unbalance, length, "
         "mass, force, time, grade).")]

# -- errors -------------------------------------------------------------------------------------
#: Exceptions that are the user's input errors: one line on stderr, exit code 2.
USER_ERRORS = (ConfigError, ParameterError, ResourceError, OSError)
#: The configuration of the command, as written (:attr:`Config.raw`), once :func:`load_machine`
#: has loaded it inside :func:`guard`: a refusal then shows its value as the user wrote it.
_WRITTEN: ContextVar[dict | None] = ContextVar("written", default=None)


def one_line(exc: BaseException) -> str:
    """The message of an input error on one line.

    Parameters
    ----------
    exc : BaseException
        The error; an OSError with a file name gives ``"<strerror>: <file>"``.

    Returns
    -------
    str
        Its message with every run of white space (newlines included) made one space, or the
        exception's class name if it has no message.
    """
    msg = " ".join(str(exc).split())
    if isinstance(exc, OSError) and exc.filename and exc.strerror:
        msg = f"{exc.strerror}: {exc.filename!s}"
    return msg or type(exc).__name__


#: How many ``error:`` lines this process printed (:func:`print_error`): the entry point adds
#: one for an interruption that typer ended silently (exit code 130, no line).
ERRORS_PRINTED = [0]


def print_error(message: str) -> None:
    """Print ``error: <message>`` on stderr, on one line.

    Parameters
    ----------
    message : str
        What went wrong; its white space (newlines included) is collapsed.
    """
    ERRORS_PRINTED[0] += 1
    typer.echo(f"error: {' '.join(message.split())}", err=True)


def fail(message: str, code: int = 2) -> NoReturn:
    """Stop the command: ``error: <message>`` on stderr, then exit with ``code``.

    Parameters
    ----------
    message : str
        What went wrong (printed on one line).
    code : int
        Exit code: 2 for the user's input errors (the default), 1 for a failed run, 128 + the
        signal number for an interruption.

    Raises
    ------
    typer.Exit
        Always.
    """
    print_error(message)
    raise typer.Exit(code)


@contextmanager
def guard() -> Iterator[None]:
    """Context manager: an input error (:data:`USER_ERRORS`) raised inside becomes one line
    ``error: <message>`` on stderr and exit code 2 (:func:`fail`); other exceptions pass.

    Raises
    ------
    typer.Exit
        With code 2, after printing the error line.
    """
    token = _WRITTEN.set(None)
    try:
        yield
    except USER_ERRORS as exc:
        fail(error_text(exc))
    finally:
        _WRITTEN.reset(token)


@contextmanager
def as_options(fields: dict[str, str]) -> Iterator[None]:
    """Context manager: an input error that names a library field the user gave through an
    option names that option instead (``monte_carlo.n = 100000: ...`` becomes ``--starts = 100000:
    ...``), so the one line speaks the command line the user typed.

    Parameters
    ----------
    fields : dict of str to str
        Library field (the start of the message) -> the option that set it, e.g.
        ``{"monte_carlo.n": "--starts"}``.

    Raises
    ------
    ConfigError or ResourceError
        The renamed error (the others pass unchanged).
    """
    try:
        yield
    except USER_ERRORS as exc:
        msg = one_line(exc)
        for field, option in fields.items():
            if msg.startswith(field) and msg[len(field):len(field) + 1] in (" ", ":", "="):
                new = f"{option}{msg[len(field):]}"
                raise (ResourceError(new) if isinstance(exc, ResourceError)
                       else ConfigError(new)) from None
        raise


def error_text(exc: BaseException) -> str:
    """The one line of an input error as the CLI prints it: :func:`one_line`, a refused value
    shown as the configuration wrote it (:func:`autobalance.config.display.as_written`, with
    the configuration the error carries or the one :func:`load_machine` loaded last).

    Parameters
    ----------
    exc : BaseException
        The error.
    """
    if isinstance(exc, (ConfigError, ParameterError)):
        return as_written(one_line(exc), getattr(exc, "written", None) or _WRITTEN.get())
    return one_line(exc)


def forget_written() -> None:
    """Forget the configuration :func:`load_machine` loaded last (a new command starts)."""
    _WRITTEN.set(None)


# -- output -------------------------------------------------------------------------------------
def print_json(obj: dict) -> None:
    """Print ``obj`` as one strict JSON object on stdout (one line, no NaN: ``null``).

    Parameters
    ----------
    obj : dict
        The result (numpy values, tuples and paths allowed: see
        :func:`autobalance.jsonable.to_jsonable`).
    """
    typer.echo(json.dumps(to_jsonable(obj), allow_nan=False))


def load_machine(source: str, sets: Optional[list[str]] = None, profile: Optional[str] = None,
                 balls: str = "any"):
    """The configuration named on the command line, with its ``--set`` and ``--profile``.

    Parameters
    ----------
    source : str
        Preset name or path of a .toml file.
    sets : list of str, optional
        ``PATH=VALUE`` overrides, applied in order.
    profile : str, optional
        A speed profile kind to switch to (``--profile``): the override ``profile.kind=...``
        after the others.
    balls : str
        ``"any"``: any machine; ``"rotor"``: a ball-balancer machine or the bare rotor (no
        liquid); ``"needed"``: a ball balancer (:meth:`autobalance.System.require_balls`);
        ``"liquid"``: a liquid balancer (a ``[liquid]`` section); ``"beside"``: a ball
        balancer, a liquid beside it allowed (analyses that only simulate); ``"balancer"``:
        balls, a liquid or both (analyses that only simulate and need no ball starts).

    Returns
    -------
    autobalance.config.Config

    Raises
    ------
    ConfigError, ParameterError, OSError
        Bad file, value or override (one line).
    """
    cfg = load_config(source, list(sets or []) + ([f"profile.kind={profile}"] if profile else []))
    _WRITTEN.set(cfg.raw)           # a later refusal shows its value as written (guard)
    if balls == "liquid":
        if cfg.system.liquid is None:
            raise ConfigError("liquid: missing; this study needs a liquid balancer, a [liquid] "
                              "section (e.g. the preset leblanc_003)")
    elif balls != "any":
        s = cfg.system
        s.require_balls("this command's analyses", allow_empty=balls == "rotor" or (
                            balls == "balancer" and s.liquid is not None),
                        allow_liquid=balls in ("beside", "balancer"))
    return cfg


# -- checks before the work ---------------------------------------------------------------------
def check_output_file(path: str | Path | None, what: str, example: str = "out.nc",
                      suffixes: tuple[str, ...] = (), inputs: Optional[dict] = None) -> None:
    """Refuse, before any work, an output file the command could not write at the end.

    The file is written to a temporary file in its directory and renamed onto it
    (:func:`autobalance.atomic.atomic_output`; a symbolic link's target is replaced), so that
    directory must be writable even when the file exists.

    Parameters
    ----------
    path : str or Path or None
        The file; None (option not given) passes.
    what : str
        The option, e.g. ``"--out"``, for the message.
    example : str
        A file name for the message, e.g. ``"run.nc"``.
    suffixes : tuple of str
        Allowed lower-case suffixes (``".png"``, ...); empty: any.
    inputs : dict, optional
        The command's input files, ``{"the input config file": path, ...}`` (the phrase for the
        message -> a path, None or a name that is no file: skipped); the output must be none of
        them (:func:`check_distinct`).

    Raises
    ------
    ConfigError
        ``path`` is a directory, a device, a FIFO or another non-regular file, its directory is
        missing or not writable, the file exists and is not writable, its suffix is not one of
        ``suffixes``, or it is one of ``inputs`` (one line).
    """
    if path is None:
        return
    from ..atomic import final_target, non_regular_kind

    path = Path(path)
    name = str(path)
    if path.is_dir():
        raise ConfigError(f"{what} {name!r}: is a directory; give a file name, e.g. "
                          f"{path / example}")
    kind = non_regular_kind(path)
    if kind is not None:
        raise ConfigError(f"{what} {name!r}: is {kind}, not a regular file; give a file name, "
                          f"e.g. {example}")
    parent = final_target(path).parent
    if not parent.is_dir():
        raise ConfigError(f"{what} {name!r}: directory {str(parent)!r} does not exist")
    if suffixes and path.suffix.lower() not in suffixes:
        raise ConfigError(f"{what} {name!r}: expected a file ending in {', '.join(suffixes)}")
    if path.exists() and not os.access(path, os.W_OK):
        raise ConfigError(f"{what} {name!r}: the file is not writable")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise ConfigError(f"{what} {name!r}: directory {str(parent)!r} is not writable"
                          + (" (the file is written beside it, then renamed)"
                             if path.exists() else ""))
    check_distinct({what: path}, inputs)


def check_plot(path: str | Path | None, suffixes: tuple = (".png",), what: str = "--plot",
               example: str = "plot.png", inputs: Optional[dict] = None) -> None:
    """Refuse, before any work, a figure file that could not be written (a directory, a device,
    a missing or read-only directory, a suffix not in ``suffixes``, one of the ``inputs``):
    :func:`check_output_file`.

    Parameters
    ----------
    path : str or Path or None
        The figure file; None passes.
    suffixes : tuple of str
        The formats this command writes, e.g. ``(".png", ".svg", ".pdf")``.
    what : str
        The option for the message.
    example : str
        A file name for the message.
    inputs : dict, optional
        The command's input files (:func:`check_output_file`).

    Raises
    ------
    ConfigError
        One line naming ``what``.
    """
    check_output_file(path, what, example, suffixes, inputs)


def check_distinct(outputs: dict, inputs: Optional[dict] = None) -> None:
    """Refuse, before any work, two outputs of one command that are the same file, or an output
    that is one of its input files (symbolic and hard links seen through:
    :func:`autobalance.atomic.same_file`).

    Parameters
    ----------
    outputs : dict
        Option -> output file (None: not given), e.g. ``{"--out": out, "--plot": plot}``.
    inputs : dict, optional
        What an input is, as the message says it -> its path, e.g. ``{"the input config
        file": source}``; a value that is None or names no existing file (a preset name) is
        skipped.

    Raises
    ------
    ConfigError
        ``--out 'm.toml' is the input config file; give another file name`` or ``--out and
        --plot are the same file 'x.png'; give each its own file name`` (one line; two names
        of one file are both shown).
    """
    from ..atomic import same_file

    given = [(opt, Path(p)) for opt, p in outputs.items() if p is not None and str(p) != ""]
    for i, (opt, p) in enumerate(given):
        for other, q in given[:i]:
            if same_file(p, q):
                both = (f"{other} and {opt} are the same file {str(q)!r}" if str(p) == str(q)
                        else f"{other} {str(q)!r} and {opt} {str(p)!r} are the same file")
                raise ConfigError(f"{both}; give each its own file name")
        for what, src in (inputs or {}).items():
            if src is not None and Path(src).is_file() and same_file(p, src):
                raise ConfigError(f"{opt} {str(p)!r} is {what}; give another file name")


def check_grade(value: float, field: str = "--grade") -> float:
    """An ISO 1940 balance-quality grade G [mm/s]: finite and > 0.

    Parameters
    ----------
    value : float
        The grade G [mm/s].
    field : str
        The option for the message.

    Returns
    -------
    float
        ``value`` as a float [mm/s].

    Raises
    ------
    ConfigError
        Not a finite number > 0 (one line).
    """
    number = isinstance(value, (int, float)) and not isinstance(value, bool)
    v = float(value) if number else float("nan")
    if not (math.isfinite(v) and v > 0):
        shown = f"{v:g}" if number else repr(value)
        raise ConfigError(f"{field} = {shown}: must be a finite ISO 1940 grade G > 0 [mm/s], "
                          "e.g. 16")
    return v


def class_text(G: float) -> str:
    """The ISO 1940 class a grade meets, short: ``"G2.5"``; ``"above G4000"``; ``"-"`` for NaN.

    Parameters
    ----------
    G : float
        A grade [mm/s] (:func:`autobalance.physics.iso1940.grade_class`).

    Returns
    -------
    str
    """
    from ..physics.iso1940 import GRADES, grade_class

    if G is None or not math.isfinite(G):
        return "-"
    cls = float(grade_class(max(float(G), 0.0)))
    return f"G{cls:g}" if math.isfinite(cls) else f"above G{GRADES[-1]:g}"


def grade_text(G: float) -> str:
    """A target grade with its ISO 1940 class, for text and figure labels.

    Parameters
    ----------
    G : float
        The target grade [mm/s] (checked: :func:`check_grade`).

    Returns
    -------
    str
        ``"G16 (ISO 1940 class G16: e*Omega <= 16 mm/s)"`` for a class of the standard series;
        ``"G10 (not an ISO 1940 class; meets class G16)"`` between two classes (the smallest
        class it meets, :func:`autobalance.physics.iso1940.grade_class`); coarser than G4000:
        ``"G5000 (above the coarsest ISO 1940 class, G4000)"``.
    """
    from ..physics.iso1940 import GRADES, grade_class

    cls = float(grade_class(G))
    if not math.isfinite(cls):
        return f"G{G:g} (above the coarsest ISO 1940 class, G{GRADES[-1]:g})"
    if math.isclose(cls, G, rel_tol=1e-9):
        return f"G{G:g} (ISO 1940 class G{cls:g}: e*Omega <= {cls:g} mm/s)"
    return f"G{G:g} (not an ISO 1940 class; meets class G{cls:g})"


def check_executor(executor: Optional[str], workers: Optional[int] = None,
                   scheduler: Optional[str] = None) -> None:
    """``--executor``, ``--workers`` and ``--scheduler`` before any work, by the sweeps' own
    check (:func:`autobalance.sweep.check_executor`): a known executor, ``--workers`` only
    where there are local worker processes, a well-formed scheduler address.

    Parameters
    ----------
    executor : str or None
        ``"serial"``, ``"local"``, ``"dask"`` or None (not given).
    workers : int or None
        ``--workers`` as given (None: not given).
    scheduler : str or None
        ``--scheduler`` as given (None: ``DASK_SCHEDULER_ADDRESS`` if set).

    Raises
    ------
    ConfigError
        One line naming the options (a :class:`autobalance.sweep.SweepError`).
    ResourceError
        The worker processes would not fit the memory limit (:func:`check_workers`).
    """
    from ..sweep import check_executor as check

    check_workers(workers)          # its own message, naming --workers
    check(executor, workers, scheduler)


#: Rough resident memory of one local worker process (Python, numpy, numba, xarray) [B].
WORKER_BYTES = 256 * 2**20


def check_workers(workers: Optional[int], field: str = "--workers") -> None:
    """A local worker count: an integer >= 1 whose processes fit the memory limit
    (:func:`autobalance.limits.check_memory`, :data:`WORKER_BYTES` each).

    Parameters
    ----------
    workers : int or None
        Number of worker processes; None (all cores) passes.
    field : str
        The option for the message.

    Raises
    ------
    ConfigError
        Not an integer >= 1.
    ResourceError
        The processes would not fit the memory limit.
    """
    if workers is None:
        return
    if isinstance(workers, bool) or int(workers) != workers or workers < 1:
        raise ConfigError(f"{field} = {workers}: must be an integer >= 1")
    from ..limits import check_memory

    check_memory(field, workers, workers * WORKER_BYTES, "worker processes")


def quiet_dask_logs() -> None:
    """Silence distributed's own log records in this process.

    The CLI reports a lost or unreachable Dask scheduler in one line itself; distributed would
    otherwise log a traceback for every reconnection attempt.
    """
    import logging

    import distributed  # noqa: F401  (configures its loggers on import)

    for name in ["distributed", *logging.root.manager.loggerDict]:
        if name.startswith("distributed"):
            logging.getLogger(name).setLevel(logging.CRITICAL)
