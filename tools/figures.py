#!/usr/bin/env python3
"""Figures in lesson texts and decks come from the programs' own tables and images.

    tools/figures.py [--out out]                 refresh timings (what the main job runs)
    tools/figures.py --check [--out out]         fail when a text's values or kept images differ (CI)
    tools/figures.py --update [--out out]        rewrite every figure from the tables
    tools/figures.py --update-images [--out out] keep the lesson texts' images (below)

A figure is a block of Markdown between two comments:

    <!-- figure: out/lesson10/rotation.md -->
    ...the table, written by this tool...
    <!-- /figure -->

The opening comment names a table a lesson program writes (a path under
out/, a `.md` file holding a pipe table or a `.csv` file) and optionally
narrows it with shell-quoted options:

    columns="a,b,c"        keep these columns, in this order
    where="column=v1|v2"   keep the rows whose cell in that column is one of
                           the values (several where= options must all hold)
    row="col=v & col2=w"   keep the rows matching every condition; with several
                           row= options a row is kept when it matches any one
    table=N                the N-th pipe table of a Markdown file (default 1)

Cells are copied as the program printed them; the tool never rounds.

Timing cells. A cell is a timing when its column's header, or its row's
first cell, contains one of the words of TIMING_WORDS (split at anything
that is not a letter or digit: `ns_per_test`, `seconds to 1e-6`, `median ns
per test`, `time_slope_res_ge_64`, `ms per Jacobi sweep`). Timings depend on
the machine and its load; every other cell (errors, counts, iterations,
verdicts) must not. So:

* `--check` compares every non-timing cell of every figure with the table
  and exits 1, listing file, line, row, column and both values, when any
  differs, when a table has a different shape, when a figure names a
  missing table or column, or when a text quotes a timing by hand outside
  a figure (a number followed by ns, µs, ms or seconds, or by s in a
  phrase like "3.3 s on"), or cites "erratum N" without linking it to
  docs/errata.md;
* the default (refresh) rewrites the figures whose non-timing cells agree,
  which updates their timings and their label, and leaves the others for
  `--update` (listing them);
* `--update` rewrites every figure from its table (after a real change of a
  program's results, to be reviewed with `git diff`).

Images. A lesson text (lessons/NN_topic/README.md) shows its program's
images where a student reads it, before anything has run (the repository
browser, a fresh clone, the student edition): every image it links is kept
in the repository as lessons/NN_topic/figures/x.png, a byte copy of
out/lessonNN/x.png, and linked as `figures/x.png`. A timing plot -- its
gnuplot script (out/lessonNN/x.gp) has a title or axis label with a word of
TIMING_WORDS, or "Mrays"/"throughput" -- differs on every run: its kept copy
shows one run (the one --update-images copied), and the gallery's rendered
page of the text shows the latest run's drawing from out/ beside the
latest run's table.

* `--update-images` copies every linked image from OUT into figures/,
  relinks each image link of the lesson texts to figures/, and deletes kept
  images no text shows any more (add an image: link it as
  `../../out/lessonNN/x.png` and run this);
* `--check` also fails when a kept image drifts from what the program drew:
  sizes differ, or more than PIXEL_SHARE of the pixels differ by more than
  PIXEL_LEVELS levels in a channel (the PNGs are decoded, so a different
  encoder or a last-bit difference of a float does not count; a timing plot
  is compared by its size only), when an image is linked in out/, a linked
  image is missing, or a file of figures/ is shown by no text.

Values in sentences. A number in a sentence that restates a program's
result is followed by a marker, `43.6<!--=name-->`, and defined once in the
same text, on a line of its own:

    <!-- value name: out/lessonNN/table.md row="col=v" column="other col" [format=F] -->
    <!-- value ratio: name / other_name format=fixed:1 -->

A cell is picked like a figure's rows (row=, where=, table=) and one
column=; a table may also be a Markdown file of the source tree
(exercises/NN_topic/README.md), and format=rows counts the rows picked;
arithmetic (+ - * / ** and numbers) combines values of the same text.
format= writes the number: cell (as printed, the default for a cell),
fixed:N (N decimals), sig:N (N significant digits), percent:N (times 100,
N decimals), int, thousands (9,600), rows. The marker vouches for the text right
before it, without a space: a number, or a `code span`. `--check` fails when
that text differs from the value (unless the value depends on a timing),
when a marker has no definition or a definition no marker; the refresh
rewrites values that depend on a timing, `--update` every value.

Links. `--check` (and `--links`, which needs no OUT) fails when a link or
an image of a text (README.md, CONTRIBUTING.md, the lesson texts, the
exercises, docs/, slides/README.md) names a file missing from the source
tree, a file in out/ (absent from a fresh clone), or a heading the linked
text does not have (tools/gallery/text_links.py).

Screenshots of the lab. A kept image named lab_*.png is a screenshot of
`illum lab` (tools/lab/screenshots.py, the main job's step "lab"): it is
drawn into OUT/lab/, not OUT/lessonNN/, and kept and checked like the
others except that --check compares only its size (its status lines carry
timings, so its pixels differ from run to run).

The label under a figure with timings names the run: date, the machine's
cores, its load average at the start and end of that program's run and the
programs that ran beside it (the main job runs those that time one thread
side by side; a "mixed" one gets the whole machine for its timings on more
threads, and its label says so), as
the main job records them in OUT/run_log.json (the file's modification time
and "load not recorded" when the program was run by hand).
"""
from __future__ import annotations

import argparse
import ast
import csv
import io
import json
import math
import os
import re
import shlex
import struct
import sys
import time
import zlib
from dataclasses import dataclass, field
from pathlib import Path

from gallery.markdown_table import is_separator_line, split_table_row
from gallery.plots import PlotCheckError, check_plots
from gallery.text_links import check_text_links
from path_options import path_argument

