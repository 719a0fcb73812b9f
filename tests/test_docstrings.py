"""Docstring meta-test: every public function and method documents its parameters,
and every physical parameter states its unit.

For each package in :data:`PACKAGES` the test walks the package and its public submodules
(a module whose own name starts with ``_`` is private and skipped, but what a public module
re-exports from it through ``__all__`` is checked). A *public function* is a module-level
function whose name does not start with ``_``, that is listed in the module's ``__all__`` when the
module has one, and that is defined in that module (or re-exported through its ``__all__``).
A *public method* is a function, staticmethod or classmethod defined in the body of a public
class (inherited ones are checked where they are defined) whose name does not start with ``_``;
public properties are checked for a docstring only. Each is checked for

(a) a docstring;
(b) a numpydoc ``Parameters`` section listing every parameter of its signature, except
    ``self``/``cls``, ``*args`` and ``**kwargs``; a documented name that is not a parameter fails
    too (stale docs), unless the function takes ``**kwargs``;
(c) the unit of every physical parameter in square brackets somewhere in its entry,
    e.g. ``speed : float`` / ``Spin speed w [rad/s].``; a dimensionless one says ``[-]``.

The unit rule (c): a bracket ``[...]`` is required unless the entry's type line names no numeric
type (:data:`NUMERIC_TYPES`: float, array, ...) and names a non-numeric one: one of
:data:`NON_NUMERIC_TYPES` (str, bool, int, callable, Path, dict, ...) or a class (a capitalised
name such as System, SpeedProfile, Simulation, Executor). ``int`` counts as non-numeric: in this
package an int is a count, an index or a seed. An entry without a type line needs a bracket.
The few remaining parameters that are not physical quantities are listed in :data:`EXEMPT`
with the reason.

The test is parametrised by package; ``python tests/test_docstrings.py`` prints every problem.
"""
from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
import sys

import pytest

#: Packages whose public API is checked (models, physics, studies, simulate, liquid).
PACKAGES = [
    "autobalance.models",
    "autobalance.physics",
    "autobalance.studies",
    "autobalance.simulate",
    "autobalance.liquid",
]

#: Type words that make a parameter numeric: its entry must state a unit in brackets.
NUMERIC_TYPES = {"float", "complex", "array", "array_like", "ndarray", "scalar", "number"}

#: Lower-case type words that are not physical quantities (capitalised names are classes and
#: count as non-numeric too).
NON_NUMERIC_TYPES = {"str", "bool", "int", "callable", "dict", "mapping", "path", "none",
                     "function", "generator", "iterator", "object", "slice", "type"}

#: (qualified name, parameter) -> why the parameter needs no unit although its type line alone
#: would ask for one. Empty today: every numeric parameter of the checked packages states its
#: unit (a state vector's mixed units are listed per component, shares and factors say [-]).
#: Add an entry only with a reason, e.g. ``("autobalance.x.f", "y"): "state vector, mixed units"``;
#: ``test_exempt_entries_exist`` refuses stale entries.
EXEMPT: dict[tuple[str, str], str] = {}

_HEADER = re.compile(r"^(\w[\w ]*)\n-{3,}\s*$", re.M)
_UNIT = re.compile(r"\[[^\]\s][^\]]*\]")
_WORD = re.compile(r"[A-Za-z_][A-Za-z_0-9.]*")


# -- docstring parsing (a small numpydoc subset: sections, "name : type" entries) ---------------
def sections(doc: str) -> dict[str, str]:
    """Split a cleaned docstring into its numpydoc sections {title: body}."""
    heads = list(_HEADER.finditer(doc))
    out = {}
    for h, nxt in zip(heads, heads[1:] + [None]):
        out[h.group(1).strip()] = doc[h.end():nxt.start() if nxt else len(doc)]
    return out


def parameter_entries(doc: str) -> dict[str, tuple[str, str]] | None:
    """{name: (type line, description)} of the Parameters section; None when there is none.

    An entry starts at a non-indented line ``name : type`` (or ``a, b : type``, or ``name``
    alone); the indented lines below it are its description.
    """
    body = sections(doc).get("Parameters")
    if body is None:
        return None
    entries: dict[str, tuple[str, str]] = {}
    current: list[str] = []
    for line in body.splitlines():
        if not line.strip():
            continue
        if not line[0].isspace():
            names, _, typ = line.partition(" : ") if " : " in line else (line.rstrip(" :"), "", "")
            current = [n.strip().lstrip("*") for n in names.split(",") if n.strip()]
            for n in current:
                entries[n] = (typ.strip(), "")
        else:
            for n in current:
                typ, desc = entries[n]
                entries[n] = (typ, (desc + " " + line.strip()).strip())
    return entries


def needs_unit(type_line: str) -> bool:
    """True unless the type line names only non-numeric types (the rule in the module doc)."""
    words = _WORD.findall(type_line.replace(" or ", " ").replace(" of ", " "))
    if not words or any(w.lower() in NUMERIC_TYPES for w in words):
        return True
    last = [w.rsplit(".", 1)[-1] for w in words]  # autobalance.models.System -> System
    return not any(w.lower() in NON_NUMERIC_TYPES or w[0].isupper() for w in last)


# -- discovery ------------------------------------------------------------------------------
def _modules(package: str):
    pkg = importlib.import_module(package)
    yield pkg
    for info in pkgutil.walk_packages(pkg.__path__, package + "."):
        if not info.name.rsplit(".", 1)[-1].startswith("_"):
            yield importlib.import_module(info.name)


def _plain(obj):
    """The Python function behind a numba dispatcher (``py_func``), else the object."""
    return getattr(obj, "py_func", obj)


