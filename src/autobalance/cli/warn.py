"""The sanity warnings of a machine on the command line: ``warning: ...`` lines on stdout in
text, a ``warnings`` list in JSON (:func:`autobalance.physics.sanity.config_warnings`).

The studies print them from their shared preparation (:func:`autobalance.cli.study._prepare`,
before any work, so a long study on a doubtful machine is seen to be doubtful at once) and
attach them to the JSON in their shared finish (:func:`autobalance.cli.study._finish`). Those
two helpers do not take the command's ``--json`` flag, so :func:`json_requested` reads it from
the running command's parameters.
"""
from __future__ import annotations

from contextvars import ContextVar
from typing import TYPE_CHECKING

import typer

if TYPE_CHECKING:
    from ..config import Config

__all__ = ["echo_warnings", "json_requested", "machine_warnings_of"]

#: The machine whose warnings were last computed in this command, and those warnings: the
#: finish of a study reuses what its preparation found (the balancing onset costs a root
#: search when the speed lies below a natural frequency).
_LAST: ContextVar[tuple | None] = ContextVar("last_warnings", default=None)


def json_requested() -> bool:
    """Whether the running command was given ``--json`` (its parameter ``json_``); False
    outside a command (a call from Python).

    Returns
    -------
    bool
    """
    try:
        from typer._click.globals import get_current_context
    except ImportError:                        # a typer that uses click itself
        from click import get_current_context
    ctx = get_current_context(silent=True)
    return bool(ctx is not None and ctx.params.get("json_"))


def machine_warnings_of(cfg: Config, units: str | None = None) -> list[str]:
    """The sanity warnings of ``cfg`` (:func:`autobalance.physics.sanity.config_warnings`),
    computed once per machine and command.

    Parameters
    ----------
    cfg : autobalance.config.Config
        The machine as loaded.
    units : str or None
        Display units of the text (``--units``).

    Returns
    -------
    list of str
        One line each, without the "warning:" prefix.
    """
    from ..physics.sanity import config_warnings

    last = _LAST.get()
    if last is not None and last[0] is cfg:
        return list(last[1])
    found = config_warnings(cfg, units)
    _LAST.set((cfg, found))
    return list(found)


def echo_warnings(cfg: Config, units: str | None = None) -> list[str]:
    """Print the sanity warnings of ``cfg`` as ``warning: ...`` lines on stdout, unless the
    command writes JSON (its ``warnings`` list carries them instead).

    Parameters
    ----------
    cfg : autobalance.config.Config
        The machine as loaded.
    units : str or None
        Display units of the text (``--units``).

    Returns
    -------
    list of str
        The warnings.
    """
    found = machine_warnings_of(cfg, units)
    if not json_requested():
        for w in found:
            typer.echo(f"warning: {w}")
    return found
