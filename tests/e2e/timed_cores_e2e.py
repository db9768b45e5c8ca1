#!/usr/bin/env python3
"""Every lesson program says how many cores its timings use, and a "one" is true.

The main job runs side by side the programs whose timings all use one thread
(`lessonNN --timed-cores` prints "one"; tools/main_job.py). A wrong "one" would
time a second thread while another program holds the second core, so:

* `--timed-cores` exits 0, prints exactly "one" or "all", and writes nothing
  (it is asked before the run, in the folder the run will use);
* a program that says "one" wrote, in its --quick run (the e2e fixture's
  test-out/lessonNN), no table with a `threads` column holding anything but 1:
  a table that records its thread count records a timing on more threads.
  Lessons 08 and 10, which time two threads, write such tables and say "all".

    python3 tests/e2e/timed_cores_e2e.py --bin build/release/bin --out build/release/test-out
"""
from __future__ import annotations

import argparse
import csv
import re
import subprocess
import sys
import tempfile
from pathlib import Path

PROGRAM = re.compile(r"^lesson\d\d$")


def tables_on_more_threads(folder: Path) -> list[str]:
    """`file: row N has threads = X` for every CSV row whose `threads` column is not 1."""
    found = []
    for table in sorted(folder.glob("*.csv")):
        with table.open(newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        if not rows or "threads" not in rows[0]:
            continue
        column = rows[0].index("threads")
        for number, row in enumerate(rows[1:], 1):
            if column < len(row) and row[column].strip() not in ("1", "1.0"):
                found.append(f"{table.name}: row {number} has threads = {row[column]}")
    return found


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bin", type=Path, required=True)
    parser.add_argument("--out", type=Path, required=True, help="the tests' output folder (test-out)")
    args = parser.parse_args()
    args.bin, args.out = args.bin.resolve(), args.out.resolve()
    programs = sorted(p for p in args.bin.iterdir() if PROGRAM.match(p.name))
    if not programs:
        print(f"timed_cores: FAILED: no lessonNN programs in {args.bin}")
        return 1
    problems, answers = [], {}
    for program in programs:
        with tempfile.TemporaryDirectory(prefix="illum-timed-cores-") as tmp:
            result = subprocess.run([str(program), "--timed-cores"], cwd=tmp, capture_output=True, text=True,
                                    stdin=subprocess.DEVNULL, timeout=60)
            written = sorted(p.name for p in Path(tmp).iterdir())
        answer = result.stdout
        if result.returncode != 0 or answer not in ("one\n", "all\n"):
            problems.append(f"{program.name} --timed-cores: exit {result.returncode}, printed {answer!r} "
                            f"(expected exit 0 and exactly 'one' or 'all'); stderr {result.stderr.strip()!r}")
            continue
        if written:
            problems.append(f"{program.name} --timed-cores wrote {', '.join(written)} (it must write nothing)")
        answers[program.name] = answer.strip()
        if answer.strip() == "one":
            folder = args.out / program.name
            if not (folder / "manifest.json").is_file():
                problems.append(f"{program.name}: no quick run in {folder} to check its 'one' against")
                continue
            for line in tables_on_more_threads(folder):
                problems.append(f"{program.name} says its timings use one core, but {line}")
    print("timed_cores: " + ", ".join(f"{name} {answer}" for name, answer in answers.items()))
    if problems:
        print("timed_cores: FAILED:\n  " + "\n  ".join(problems))
        return 1
    print(f"timed_cores: {len(answers)} program(s) answer, and every 'one' wrote no table on more threads")
    return 0


if __name__ == "__main__":
    sys.exit(main())
