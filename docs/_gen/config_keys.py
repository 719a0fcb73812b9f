"""The page of every configuration key, from :mod:`autobalance.config.schema` and the models.

For each key: its section, name, unit (the schema's kind, :data:`UNIT_LABEL`), default (from
``dataclasses.fields`` or the profile constructor's signature), whether it is required, the
choices (schema) and bounds (the models' checks, read from their source) and its meaning (the
numpydoc ``Parameters`` entry of the model dataclass or constructor).
"""
from __future__ import annotations

import ast
import dataclasses
import inspect
import math
import re
from pathlib import Path

from autobalance.config import schema
from autobalance.config.units import KINDS, UNIT_LABEL
from autobalance.models import profile as profile_models

#: Top-level keys that are not sections, and what they hold.
TOP_KEYS = {"name": "the machine's name (default: the file's stem); a string",
            "description": "one line saying what the machine is; a string"}

#: The section each model's checks name in their messages (MotorDrive says ``drive.``).
_CHECK_PREFIX = {"drive": "profile"}


# -- numpydoc ----------------------------------------------------------------------------------
def parameters(doc: str | None) -> dict[str, str]:
    """{name: meaning} of a numpydoc ``Parameters`` section; ``kx, ky : float`` gives both."""
    if not doc:
        return {}
    lines = inspect.cleandoc(doc).splitlines() + [""]

    def underline(i: int) -> bool:
        return i < len(lines) and bool(lines[i].strip()) and set(lines[i].strip()) == {"-"}

    try:
        start = next(i for i in range(len(lines) - 1)
                     if lines[i].strip() == "Parameters" and underline(i + 1))
    except StopIteration:
        return {}
    out: dict[str, str] = {}
    names: list[str] = []
    body: list[str] = []
    for i in range(start + 2, len(lines)):
        ln = lines[i]
        if ln and not ln.startswith(" "):
            for n in names:
                out[n] = " ".join(body)
            if underline(i + 1):                   # the next section's title
                return out
            names = [n.strip() for n in ln.split(" : ")[0].split(",") if n.strip()]
            body = []
        elif ln.strip():
            body.append(ln.strip())
    for n in names:
        out[n] = " ".join(body)
    return out


# -- bounds from the models' checks ------------------------------------------------------------
def _literal(node):
    try:
        return ast.literal_eval(node)
    except Exception:   # noqa: BLE001 - not a literal: no bound shown
        return None


