"""What a reproduction target is: one or more tables/figures of a seed, how to compute them, and
which published numbers they claim to compare.

A study module (``autobalance.studies.*``) exposes ``TARGETS: list[Target]``. The report runs
each target's ``run(ctx)`` and gets an :class:`Outcome`: comparison rows, matplotlib figures
and the data behind them.

Rows are dicts ``{key, quantity, published, computed, tolerance, ok, note}``. ``key`` names the
published number: ``"<prefix>/<path>"`` where ``<path>`` is the path of a leaf in the target's
``published`` mapping (the study's ``PUBLISHED[...]`` section). :func:`claims` lists every such
leaf (keys named ``source`` or starting with ``_`` are descriptions, not numbers), and the report
flags a claim without a row as *unreported*: no published number is skipped silently.

The one way a paper module writes its rows is :class:`Rows`: a list bound to one key prefix and
one published section, whose :meth:`Rows.add` takes the *path* of the published number and looks
the number up itself (the key and the published value cannot disagree with the claim), and whose
:meth:`Rows.missing` answers a claim this variant does not compute. :func:`row` and
:func:`not_computed` are the plain dict constructors underneath (for tests and the report).

Status of a row: ``pass`` (ok), ``miss`` (computed, outside the tolerance) or ``not computed``
(``computed is None``: the case does not run in this variant, e.g. ``--quick``).
"""
from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any, Callable, Mapping, Optional

__all__ = ["Context", "Outcome", "Rows", "Target", "claims", "not_computed", "row", "status"]


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


#: Default reason of a :func:`not_computed` row.
NOT_COMPUTED = "not computed in this variant (run with --full)"


def row(key: str, quantity: str, published: Any, computed: Any, tolerance: float | str, ok: bool,
        note: str = "") -> dict:
    """A comparison row. ``key``: the claim it answers (see :func:`claims`); ``quantity``: label
    with units in brackets; ``tolerance``: a number or a short text (e.g. ``"+-0.5"``)."""
    return {"key": key, "quantity": quantity, "published": published, "computed": computed,
            "tolerance": tolerance, "ok": bool(ok), "note": note}


def not_computed(key: str, quantity: str, published: Any, why: str = NOT_COMPUTED) -> dict:
    """A row for a published number whose case this variant does not run."""
    return row(key, quantity, published, None, "-", False, why)


def _shown(value):
    """A published leaf as a row shows it: a (lo, hi) pair of numbers is a published range and
    reads ``"lo-hi"``; anything else as it is."""
    if (isinstance(value, tuple) and len(value) == 2
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        return f"{value[0]:g}-{value[1]:g}"
    return value


_LEAF = object()  # Rows.add's default "shown": the published leaf itself


class Rows(list):
    """The comparison rows of one target: the one convention for writing them.

    A list of :func:`row` dicts bound to a key prefix and the published section the rows answer.
    Each row is added by the *path* of its published number in that section; the key
    (``prefix/path``) and the published value come from the path, so a row cannot name one
    claim and show another's number, and a path that is not in the section fails at once
    (KeyError). Typical use in a target's run::

        rows = Rows.of(target)                  # or Rows(prefix, PUBLISHED[section])
        rows.add("omega0_rad_s/V100ml/g10", "omega_0, V = 100 ml [1/s]", 28.04, "+-0.5", ok)
        rows.add("share_std", "share [%]", 41.0, "+-5", ok, shown=100 * share)  # leaf in %
        rows.missing("runs", "runs")            # a claim this variant does not compute
        return Outcome(rows, figures, data)

    Parameters
    ----------
    prefix : str
        Key prefix of the rows (a target's :attr:`Target.key_prefix`, or a sub-path of it when
        one function answers one sub-section, e.g. ``"000-table3-4/table3"``).
    published : mapping
        The published section the paths are looked up in (``target.published`` or the
        sub-section that matches ``prefix``).
    """

    def __init__(self, prefix: str, published: Mapping):
        super().__init__()
        self.prefix = prefix
        self.section = published

    @classmethod
    def of(cls, target: "Target") -> "Rows":
        """The rows of ``target``: its key prefix and its published section."""
        return cls(target.key_prefix, target.published or {})

    def _published_shown(self, path: str, shown):
        leaf = self.published(path)
        return _shown(leaf) if shown is _LEAF else shown

    def published(self, path: str):
        """The published leaf at ``path`` ("a/b/c") of the section (KeyError if absent)."""
        node = self.section
        for p in path.split("/"):
            node = node[p]
        return node

    def add(self, path: str, quantity: str, computed: Any, tolerance: float | str, ok: bool,
            note: str = "", *, shown: Any = _LEAF) -> dict:
        """Append and return the row answering the published number at ``path``.

        Parameters
        ----------
        path : str
            Path of the published leaf in the section; the row's key is ``prefix/path``.
        quantity : str
            What is compared, with its unit in brackets.
        computed
            Our value (a number or a short text).
        tolerance
            A number or a short text (e.g. ``"+-0.5"``).
        ok : bool
            Whether the published value is reproduced within the tolerance.
        note : str
            Why, how, or the reason for a miss.
        shown : optional
            The published number as the row shows it when that is not the leaf itself: the
            leaf in other units (a fraction shown in %) or formatted (a list of ranges). The
            leaf must still exist. Default: the leaf (a (lo, hi) range as ``"lo-hi"``).
        """
        r = row(f"{self.prefix}/{path}", quantity, self._published_shown(path, shown), computed,
                tolerance, bool(ok), note)
        self.append(r)
        return r

    def missing(self, path: str, quantity: str, why: str = NOT_COMPUTED, *,
                shown: Any = _LEAF) -> dict:
        """Append and return the :func:`not_computed` row of the published number at ``path``
        (``shown`` as in :meth:`add`)."""
        r = not_computed(f"{self.prefix}/{path}", quantity, self._published_shown(path, shown), why)
        self.append(r)
        return r


def status(r: Mapping) -> str:
    """``pass``, ``miss`` or ``not computed``."""
    if r.get("computed") is None:
        return "not computed"
    return "pass" if r["ok"] else "miss"
