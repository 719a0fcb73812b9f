"""Import graph of src/autobalance: one direction of dependency, no package cycles.

Every module under src/autobalance is parsed with ``ast`` (nothing is imported). Its imports of
autobalance modules are collected: absolute and relative, at module level and inside functions
or ``if`` blocks. ``from pkg import name`` counts as an import of ``pkg.name`` when that is a
module, of ``pkg`` otherwise; importing ``a.b.c`` also runs the ``__init__`` of ``a.b`` (an
implied edge). The root package ``autobalance/__init__.py`` is the public facade: its own imports
are not checked, ``from autobalance import __version__`` is allowed everywhere (the root is
always initialised first), and a name it re-exports counts as an import of the module defining it.

Layers, lowest first (docs/architecture.md). A module may import modules of its own layer and
of lower layers:

    0  core                        numba kernels on plain floats/arrays (no models, no units)
    1  limits, validation,         resource settings and guards; the reproduction contract;
       jsonable, atomic            JSON-safe conversion; atomic output files (none imports
                                   the package)
    2  models                      frozen SI dataclasses
    3  config                      units, schema, presets, overrides (needs only models)
    4  physics, liquid             closed forms; the liquid balancer package
    5  plotting                    data in, matplotlib Figure out
    6  simulate                    one run / a batch and what it returns, packing, fast paths
    7  sweep                       descriptions, plans, executors, the store
    8  studies                     machine-agnostic analyses (they run sweeps)
    9  papers                      the seeds' published numbers and target wiring
    10 report                      runner, HTML, markdown; never imports the CLI
    11 cli, __main__

The checks fail on (a) a cycle between packages (strongly connected components of the graph of
top-level units, and of the graph of (sub)packages) and (b) an upward import, unless it is in
KNOWN_VIOLATIONS (empty); they also fail on a KNOWN_VIOLATIONS
entry that no longer occurs, so that list only shrinks. A new top-level module or package must be given a layer in LAYERS.
"""
from __future__ import annotations

import ast
import functools
from collections import defaultdict
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
ROOT = "autobalance"

LAYERS = [
    ("core",),
    ("limits", "validation", "jsonable", "atomic", "confidence"),
    ("models",),
    ("config",),
    ("physics", "liquid"),
    ("plotting",),
    ("simulate",),
    ("sweep",),
    ("studies",),
    ("papers",),
    ("report",),
    ("cli", "__main__"),
]

# Today's violations (module -> imported module, without the "autobalance." prefix; a cycle as
# "cycle: <members>"). Remove an entry when the refactor fixes it; never add one silently.
KNOWN_VIOLATIONS: set = set()


# -- the graph -----------------------------------------------------------------------------------
def module_files(src: Path = SRC, root: str = ROOT) -> dict:
    """Dotted module name -> (path, is_package) for every .py file of the package."""
    mods = {}
    for p in sorted((src / root).rglob("*.py")):
        parts = p.relative_to(src).with_suffix("").parts
        is_pkg = parts[-1] == "__init__"
        mods[".".join(parts[:-1] if is_pkg else parts)] = (p, is_pkg)
    return mods


def _root_reexports(mods: dict, root: str) -> dict:
    """Names the root __init__ re-exports from its submodules -> the defining module."""
    path, _ = mods[root]
    out = {}
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module:
            for a in node.names:
                out[a.asname or a.name] = f"{root}.{node.module}"
    return out


