"""Counts of the package's structure, for a maintainer: functions longer than 60 lines, functions
with more than 10 parameters, ``liquid is None`` branches, modules over 600 lines and import
cycles between modules (imports inside functions included; a package's ``__init__`` left
out). ``python benchmarks/structure.py [--list]`` (``--list`` names each).

Function length is counted as the architecture test counts it (tests/test_architecture.py:
the body without its docstring); parameters are every positional, keyword and star parameter
but ``self`` / ``cls``.
"""
from __future__ import annotations

import argparse
import ast
import re
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "autobalance"
LONG_FUNCTION, MANY_PARAMETERS, LONG_MODULE = 60, 10, 600
LIQUID_NONE = re.compile(r"\bliquid\s+is\s+(not\s+)?None\b")


def _body_lines(n: ast.FunctionDef) -> int:
    first = n.body[0]
    doc = (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
           and isinstance(first.value.value, str))
    start = first.end_lineno + 1 if doc and len(n.body) > 1 else first.lineno
    return n.end_lineno - start + 1


def _parameters(n: ast.FunctionDef) -> int:
    a = n.args
    names = [p.arg for p in (*a.posonlyargs, *a.args, *a.kwonlyargs)]
    names += [p.arg for p in (a.vararg, a.kwarg) if p is not None]
    return len([x for x in names if x not in ("self", "cls")])


def _module(path: Path, src: Path = SRC) -> str:
    rel = path.relative_to(src.parent).with_suffix("")
    parts = list(rel.parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(tree: ast.Module, mod: str, is_pkg: bool, known: set) -> set:
    """The package's modules that ``mod`` imports anywhere (inside functions too)."""
    out = set()
    pkg = mod if is_pkg else mod.rpartition(".")[0]
    for n in ast.walk(tree):
        if isinstance(n, ast.ImportFrom):
            base = n.module or ""
            if n.level:
                up = pkg.split(".")[: len(pkg.split(".")) - (n.level - 1)]
                base = ".".join(up + ([base] if base else []))
            for a in n.names:
                full = f"{base}.{a.name}"
                out.add(full if full in known else base)
        elif isinstance(n, ast.Import):
            out |= {a.name for a in n.names}
    return {m for m in out if m in known and m != mod}


def _cycles(graph: dict) -> list:
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
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
                comps.append(sorted(comp))

    sys.setrecursionlimit(10_000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(comps)


def counts(src: Path = SRC) -> dict:
    """Every count of this module's docstring, with the places counted."""
    files = sorted(src.rglob("*.py"))
    known = {_module(p, src) for p in files}
    long_f, many_p, liquid, long_m, graph = [], [], [], [], {}
    for p in files:
        text = p.read_text()
        tree = ast.parse(text)
        rel = p.relative_to(src.parent).as_posix()
        mod = _module(p, src)
        graph[mod] = _imports(tree, mod, p.name == "__init__.py", known)
        if text.count("\n") > LONG_MODULE:
            long_m.append(f"{rel}: {text.count(chr(10))} lines")
        for n in ast.walk(tree):
            if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if _body_lines(n) > LONG_FUNCTION:
                    long_f.append(f"{rel}::{n.name}: {_body_lines(n)} lines")
                if _parameters(n) > MANY_PARAMETERS:
                    many_p.append(f"{rel}::{n.name}: {_parameters(n)} parameters")
        for i, line in enumerate(text.splitlines(), 1):
            code = line.split("#", 1)[0]
            liquid += [f"{rel}:{i}"] * len(LIQUID_NONE.findall(code))
    # cycles between modules: a package's __init__ (which imports its modules to re-export
    # them) is left out of the graph
    pkgs = {_module(p, src) for p in files if p.name == "__init__.py"}
    graph = {m: {d for d in deps if d not in pkgs} for m, deps in graph.items() if m not in pkgs}
    return {"functions_over_60_lines": long_f, "functions_over_10_parameters": many_p,
            "liquid_is_none_branches": liquid, "modules_over_600_lines": long_m,
            "module_import_cycles": [", ".join(c) for c in _cycles(graph)]}


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--list", action="store_true", help="name every place counted")
    args = ap.parse_args(argv)
    for name, places in counts().items():
        print(f"{name:<32} {len(places)}")
        if args.list:
            for p in places:
                print(f"    {p}")


if __name__ == "__main__":
    main()
