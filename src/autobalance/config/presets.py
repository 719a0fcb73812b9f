"""The presets shipped with the package: ``autobalance/presets/<name>.toml``."""
from __future__ import annotations

import importlib.resources
import tomllib
from pathlib import Path

from .units import ConfigError


def _preset_dir() -> Path:
    return Path(str(importlib.resources.files("autobalance") / "presets"))


def preset_path(name: str) -> Path:
    """Path of the preset ``name`` (file ``presets/<name>.toml`` in the package).

    Parameters
    ----------
    name : str
        Preset name, e.g. ``"vub_jeffcott_004"`` (see :func:`list_presets`).

    Returns
    -------
    Path
        The preset's TOML file.

    Raises
    ------
    ConfigError
        If there is no such preset.
    """
    path = _preset_dir() / f"{name}.toml"
    if not path.is_file():
        names = ", ".join(p["name"] for p in list_presets())
        raise ConfigError(f"unknown preset {name!r}; available: {names} "
                          "(or give the path of a .toml file)")
    return path


def list_presets() -> list[dict]:
    """The presets shipped with the package.

    Parameters
    ----------
    None

    Returns
    -------
    list of dict
        ``[{"name", "description", "path"}, ...]`` sorted by name.
    """
    out = []
    for path in sorted(_preset_dir().glob("*.toml")):
        try:
            desc = tomllib.loads(path.read_text(encoding="utf-8")).get("description", "")
        except (OSError, ValueError):
            desc = "(unreadable preset)"
        out.append({"name": path.stem, "description": desc, "path": str(path)})
    return out
