"""All reproduction targets of the four seeds, and selection by name.

Each paper module returned by :func:`modules` exposes ``TARGETS`` (a list of
:class:`~autobalance.validation.target.Target`) and ``ITEMS_<paper>`` tuples: every table and figure
of its seed(s). :func:`coverage` checks that each item is covered by exactly one target.
"""
from __future__ import annotations

import re
from collections.abc import Iterable, Sequence

from ..config import ConfigError
from ..validation.target import Target

__all__ = ["PAPERS", "all_targets", "coverage", "seed_items", "select"]

def modules() -> tuple:
    """The paper modules that define targets, in report order (imported when first asked for)."""
    from ..papers.p000 import targets as p000
    from ..papers.p001 import targets as p001
    from ..papers.p003 import targets as p003
    from ..papers.p004 import targets as p004

    return (p000, p004, p003, p001)


#: Seed -> (short title, the paper's text file name, shown in the HTML report).
PAPERS = {
    "000": ("Majewski et al.: self-balancing of a washing machine (balls/rollers)",
            "000_d14c4c556587a3f7.txt"),
    "004": ("Van De Velde et al. 2020: temporary speed reduction (ball balancer, Jeffcott rotor)",
            "004_3e8e8806a86a955c.txt"),
    "003": ("Drach, Dykha, Matiukh, Dykha 2025: Leblanc balancer on a vertical rotor",
            "003_84771e644935e2a5.txt"),
    "001": ("Drach 2018: fluid balancer, influence of the liquid's viscosity",
            "001_3c093286738a7922.txt"),
}

#: Names that select several papers.
GROUPS = {"all": tuple(PAPERS), "liquid": ("001", "003"), "balls": ("000", "004")}


def all_targets() -> list:
    """Every target, in report order (paper order of :data:`PAPERS`, then module order)."""
    out = []
    for mod in modules():
        out.extend(mod.TARGETS)
    order = list(PAPERS)
    return sorted(out, key=lambda t: order.index(t.paper))


def seed_items() -> dict:
    """Paper -> every table and figure of that seed (from the modules' ``ITEMS_<paper>``)."""
    items = {}
    for mod in modules():
        for paper in PAPERS:
            if hasattr(mod, f"ITEMS_{paper}"):
                items.setdefault(paper, []).extend(getattr(mod, f"ITEMS_{paper}"))
    return {p: tuple(v) for p, v in items.items()}


def coverage(targets: Sequence[Target] | None = None) -> dict:
    """Paper -> {"missing": items no target covers, "twice": items covered more than once}."""
    targets = all_targets() if targets is None else targets
    out = {}
    for paper, items in seed_items().items():
        covered = [i for t in targets if t.paper == paper for i in t.items]
        out[paper] = {"missing": [i for i in items if i not in covered],
                      "twice": sorted({i for i in covered if covered.count(i) > 1}),
                      "unknown": sorted({i for i in covered if i not in items})}
    return out


_ID = re.compile(r"^[a-z0-9][a-z0-9.-]*$")


def select(names: Iterable[str] | None) -> list:
    """Targets named by ``names``: ``all``, a paper (``000``, ``001``, ``003``, ``004``), a group
    (``liquid`` = 001 + 003, ``balls`` = 000 + 004) or target ids; order of the report, no
    duplicates. Unknown names raise ConfigError (one line, with what is allowed)."""
    targets = all_targets()
    by_id = {name: t for t in targets for name in (t.id, *t.aliases)}
    names = [n.strip() for n in (names or ["all"]) if n.strip()] or ["all"]
    chosen = set()
    for n in names:
        if n in GROUPS:
            chosen |= {t.id for t in targets if t.paper in GROUPS[n]}
        elif n in PAPERS:
            chosen |= {t.id for t in targets if t.paper == n}
        elif n in by_id:
            chosen.add(by_id[n].id)
        else:
            raise ConfigError(f"TARGET = {n!r}: unknown; allowed: all, liquid, balls, "
                              f"{', '.join(PAPERS)} or a target id "
                              f"({', '.join(t.id for t in targets)}) or alias "
                              f"({', '.join(a for t in targets for a in t.aliases)})")
    return [t for t in targets if t.id in chosen]


def check_ids(targets: Iterable[Target]) -> None:
    """Target ids and aliases are unique and well formed (lower case, digits, '-', '.') and none
    is a paper or group name."""
    seen = set(PAPERS) | set(GROUPS)
    for t in targets:
        if not isinstance(t, Target) or t.paper not in PAPERS:
            raise ValueError(f"bad target {getattr(t, 'id', t)!r}")
        for name in (t.id, *t.aliases):
            if not _ID.match(name) or name in seen:
                raise ValueError(f"bad or duplicate target name {name!r}")
            seen.add(name)
