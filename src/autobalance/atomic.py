"""Output files written whole or not at all.

Every file the package writes for the user (NetCDF, figures, JSON, HTML, markdown) goes through
:func:`atomic_output`: the writer fills a hidden temporary file in the same directory as the
final one (``.run.nc.1f2e3d4c.tmp.nc``: the final suffix kept, so matplotlib and xarray infer
the format), which is flushed to disk (``fsync``) and renamed onto the final name
(``os.replace``, atomic on POSIX). So the final name holds either the previous file or the new
one, never a part of either:

* an exception in the writer (a full disk, a file size limit, a NetCDF/HDF5 error, Ctrl-C)
  removes the temporary file and leaves the previous file untouched;
* a process killed during the write (``kill -9``, a power cut) leaves the previous file and a
  hidden ``.<name>.<random>.tmp<suffix>`` beside it, which may be deleted;
* a final path that is a symbolic link: the link's target is replaced (the temporary file is
  written next to the target), the link stays a link;
* the new file keeps the previous file's permission bits (a new one gets ``0o666`` less the
  umask, as ``open`` would give it).

A failed write raises :class:`OutputError` (an ``OSError``), whose message is one line naming
the option (when given), the file and the reason, e.g. ``--out 'run.nc': No space left on
device; the previous file is unchanged``; the command line prints it as ``error: <message>``
and exits with code 2 (:func:`autobalance.cli.common.guard`).

This module sits below every other one (it imports nothing from autobalance).
"""
from __future__ import annotations

import errno
import os
import secrets
import stat
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Iterator, Optional

__all__ = ["OutputError", "atomic_output", "final_target", "non_regular_kind", "same_file",
           "save_figure", "write_atomic"]

#: Longest part of the final name kept in the temporary name [characters] (NAME_MAX is 255).
_NAME_KEEP = 200
#: Free space under which a NetCDF/HDF5 error is reported as a full disk [B].
_FULL_DISK_BYTES = 1 << 20


class OutputError(OSError):
    """An output file that could not be written; the previous file (if any) is unchanged.

    Parameters
    ----------
    path : str
        The final file, as the caller gave it.
    reason : str
        Why the write failed, e.g. ``"No space left on device"``.
    option : str, optional
        The command-line option that named the file (``"--out"``), for the message.
    kept : bool
        A previous file exists under the final name (and is unchanged).
    code : int, optional
        The ``errno`` of the failure (``errno.ENOSPC``, ...), when known.
    """

    def __init__(self, path: str, reason: str, option: Optional[str] = None,
                 kept: bool = False, code: Optional[int] = None) -> None:
        super().__init__(reason)
        self.errno = code
        self.path, self.reason, self.option, self.kept = str(path), reason, option, kept

    def __reduce__(self):
        return type(self), (self.path, self.reason, self.option, self.kept, self.errno)

    def __str__(self) -> str:
        where = f"{self.option} {self.path!r}" if self.option else f"cannot write {self.path!r}"
        outcome = "the previous file is unchanged" if self.kept else "nothing was written"
        return f"{where}: {self.reason}; {outcome}"


def final_target(path: str | Path) -> Path:
    """The file a write to ``path`` replaces: ``path`` itself, or the final target of a symbolic
    link (which need not exist yet).

    Parameters
    ----------
    path : str or Path
        The output file as given.

    Returns
    -------
    Path
    """
    p = Path(path)
    return Path(os.path.realpath(p)) if p.is_symlink() else p