def _key(node) -> str | None:
    """The dotted key a check names: a string, or the leading text of an f-string."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        text = node.value
    elif isinstance(node, ast.JoinedStr) and node.values and isinstance(node.values[0], ast.Constant):
        text = node.values[0].value
    else:
        return None
    m = re.match(r"([a-z_]+)\.([a-z_]+)(?![.\w])", text)
    if not m:
        return None
    return f"{_CHECK_PREFIX.get(m.group(1), m.group(1))}.{m.group(2)}"


def bounds() -> dict[str, str]:
    """{"section.key": "> 0" | ">= 0" | "in [lo, hi]" | ...} from the calls of the checks in
    ``autobalance/models/*.py`` (``positive``, ``nonneg``, ``in_range``, ``count``)."""
    out: dict[str, str] = {}
    root = Path(profile_models.__file__).parent
    for path in sorted(root.glob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        checks = {"positive": "> 0", "nonneg": ">= 0"}
        for fn in tree.body:               # a module's own check: "... within [lo, hi] ..."
            if isinstance(fn, ast.FunctionDef) and (m := re.search(
                    r"within \[([^\]]+)\]", ast.get_docstring(fn) or "")):
                checks[fn.name] = f"in [{m.group(1)}]"
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.args):
                continue
            key = _key(node.args[0])
            if key is None:
                continue
            fn, args = node.func.id, node.args
            text = None
            if fn == "positive":
                text = "> 0"
            elif fn == "nonneg":
                text = ">= 0"
            elif fn == "in_range" and len(args) >= 4:
                lo, hi = _literal(args[2]), _literal(args[3])
                if lo is not None and hi is not None:
                    text = f"in [{lo:g}, {hi:g}]"
            elif fn == "per_ball" and len(args) >= 4 and isinstance(args[3], ast.Name):
                text = checks.get(args[3].id)
            elif fn == "count":
                lo = _literal(args[2]) if len(args) >= 3 else 0
                if lo is not None:
                    text = f"an integer >= {lo}"
            if text and key not in out:
                out[key] = text
    return out


# -- one row -----------------------------------------------------------------------------------
def unit_of(spec: schema.F) -> str:
    if spec.kind == "int":
        return "integer"
    if spec.kind == "bool":
        return "true/false"
    if spec.kind == "text":
        return "text"
    if spec.shape == "pairs":
        return "pairs `[" + ", ".join(_unit(k) for k in spec.pair_kinds) + "]`"
    return f"`{_unit(spec.kind)}`"


def _unit(kind: str) -> str:
    """The SI unit of a kind as a file writes it (``kg*m^2``; ``-`` if dimensionless)."""
    return KINDS[kind][0] or UNIT_LABEL[kind]


def shape_of(spec: schema.F) -> str:
    return {"per_ball": "one value, or a list with one per ball",
            "per_chamber": "one value, or a list with one per chamber from the axis outwards",
            "list": "a list", "pairs": "a list of [time, unbalance] pairs"}.get(spec.shape, "")


def _number(v: float) -> str:
    return f"{v:.6g}"


def default_text(spec: schema.F, value) -> str:
    """A default as written in a file: SI with its unit (speeds also in Hz)."""
    if value is dataclasses.MISSING or value is inspect.Parameter.empty:
        return ""
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, (tuple, list)):
        return "[]" if not value else "[" + ", ".join(map(str, value)) + "]"
    if isinstance(value, int) and spec.kind == "int":
        return str(value)
    if isinstance(value, (int, float)):
        unit = _unit(spec.kind) if spec.kind in KINDS else ""
        text = _number(float(value)) + ("" if unit in ("", "-") else f" {unit}")
        if spec.kind == "speed" and abs(value) >= 1:
            text += f" ({_number(value / (2 * math.pi))} Hz)"
        if spec.kind == "angle" and value:
            text += f" ({_number(math.degrees(value))} deg)"
        return text
    return str(value)


def allowed_text(section: str, key: str, spec: schema.F, limits: dict[str, str]) -> str:
    parts = []
    if spec.choices:
        parts.append("one of " + ", ".join(f"`{c}`" for c in spec.choices))
    if f"{section}.{key}" in limits:
        parts.append(limits[f"{section}.{key}"])
    return "; ".join(parts)


_ROLE = re.compile(r":(?:data|func|class|meth|attr|mod):`~?([^`]+)`")


def _cell(text: str) -> str:
    """One table cell: one line, Sphinx roles as code, pipes escaped, and outside code the
    characters markdown would read as emphasis or HTML (``kg*m``, ``<``) escaped."""
    text = _ROLE.sub(r"`\1`", " ".join(str(text).split())).replace("``", "`")
    parts = text.split("`")
    for i in range(0, len(parts), 2):               # outside code spans
        parts[i] = (parts[i].replace("*", "\\*").replace("_", "\\_").replace("<", "&lt;")
                    .replace(">", "&gt;").replace("|", "\\|"))
    return "`".join(parts)


def table(section: str, specs: dict[str, schema.F], defaults: dict, meanings: dict[str, str],
          limits: dict[str, str]) -> list[str]:
    rows = ["| key | unit | default | required | allowed | meaning |",
            "|---|---|---|---|---|---|"]
    for key, spec in specs.items():
        meaning = meanings.get(key, "")
        shape = shape_of(spec)
        if shape:
            meaning = f"{meaning} ({shape})" if meaning else shape
        required = "**required**" if spec.required else ""
        default = "" if spec.required else default_text(spec, defaults.get(key, dataclasses.MISSING))
        default = f"`{default}`" if default else ""
        rows.append(f"| `{section}.{key}` | {_cell(unit_of(spec))} | {_cell(default)} | "
                    f"{required} | {_cell(allowed_text(section, key, spec, limits))} | "
                    f"{_cell(meaning)} |")
    return rows


def _field_defaults(cls) -> dict:
    out = {}
    for f in dataclasses.fields(cls):
        if f.default is not dataclasses.MISSING:
            out[f.name] = f.default
        elif f.default_factory is not dataclasses.MISSING:
            out[f.name] = f.default_factory()
    return out


def _signature_defaults(fn) -> dict:
    return {n: p.default for n, p in inspect.signature(fn).parameters.items()
            if p.default is not inspect.Parameter.empty}


# -- the page ----------------------------------------------------------------------------------
def page() -> str:
    """The markdown of the configuration reference."""
    limits = bounds()
    sections = [s for s in schema.TOP_LEVEL if s in schema.SECTIONS or s == "profile"]
    out = [
        "# Configuration keys",
        "",
        "Every key of a machine's TOML file, generated from the code "
        "(`autobalance.config.schema` and the model dataclasses in `autobalance.models`) when "
        "this site is built. A value is a bare number, meaning SI, or a string with its unit "
        "(`\"20 N/mm\"`, `\"0.025 kg*m\"`, `\"1000 rpm\"`, `\"61 deg\"`); a pure inverse time "
        "(`Hz`, `1/s`, `min^-1`) counts revolutions. The unit column gives the SI unit a bare "
        "number is read in. `--set section.key=value` changes one key for one run, with the "
        "same units; a key left out takes the default below.",
        "",
        "Sections (`" + "`, `".join(schema.TOP_LEVEL) + "` at the top level): "
        + ", ".join(f"`[{s}]`" for s in sections) + "; required: "
        + ", ".join(f"`[{s}]`" for s in schema.REQUIRED_SECTIONS) + ". A machine without "
        "`[balancer]` has no balls; with `[liquid]` it is a liquid (Leblanc) balancer, with both "
        "it has balls beside a liquid.",
        "",
        "| key | meaning |",
        "|---|---|",
    ]
    out += [f"| `{k}` | {v} |" for k, v in TOP_KEYS.items()]
    out.append("")
    for section in sections:
        if section == "profile":
            out += profile_section(limits)
            continue
        cls = schema.SECTION_MODELS[section]
        summary = _cell(inspect.getdoc(cls).split("\n\n")[0])
        required = section in schema.REQUIRED_SECTIONS
        out += [f"## [{section}]", "",
                f"{summary} Model: `autobalance.models.{cls.__name__}`"
                + ("; the section is required." if required else "; the section is optional."),
                ""]
        out += table(section, schema.SECTIONS[section], _field_defaults(cls),
                     parameters(cls.__doc__), limits)
        out.append("")
    return "\n".join(out) + "\n"


def profile_section(limits: dict[str, str]) -> list[str]:
    kinds = schema.PROFILE_KINDS
    out = ["## [profile]", "",
           "The speed profile: `kind` (**required**, one of "
           + ", ".join(f"`{k}`" for k in kinds) + ") and the keys of that kind. "
           "`--profile KIND` switches the kind of a file's profile; keys the new kind does not "
           "take are dropped. Speeds are read as on drawings: `\"800 rpm\"`, `\"167 Hz\"`.",
           ""]
    for kind, specs in kinds.items():
        ctor = profile_models.PROFILE_KINDS[kind]
        doc = inspect.getdoc(ctor) or ""
        summary = _cell(doc.split("\n\n")[0])
        if inspect.isclass(ctor):
            defaults = _field_defaults(ctor)
            where = f"`autobalance.models.{ctor.__name__}`"
        else:
            defaults = _signature_defaults(ctor)
            where = f"`autobalance.models.{ctor.__qualname__}`"
        out += [f"### kind = \"{kind}\"", "", f"{summary} Built by {where}.", ""]
        out += table("profile", specs, defaults, parameters(doc), limits)
        out.append("")
    return out


__all__ = ["page", "parameters", "bounds"]