def _imports(name: str, path: Path, is_pkg: bool, mods: dict, root: str, reexports: dict) -> set:
    """Autobalance modules ``name`` imports (anywhere in its source)."""
    package = name if is_pkg else name.rpartition(".")[0]
    found = set()

    def add(target):
        if target == root:
            raise AssertionError(f"{name} imports the facade {root} itself; import the module")
        found.add(target)

    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name == root or a.name.startswith(root + "."):
                    add(a.name if a.name in mods else _known_prefix(a.name, mods))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - (node.level - 1)]
                if not base:
                    raise AssertionError(f"{name}: relative import beyond the top package")
                base = ".".join(base + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            if base != root and not base.startswith(root + "."):
                continue
            for a in node.names:
                sub = f"{base}.{a.name}"
                if sub in mods:
                    add(sub)
                elif base == root:
                    if a.name == "__version__":
                        continue                     # a constant of the root, always loaded
                    if a.name not in reexports:
                        raise AssertionError(f"{name}: from {root} import {a.name}: not re-exported")
                    add(reexports[a.name])
                else:
                    add(_known_prefix(base, mods))
    found.discard(name)
    return found


def _known_prefix(dotted: str, mods: dict) -> str:
    parts = dotted.split(".")
    while parts and ".".join(parts) not in mods:
        parts.pop()
    assert parts, dotted
    return ".".join(parts)


def _ancestors(mod: str, root: str) -> list:
    """Packages whose __init__ importing ``mod`` runs (the root excluded: always loaded)."""
    parts = mod.split(".")
    return [".".join(parts[:i]) for i in range(2, len(parts))]


@functools.lru_cache(maxsize=None)
def _direct_graph(src: Path, root: str) -> dict:
    mods = module_files(src, root)
    reexports = _root_reexports(mods, root)
    return {name: frozenset(_imports(name, path, is_pkg, mods, root, reexports) - {name})
            for name, (path, is_pkg) in mods.items() if name != root}


def import_graph(src: Path = SRC, root: str = ROOT, implied: bool = False) -> dict:
    """module -> set of modules it imports (the root facade's own imports left out); with
    ``implied`` also the packages whose __init__ those imports run (for the cycles)."""
    graph = {}
    for name, direct in _direct_graph(src, root).items():
        targets = set(direct)
        if implied:
            targets |= {a for t in direct for a in _ancestors(t, root)}
        graph[name] = targets - {name}
    return graph


def _short(mod: str, root: str = ROOT) -> str:
    return mod.removeprefix(root + ".")


def unit(mod: str, root: str = ROOT) -> str:
    """Top-level module or package: autobalance.papers.p004.tsr -> papers."""
    return _short(mod, root).split(".")[0]


def package(mod: str, mods: dict, root: str = ROOT) -> str:
    """The (sub)package a module belongs to; a top-level module file is its own package."""
    if mods[mod][1] or mod.count(".") == 1:
        return _short(mod, root)
    return _short(mod.rpartition(".")[0], root)


def strongly_connected(nodes, edges) -> list:
    """Tarjan's algorithm: the components of more than one node (sorted member lists)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return sorted(out)


def cycles(graph: dict, mods: dict, root: str = ROOT) -> set:
    """"cycle: a, b" for every cycle between top-level units or between (sub)packages."""
    found = set()
    for key in (lambda m: unit(m, root), lambda m: package(m, mods, root)):
        edges = defaultdict(set)
        for m, targets in graph.items():
            for t in targets:
                if key(m) != key(t):
                    edges[key(m)].add(key(t))
        nodes = {key(m) for m in graph} | {key(t) for ts in graph.values() for t in ts}
        found |= {"cycle: " + ", ".join(c) for c in strongly_connected(nodes, edges)}
    return found


def module_cycles(src: Path = SRC, root: str = ROOT) -> set:
    """"module cycle: a, b" for every cycle between modules (imports inside functions
    included), a package's __init__ left out (it imports its modules to re-export them)."""
    mods = module_files(src, root)
    pkgs = {m for m, (_, is_pkg) in mods.items() if is_pkg}
    edges = {m: {t for t in ts if t not in pkgs} for m, ts in import_graph(src, root).items()
             if m not in pkgs}
    return {"module cycle: " + ", ".join(_short(x, root) for x in c)
            for c in strongly_connected(set(edges), edges)}


def layer_of(layers) -> dict:
    return {u: i for i, group in enumerate(layers) for u in group}


def upward(graph: dict, layers, root: str = ROOT) -> set:
    """"a.b -> c.d" for every import of a higher layer's module."""
    level = layer_of(layers)
    missing = sorted({unit(m, root) for m in graph} - set(level))
    assert not missing, f"no layer for {missing}: add them to LAYERS in tests/test_architecture.py"
    return {f"{_short(m, root)} -> {_short(t, root)}" for m, ts in graph.items() for t in ts
            if level[unit(t, root)] > level[unit(m, root)]}


def violations(src: Path = SRC, root: str = ROOT, layers=LAYERS) -> set:
    return (upward(import_graph(src, root), layers, root)
            | cycles(import_graph(src, root, implied=True), module_files(src, root), root))


# -- the checks ----------------------------------------------------------------------------------
def test_layer_table_names_each_unit_once():
    names = [u for group in LAYERS for u in group]
    assert len(names) == len(set(names))


def test_no_new_upward_imports_or_cycles():
    new = sorted(violations() - KNOWN_VIOLATIONS)
    assert not new, ("imports against the layers (see this file's docstring) or package cycles:\n  "
                     + "\n  ".join(new))


def test_known_violations_still_occur():
    """A fixed violation must leave KNOWN_VIOLATIONS (the list only shrinks)."""
    gone = sorted(KNOWN_VIOLATIONS - violations())
    assert not gone, "fixed, remove from KNOWN_VIOLATIONS:\n  " + "\n  ".join(gone)


def test_graph_sees_the_imports_it_should():
    """Spot checks on the real tree: a function-level relative import, an absolute-style
    module import, a package-level import and an implied __init__."""
    g = import_graph(implied=True)
    assert "autobalance.simulate" in g["autobalance.studies.equilibria"]        # inside a function
    assert "autobalance.papers.p004.targets" in g["autobalance.report.registry"]
    assert "autobalance.papers.p004" in g["autobalance.report.registry"]        # its __init__ runs
    assert "autobalance.papers.p004" not in import_graph()["autobalance.report.registry"]
    assert "autobalance.models" in g["autobalance.config.load"]
    assert "autobalance.models._validate" in g["autobalance.physics.iso1940"]


# -- the checker can fail ------------------------------------------------------------------------
def _tree(tmp_path, files: dict) -> Path:
    for rel, text in files.items():
        p = tmp_path / "pkg" / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return tmp_path


def test_no_import_cycle_between_modules():
    found = sorted(module_cycles())
    assert not found, "break these cycles (a shared helper in a module of its own):\n  " + \
        "\n  ".join(found)


def test_module_cycle_check_finds_a_cycle_inside_a_package(tmp_path):
    src = _tree(tmp_path, {
        "__init__.py": "from .sim.run import go\n",
        "sim/__init__.py": "from .run import go\nfrom .hybrid import mix\n",
        "sim/run.py": "def go():\n    from .hybrid import mix\n",       # inside a function
        "sim/hybrid.py": "from .run import go\ndef mix():\n    pass\n",
        "sim/pack.py": "from . import run\n",                       # via the package: no cycle
    })
    assert module_cycles(src, "pkg") == {"module cycle: sim.hybrid, sim.run"}


def test_checker_finds_upward_imports_and_cycles(tmp_path):
    src = _tree(tmp_path, {
        "__init__.py": "__version__ = '1'\nfrom .low import f\n",
        "low/__init__.py": "",
        "low/a.py": "from .. import __version__\n"
                    "def g():\n    from ..high.b import h\n",   # upward, inside a function
        "high/__init__.py": "",
        "high/b.py": "import pkg.low.a\nfrom pkg import f\n",     # downward; f re-exported by root
        "side/__init__.py": "from pkg.other import x\n",
        "other.py": "from .side import y\n",
        "top.py": "from .low import a\n",
    })
    layers = [("low",), ("high", "side", "other"), ("top",)]
    g = import_graph(src, "pkg", implied=True)
    assert g["pkg.low.a"] == {"pkg.high.b", "pkg.high"}
    assert g["pkg.high.b"] == {"pkg.low.a", "pkg.low"}             # f: re-exported from .low
    assert g["pkg.top"] == {"pkg.low.a", "pkg.low"}
    assert import_graph(src, "pkg")["pkg.top"] == {"pkg.low.a"}
    assert violations(src, "pkg", layers) == {"low.a -> high.b", "cycle: high, low",
                                              "cycle: other, side"}
    with pytest.raises(AssertionError, match="no layer for"):
        violations(src, "pkg", [("low",), ("high", "side")])


# -- size: no module over 600 lines, no function body over 100 --------------------------------
#: Functions allowed over the function cap (never a module over its cap): the compiled
#: integrator loop, one numba function kept whole because a call between numba functions passes
#: every array as its exploded struct (core/jit.py) and the loop's locals are its state
#: (core/integrate.py says why). The right-hand side is split into inlined parts.
SIZE_EXCEPTIONS = {"autobalance/core/integrate.py": ("_integrate",)}
MAX_MODULE_LINES, MAX_FUNCTION_LINES = 600, 100


def _function_sizes(tree):
    for n in ast.walk(tree):
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)):
            first = n.body[0]
            doc = (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
                   and isinstance(first.value.value, str))
            start = first.end_lineno + 1 if doc and len(n.body) > 1 else first.lineno
            yield n.name, n.end_lineno - start + 1