SOURCE = Path(__file__).resolve().parent.parent
# The Markdown files that may hold figures, relative to the source tree.
TEXT_GLOBS = ("lessons/*/README.md", "slides/*.md", "exercises/*/README.md", "docs/*.md")
# Header words that make a column (or a row, by its first cell) a timing.
TIMING_WORDS = frozenset({
    "ns", "us", "µs", "ms", "sec", "secs", "second", "seconds", "nanoseconds", "microseconds",
    "milliseconds", "time", "timing", "speedup", "speed", "elapsed",
})
OPEN = re.compile(r"^\s*<!--\s*figure:\s*(?P<spec>.*?)\s*-->\s*$")
CLOSE = re.compile(r"^\s*<!--\s*/figure\s*-->\s*$")
LABEL_PREFIX = "*Table "
# Hand-typed timings outside figures: "16 ns", "0.58 ms", "2 seconds", "3.3 s on", "about 15 s".
HAND_TIMING = re.compile(
    r"(?<![\w.])\d[\d.,]*(?:\s*[–-]\s*\d[\d.,]*)?\s*(?:ns|µs|μs|ms|seconds?|minutes?)\b"
    r"|(?<![\w.])\d[\d.,]*(?:\s*[–-]\s*\d[\d.,]*)?\s?s\b(?=\s+(?:on|while|for|per|in|at)\b|[),;*]|\.(?:\s|$))")


# "erratum 4" not already the text of a link ([erratum 4](...)).
UNLINKED_ERRATUM = re.compile(r"(?<!\[)\b[Ee]rratum \d{1,2}\b(?!\])")


class FigureError(Exception):
    pass


def words(text: str) -> set[str]:
    return {w.lower() for w in re.split(r"[^0-9A-Za-zµ]+", text) if w}


def is_timing_name(text: str) -> bool:
    return bool(words(text) & TIMING_WORDS)


# --- tables --------------------------------------------------------------------------

@dataclass
class Table:
    header: list[str]
    rows: list[list[str]]

    def timing_mask(self) -> list[list[bool]]:
        timing_columns = [is_timing_name(h) for h in self.header]
        return [[timing_columns[c] or (bool(row) and is_timing_name(row[0])) for c in range(len(row))]
                for row in self.rows]

    def has_timings(self) -> bool:
        return any(any(r) for r in self.timing_mask())

    def markdown(self) -> list[str]:
        def line(cells: list[str]) -> str:
            return "| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |"
        return [line(self.header), "|" + "---|" * len(self.header)] + [line(r) for r in self.rows]


def markdown_tables(lines: list[str]) -> list[tuple[int, Table]]:
    """Every pipe table in `lines`: (index of its header line, table)."""
    tables, i = [], 0
    while i + 1 < len(lines):
        if lines[i].lstrip().startswith("|") and is_separator_line(lines[i + 1]):
            start, header = i, split_table_row(lines[i])
            rows, i = [], i + 2
            while i < len(lines) and lines[i].lstrip().startswith("|"):
                rows.append(split_table_row(lines[i]))
                i += 1
            tables.append((start, Table(header, rows)))
        else:
            i += 1
    return tables


def read_table(path: Path, number: int) -> Table:
    if not path.is_file():
        raise FigureError(f"{path} does not exist (run the main job, or the lesson program, first)")
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".csv":
        rows = [r for r in csv.reader(io.StringIO(text)) if r]
        if not rows:
            raise FigureError(f"{path} is empty")
        return Table(rows[0], rows[1:])
    tables = markdown_tables(text.splitlines())
    if len(tables) < number:
        raise FigureError(f"{path} holds {len(tables)} table(s); the figure asks for table {number}")
    return tables[number - 1][1]


# --- figure specifications ------------------------------------------------------------

@dataclass
class Spec:
    path: str
    columns: list[str] | None = None
    where: list[tuple[str, set[str]]] = field(default_factory=list)
    rows: list[list[tuple[str, str]]] = field(default_factory=list)
    table: int = 1


def parse_spec(text: str) -> Spec:
    try:
        parts = shlex.split(text)
    except ValueError as e:
        raise FigureError(f"cannot read the figure comment '{text}': {e}") from None
    if not parts:
        raise FigureError("the figure comment names no table")
    spec = Spec(parts[0])
    if not re.fullmatch(r"out/[\w.\-/]+\.(md|csv)", spec.path) or ".." in spec.path:
        raise FigureError(f"figure source '{spec.path}' must be a .md or .csv path under out/")
    for option in parts[1:]:
        key, sep, value = option.partition("=")
        if not sep:
            raise FigureError(f"figure option '{option}' is not key=value")
        if key == "columns":
            spec.columns = [c.strip() for c in value.split(",")]
        elif key == "where":
            column, sep, values = value.partition("=")
            if not sep:
                raise FigureError(f"where='{value}' must read column=value1|value2")
            spec.where.append((column.strip(), {v.strip() for v in values.split("|")}))
        elif key == "row":
            conditions = []
            for part in value.split("&"):
                column, sep, cell = part.partition("=")
                if not sep:
                    raise FigureError(f"row='{value}' must read column=value & column=value")
                conditions.append((column.strip(), cell.strip()))
            spec.rows.append(conditions)
        elif key == "table":
            if not value.isdigit() or int(value) < 1:
                raise FigureError(f"table={value} must be a positive number")
            spec.table = int(value)
        else:
            raise FigureError(f"unknown figure option '{key}' (columns=, where=, row=, table=)")
    return spec


