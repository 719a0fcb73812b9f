"""Helpers shared by the command-line modules (cli.py and its sub-command groups): one-line
input errors with exit code 2, strict JSON output."""
from __future__ import annotations

import json
import math
import os
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import typer

from .config import ConfigError
from .limits import ResourceError
from .models import ParameterError

#: Exceptions that are the user's input errors: one line on stderr, exit code 2.
USER_ERRORS = (ConfigError, ParameterError, ResourceError, OSError)


def _one_line(exc: BaseException) -> str:
    msg = " ".join(str(exc).split())
    if isinstance(exc, OSError) and exc.filename and exc.strerror:
        msg = f"{exc.strerror}: {exc.filename!s}"
    return msg or type(exc).__name__


def _fail(message: str, code: int = 2):
    typer.echo(f"error: {' '.join(message.split())}", err=True)
    raise typer.Exit(code)


@contextmanager
def _guard():
    """Turn input errors into ``error: <message>`` on stderr and exit code 2."""
    try:
        yield
    except USER_ERRORS as exc:
        _fail(_one_line(exc))


def check_grade(value: float, field: str = "--grade") -> float:
    """An ISO 1940 balance-quality grade G [mm/s]: finite and > 0; ConfigError otherwise (one
    line). Shared by every command that takes ``--grade``."""
    number = isinstance(value, (int, float)) and not isinstance(value, bool)
    v = float(value) if number else float("nan")
    if not (math.isfinite(v) and v > 0):
        shown = f"{v:g}" if number else repr(value)
        raise ConfigError(f"{field} = {shown}: must be a finite ISO 1940 grade G > 0 [mm/s], "
                          "e.g. 16")
    return v


def check_output_file(path, what: str, example: str = "out.nc", suffixes=()) -> None:
    """Refuse, before any work, an output file the command could not write at the end.

    ``path`` must not be a directory, its directory must exist and be writable and an existing
    file must be writable; with ``suffixes`` its name must end in one of them. ``what`` is the
    option (``"--out"``), ``example`` a file name for the message. ConfigError (one line).
    """
    if path is None:
        return
    path = Path(path)
    name = str(path)
    if path.is_dir():
        raise ConfigError(f"{what} {name!r}: is a directory; give a file name, e.g. "
                          f"{path / example}")
    parent = path.parent
    if not parent.is_dir():
        raise ConfigError(f"{what} {name!r}: directory {str(parent)!r} does not exist")
    if suffixes and path.suffix.lower() not in suffixes:
        raise ConfigError(f"{what} {name!r}: expected a file ending in {', '.join(suffixes)}")
    if path.exists() and not os.access(path, os.W_OK):
        raise ConfigError(f"{what} {name!r}: the file is not writable")
    if not path.exists() and not os.access(parent, os.W_OK | os.X_OK):
        raise ConfigError(f"{what} {name!r}: directory {str(parent)!r} is not writable")


def check_executor(executor) -> None:
    """``--executor``: None (the default) or one of autobalance.sweep.EXECUTORS; ConfigError."""
    from .sweep import EXECUTORS

    if executor is not None and executor not in EXECUTORS:
        raise ConfigError(f"--executor = {executor!r}: must be {', '.join(EXECUTORS)}")


#: Rough resident memory of one local worker process (Python, numpy, numba, xarray) [B].
WORKER_BYTES = 256 * 2**20


def check_workers(workers, field: str = "--workers") -> None:
    """A local worker count: an integer >= 1 whose processes fit the memory limit
    (:func:`autobalance.limits.check_memory`, WORKER_BYTES each); ConfigError / ResourceError."""
    if workers is None:
        return
    if isinstance(workers, bool) or int(workers) != workers or workers < 1:
        raise ConfigError(f"{field} = {workers}: must be an integer >= 1")
    from .limits import check_memory

    check_memory(field, workers, workers * WORKER_BYTES, "worker processes")


def _clean(obj: Any) -> Any:
    """JSON-able copy: numpy -> Python, tuples -> lists, NaN/inf -> None, Paths -> str."""
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if hasattr(obj, "tolist") and not isinstance(obj, (str, bytes)):
        return _clean(obj.tolist())
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, (str, int, bool)) or obj is None:
        return obj
    if isinstance(obj, Path):
        return str(obj)
    if hasattr(obj, "item"):
        return _clean(obj.item())
    return str(obj)


def _print_json(obj: dict) -> None:
    typer.echo(json.dumps(_clean(obj), allow_nan=False))


def quiet_dask_logs() -> None:
    """The CLI reports a lost or unreachable Dask scheduler in one line itself: silence
    distributed's own log records (tracebacks of every reconnection attempt) in this process."""
    import logging

    import distributed  # noqa: F401  (configures its loggers on import)

    for name in ["distributed", *logging.root.manager.loggerDict]:
        if name.startswith("distributed"):
            logging.getLogger(name).setLevel(logging.CRITICAL)
