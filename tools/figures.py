#!/usr/bin/env python3
"""Figures in lesson texts and decks come from the programs' own tables.

    tools/figures.py [--out out]            refresh timings (what the main job runs)
    tools/figures.py --check [--out out]    fail when a text's values differ (what CI runs)
    tools/figures.py --update [--out out]   rewrite every figure from the tables

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

The label under a figure with timings names the run: date, the machine's
cores and its load average at the start and end of that program's run, as
the main job records them in OUT/run_log.json (the file's modification time
and "load not recorded" when the program was run by hand).
"""
from __future__ import annotations

import argparse
import csv
import io
import json
import os
import re
import shlex
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from gallery.markdown_table import is_separator_line, split_table_row

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


def texts(source: Path) -> list[Path]:
    found: list[Path] = []
    for pattern in TEXT_GLOBS:
        found.extend(sorted(source.glob(pattern)))
    return found


def process(source: Path, out: Path, mode: str, log=print) -> int:
    """mode: 'refresh', 'check' or 'update'. Returns the exit code."""
    problems: list[str] = []
    left: list[str] = []
    written = figures = 0
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
        changed = False
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
            tmp = path.with_name(path.name + ".tmp-figures")
            tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
            os.replace(tmp, path)
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
        if problems:
            log(f"figures: FAILED: {len(problems)} problem(s) in {figures} figure(s)")
            return 1
        log(f"figures: OK: the non-timing values of {figures} figure(s) match the tables in {out}, "
            "and no text quotes a timing by hand")
        return 0
    log(f"figures: {figures} figure(s), {written} file(s) rewritten")
    return 1 if problems else 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--check", action="store_true", help="compare, write nothing; exit 1 on a difference")
    group.add_argument("--update", action="store_true", help="rewrite every figure from its table")
    parser.add_argument("--out", type=Path, default=None, help="the main job's output folder (default: SOURCE/out)")
    parser.add_argument("--source", type=Path, default=SOURCE, help="the source tree (default: this checkout)")
    args = parser.parse_args(argv)
    source = args.source.resolve()
    out = (args.out or source / "out").resolve()
    mode = "check" if args.check else "update" if args.update else "refresh"
    return process(source, out, mode)


if __name__ == "__main__":
    sys.exit(main())