def select(table: Table, spec: Spec, source_name: str) -> Table:
    def index(column: str) -> int:
        if column not in table.header:
            raise FigureError(f"{source_name} has no column '{column}' (it has: {', '.join(table.header)})")
        return table.header.index(column)

    rows = table.rows
    for column, values in spec.where:
        c = index(column)
        rows = [r for r in rows if c < len(r) and r[c] in values]
        found = {r[c] for r in rows}
        if values - found:
            raise FigureError(f"{source_name}: no row has {column} = {', '.join(sorted(values - found))}")
    if spec.rows:
        picks = [[(index(column), cell) for column, cell in conditions] for conditions in spec.rows]
        for conditions, pick in zip(spec.rows, picks):
            if not any(all(c < len(r) and r[c] == cell for c, cell in pick) for r in rows):
                raise FigureError(f"{source_name}: no row has " + " and ".join(f"{a} = {b}" for a, b in conditions))
        rows = [r for r in rows if any(all(c < len(r) and r[c] == cell for c, cell in pick) for pick in picks)]
    if spec.columns is None:
        return Table(list(table.header), [list(r) for r in rows])
    picks = [index(c) for c in spec.columns]
    return Table([table.header[c] for c in picks], [[r[c] if c < len(r) else "" for c in picks] for r in rows])


# --- the run that produced a table ----------------------------------------------------

def run_label(out: Path, spec: Spec, table: Table) -> str:
    source = f"`{spec.path}`"
    program = spec.path.split("/")[1] if spec.path.count("/") >= 2 else ""
    if not table.has_timings():
        return f"{LABEL_PREFIX}{source}, written by `{program}`.*"
    log = {}
    log_path = out / "run_log.json"
    if log_path.is_file():
        try:
            log = json.loads(log_path.read_text(encoding="utf-8"))
        except (json.JSONDecodeError, UnicodeDecodeError):
            log = {}
    run = log.get(program) if isinstance(log, dict) else None
    if isinstance(run, dict) and "started" in run:
        load = run.get("load_before", ["?"])[0], run.get("load_after", ["?"])[0]
        machine = (f"{run.get('cores', '?')} cores, load average {load[0]} at the start of the run "
                   f"and {load[1]} at its end")
        beside = run.get("beside")
        names = [f"`{name}`" for name in beside if isinstance(name, str)] if isinstance(beside, list) else []
        if names:
            machine += (f", side by side with {', '.join(names[:-1]) + ' and ' if len(names) > 1 else ''}"
                        f"{names[-1]} (each timing one thread while they overlapped)")
            if "whole_machine_seconds" in run:  # a "mixed" program (lib/illum/io/whole_machine.hpp)
                machine += "; its timings on more threads had the machine to themselves"
        date = run["started"]
    else:
        stamp = (out / Path(spec.path).relative_to("out")).stat().st_mtime
        date = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime(stamp))
        machine = f"{os.cpu_count()} cores, load not recorded (run outside the main job)"
    return (f"{LABEL_PREFIX}{source}, written by `{program}`; its timings were measured {date} "
            f"on {machine}: rerun to measure yours, they vary with the machine and its load.*")


# --- texts -----------------------------------------------------------------------------

@dataclass
class Block:
    text: Path
    open_line: int          # 0-based index of the opening comment
    close_line: int         # 0-based index of the closing comment
    spec_text: str


def find_blocks(path: Path, lines: list[str]) -> list[Block]:
    blocks, current = [], None
    fence = False
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            fence = not fence
        if fence:
            continue
        m = OPEN.match(line)
        if m:
            if current is not None:
                raise FigureError(f"{path}:{current[0] + 1}: figure not closed before the next one "
                                  f"(line {i + 1}); end it with <!-- /figure -->")
            current = (i, m.group("spec"))
        elif CLOSE.match(line):
            if current is None:
                raise FigureError(f"{path}:{i + 1}: <!-- /figure --> without an opening figure comment")
            blocks.append(Block(path, current[0], i, current[1]))
            current = None
    if current is not None:
        raise FigureError(f"{path}:{current[0] + 1}: figure never closed (add <!-- /figure -->)")
    return blocks


def render(out: Path, spec: Spec) -> tuple[Table, list[str]]:
    table = select(read_table(out / Path(spec.path).relative_to("out"), spec.table), spec, spec.path)
    return table, table.markdown() + ["", run_label(out, spec, table)]


def compare(block: Block, lines: list[str], new: Table) -> list[str]:
    """Differences in non-timing cells between the text's table and the program's."""
    where = f"{block.text}:{block.open_line + 1}"
    inner = lines[block.open_line + 1:block.close_line]
    tables = markdown_tables(inner)
    if len(tables) != 1:
        return [f"{where}: the figure holds {len(tables)} tables, expected one (run tools/figures.py --update)"]
    start, old = tables[0]
    if old.header != new.header:
        return [f"{where}: columns differ: text has {old.header}, the program writes {new.header}"]
    if len(old.rows) != len(new.rows):
        return [f"{where}: the text's table has {len(old.rows)} rows, the program's {len(new.rows)}"]
    problems = []
    mask = new.timing_mask()
    for r, (a, b) in enumerate(zip(old.rows, new.rows)):
        if len(a) != len(b):
            problems.append(f"{where}: row {r + 1} has {len(a)} cells, the program's {len(b)}")
            continue
        for c, (x, y) in enumerate(zip(a, b)):
            if not mask[r][c] and x != y:
                line = block.open_line + 1 + start + 2 + r + 1
                problems.append(f"{block.text}:{line}: row '{b[0]}', column '{new.header[c]}': "
                                f"the text says {x}, the program wrote {y}")
    return problems


def hand_timings(path: Path, lines: list[str], blocks: list[Block]) -> list[str]:
    inside = set()
    for b in blocks:
        inside.update(range(b.open_line, b.close_line + 1))
    problems = []
    for start, table in markdown_tables(lines):
        if start not in inside and table.has_timings():
            problems.append(f"{path}:{start + 1}: a table with timings typed by hand: include it with "
                            f"a figure comment naming the program's table")
    for i, line in enumerate(lines):
        if i in inside:
            continue
        for m in HAND_TIMING.finditer(re.sub(r"`[^`]*`", "", line)):
            problems.append(f"{path}:{i + 1}: hand-typed timing '{m.group(0).strip()}': include the "
                            f"table with a figure comment, or state a ratio or growth and name the table")
    return problems