def non_regular_kind(path: str | Path) -> Optional[str]:
    """What an existing file that is not a regular file is (symbolic links followed).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    str or None
        ``"a directory"``, ``"a character device"``, ``"a block device"``, ``"a FIFO"``,
        ``"a socket"`` or ``"not a regular file"``; None for a regular file or a missing one.
    """
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return None
    if stat.S_ISREG(mode):
        return None
    for test, kind in ((stat.S_ISDIR, "a directory"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return kind
    return "not a regular file"


def same_file(a: str | Path, b: str | Path) -> bool:
    """Whether two paths name the same file: the same inode when both exist (hard and symbolic
    links included), else the same fully resolved path (a file not written yet).

    Parameters
    ----------
    a, b : str or Path
        The paths.

    Returns
    -------
    bool
    """
    try:
        if os.path.exists(a) and os.path.exists(b):
            return os.path.samefile(a, b)
    except OSError:
        pass
    return os.path.normcase(os.path.realpath(a)) == os.path.normcase(os.path.realpath(b))


def _reserve(target: Path, suffix: str) -> Path:
    """Create an empty hidden temporary file beside ``target`` (a fresh name, ``0o666`` less
    the umask) and return its path."""
    keep = target.name[:_NAME_KEEP]
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0)
    for _ in range(64):
        tmp = target.with_name(f".{keep}.{secrets.token_hex(4)}.tmp{suffix}")
        try:
            os.close(os.open(tmp, flags, 0o666))
        except FileExistsError:
            continue
        return tmp
    raise FileExistsError(errno.EEXIST, "no free temporary file name", str(target.parent))


def _commit(tmp: Path, target: Path, mode: Optional[int]) -> None:
    """Flush ``tmp`` to disk, give it ``mode`` (None: keep) and rename it onto ``target``."""
    fd = os.open(tmp, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
    if mode is not None:
        os.chmod(tmp, mode)
    os.replace(tmp, target)
    try:                                    # the rename itself on disk (POSIX; best effort)
        dfd = os.open(target.parent, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(dfd)
    except OSError:
        pass
    finally:
        os.close(dfd)


def _size_limit() -> Optional[int]:
    """The process's file size limit (``ulimit -f``) [B], or None when unlimited."""
    try:
        import resource
    except ImportError:                     # not on POSIX
        return None
    soft = resource.getrlimit(resource.RLIMIT_FSIZE)[0]
    return None if soft == resource.RLIM_INFINITY else int(soft)


def _diagnosis(tmp: Path) -> tuple[Optional[str], Optional[int]]:
    """The likely cause of a write error that carries no errno (NetCDF/HDF5 report "HDF
    error"): the file size limit reached by ``tmp`` or a full disk; (None, None) otherwise."""
    limit = _size_limit()
    try:
        size = os.stat(tmp).st_size
    except OSError:
        size = 0
    if limit is not None and size >= limit - (64 << 10):
        return f"File too large (the file size limit, ulimit -f, is {limit} bytes)", errno.EFBIG
    try:
        st = os.statvfs(tmp.parent)
    except (OSError, AttributeError):
        return None, None
    if st.f_bavail * st.f_frsize < _FULL_DISK_BYTES:
        return os.strerror(errno.ENOSPC), errno.ENOSPC
    return None, None


def _reason(exc: BaseException, tmp: Optional[Path]) -> tuple[Optional[str], Optional[int]]:
    """(reason, errno) of a failed write, or (None, None) when ``exc`` is not a write error
    (a bug or an interruption in the writer: it passes unchanged)."""
    if isinstance(exc, OutputError):        # a nested atomic write (a library writer)
        return exc.reason, exc.errno
    text = " ".join(str(getattr(exc, "strerror", None) or exc).split())
    code = getattr(exc, "errno", None) if isinstance(exc, OSError) else None
    if isinstance(code, int) and code > 0:
        reason = os.strerror(code)
        other = getattr(exc, "filename", None)
        if other is not None and (tmp is None or tmp.name not in str(other)):
            reason += f": {other!s}"        # about another file than this output
        limit = _size_limit() if code == errno.EFBIG else None
        return (reason if limit is None else
                f"{reason} (the file size limit, ulimit -f, is {limit} bytes)"), code
    if not isinstance(exc, OSError) and "NetCDF" not in text and "HDF" not in text:
        return None, None
    found, code = _diagnosis(tmp) if tmp is not None else (None, None)
    return (found or text or type(exc).__name__), code


@contextmanager
def atomic_output(path: str | Path, option: Optional[str] = None) -> Iterator[Path]:
    """Context manager: a temporary file to write instead of ``path``, renamed onto ``path``
    when the block ends normally (see the module docstring).

    Parameters
    ----------
    path : str or Path
        The final file; a symbolic link's target is replaced, the link kept.
    option : str, optional
        The option that named the file (``"--out"``), for the error message.

    Yields
    ------
    Path
        The temporary file (hidden, in the final file's directory, the final suffix kept; it
        exists, empty): write it whole, e.g. ``fig.savefig(tmp)`` or ``ds.to_netcdf(tmp)``.

    Raises
    ------
    OutputError
        The final path is not a regular file (a device, a FIFO, a directory), or the write
        failed with an OSError (full disk, file size limit, permission, read-only file system)
        or a NetCDF/HDF5 error: one line; the previous file is unchanged, no temporary file is
        left. Any other exception of the block (Ctrl-C included) passes unchanged, the
        temporary file removed and the previous file unchanged.
    """
    target = final_target(path)
    kind = non_regular_kind(target)
    kept = target.is_file()
    if kind is not None:
        raise OutputError(str(path), f"is {kind}, not a regular file; give a file name",
                          option, kept=True)
    tmp: Optional[Path] = None
    try:
        mode = stat.S_IMODE(os.stat(target).st_mode) if kept else None
        tmp = _reserve(target, Path(path).suffix)
        yield tmp
        _commit(tmp, target, mode)
    except BaseException as exc:
        reason, code = _reason(exc, tmp)
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass
        if reason is None:
            raise
        raise OutputError(str(path), reason, option, kept, code) from exc


def write_atomic(path: str | Path, data: str | bytes, option: Optional[str] = None,
                 encoding: str = "utf-8") -> Path:
    """Write text or bytes to ``path`` atomically (:func:`atomic_output`).

    Parameters
    ----------
    path : str or Path
        The final file.
    data : str or bytes
        The content; text is encoded with ``encoding``.
    option : str, optional
        The option that named the file, for the error message.
    encoding : str
        Encoding of text.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    OutputError
        The write failed (one line; the previous file unchanged).
    """
    raw = data.encode(encoding) if isinstance(data, str) else bytes(data)
    with atomic_output(path, option) as tmp:
        with open(tmp, "wb") as f:
            f.write(raw)
    return Path(path)


def save_figure(fig: Any, path: str | Path, option: Optional[str] = None,
                **savefig: Any) -> Path:
    """Save a matplotlib figure to ``path`` atomically (:func:`atomic_output`; the format from
    the suffix of ``path``).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : str or Path
        The final file (.png, .svg, .pdf, ...).
    option : str, optional
        The option that named the file, for the error message.
    **savefig
        Passed to ``fig.savefig`` (e.g. ``dpi=120``).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    OutputError
        The write failed (one line; the previous file unchanged).
    """
    with atomic_output(path, option) as tmp:
        fig.savefig(tmp, **savefig)
    return Path(path)
