"""What a reproduction target is: one or more tables/figures of a seed, how to compute them, and
which published numbers they claim to compare.

A study module (``autobalance.studies.*``) exposes ``TARGETS: list[Target]``. The report runs
each target's ``run(ctx)`` and gets an :class:`Outcome`: comparison rows, matplotlib figures
and the data behind them.

Rows are dicts ``{key, quantity, published, computed, tolerance, ok, note}`` made with
:func:`row` (or :func:`not_computed`). ``key`` names the published number: ``"<prefix>/<path>"``
where ``<path>`` is the path of a leaf in the target's ``published`` mapping (the study's
``PUBLISHED[...]`` section). :func:`claims` lists every such leaf (keys named ``source`` or
starting with ``_`` are descriptions, not numbers), and the report flags a claim without a row
as *unreported*: no published number is skipped silently.

Status of a row: ``pass`` (ok), ``miss`` (computed, outside the tolerance) or ``not computed``
(``computed is None``: the case does not run in this variant, e.g. ``--quick``).
"""
from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any, Callable, Mapping, Optional

__all__ = ["Context", "Outcome", "Target", "claims", "not_computed", "row", "status"]


@dataclasses.dataclass(frozen=True)
class Context:
    """How to run: ``quick`` (coarse grids, minutes for everything) or full (the paper's grids);
    ``out`` the report directory; sweep stores go under ``stores`` (reused on a rerun: resumable);
    ``executor`` / ``workers`` / ``scheduler`` as for :func:`autobalance.sweep`."""
    quick: bool = True
    out: Optional[Path] = None
    executor: str = "local"
    workers: Optional[int] = None
    scheduler: Optional[str] = None

    @property
    def stores(self) -> Optional[Path]:
        return None if self.out is None else Path(self.out) / "stores"


@dataclasses.dataclass
class Outcome:
    """What a target's run returns. ``figures``: name -> matplotlib Figure (saved as PNG and SVG);
    ``data``: an xarray.Dataset (saved as NetCDF), a dict of them, or None; ``notes``: what this
    run did (grid sizes, variant) in one or two sentences."""
    rows: list
    figures: dict = dataclasses.field(default_factory=dict)
    data: Any = None
    notes: str = ""


@dataclasses.dataclass(frozen=True)
class Target:
    """One reproduction target.

    id : str
        ``<paper>-<items>``, lower case, e.g. ``"004-fig5-6-table2"``; the CLI's TARGET name.
    paper : str
        ``"000"``, ``"001"``, ``"003"`` or ``"004"``.
    items : tuple of str
        The seed's tables, figures and equations covered, e.g. ``("Fig. 5", "Fig. 6", "Table 2")``.
    title : str
        One line.
    run : callable(Context) -> Outcome, or None
        None for a schematic, photograph or parameter list: nothing to compute; ``notes`` says why.
    published : mapping or None
        The published numbers this target claims (a ``PUBLISHED[...]`` section); every leaf must
        become a row with key ``prefix/path``.
    prefix : str
        Key prefix of the rows (default: the target id).
    notes : str
        Assumptions, choices and the reasons for known misses (plain text, shown in the report).
    quick : str
        What ``--quick`` changes (shown in the report); empty when quick = full.
    aliases : tuple of str
        Other names the CLI accepts for this target (e.g. ``"tsr-mc"``).
    """
    id: str
    paper: str
    items: tuple
    title: str
    run: Optional[Callable[[Context], Outcome]] = None
    published: Optional[Mapping] = None
    prefix: str = ""
    notes: str = ""
    quick: str = ""
    aliases: tuple = ()

    @property
    def key_prefix(self) -> str:
        return self.prefix or self.id


def _is_description(key: str) -> bool:
    return key == "source" or key.startswith("_")


def claims(target: Target) -> list:
    """Keys of every published number the target claims: ``prefix/path/to/leaf``. A leaf is any
    value that is not a mapping (numbers, strings, tuples of ranges, ...)."""
    out = []

    def walk(node, path):
        for k, v in node.items():
            if _is_description(str(k)):
                continue
            p = f"{path}/{k}"
            if isinstance(v, Mapping):
                walk(v, p)
            else:
                out.append(p)

    if target.published:
        walk(target.published, target.key_prefix)
    return out


def row(key: str, quantity: str, published, computed, tolerance, ok: bool, note: str = "") -> dict:
    """A comparison row. ``key``: the claim it answers (see :func:`claims`); ``quantity``: label
    with units in brackets; ``tolerance``: a number or a short text (e.g. ``"+-0.5"``)."""
    return {"key": key, "quantity": quantity, "published": published, "computed": computed,
            "tolerance": tolerance, "ok": bool(ok), "note": note}


def not_computed(key: str, quantity: str, published, why: str = "not computed in this variant "
                                                                "(run with --full)") -> dict:
    """A row for a published number whose case this variant does not run."""
    return row(key, quantity, published, None, "-", False, why)


def status(r: Mapping) -> str:
    """``pass``, ``miss`` or ``not computed``."""
    if r.get("computed") is None:
        return "not computed"
    return "pass" if r["ok"] else "miss"
