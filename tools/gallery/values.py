"""Values in sentences: `43.6<!--=name-->`, defined once in the same text by
`<!-- value name: out/lessonNN/table.md row="…" column="…" [format=F] -->` or by arithmetic over
other values (CONTRIBUTING.md, "Numbers in sentences come from the run too")."""

import ast
import math
import re
import shlex
from dataclasses import dataclass
from graphlib import CycleError, TopologicalSorter
from pathlib import Path

from common.markdown import outside_fences

from .tables import FigureError, Spec, parse_spec, read_table, select

VALUE_MARKER = re.compile(r"<!--\s*=(?P<name>[A-Za-z_]\w*)\s*-->")
VALUE_DEF = re.compile(r"^\s*<!--\s*value\s+(?P<name>[A-Za-z_]\w*)\s*:\s*(?P<spec>.*?)\s*-->\s*$")
# What a marker vouches for: the `code span`, or the run of characters that are not spaces, opening
# brackets or quotes, right before it ("(43.6" vouches for 43.6).
VALUE_TEXT = re.compile(r"(?:`[^`]+`|[^\s(\[{\"'“‘`]+)$")
VALUE_FORMATS = "cell, fixed:N, sig:N, percent:N, int, thousands, rows"
NAME = re.compile(r"[A-Za-z_]\w*")


@dataclass
class ValueDef:
    name: str
    line: int                      # 0-based
    path: str | None = None        # a cell: its table (out/… or a source-tree .md) and spec
    spec: Spec | None = None
    column: str | None = None
    expression: str | None = None  # or arithmetic over other values of the text
    format: str = "cell"


def parse_value_def(name: str, line: int, text: str) -> ValueDef:
    fmt = re.search(r"(?:^|\s)format=(\S+)\s*$", text)
    body = text[:fmt.start()].strip() if fmt else text.strip()
    value = ValueDef(name, line, format=fmt.group(1) if fmt else "cell")
    if not re.fullmatch(r"cell|int|thousands|rows|(?:fixed|sig|percent):\d{1,2}", value.format):
        raise FigureError(f"value {name}: unknown format '{value.format}' (one of {VALUE_FORMATS})")
    first = body.split(None, 1)[0] if body else ""
    if first.startswith("out/") or re.fullmatch(r"[\w\-]+(?:/[\w\-.]+)*\.md", first):
        return _cell_def(value, body)
    if value.format == "cell":
        raise FigureError(f"value {name}: arithmetic '{body}' needs a format= ({VALUE_FORMATS})")
    value.expression = body
    _evaluate(body, {n: 1.0 + 0.37 * i for i, n in enumerate(NAME.findall(body))}, name)  # its form only
    return value


def _cell_def(value: ValueDef, body: str) -> ValueDef:
    try:
        parts = shlex.split(body)
    except ValueError as e:
        raise FigureError(f"value {value.name}: cannot read '{body}': {e}") from None
    if ".." in parts[0]:
        raise FigureError(f"value {value.name}: '{parts[0]}' must name a table under out/ or in the source tree")
    columns = [p[len("column="):] for p in parts[1:] if p.startswith("column=")]
    if value.format == "rows" and columns:
        raise FigureError(f"value {value.name}: format=rows counts rows; it names no column=")
    if value.format != "rows" and len(columns) != 1:
        raise FigureError(f"value {value.name}: name exactly one column= (the cell's column)")
    value.path, value.column = parts[0], columns[0] if columns else None
    # parse_spec checks the options; a source-tree table is read from SOURCE, not OUT.
    options = [p for p in parts[1:] if not p.startswith("column=")]
    spec_path = parts[0] if parts[0].startswith("out/") else "out/" + parts[0]
    value.spec = parse_spec(" ".join(shlex.quote(p) for p in [spec_path] + options))
    value.spec.path = parts[0]
    if value.spec.columns is not None:
        raise FigureError(f"value {value.name}: columns= picks a figure's columns; a value names one column=")
    return value