def unlinked_errata(path: Path, lines: list[str]) -> list[str]:
    if path.as_posix() == "docs/errata.md":
        return []
    problems, fence = [], False
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            fence = not fence
            continue
        if fence:
            continue
        for m in UNLINKED_ERRATUM.finditer(re.sub(r"`[^`]*`", "", line)):
            problems.append(f"{path}:{i + 1}: '{m.group(0)}' is not linked: write "
                            f"[{m.group(0)}](<relative path>/docs/errata.md#{m.group(0).lower().replace(' ', '-')})")
    return problems



# --- values in sentences ---------------------------------------------------------------
#
# A number in a sentence that restates a program's result is written where it
# stands, followed by a marker naming it, and defined once in the same file:
#
#     ... at the price of 43.6<!--=bvh_nodes--> box tests per shadow ray ...
#     <!-- value bvh_nodes: out/lesson08/light_buffer.md row="method=BVH (any hit)" column="nodes or cells per shadow ray" -->
#
# Rendered (GitHub, the gallery's pages, a deck) both comments vanish and the
# sentence reads "43.6 box tests"; raw, the marker says where the number comes
# from and the definition, on a line of its own, says exactly which cell.

VALUE_MARKER = re.compile(r"<!--\s*=(?P<name>[A-Za-z_]\w*)\s*-->")
VALUE_DEF = re.compile(r"^\s*<!--\s*value\s+(?P<name>[A-Za-z_]\w*)\s*:\s*(?P<spec>.*?)\s*-->\s*$")
# The text a marker vouches for: what stands right before it, without a space:
# a `code span`, or a run of characters that are not spaces and not opening
# brackets or quotes ("(43.6" vouches for 43.6).
VALUE_TEXT = re.compile(r"(?:`[^`]+`|[^\s(\[{\"'“‘`]+)$")
VALUE_FORMATS = "cell, fixed:N, sig:N, percent:N, int, thousands, rows"


@dataclass
class ValueDef:
    name: str
    line: int                       # 0-based
    path: str | None = None         # a cell: out/... and its spec
    spec: Spec | None = None
    column: str | None = None
    expression: str | None = None   # or arithmetic over other values of the file
    format: str = "cell"


def parse_value_def(name: str, line: int, text: str) -> ValueDef:
    fmt = re.search(r"(?:^|\s)format=(\S+)\s*$", text)
    body = text[:fmt.start()].strip() if fmt else text.strip()
    value = ValueDef(name, line, format=fmt.group(1) if fmt else "cell")
    if not re.fullmatch(r"cell|int|thousands|rows|(?:fixed|sig|percent):\d{1,2}", value.format):
        raise FigureError(f"value {name}: unknown format '{value.format}' (one of {VALUE_FORMATS})")
    first = body.split(None, 1)[0] if body else ""
    if first.startswith("out/") or re.fullmatch(r"[\w\-]+(?:/[\w\-.]+)*\.md", first):
        try:
            parts = shlex.split(body)
        except ValueError as e:
            raise FigureError(f"value {name}: cannot read '{body}': {e}") from None
        if ".." in parts[0]:
            raise FigureError(f"value {name}: '{parts[0]}' must name a table under out/ or in the source tree")
        options = [p for p in parts[1:] if not p.startswith("column=")]
        columns = [p[len("column="):] for p in parts[1:] if p.startswith("column=")]
        if value.format == "rows" and columns:
            raise FigureError(f"value {name}: format=rows counts rows; it names no column=")
        if value.format != "rows" and len(columns) != 1:
            raise FigureError(f"value {name}: name exactly one column= (the cell's column)")
        value.path, value.column = parts[0], columns[0] if columns else None
        # parse_spec checks the options; a source-tree table is read from SOURCE, not OUT.
        spec_path = parts[0] if parts[0].startswith("out/") else "out/" + parts[0]
        value.spec = parse_spec(" ".join(shlex.quote(p) for p in [spec_path] + options))
        value.spec.path = parts[0]
        if value.spec.columns is not None:
            raise FigureError(f"value {name}: columns= picks a figure's columns; a value names one column=")
    else:
        if value.format == "cell":
            raise FigureError(f"value {name}: arithmetic '{body}' needs a format= ({VALUE_FORMATS})")
        value.expression = body
        names = re.findall(r"[A-Za-z_]\w*", body)
        _evaluate(body, {n: 1.0 + 0.37 * i for i, n in enumerate(names)}, name)  # its form, not its value
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
    if kind == "int":
        return str(round(x))
    if kind == "thousands":
        return f"{round(x):,}"
    if kind == "fixed":
        return f"{x:.{int(digits)}f}"
    if kind == "percent":
        return f"{100 * x:.{int(digits)}f}"
    return f"{x:.{int(digits)}g}"  # sig


def _evaluate(expression: str, known: dict[str, float], name: str) -> float:
    try:
        tree = ast.parse(expression, mode="eval")
    except SyntaxError:
        raise FigureError(f"value {name}: cannot read the arithmetic '{expression}'") from None
    operators = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b,
                 ast.Mult: lambda a, b: a * b, ast.Div: lambda a, b: a / b,
                 ast.Pow: lambda a, b: abs(a) ** b}  # a rate per step: (e4 / e10) ** (1 / 6)

    def walk(node: ast.AST) -> float:
        if isinstance(node, ast.BinOp) and type(node.op) in operators:
            left, right = walk(node.left), walk(node.right)
            if isinstance(node.op, ast.Div) and right == 0:
                raise FigureError(f"value {name}: '{expression}' divides by zero")
            return operators[type(node.op)](left, right)
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


