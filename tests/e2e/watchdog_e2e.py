#!/usr/bin/env python3
"""The per-test time limit of the test programs' own main (tests/support/test_main.cpp).

The command a student runs first, `build/student/bin/tests_lessonNN -ts=lessonNN`,
must not hang in silence on an endless loop: a test case that runs longer than
ILLUM_GRADE_TEST_TIMEOUT seconds (tools/grade's limit, default 60) stops the
program with a message that names the test and asks "an endless loop?". Checked
on a real test case that takes far longer than a tiny limit:

* with the limit at 0.05 s: exit status 124, the message on stderr, well before
  the test could have finished on its own;
* with ILLUM_GRADE_TEST_TIMEOUT=0 (switched off) and under the grader
  (ILLUM_GRADE_RECORDS_FD set: the grader keeps its own limit, from outside the
  program) the same test runs to its end and passes.

A crash does not end the run either (the supervisor of test_main.cpp): in
tests_harness's suite "supervisor", a test that raises SIGSEGV is named with the
signal and the test after it still runs, in a new process; the exit status is 1.

    python3 tests/e2e/watchdog_e2e.py --bin build/release/bin
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

# A grading test of lesson 09 that takes about a second: far above 0.05 s on any machine.
PROGRAM = "tests_lesson09_ungraded"  # the slow test below is an ungraded one
TEST = "the matrix to a tolerance is the same bit for bit on 1 and 2 threads, on a non-regular scene"


def run(program: Path, env_extra: dict[str, str]) -> tuple[int, str, float]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ILLUM_GRADE_")}
    env.update(env_extra)
    start = time.monotonic()
    done = subprocess.run([str(program), "-tc=" + TEST.split(",")[0] + "*", "--no-version"], env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, errors="replace", timeout=600)
    return done.returncode, done.stderr, time.monotonic() - start


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", type=Path, required=True, help="the build's bin folder")
    program = parser.parse_args().bin / PROGRAM
    problems = []

    status, stderr, _ = run(program, {"ILLUM_GRADE_TEST_TIMEOUT": "0"})
    if status != 0:
        problems.append(f"with the limit switched off the test should pass; exit {status}:\n{stderr[-2000:]}")
    # How long the test takes on its own here: the limit below must be far under it.
    _, _, alone = run(program, {"ILLUM_GRADE_TEST_TIMEOUT": "0"})

    status, stderr, seconds = run(program, {"ILLUM_GRADE_TEST_TIMEOUT": "0.05"})
    expected = f'the test case "{TEST}" did not finish within 0.05 s (an endless loop?)'
    if status != 124:
        problems.append(f"over the limit: exit status {status}, expected 124\n{stderr[-2000:]}")
    if expected not in stderr:
        problems.append(f"over the limit: stderr does not say {expected!r}:\n{stderr[-2000:]}")
    if alone > 0.5 and seconds > 0.8 * alone:
        problems.append(f"over the limit: stopped after {seconds:.2f} s, the test alone takes {alone:.2f} s")

    # Under the grader the grader's own limit applies: the program's watchdog stays off.
    read_end, write_end = os.pipe()
    os.close(read_end)  # nothing reads it: the test program is not run with the grader's reporter
    status, stderr, _ = run(program, {"ILLUM_GRADE_TEST_TIMEOUT": "0.05", "ILLUM_GRADE_RECORDS_FD": str(write_end)})
    os.close(write_end)
    if status != 0 or "endless loop" in stderr:
        problems.append(f"under the grader the watchdog must stay off; exit {status}:\n{stderr[-2000:]}")

    env = {k: v for k, v in os.environ.items() if not k.startswith("ILLUM_GRADE_")}
    done = subprocess.run([str(program.with_name("tests_harness")), "-ts=supervisor", "--no-version"],
                          env=dict(env, ILLUM_HARNESS_CRASH="1"), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          text=True, errors="replace", timeout=600)
    named = '[illum] the test case "supervisor: a test that crashes when asked" did not end: killed by SIGSEGV'
    if done.returncode != 1 or named not in done.stderr:
        problems.append(f"a crash: exit {done.returncode} (expected 1), stderr must name it:\n{done.stderr[-2000:]}")
    if "supervisor: the test after the crash ran" not in done.stdout:
        problems.append(f"a crash: the test after it did not run:\n{done.stdout[-2000:]}")

    for problem in problems:
        print(f"PROBLEM {problem}")
    print("watchdog: " + ("ok" if not problems else f"FAILED ({len(problems)} problem(s))"))
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main())