def format_value(number_text: str, fmt: str, name: str) -> str:
    if fmt == "cell":
        return number_text
    try:
        x = float(number_text)
    except ValueError:
        raise FigureError(f"value {name}: '{number_text}' is not a number (format={fmt})") from None
    if not math.isfinite(x):
        raise FigureError(f"value {name}: {number_text} cannot be written with format={fmt}")
    kind, _, digits = fmt.partition(":")
    if kind in ("int", "thousands"):
        return f"{round(x):,}" if kind == "thousands" else str(round(x))
    return f"{100 * x if kind == 'percent' else x:.{int(digits)}{'g' if kind == 'sig' else 'f'}}"


_OPERATORS = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b,
              ast.Div: lambda a, b: a / b, ast.Pow: lambda a, b: abs(a) ** b}  # a rate: (e4 / e10) ** (1 / 6)


def _evaluate(expression: str, known: dict[str, float], name: str) -> float:
    try:
        tree = ast.parse(expression, mode="eval")
    except SyntaxError:
        raise FigureError(f"value {name}: cannot read the arithmetic '{expression}'") from None

    def walk(node: ast.AST) -> float:
        if isinstance(node, ast.BinOp) and type(node.op) in _OPERATORS:
            left, right = walk(node.left), walk(node.right)
            if isinstance(node.op, ast.Div) and right == 0:
                raise FigureError(f"value {name}: '{expression}' divides by zero")
            return _OPERATORS[type(node.op)](left, right)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return -walk(node.operand)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return float(node.value)
        if isinstance(node, ast.Name):
            if node.id not in known:
                raise FigureError(f"value {name}: '{node.id}' is not a value defined in this file")
            return known[node.id]
        raise FigureError(f"value {name}: '{expression}' may use only + - * / **, numbers and other values")
    return walk(tree.body)


def _cell(out: Path, source: Path, d: ValueDef) -> tuple[str, float | None, bool]:
    """(text, number or None, depends on a timing) of a value defined by a table's cell or rows."""
    where = out / Path(d.path).relative_to("out") if d.path.startswith("out/") else source / d.path
    table = select(read_table(where, d.spec.table), d.spec, d.path)
    if d.format == "rows":
        return str(len(table.rows)), float(len(table.rows)), False
    if d.column not in table.header:
        raise FigureError(f"value {d.name}: {d.path} has no column '{d.column}' (it has: {', '.join(table.header)})")
    if len(table.rows) != 1:
        raise FigureError(f"value {d.name}: row=/where= pick {len(table.rows)} rows of {d.path}; a value is one cell")
    c = table.header.index(d.column)
    cell = table.rows[0][c] if c < len(table.rows[0]) else ""
    # Formatted, or combined with other values, a cell counts with its full digits; as printed, it is the .md's text.
    full = _full_digits(where, d.spec.table, table.rows[0], c) or cell
    try:
        number = float(full)
    except ValueError:
        number = None
    return format_value(cell if d.format == "cell" else full, d.format, d.name), number, table.timing_mask()[0][c]


def _full_digits(where: Path, number: int, row: list[str], column: int) -> str | None:
    """The cell's full digits from the `.csv` beside a program's `.md` table (the same header and rows), so that
    a value formatted here is not rounded twice (0.25492, shown 0.255, is 25%, not 26%); None without one."""
    csv_path = where.with_suffix(".csv")
    if where.suffix != ".md" or not csv_path.is_file():
        return None
    shown, full = read_table(where, number), read_table(csv_path, 1)
    if shown.header != full.header or len(shown.rows) != len(full.rows) or row not in shown.rows:
        return None
    return full.rows[shown.rows.index(row)][column]