def resolve_values(out: Path, defs: dict[str, ValueDef], source: Path = SOURCE) -> dict[str, tuple[str, bool]]:
    """Each value's text as the program's tables give it, and whether it depends on a timing."""
    resolved: dict[str, tuple[str, bool]] = {}
    numbers: dict[str, float] = {}
    timings: dict[str, bool] = {}
    pending = sorted(defs.values(), key=lambda d: d.expression is not None)  # cells first
    for _ in range(len(pending) + 1):
        waiting = []
        for d in pending:
            if d.path is not None:
                where = out / Path(d.path).relative_to("out") if d.path.startswith("out/") else source / d.path
                table = select(read_table(where, d.spec.table), d.spec, d.path)
                if d.format == "rows":
                    numbers[d.name], timings[d.name] = float(len(table.rows)), False
                    resolved[d.name] = (str(len(table.rows)), False)
                    continue
                if d.column not in table.header:
                    raise FigureError(f"value {d.name}: {d.path} has no column '{d.column}' "
                                      f"(it has: {', '.join(table.header)})")
                if len(table.rows) != 1:
                    raise FigureError(f"value {d.name}: row=/where= pick {len(table.rows)} rows of {d.path}; "
                                      "a value is one cell")
                c = table.header.index(d.column)
                cell = table.rows[0][c] if c < len(table.rows[0]) else ""
                timings[d.name] = table.timing_mask()[0][c]
                try:
                    numbers[d.name] = float(cell)
                except ValueError:
                    pass
                resolved[d.name] = (format_value(cell, d.format, d.name), timings[d.name])
            else:
                names = set(re.findall(r"[A-Za-z_]\w*", d.expression))
                if not names <= set(numbers):
                    if names - set(defs):
                        raise FigureError(f"value {d.name}: {', '.join(sorted(names - set(defs)))} is not "
                                          "defined in this file")
                    waiting.append(d)
                    continue
                x = _evaluate(d.expression, numbers, d.name)
                numbers[d.name] = x
                timings[d.name] = any(timings[n] for n in names)
                resolved[d.name] = (format_value(repr(x), d.format, d.name), timings[d.name])
        if not waiting:
            return resolved
        pending = waiting
    raise FigureError("values defined in terms of each other: " + ", ".join(d.name for d in pending))


@dataclass
class ValueUse:
    name: str
    line: int       # 0-based
    start: int      # span of the text it vouches for
    end: int


def find_values(path: Path, lines: list[str], blocks: list[Block]) -> tuple[dict[str, ValueDef], list[ValueUse]]:
    """The value definitions and the markers of a text (outside code fences and figures)."""
    inside = set()
    for b in blocks:
        inside.update(range(b.open_line, b.close_line + 1))
    defs: dict[str, ValueDef] = {}
    uses: list[ValueUse] = []
    fence = False
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            fence = not fence
            continue
        if fence or i in inside:
            continue
        m = VALUE_DEF.match(line)
        if m:
            if m["name"] in defs:
                raise FigureError(f"{path}:{i + 1}: value {m['name']} is defined twice (first on line "
                                  f"{defs[m['name']].line + 1})")
            try:
                defs[m["name"]] = parse_value_def(m["name"], i, m["spec"])
            except FigureError as e:
                raise FigureError(f"{path}:{i + 1}: {e}") from None
            continue
        for u in VALUE_MARKER.finditer(line):
            text = VALUE_TEXT.search(line[:u.start()])
            if not text:
                raise FigureError(f"{path}:{i + 1}: the marker <!--={u['name']}--> follows no value: write it "
                                  "right after the number, without a space (43.6<!--=name-->)")
            uses.append(ValueUse(u["name"], i, text.start(), text.end()))
    used = {u.name for u in uses}
    for u in uses:
        if u.name not in defs:
            raise FigureError(f"{path}:{u.line + 1}: value {u.name} is used but not defined: add a line "
                              f"<!-- value {u.name}: out/lessonNN/table.md row=\"…\" column=\"…\" -->")
    referenced = set()
    for d in defs.values():
        if d.expression:
            referenced |= set(re.findall(r"[A-Za-z_]\w*", d.expression))
    for d in defs.values():
        if d.name not in used and d.name not in referenced:
            raise FigureError(f"{path}:{d.line + 1}: value {d.name} is defined but no sentence uses it")
    return defs, uses


def process_values(out: Path, path: Path, lines: list[str], blocks: list[Block], mode: str,
                   problems: list[str], left: list[str], source: Path = SOURCE) -> tuple[bool, int]:
    """Checks (mode 'check') or rewrites the values in one text: (whether `lines` changed, values seen)."""
    try:
        defs, uses = find_values(path, lines, blocks)
        if not defs:
            return False, 0
        resolved = resolve_values(out, defs, source)
    except FigureError as e:
        problems.append(str(e) if str(e).startswith(str(path)) else f"{path}: {e}")
        return False, 0
    changed = False
    for u in reversed(uses):  # right to left: earlier spans on a line stay valid
        line = lines[u.line]
        written = line[u.start:u.end]
        shown = written[1:-1] if written.startswith("`") and written.endswith("`") and len(written) > 1 else written
        value, timing = resolved[u.name]
        if shown == value:
            continue
        difference = f"{path}:{u.line + 1}: value {u.name}: the text says {shown}, the program wrote {value}"
        if mode == "check":
            if not timing:
                problems.append(difference)
            continue
        if mode == "refresh" and not timing:
            left.append(difference)
            continue
        replacement = f"`{value}`" if written.startswith("`") else value
        lines[u.line] = line[:u.start] + replacement + line[u.end:]
        changed = True
    return changed, len(uses)


def texts(source: Path) -> list[Path]:
    found: list[Path] = []
    for pattern in TEXT_GLOBS:
        found.extend(sorted(source.glob(pattern)))
    return found


