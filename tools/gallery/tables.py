"""The programs' tables as the texts quote them: read, narrowed by a figure's options, timings told apart."""

import csv
import io
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path

from common import markdown

# Header words that make a column (or a row, by its first cell) a timing.
TIMING_WORDS = frozenset({"ns", "us", "µs", "ms", "sec", "secs", "second", "seconds", "nanoseconds", "microseconds",
                          "milliseconds", "time", "timing", "speedup", "speed", "elapsed"})


class FigureError(Exception):
    pass


def words(text: str) -> set[str]:
    return {w.lower() for w in re.split(r"[^0-9A-Za-zµ]+", text) if w}


def is_timing_name(text: str) -> bool:
    return bool(words(text) & TIMING_WORDS)


class Table(markdown.Table):
    def timing_mask(self) -> list[list[bool]]:
        columns = [is_timing_name(h) for h in self.header]
        return [[columns[c] or is_timing_name(row[0]) for c in range(len(row))] for row in self.rows]

    def has_timings(self) -> bool:
        return any(any(r) for r in self.timing_mask())

    def markdown(self) -> list[str]:
        def line(cells: list[str]) -> str:
            return "| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |"
        return [line(self.header), "|" + "---|" * len(self.header)] + [line(r) for r in self.rows]


def markdown_tables(lines: list[str]) -> list[Table]:
    return [Table(t.header, t.rows, t.start) for t in markdown.parse_tables(lines)[0]]


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
    return tables[number - 1]


@dataclass
class Spec:
    path: str
    columns: list[str] | None = None
    where: list[tuple[str, set[str]]] = field(default_factory=list)
    rows: list[list[tuple[str, str]]] = field(default_factory=list)
    table: int = 1


def _pairs(key: str, text: str, separator: str, form: str) -> list[tuple[str, str]]:
    pairs = [part.partition("=") for part in text.split(separator)]
    if not all(sep for _, sep, _ in pairs):
        raise FigureError(f"{key}='{text}' must read {form}")
    return [(a.strip(), b.strip()) for a, _, b in pairs]


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
            [(column, cells)] = _pairs(key, value, "\0", "column=value1|value2")
            spec.where.append((column, {v.strip() for v in cells.split("|")}))
        elif key == "row":
            spec.rows.append(_pairs(key, value, "&", "column=value & column=value"))
        elif key == "table" and value.isdigit() and int(value) >= 1:
            spec.table = int(value)
        else:
            raise FigureError(f"table={value} must be a positive number" if key == "table" else
                              f"unknown figure option '{key}' (columns=, where=, row=, table=)")
    return spec


def select(table: Table, spec: Spec, source_name: str) -> Table:
    def index(column: str) -> int:
        if column not in table.header:
            raise FigureError(f"{source_name} has no column '{column}' (it has: {', '.join(table.header)})")
        return table.header.index(column)

    def matches(row: list[str], pick: list[tuple[int, str]]) -> bool:
        return all(c < len(row) and row[c] == cell for c, cell in pick)

    rows = table.rows
    for column, cells in spec.where:
        c = index(column)
        rows = [r for r in rows if c < len(r) and r[c] in cells]
        if cells - {r[c] for r in rows}:
            raise FigureError(f"{source_name}: no row has {column} = {', '.join(sorted(cells - {r[c] for r in rows}))}")
    picks = [[(index(column), cell) for column, cell in conditions] for conditions in spec.rows]
    for conditions, pick in zip(spec.rows, picks):
        if not any(matches(r, pick) for r in rows):
            raise FigureError(f"{source_name}: no row has " + " and ".join(f"{a} = {b}" for a, b in conditions))
    rows = [r for r in rows if not picks or any(matches(r, pick) for pick in picks)]
    if spec.columns is None:
        return Table(list(table.header), [list(r) for r in rows])
    columns = [index(c) for c in spec.columns]
    return Table([table.header[c] for c in columns], [[r[c] if c < len(r) else "" for c in columns] for r in rows])