def test_no_module_over_600_lines_and_no_function_body_over_100():
    too_long = []
    for path in sorted((SRC / ROOT).rglob("*.py")):
        rel = path.relative_to(SRC).as_posix()
        text = path.read_text()
        allowed = SIZE_EXCEPTIONS.get(rel, ())
        if text.count("\n") > MAX_MODULE_LINES:
            too_long.append(f"{rel}: {text.count(chr(10))} lines")
        for name, n in _function_sizes(ast.parse(text)):
            if n > MAX_FUNCTION_LINES and name not in allowed:
                too_long.append(f"{rel}::{name}: {n} lines without its docstring")
    assert not too_long, "split these (docs/architecture.md):\n" + "\n".join(too_long)


# -- type hints: every public parameter is annotated -------------------------------------------
def public_parameters(tree) -> list:
    """(function, parameter, annotated) for every parameter but self/cls of every public function
    and method (names not starting with ``_``, ``__init__`` included) of public classes."""
    out = []

    def visit(body, owner=""):
        for n in body:
            if isinstance(n, ast.ClassDef) and not n.name.startswith("_"):
                visit(n.body, f"{owner}{n.name}.")
            elif isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and (
                    not n.name.startswith("_") or n.name == "__init__"):
                a = n.args
                for p in (a.posonlyargs + a.args + a.kwonlyargs
                          + [x for x in (a.vararg, a.kwarg) if x is not None]):
                    if p.arg not in ("self", "cls"):
                        out.append((f"{owner}{n.name}", p.arg, p.annotation is not None))

    visit(tree.body)
    return out


def test_every_public_parameter_is_annotated():
    """Public modules (no path part starting with ``_`` but ``__init__``/``__main__``)."""
    missing = []
    for path in sorted((SRC / ROOT).rglob("*.py")):
        rel = path.relative_to(SRC)
        if any(p.startswith("_") and p not in ("__init__.py", "__main__.py") for p in rel.parts):
            continue
        missing += [f"{rel.as_posix()}: {f}({p})" for f, p, ok in
                    public_parameters(ast.parse(path.read_text())) if not ok]
    assert not missing, f"{len(missing)} unannotated public parameters:\n" + "\n".join(missing[:40])


def test_annotation_check_can_fail():
    tree = ast.parse("def f(a, b: int, *c, d=1, **e): ...\nclass C:\n    def g(self, x): ...\n"
                     "    def _h(self, y): ...\ndef _p(z): ...")
    assert [(f, p) for f, p, ok in public_parameters(tree) if not ok] == \
        [("f", "a"), ("f", "d"), ("f", "c"), ("f", "e"), ("C.g", "x")]