# --- kept images -----------------------------------------------------------------------
#
# A lesson text shows its program's images where a student reads it: in the
# repository browser and in the student edition, before anything has run. So
# every image a lesson text links is kept in the repository, in
# lessons/NN_topic/figures/, a copy of what the main job drew in
# out/lessonNN/; the text links `figures/x.png`. A timing plot (its title or
# an axis label names a time, or a throughput) is different on every run: its
# kept copy is compared by size only, and the rendered page shows the run's.

FIGURES_FOLDER = "figures"
IMAGE_LINK = re.compile(r"!\[[^\]]*\]\((?P<target>[^()\s]+\.png)\)")
OUT_IMAGE = re.compile(r"\.\./\.\./out/lesson(?P<lesson>\d\d)/(?P<name>[\w.\-]+\.png)")
KEPT_IMAGE = re.compile(FIGURES_FOLDER + r"/(?P<name>[\w.\-]+\.png)")
# gnuplot's labels in the .gp file written beside each plot.
PLOT_LABEL = re.compile(r'^\s*set\s+(?:title|[xy]2?label)\s+"(?P<label>(?:[^"\\]|\\.)*)"', re.M)
# Words of a plot label that make it a timing plot, beyond TIMING_WORDS ("Mrays/s").
PLOT_TIMING_WORDS = TIMING_WORDS | {"mrays", "throughput"}
# Two drawings of one figure agree when their sizes match and at most this
# share of pixels differs by more than PIXEL_LEVELS in a channel: a last-bit
# change of a float moves an 8-bit value by one or two levels, a change of
# what the program draws moves many pixels by much more.
PIXEL_LEVELS = 4
PIXEL_SHARE = 0.001
# The repository stays small: all kept images together (CONTRIBUTING.md, "Images show where students read").
KEPT_BUDGET_BYTES = 6_000_000


def lesson_texts(source: Path) -> list[Path]:
    return sorted(source.glob("lessons/[0-9][0-9]_*/README.md"))


@dataclass
class ImageLink:
    line: int       # 0-based
    start: int      # span of the link's target in the line
    end: int
    lesson: str     # the program that draws it: out/lesson<lesson>/<name>
    name: str
    kept: bool      # the text links figures/<name>


def image_links(text: Path, lines: list[str]) -> tuple[list[ImageLink], list[str]]:
    """The lesson text's image links to its program's outputs or its kept figures; problems."""
    lesson = text.parent.name[:2]
    links, problems, fence = [], [], False
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            fence = not fence
        if fence:
            continue
        for m in IMAGE_LINK.finditer(line):
            target = m.group("target")
            out_match, kept_match = OUT_IMAGE.fullmatch(target), KEPT_IMAGE.fullmatch(target)
            if kept_match:
                links.append(ImageLink(i, m.start("target"), m.end("target"), lesson, kept_match["name"], True))
            elif out_match and out_match["lesson"] == lesson:
                links.append(ImageLink(i, m.start("target"), m.end("target"), lesson, out_match["name"], False))
            elif out_match:
                problems.append(f"{text}:{i + 1}: '{target}' is drawn by another lesson's program: a lesson text "
                                f"shows its own program's images (link that figure from lesson "
                                f"{out_match['lesson']}'s text)")
    return links, problems


LAB_SCREENSHOT = "lab_"


def drawn_path(out: Path, link: "ImageLink") -> Path:
    """Where the main job draws a linked image: OUT/lessonNN/, or OUT/lab/ for a screenshot of the lab."""
    if link.name.startswith(LAB_SCREENSHOT):
        return out / "lab" / link.name
    return out / f"lesson{link.lesson}" / link.name


def timing_plot(out: Path, lesson: str, name: str) -> str | None:
    """The label that makes out/lessonNN/<name> a timing plot, or None (a render, a deterministic plot)."""
    script = out / f"lesson{lesson}" / (Path(name).stem + ".gp")
    if not script.is_file():
        return None
    for m in PLOT_LABEL.finditer(script.read_text(encoding="utf-8", errors="replace")):
        if words(m.group("label")) & PLOT_TIMING_WORDS:
            return m.group("label")
    return None


