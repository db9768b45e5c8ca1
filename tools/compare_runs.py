#!/usr/bin/env python3
"""Two main-job runs compared: did a change of the code change what the programs compute?

    tools/compare_runs.py BEFORE AFTER [--lessons 06 11]

BEFORE and AFTER are two output folders of the main job (copies of out/).
For every lessonNN folder of BEFORE it compares, with AFTER's:

* every CSV table, cell by cell, except timings: a column whose header, or
  a row whose first cell, names time (tools/figures.py's TIMING_WORDS: ns,
  seconds, speedup, …) or says "timing-dependent";
* every PNG image whose pixels do not depend on timing (not a timing plot
  by tools/figures.py's rule), decoded, pixel for pixel;
* the list of files (a file in one run only is reported).

A refactoring that keeps the programs' results must report no difference.
Prints one line per difference and a summary; exit 0 when there is none, 1
otherwise. Text files (.txt, .md, .json) are not compared: they quote
timings and paths.
"""
from __future__ import annotations

import argparse
import csv
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import figures  # noqa: E402

_LESSON = re.compile(r"lesson(\d\d)$")


def is_timing(text: str) -> bool:
    return figures.is_timing_name(text) or "timing-dependent" in text


def read_csv(path: Path) -> list[list[str]]:
    with path.open(newline="", encoding="utf-8") as f:
        return [row for row in csv.reader(f)]


def compare_csv(name: str, before: Path, after: Path) -> tuple[list[str], int]:
    """(differences, cells compared)."""
    old, new = read_csv(before), read_csv(after)
    if not old or not new:
        return ([] if old == new else [f"{name}: one of the tables is empty"]), 0
    if old[0] != new[0]:
        return [f"{name}: the header changed: {old[0]} -> {new[0]}"], 0
    if len(old) != len(new):
        return [f"{name}: {len(old) - 1} rows before, {len(new) - 1} after"], 0
    header = old[0]
    timing_column = [is_timing(h) for h in header]
    problems, compared = [], 0
    for r, (a, b) in enumerate(zip(old[1:], new[1:]), start=1):
        if len(a) != len(b):
            problems.append(f"{name}: row {r} has {len(a)} cells before, {len(b)} after")
            continue
        timing_row = bool(a) and is_timing(a[0])
        for c, (x, y) in enumerate(zip(a, b)):
            if timing_row or timing_column[c]:
                continue
            compared += 1
            if x != y:
                problems.append(f"{name}: row {r} ({a[0]}), column '{header[c]}': {x} -> {y}")
    return problems, compared


def compare_png(name: str, before: Path, after: Path) -> str | None:
    w0, h0, c0, p0 = figures.decode_png(before.read_bytes())
    w1, h1, c1, p1 = figures.decode_png(after.read_bytes())
    if (w0, h0) != (w1, h1):
        return f"{name}: {w0}x{h0} before, {w1}x{h1} after"
    if p0 != p1 or c0 != c1:
        differing = sum(1 for a, b in zip(p0, p1) if a != b)
        return f"{name}: {differing} of {len(p0)} channel values differ"
    return None


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    parser.add_argument("--lessons", nargs="*", help="only these lessons (NN)")
    args = parser.parse_args(argv)
    problems: list[str] = []
    tables = cells = images = 0
    for folder in sorted(p for p in args.before.iterdir() if p.is_dir() and _LESSON.match(p.name)):
        lesson = _LESSON.match(folder.name).group(1)
        if args.lessons and lesson not in args.lessons:
            continue
        other = args.after / folder.name
        if not other.is_dir():
            problems.append(f"{folder.name}: missing in {args.after}")
            continue
        names = {p.name for p in folder.iterdir() if p.suffix in (".csv", ".png")}
        new_names = {p.name for p in other.iterdir() if p.suffix in (".csv", ".png")}
        for extra in sorted(new_names - names):
            problems.append(f"{folder.name}/{extra}: only in {args.after}")
        for name in sorted(names):
            label = f"{folder.name}/{name}"
            if name not in new_names:
                problems.append(f"{label}: only in {args.before}")
                continue
            if name.endswith(".csv"):
                found, compared = compare_csv(label, folder / name, other / name)
                problems += found
                tables += 1
                cells += compared
            elif figures.timing_plot(args.before, lesson, Path(name).stem) is None:
                images += 1
                problem = compare_png(label, folder / name, other / name)
                if problem:
                    problems.append(problem)
    for problem in problems:
        print(problem)
    print(f"compare_runs: {tables} tables ({cells} non-timing cells) and {images} deterministic images compared: "
          + ("no difference" if not problems else f"{len(problems)} difference(s)"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
