"""``--set path=value`` overrides of a parsed TOML dict (before validation)."""
from __future__ import annotations

import copy
import tomllib
from collections.abc import Iterable
from typing import Any

from ..limits import max_nesting
from .reader import bracket_depth, check_nesting
from .schema import PROFILE_KINDS, RETIRED, SECTIONS, TOP_LEVEL
from .units import ConfigError

#: Every key a ``[profile]`` table may hold (over all kinds).
PROFILE_KEYS = sorted({"kind"}.union(*PROFILE_KINDS.values()))


def split_path(path: str, prefix: str = "") -> tuple[str, str]:
    """Check a dotted config path and split it into (section, key).

    Parameters
    ----------
    path : str
        ``"section.key"`` (``"suspension.kx"``, ``"profile.plateau"``), or ``"name"`` or
        ``"description"``.
    prefix : str
        Put before the path in the error message (``"--set "``).

    Returns
    -------
    tuple of str
        (section, key); for ``name`` and ``description``: ("", path).

    Raises
    ------
    ConfigError
        Unknown section or key (one line listing what is allowed).
    """
    parts = path.split(".")
    if len(parts) == 1:
        if path not in ("name", "description"):
            raise ConfigError(f"{prefix}{path}: unknown path; use section.key with a section "
                              f"in {', '.join(TOP_LEVEL[2:])} (or name, description)")
        return "", path
    if len(parts) != 2 or parts[0] not in TOP_LEVEL[2:]:
        raise ConfigError(f"{prefix}{path}: unknown path; sections: {', '.join(TOP_LEVEL[2:])}")
    section, key = parts
    allowed = PROFILE_KEYS if section == "profile" else list(SECTIONS[section])
    if (section, key) in RETIRED:
        raise ConfigError(f"{prefix}{path}: {RETIRED[section, key]}")
    if key not in allowed:
        raise ConfigError(f"{prefix}{path}: unknown key; allowed: {', '.join(allowed)}")
    return section, key


def _parse_value(text: str, where: str = "--set") -> Any:
    """An override value: a TOML scalar/array, else a bare string such as ``100 Hz``; arrays
    nested deeper than :func:`autobalance.limits.max_nesting` are refused (``where`` names the
    override in the message)."""
    text = text.strip()
    shown = text if len(text) <= 40 else text[:37] + "..."
    try:
        value = tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        pass
    except RecursionError:                  # thousands of nested arrays or inline tables
        raise ConfigError(f"{where}={shown}: arrays nested too deeply to parse; at most "
                          f"{max_nesting()} levels are allowed (set AUTOBALANCE_MAX_NESTING to "
                          "raise it)") from None
    else:
        check_nesting(value, f"{where}={shown}")
        return value
    if bracket_depth(text) > max_nesting():
        raise ConfigError(f"{where}={shown}: arrays nested more than {max_nesting()} levels "
                          "deep; at most that many are allowed (set AUTOBALANCE_MAX_NESTING to "
                          "raise it)")
    if text.startswith("[") and text.endswith("]"):
        items = [t.strip() for t in text[1:-1].split(",") if t.strip()]
        return [_parse_value(t, where) for t in items]
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "\"'":
        return text[1:-1]
    return text


def parse_override(item: str | tuple) -> tuple[str, Any]:
    """Split one ``path=value`` override and read its value.

    Parameters
    ----------
    item : str or tuple
        ``"suspension.kx=25 N/mm"``, ``'rotor.unbalance="0.05 kg*m"'``,
        ``"initial.ball_angles=[0, 3.1]"``. The value is read as a TOML scalar or array if it
        is one, else as a bare string (a number with units). Or a ``(path, value)`` pair, the
        value as it would be in a TOML file.

    Returns
    -------
    tuple
        (path, value), the path checked by :func:`split_path`.

    Raises
    ------
    ConfigError
        No ``=``, or an unknown path (one line starting with ``--set``).
    """
    if isinstance(item, tuple) and len(item) == 2:   # (path, value) given in Python
        split_path(str(item[0]), "--set ")
        return str(item[0]), item[1]
    if "=" not in item:
        raise ConfigError(f"--set {item!r}: expected path=value, e.g. suspension.kx='20 N/mm'")
    path, text = (s.strip() for s in item.split("=", 1))
    split_path(path, "--set ")
    return path, _parse_value(text, f"--set {path}")


def apply_overrides(raw: dict, overrides: Iterable[str | tuple[str, Any]] = ()) -> dict:
    """Apply ``path=value`` overrides to a copy of a TOML dict.

    Parameters
    ----------
    raw : dict
        Parsed TOML (not modified).
    overrides : iterable of str or (path, value)
        ``"suspension.kx=25 N/mm"``, ``'rotor.unbalance="0.05 kg*m"'``,
        ``"initial.ball_angles=[0, 3.1]"``, ``"profile.kind=tsr"``, ``("options.rtol", 1e-7)``
        (see :func:`parse_override`).

    Returns
    -------
    dict
        The merged dict.

    Notes
    -----
    Switching the profile kind (``profile.kind=NAME``; the CLI's ``--profile NAME``) keeps the
    ``[profile]`` keys that the new kind accepts and silently drops the others **if they came
    from the file or preset**; a key given with ``--set`` that the new kind does not accept is
    an error. The new kind's missing optional keys take the constructor defaults (std/tsr:
    004 values); its missing required keys (e.g. std/tsr ``nominal``) are reported missing.

    Raises
    ------
    ConfigError
        Malformed override or unknown path (one line).
    """
    out = copy.deepcopy(raw)
    base_kind = out.get("profile", {}).get("kind") if isinstance(out.get("profile"), dict) else None
    set_in_profile = set()
    for item in overrides or ():
        path, value = parse_override(item)
        section, key = split_path(path)
        if not section:
            out[key] = value
            continue
        if not isinstance(out.get(section, {}), dict):
            out[section] = {}
        out.setdefault(section, {})[key] = value
        if section == "profile":
            set_in_profile.add(key)
    prof = out.get("profile")
    if isinstance(prof, dict) and prof.get("kind") != base_kind and prof.get("kind") in PROFILE_KINDS:
        keep = set(PROFILE_KINDS[prof["kind"]]) | {"kind"} | set_in_profile
        out["profile"] = {k: v for k, v in prof.items() if k in keep}
    return out
