"""The ``autobalance`` console script's entry point, outside the package.

Importing :mod:`autobalance` loads numpy, numba and the compiled kernels (about a second). A
Ctrl-C in that second would end the command with a ``KeyboardInterrupt`` traceback from the
import, before :func:`autobalance.cli.main` can turn it into one line. This module imports
nothing heavy: it holds SIGINT while the package loads (a Ctrl-C then prints
``error: interrupted`` and exits with 130), then hands the command to
:func:`autobalance.cli.main`, which handles Ctrl-C itself from there on.
"""
import _signal  # the C module: ``signal`` imports enum and functools, which take milliseconds
import os


def _interrupted_while_loading(signum: int, frame) -> None:
    """SIGINT before the command started: one line on stderr, exit 128 + ``signum``."""
    try:
        os.write(2, b"error: interrupted\n")
    finally:
        os._exit(128 + signum)


def main() -> None:
    """Run ``autobalance`` with the process's arguments (the console script).

    Raises
    ------
    SystemExit
        Always, with the command's exit code (:func:`autobalance.cli.main`).
    """
    held = _signal.getsignal(_signal.SIGINT) is _signal.default_int_handler
    if held:
        _signal.signal(_signal.SIGINT, _interrupted_while_loading)
    from autobalance.cli import main as cli_main

    if held:
        _signal.signal(_signal.SIGINT, _signal.default_int_handler)
    cli_main()
