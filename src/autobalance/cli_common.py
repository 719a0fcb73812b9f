"""Helpers shared by the command-line modules (cli.py and its sub-command groups): one-line
input errors with exit code 2, strict JSON output."""
from __future__ import annotations

import json
import math
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import typer

from .config import ConfigError
from .models import ParameterError

#: Exceptions that are the user's input errors: one line on stderr, exit code 2.
USER_ERRORS = (ConfigError, ParameterError, OSError)


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