def public_api(package: str):
    """[(qualified name, object, kind)] with kind "function", "method" or "property"."""
    seen, out = set(), []
    for mod in _modules(package):
        exported = getattr(mod, "__all__", None)
        names = exported if exported is not None else [n for n in vars(mod) if not n.startswith("_")]
        for name in names:
            obj = _plain(getattr(mod, name))
            home = getattr(obj, "__module__", "") or ""
            if not home.startswith("autobalance") or (home != mod.__name__ and exported is None):
                continue
            if not (inspect.isfunction(obj) or inspect.isclass(obj)) or id(obj) in seen:
                continue
            seen.add(id(obj))
            qual = f"{home}.{obj.__qualname__}"
            if inspect.isfunction(obj):
                out.append((qual, obj, "function"))
                continue
            for mname, member in vars(obj).items():
                if mname.startswith("_"):
                    continue
                if isinstance(member, (staticmethod, classmethod)):
                    member = member.__func__
                if isinstance(member, property):
                    out.append((f"{qual}.{mname}", member, "property"))
                elif inspect.isfunction(_plain(member)):
                    out.append((f"{qual}.{mname}", _plain(member), "method"))
    return out


# -- the checks -----------------------------------------------------------------------------
def problems(qual: str, obj, kind: str = "function", exempt=None) -> list[str]:
    """Every docstring problem of one function, method or property (empty list = fine)."""
    exempt = EXEMPT if exempt is None else exempt
    doc = inspect.getdoc(obj)
    if not doc or not doc.strip():
        return [f"{qual}: no docstring"]
    if kind == "property":
        return []
    params = [p for p in inspect.signature(obj).parameters.values()
              if p.name not in ("self", "cls")
              and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    takes_kw = any(p.kind == p.VAR_KEYWORD for p in inspect.signature(obj).parameters.values())
    entries = parameter_entries(doc)
    if entries is None:
        return [f"{qual}: no Parameters section"] if params else []
    out = []
    for p in params:
        if p.name not in entries:
            out.append(f"{qual}: parameter {p.name!r} not in the Parameters section")
            continue
        typ, desc = entries[p.name]
        if needs_unit(typ) and not _UNIT.search(typ + " " + desc) \
                and (qual, p.name) not in exempt:
            out.append(f"{qual}: parameter {p.name!r} ({typ or 'no type'}) states no unit in [...]"
                       " (write [-] if dimensionless)")
    if not takes_kw:
        extra = sorted(set(entries) - {p.name for p in inspect.signature(obj).parameters.values()})
        out += [f"{qual}: documents {n!r}, which is not a parameter" for n in extra]
    return out


@pytest.mark.parametrize("package", PACKAGES)
def test_public_docstrings(package):
    api = public_api(package)
    assert api, f"no public functions found in {package}"
    found = [msg for qual, obj, kind in api for msg in problems(qual, obj, kind)]
    assert not found, f"{len(found)} docstring problem(s):\n" + "\n".join(found)


def test_exempt_entries_exist():
    """Every EXEMPT entry names a checked function and one of its parameters (no stale ones)."""
    api = {qual: obj for package in PACKAGES for qual, obj, kind in public_api(package)
           if kind != "property"}
    for (qual, name), reason in EXEMPT.items():
        assert reason.strip(), (qual, name)
        assert qual in api, f"EXEMPT names {qual}, which is not a checked function"
        assert name in inspect.signature(api[qual]).parameters, (qual, name)


# -- self-test: the checks can fail -----------------------------------------------------------
def _fake_missing(speed, system, mass):
    """A fake function.

    Parameters
    ----------
    speed : float
        Spin speed [rad/s].
    system : System
        The machine.
    """


def _fake_no_unit(speed, flag=False, n=2, *args, **kw):
    """A fake function.

    Parameters
    ----------
    speed : float
        Spin speed, unit forgotten.
    flag : bool
        A switch.
    n : int
        A count.
    """


def _fake_good(speed, ratio, system, name="x", *, quick=False):
    """A fake function.

    Parameters
    ----------
    speed, ratio : float
        Spin speed [rad/s] and a ratio [-].
    system : System
        The machine.
    name : str
        A label.
    quick : bool
        Fewer cases.

    Returns
    -------
    float
        Something [m].
    """


def _fake_stale(a):
    """A fake function.

    Parameters
    ----------
    a : float
        Length [m].
    b : float
        Gone [m].
    """


def test_self_test_checks_can_fail():
    assert problems("fake", _fake_missing) == ["fake: parameter 'mass' not in the Parameters section"]
    assert problems("fake", _fake_no_unit) == [
        "fake: parameter 'speed' (float) states no unit in [...] (write [-] if dimensionless)"]
    assert problems("fake", _fake_no_unit, exempt={("fake", "speed"): "test"}) == []
    assert problems("fake", _fake_good) == []
    assert problems("fake", _fake_stale) == ["fake: documents 'b', which is not a parameter"]
    assert problems("fake", lambda x: x) == ["fake: no docstring"]
    assert problems("fake", property(lambda self: 1.0), "property") == ["fake: no docstring"]
    assert needs_unit("float or None") and needs_unit("tuple") and needs_unit("")
    assert not needs_unit("System") and not needs_unit("str or Path") and not needs_unit("int")


if __name__ == "__main__":
    total = 0
    for package in PACKAGES:
        for qual, obj, kind in public_api(package):
            for msg in problems(qual, obj, kind):
                print(msg)
                total += 1
    print(f"{total} problem(s)")
    sys.exit(1 if total else 0)