def decode_png(data: bytes) -> tuple[int, int, int, bytes]:
    """(width, height, channels, pixels) of an 8-bit, non-interlaced grey/RGB/RGBA PNG."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise FigureError("not a PNG file")
    chunks, pos, header = [], 8, None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            chunks.append(body)
        elif kind == b"IEND":
            break
    if header is None:
        raise FigureError("PNG without IHDR")
    width, height, depth, colour, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace:
        raise FigureError(f"unsupported PNG (bit depth {depth}, colour type {colour}, interlace {interlace})")
    raw = zlib.decompress(b"".join(chunks))
    stride = width * channels
    if len(raw) != height * (stride + 1):
        raise FigureError("PNG data of the wrong length")
    pixels = bytearray(height * stride)
    previous = bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        row = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if kind == 1:    # Sub
            for i in range(channels, stride):
                row[i] = (row[i] + row[i - channels]) & 255
        elif kind == 2:  # Up
            row = bytearray((a + b) & 255 for a, b in zip(row, previous))
        elif kind == 3:  # Average
            for i in range(stride):
                left = row[i - channels] if i >= channels else 0
                row[i] = (row[i] + ((left + previous[i]) >> 1)) & 255
        elif kind == 4:  # Paeth
            for i in range(stride):
                a = row[i - channels] if i >= channels else 0
                b = previous[i]
                c = previous[i - channels] if i >= channels else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        elif kind != 0:
            raise FigureError(f"PNG row {y} has unknown filter {kind}")
        pixels[y * stride:(y + 1) * stride] = row
        previous = row
    return width, height, channels, bytes(pixels)


def image_difference(kept: bytes, drawn: bytes) -> str | None:
    """None when two PNGs show the same picture (within PIXEL_LEVELS/PIXEL_SHARE), else how they differ."""
    if kept == drawn:
        return None
    (w1, h1, c1, p1), (w2, h2, c2, p2) = decode_png(kept), decode_png(drawn)
    if (w1, h1, c1) != (w2, h2, c2):
        return f"the kept figure is {w1}×{h1} with {c1} channel(s), the program drew {w2}×{h2} with {c2}"
    differing, largest = 0, 0
    for i in range(0, len(p1), c1):
        step = max(abs(a - b) for a, b in zip(p1[i:i + c1], p2[i:i + c1]))
        if step > PIXEL_LEVELS:
            differing += 1
        largest = max(largest, step)
    if differing > PIXEL_SHARE * w1 * h1:
        return (f"{differing} of {w1 * h1} pixels differ by more than {PIXEL_LEVELS} levels "
                f"(largest difference {largest}; at most {PIXEL_SHARE:.1%} may)")
    return None


def check_images(source: Path, out: Path) -> tuple[list[str], int]:
    """Problems with the lesson texts' images, and how many kept figures were compared."""
    problems, compared, total = [], 0, 0
    for path in lesson_texts(source):
        rel = path.relative_to(source)
        links, found = image_links(rel, path.read_text(encoding="utf-8").splitlines())
        problems += found
        folder = path.parent / FIGURES_FOLDER
        for link in links:
            where = f"{rel}:{link.line + 1}"
            drawn = drawn_path(out, link)
            if not drawn.is_file():
                problems.append(f"{where}: {link.name}: the program wrote no {drawn.relative_to(out)} in {out}")
                continue
            timing = timing_plot(out, link.lesson, link.name)
            if not link.kept:
                problems.append(f"{where}: {link.name} is linked in out/, which is empty until the program has run "
                                f"(and in a fresh clone): keep it with tools/figures.py --update-images")
            else:
                kept = folder / link.name
                if not kept.is_file():
                    problems.append(f"{where}: {rel.parent}/{FIGURES_FOLDER}/{link.name} is missing "
                                    "(tools/figures.py --update-images)")
                    continue
                compared += 1
                try:
                    if link.name.startswith(LAB_SCREENSHOT) or timing:  # a screenshot, a timing plot: its size only
                        kept_size, drawn_size = decode_png(kept.read_bytes())[:2], decode_png(drawn.read_bytes())[:2]
                        difference = None if kept_size == drawn_size else f"its size {kept_size} is now {drawn_size}"
                    else:
                        difference = image_difference(kept.read_bytes(), drawn.read_bytes())
                except FigureError as e:
                    difference = str(e)
                if difference:
                    problems.append(f"{where}: {rel.parent}/{FIGURES_FOLDER}/{link.name} drifted from what "
                                    f"lesson{link.lesson} draws: {difference}; review and refresh with "
                                    "tools/figures.py --update-images")
        linked = {link.name for link in links if link.kept}
        for orphan in sorted(folder.glob("*")) if folder.is_dir() else []:
            total += orphan.stat().st_size
            if orphan.name not in linked:
                problems.append(f"{orphan.relative_to(source)} is not shown by {rel}: delete it "
                                "(tools/figures.py --update-images does)")
    if total > KEPT_BUDGET_BYTES:
        problems.append(f"the kept images of lessons/*/{FIGURES_FOLDER}/ take {total / 1e6:.1f} MB, more than "
                        f"{KEPT_BUDGET_BYTES / 1e6:.0f} MB: show fewer, or have the program draw them smaller")
    return problems, compared


def write_atomically(path: Path, data: bytes) -> None:
    """Writes a file through a temporary one named with this process's PID, then a rename: never
    half a file; a temporary a killed run left is known by its PID (remove_stale_temporaries)."""
    tmp = path.with_name(f"{path.name}{TEMPORARY}{os.getpid()}")
    try:
        tmp.write_bytes(data)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def write_lines_atomically(path: Path, lines: list[str]) -> None:
    write_atomically(path, ("\n".join(lines) + "\n").encode("utf-8"))


TEMPORARY = ".tmp-figures-"


def remove_stale_temporaries(source: Path, log=print) -> None:
    """Removes the temporaries of runs killed without warning (SIGKILL) beside the texts and their
    kept figures: those whose PID no longer runs (or that name none, as this tool's older ones)."""
    folders = {p.parent for p in texts(source)} | {p.parent / FIGURES_FOLDER for p in lesson_texts(source)}
    for folder in sorted(f for f in folders if f.is_dir()):
        for tmp in sorted(folder.glob("*.tmp-figures*")):
            pid = tmp.name.rpartition(TEMPORARY)[2]
            try:
                if pid.isdigit():
                    os.kill(int(pid), 0)
                    continue  # another run of this tool, still writing
            except ProcessLookupError:
                pass
            except PermissionError:
                continue
            tmp.unlink()
            log(f"figures: removed {tmp.relative_to(source)}, left by a run that was killed before it finished")


def update_images(source: Path, out: Path, log=print) -> int:
    """Keeps a copy of every deterministic image the lesson texts show, links the texts to it, drops the rest."""
    problems, copied, texts_written, kept_total = [], 0, 0, 0
    for path in lesson_texts(source):
        rel = path.relative_to(source)
        lines = path.read_text(encoding="utf-8").splitlines()
        links, found = image_links(rel, lines)
        problems += found
        folder = path.parent / FIGURES_FOLDER
        keep: set[str] = set()
        changed = False
        for link in reversed(links):  # right to left: earlier spans on a line stay valid
            drawn = drawn_path(out, link)
            if not drawn.is_file():
                problems.append(f"{rel}:{link.line + 1}: {drawn.relative_to(out)} does not exist in "
                                f"{out} (run the main job first)")
                if link.kept:
                    keep.add(link.name)  # leave it as it is
                continue
            target = f"{FIGURES_FOLDER}/{link.name}"
            keep.add(link.name)
            kept = folder / link.name
            data = drawn.read_bytes()
            if not kept.is_file() or kept.read_bytes() != data:
                folder.mkdir(exist_ok=True)
                write_atomically(kept, data)
                copied += 1
            line = lines[link.line]
            if line[link.start:link.end] != target:
                lines[link.line] = line[:link.start] + target + line[link.end:]
                changed = True
        for orphan in sorted(folder.glob("*")) if folder.is_dir() else []:
            if orphan.name not in keep:
                orphan.unlink()
                log(f"figures: removed {orphan.relative_to(source)} (no longer shown)")
        if folder.is_dir() and not any(folder.iterdir()):
            folder.rmdir()
        kept_total += len(keep)
        if changed:
            write_lines_atomically(path, lines)
            texts_written += 1
            log(f"figures: relinked the images of {rel}")
    for p in problems:
        log(f"figures: {p}")
    log(f"figures: {kept_total} kept figure(s) in lessons/*/{FIGURES_FOLDER}/, {copied} copied from {out}, "
        f"{texts_written} text(s) relinked")
    return 1 if problems else 0


