#!/usr/bin/env python3
"""Compares two runs of a lesson program (two --out folders).

    tools/compare_runs.py EXPECTED_FOLDER OTHER_FOLDER

The tables (CSV files) must hold the same values cell for cell, but for timings (columns or rows named by a
timing word of tools/gallery/tables.py, and rates: Mrays, throughput, "per s"): tools/check_platforms arm64
compares lesson 01's run natively and under qemu-aarch64. Exit 0 when they agree, 1 listing the first
differing cells of each table, 2 when a folder or a table is missing.

    tools/compare_runs.py --speed FIRST_FOLDER OTHER_FOLDER

How much faster the other run was, over the timing cells of the tables both hold alike: FIRST/OTHER for a
time, OTHER/FIRST for a rate (a speed-up column is left out): the number of cells, their median and their
10th and 90th percentiles (docs/measurements.md). Exit 0, or 2 when a folder or every timing cell is missing.
"""

import csv
import re
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from gallery.tables import TIMING_WORDS, is_timing_name, words  # noqa: E402

RATE_WORDS = {"mrays", "throughput"}  # words() splits at "_" and "/": Mrays/s is {"mrays", "s"}
PER_SECOND = re.compile(r"\bper\s+(s|sec|second)\b|/s\b", re.I)


def is_timing(name: str) -> bool:
    return is_timing_name(name) or bool(words(name) & RATE_WORDS) or "/s" in name


def read(path: Path) -> list[list[str]]:
    with path.open(newline="", encoding="utf-8") as f:
        return list(csv.reader(f))


def compare_table(expected: Path, other: Path, limit: int = 5) -> list[str]:
    a, b = read(expected), read(other)
    if not a:
        return [] if not b else [f"{expected.name}: empty in the first run only"]
    if not b or a[0] != b[0]:
        return [f"{expected.name}: the headers differ: {a[0]} against {b[0] if b else 'nothing'}"]
    if len(a) != len(b):
        return [f"{expected.name}: {len(a) - 1} rows against {len(b) - 1}"]
    header, problems = a[0], []
    for r, (x, y) in enumerate(zip(a[1:], b[1:]), 1):
        if x and is_timing(x[0]):
            continue
        for c, (u, v) in enumerate(zip(x, y)):
            if u != v and not (c < len(header) and is_timing(header[c])):
                problems.append(f"{expected.name}: row {r}, column {header[c] if c < len(header) else c}: {u} "
                                f"against {v}")
                if len(problems) == limit:
                    return problems
        if len(x) != len(y):
            problems.append(f"{expected.name}: row {r} has {len(x)} cells against {len(y)}")
    return problems


def speed_kind(name: str) -> str | None:
    """'rate' (higher is faster), 'time' (lower is faster) or None (a speed-up, a count, no timing)."""
    w = words(name)
    if "speedup" in w or {"speed", "up"} <= w:
        return None
    if w & RATE_WORDS or PER_SECOND.search(name):
        return "rate"
    return "time" if w & (TIMING_WORDS - {"timing", "speedup", "speed"}) else None


def speed_factors(first: Path, other: Path) -> list[float]:
    """Each timing cell's speed of OTHER against FIRST (> 1: OTHER was faster), over the tables both folders
    hold with the same header and row count."""
    factors = []
    for table in sorted(first.glob("*.csv")):
        a, b = read(table), read(other / table.name) if (other / table.name).is_file() else []
        if not a or not b or a[0] != b[0] or len(a) != len(b):
            continue
        kinds = [speed_kind(h) for h in a[0]]
        for x, y in zip(a[1:], b[1:]):
            for kind, u, v in zip(kinds, x, y):
                try:
                    u_value, v_value = float(u), float(v)
                except ValueError:
                    continue
                if kind is not None and u_value > 0 and v_value > 0:
                    factors.append(u_value / v_value if kind == "time" else v_value / u_value)
    return factors


def speed_main(first: Path, other: Path) -> int:
    factors = speed_factors(first, other)
    if len(factors) < 2:
        print(f"compare_runs: --speed: {len(factors)} timing cell(s) in the tables {first} and {other} share; "
              "at least 2 are needed", file=sys.stderr)
        return 2
    deciles = statistics.quantiles(factors, n=10, method="inclusive")
    print(f"compare_runs: {len(factors)} timing cells; speed of {other} against {first}: "
          f"median {statistics.median(factors):.2f}, 10th-90th percentile {deciles[0]:.2f}-{deciles[-1]:.2f}")
    return 0


def main(argv: list[str]) -> int:
    speed, asked = argv[:1] == ["--speed"], argv[:1] in (["-h"], ["--help"])
    if asked or len(argv) != 2 + speed:
        print(__doc__.strip(), file=sys.stdout if asked else sys.stderr)
        return 0 if asked else 2
    first, second = (Path(a) for a in argv[speed:])
    if missing := [folder for folder in (first, second) if not folder.is_dir()]:
        print(f"compare_runs: {missing[0]} is not a folder", file=sys.stderr)
        return 2
    if speed:
        return speed_main(first, second)
    tables = sorted(p.name for p in first.glob("*.csv"))
    if not tables:
        print(f"compare_runs: {first} holds no table (*.csv)", file=sys.stderr)
        return 2
    problems = [p for name in tables for p in (compare_table(first / name, second / name)
                                               if (second / name).is_file() else [f"{name}: missing from {second}"])]
    problems += [f"{p.name}: only in {second}" for p in sorted(second.glob("*.csv")) if not (first / p.name).is_file()]
    for problem in problems:
        print(f"compare_runs: {problem}")
    print(f"compare_runs: {len(tables)} tables, "
          + ("the same values" if not problems else f"{len(problems)} difference(s)"))
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