def resolve_values(out: Path, defs: dict[str, ValueDef], source: Path) -> dict[str, tuple[str, bool]]:
    """Each value's text as the programs' tables give it, and whether it depends on a timing; an arithmetic
    value is worked out after the values it names."""
    needs = {d.name: set(NAME.findall(d.expression)) if d.expression else set() for d in defs.values()}
    for name, names in needs.items():
        if names - set(defs):
            raise FigureError(f"value {name}: {', '.join(sorted(names - set(defs)))} is not defined in this file")
    try:
        order = list(TopologicalSorter(needs).static_order())
    except CycleError as e:
        raise FigureError("values defined in terms of each other: " + ", ".join(e.args[1][:-1])) from None
    resolved: dict[str, tuple[str, bool]] = {}
    numbers: dict[str, float] = {}
    for d in (defs[name] for name in order):
        if d.path is not None:
            text, number, timing = _cell(out, source, d)
            if number is not None:
                numbers[d.name] = number
            resolved[d.name] = (text, timing)
        elif needs[d.name] - set(numbers):
            raise FigureError(f"value {d.name}: {', '.join(sorted(needs[d.name] - set(numbers)))} is not a number")
        else:
            numbers[d.name] = _evaluate(d.expression, numbers, d.name)
            resolved[d.name] = (format_value(repr(numbers[d.name]), d.format, d.name),
                                any(resolved[n][1] for n in needs[d.name]))
    return resolved


@dataclass
class ValueUse:
    name: str
    line: int   # 0-based
    start: int  # span of the text it vouches for
    end: int


def find_values(path: Path, lines: list[str], inside: set[int]) -> tuple[dict[str, ValueDef], list[ValueUse]]:
    """The value definitions and markers of a text, outside code fences and figures (`inside`)."""
    defs: dict[str, ValueDef] = {}
    uses: list[ValueUse] = []
    for i, line in outside_fences(lines):
        if i in inside:
            continue
        if m := VALUE_DEF.match(line):
            if m["name"] in defs:
                raise FigureError(f"{path}:{i + 1}: value {m['name']} is defined twice (first on line "
                                  f"{defs[m['name']].line + 1})")
            try:
                defs[m["name"]] = parse_value_def(m["name"], i, m["spec"])
            except FigureError as e:
                raise FigureError(f"{path}:{i + 1}: {e}") from None
            continue
        for u in VALUE_MARKER.finditer(line):
            if not (text := VALUE_TEXT.search(line[:u.start()])):
                raise FigureError(f"{path}:{i + 1}: the marker <!--={u['name']}--> follows no value: write it "
                                  "right after the number, without a space (43.6<!--=name-->)")
            uses.append(ValueUse(u["name"], i, text.start(), text.end()))
    for u in uses:
        if u.name not in defs:
            raise FigureError(f"{path}:{u.line + 1}: value {u.name} is used but not defined: add a line "
                              f"<!-- value {u.name}: out/lessonNN/table.md row=\"…\" column=\"…\" -->")
    used = {u.name for u in uses} | {n for d in defs.values() if d.expression for n in NAME.findall(d.expression)}
    for d in defs.values():
        if d.name not in used:
            raise FigureError(f"{path}:{d.line + 1}: value {d.name} is defined but no sentence uses it")
    return defs, uses


def process_values(run, path: Path, lines: list[str], inside: set[int]) -> int:
    """Checks (run.mode 'check') or rewrites in `lines` the values of one text, as run.may_rewrite says (run: a
    gallery.figures.Run); returns how many it saw."""
    try:
        defs, uses = find_values(path, lines, inside)
        if not defs:
            return 0
        resolved = resolve_values(run.out, defs, run.source)
    except FigureError as e:
        run.problems.append(str(e) if str(e).startswith(str(path)) else f"{path}: {e}")
        return 0
    for u in reversed(uses):  # right to left: earlier spans on a line stay valid
        line = lines[u.line]
        written = line[u.start:u.end]
        shown = written[1:-1] if written.startswith("`") and written.endswith("`") and len(written) > 1 else written
        value, timing = resolved[u.name]
        if shown == value:
            continue
        difference = f"{path}:{u.line + 1}: value {u.name}: the text says {shown}, the program wrote {value}"
        if run.may_rewrite([] if timing else [difference]):
            lines[u.line] = line[:u.start] + (f"`{value}`" if written.startswith("`") else value) + line[u.end:]
    return len(uses)