def process(source: Path, out: Path, mode: str, log=print, plots: bool = True) -> int:
    """mode: 'refresh', 'check' or 'update' (check: also the plots in OUT unless `plots` is False).
    Returns the exit code."""
    problems: list[str] = []
    left: list[str] = []
    written = figures = values = 0
    for path in texts(source):
        rel = path.relative_to(source)
        lines = path.read_text(encoding="utf-8").splitlines()
        try:
            blocks = find_blocks(rel, lines)
        except FigureError as e:
            problems.append(str(e))
            continue
        if mode == "check":
            # Measured timings live in the lesson texts and decks; docs/ states
            # settings (a grader's time-outs) and tool-written reports, not studies.
            if rel.parts[0] in ("lessons", "slides"):
                problems += hand_timings(rel, lines, blocks)
            problems += unlinked_errata(rel, lines)
        # Values first: they change text within lines, the figures change the number of lines.
        changed, found = process_values(out, rel, lines, blocks, mode, problems, left, source)
        values += found
        for block in reversed(blocks):  # bottom up: earlier line numbers stay valid
            figures += 1
            try:
                spec = parse_spec(block.spec_text)
                table, new_lines = render(out, spec)
            except FigureError as e:
                problems.append(f"{rel}:{block.open_line + 1}: {e}")
                continue
            differences = compare(block, lines, table)
            if mode == "check":
                problems += differences
                continue
            if differences and mode == "refresh":
                left += differences
                continue
            if lines[block.open_line + 1:block.close_line] != new_lines:
                lines[block.open_line + 1:block.close_line] = new_lines
                changed = True
        if changed:
            write_lines_atomically(path, lines)
            written += 1
            log(f"figures: refreshed {rel}")
    for p in problems:
        log(f"figures: {p}")
    if left:
        log(f"figures: {len(left)} value(s) in the texts differ from the programs' tables; those "
            "figures were left as they are. Review the change and accept it with tools/figures.py --update:")
        for p in left:
            log(f"figures:   {p}")
    if mode == "check":
        image_problems, compared = check_images(source, out)
        links, link_count = link_problems(source)
        plot_count = 0
        try:
            if plots:
                plots, plot_count = check_plots(out)
            else:
                plots = []
        except PlotCheckError as e:
            plots = [f"cannot check the plots: {e}"]
        for p in image_problems + links + plots:
            log(f"figures: {p}")
        problems += image_problems + links + plots
        if problems:
            log(f"figures: FAILED: {len(problems)} problem(s) in {figures} figure(s), {values} value(s), the "
                "lesson texts' images and links, and the plots")
            return 1
        log(f"figures: OK: the non-timing values of {figures} figure(s) and {values} value(s) in sentences "
            f"match the tables in {out}, no text quotes a timing by hand, the {compared} kept image(s) match "
            f"what the programs drew, the texts' {link_count} links resolve, and the {plot_count} plots show "
            "all their points")
        return 0
    log(f"figures: {figures} figure(s), {written} file(s) rewritten")
    return 1 if problems else 0


def link_problems(source: Path) -> tuple[list[str], int]:
    return check_text_links(source)


def check_links_only(source: Path, log=print) -> int:
    problems, checked = link_problems(source)
    for p in problems:
        log(f"figures: {p}")
    if problems:
        log(f"figures: FAILED: {len(problems)} of {checked} links and images of the texts do not resolve")
        return 1
    log(f"figures: OK: the {checked} links and images of the texts resolve in {source}")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--check", action="store_true", help="compare, write nothing; exit 1 on a difference")
    group.add_argument("--update", action="store_true", help="rewrite every figure from its table")
    group.add_argument("--update-images", action="store_true",
                       help="keep a copy of every image the lesson texts show in "
                            "lessons/NN_topic/figures/ and link it there")
    group.add_argument("--links", action="store_true",
                       help="only check that every link and image of the texts resolves in the source tree "
                            "(needs no OUT)")
    parser.add_argument("--out", type=path_argument, default=None,
                        help="the main job's output folder (default: SOURCE/out)")
    parser.add_argument("--source", type=path_argument, default=SOURCE,
                        help="the source tree (default: this checkout)")
    args = parser.parse_args(argv)
    source = args.source.resolve()
    out = (args.out or source / "out").resolve()
    if not (source / "lessons").is_dir():
        parser.error(f"--source {args.source}: not an illum source tree (no lessons/ folder in it)")
    # One clear line rather than a missing-file problem for each of the texts' figures.
    if not args.links and not out.is_dir():
        parser.error(f"--out {args.out or out}: not a folder of the main job's outputs (run tools/bootstrap, "
                     "or tools/main_job.py --bin build/release/bin --out out)")
    if not args.check and not args.links:  # the modes that write
        remove_stale_temporaries(source)
    if args.update_images:
        return update_images(source, out)
    if args.links:
        return check_links_only(source)
    mode = "check" if args.check else "update" if args.update else "refresh"
    return process(source, out, mode)


if __name__ == "__main__":
    sys.exit(main())
