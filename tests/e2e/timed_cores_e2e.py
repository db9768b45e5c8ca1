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
  Lessons that time two threads write such tables and say "mixed" or "all";
* a program that says "mixed" (its timings on more threads each inside a
  WholeMachine, lib/illum/io/whole_machine.hpp) asks for the whole machine
  when run --quick under a stand-in for the main job, which answers "go" only
  SETTLE + WAIT seconds later: it asks at least once, it prints nothing in
  those WAIT seconds and does not end while it waits (it did wait), and it
  exits 0. Lessons 08-10 say so.

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


WAIT = 1.0  # seconds the stand-in main job lets a request wait
# Seconds first allowed for what the program printed before it asked to reach the reader thread: a
# line written just before the request may be read just after it.
SETTLE = 0.5


def run_under_stand_in_job(program: Path, folder: Path) -> list[str]:
    """Runs `program --quick --out folder` linked to a stand-in main job (the pipes of
    tools/main_job.py) and returns what went wrong, if anything."""
    import os
    import threading
    import time

    from_job_r, from_job_w = os.pipe()
    requests_r, to_job_w = os.pipe()
    env = dict(os.environ, ILLUM_MAIN_JOB_FDS=f"{from_job_r},{to_job_w}")
    proc = subprocess.Popen([str(program), "--quick", "--out", str(folder)], stdin=subprocess.DEVNULL,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                            pass_fds=(from_job_r, to_job_w))
    os.close(from_job_r)
    os.close(to_job_w)
    printed: list[tuple[float, str]] = []

    def read_output() -> None:
        for raw in proc.stdout:
            printed.append((time.monotonic(), raw.decode("utf-8", errors="replace").rstrip()))

    reader = threading.Thread(target=read_output)
    reader.start()
    problems, waits = [], []
    with open(requests_r, "r", encoding="utf-8", errors="replace") as requests:
        for line in requests:
            word = line.strip()
            if word == "machine":
                time.sleep(SETTLE)
                printed_before = len(printed)
                time.sleep(WAIT)  # another program still running, as the main job would have it
                if proc.poll() is not None:
                    problems.append(f"{program.name} ended while it waited for the whole machine")
                waits.append(printed[printed_before:])
                try:
                    os.write(from_job_w, b"go\n")
                except OSError:
                    pass
            elif word != "release":
                problems.append(f"{program.name} sent {word[:40]!r} (expected 'machine' or 'release')")
    code = proc.wait(timeout=600)
    reader.join()
    os.close(from_job_w)
    if code != 0:
        problems.append(f"{program.name} --quick under the stand-in main job exited {code}: "
                        + " | ".join(line for _, line in printed[-5:]))
    if not waits:
        problems.append(f"{program.name} says 'mixed' but never asked for the whole machine")
    for during in waits:
        early = [line for _, line in during]
        if early:
            problems.append(f"{program.name} printed {early[0]!r} while it waited for the whole machine "
                            "(it did not wait for the answer)")
    return problems


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
        if result.returncode != 0 or answer not in ("one\n", "mixed\n", "all\n"):
            problems.append(f"{program.name} --timed-cores: exit {result.returncode}, printed {answer!r} "
                            f"(expected exit 0 and exactly 'one', 'mixed' or 'all'); "
                            f"stderr {result.stderr.strip()!r}")
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
        if answer.strip() == "mixed":
            with tempfile.TemporaryDirectory(prefix="illum-mixed-") as tmp:
                problems += run_under_stand_in_job(program, Path(tmp) / program.name)
    print("timed_cores: " + ", ".join(f"{name} {answer}" for name, answer in answers.items()))
    if problems:
        print("timed_cores: FAILED:\n  " + "\n  ".join(problems))
        return 1
    print(f"timed_cores: {len(answers)} program(s) answer, every 'one' wrote no table on more threads, "
          "and every 'mixed' waited for the whole machine")
    return 0


if __name__ == "__main__":
    sys.exit(main())
