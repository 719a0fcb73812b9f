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
sys.path.insert(0, str(SRC.parents[1] / "tests"))
from test_architecture import module_cycles  # noqa: E402  (one count of the cycles)
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


def counts(src: Path = SRC) -> dict:
    """Every count of this module's docstring, with the places counted."""
    files = sorted(src.rglob("*.py"))
    long_f, many_p, liquid, long_m = [], [], [], []
    for p in files:
        text = p.read_text()
        tree = ast.parse(text)
        rel = p.relative_to(src.parent).as_posix()
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
    # cycles between modules: the architecture test's own count (tests/test_architecture.py)
    cycles = sorted(c.removeprefix("module cycle: ") for c in module_cycles(src.parent))
    return {"functions_over_60_lines": long_f, "functions_over_10_parameters": many_p,
            "liquid_is_none_branches": liquid, "modules_over_600_lines": long_m,
            "module_import_cycles": cycles}


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
