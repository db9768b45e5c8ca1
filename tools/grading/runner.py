"""Running the ``lessonNN`` suite of one test program through our reporter.

Each suite runs twice: ``--list-test-cases`` says which tests exist, the run
says how they went. The reporter writes to a file of its own (``--out``), so
whatever a student's code prints on stdout cannot corrupt the results, and
a crash or a time-out (an endless loop in a student's code) still leaves a
result for every test.
"""
from __future__ import annotations

import os
import signal
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from .results import TestResult, merge, parse_lines

# Seconds a test program may run; ILLUM_GRADE_TIMEOUT overrides.
DEFAULT_TIMEOUT = 600.0


def timeout_seconds() -> float:
    return float(os.environ.get("ILLUM_GRADE_TIMEOUT", DEFAULT_TIMEOUT))


@dataclass
class SuiteRun:
    """The results of one suite of one program, and what went wrong running it."""

    program: Path
    suite: str
    results: list[TestResult] = field(default_factory=list)
    problem: str = ""  # a crash, a time-out, a missing program
    output: str = ""   # the program's own stdout and stderr, for diagnosis


def _describe_exit(returncode: int) -> str:
    if returncode < 0:
        try:
            name = signal.Signals(-returncode).name
        except ValueError:
            name = f"signal {-returncode}"
        return f"the test program was killed by {name}"
    return f"the test program exited with status {returncode}"


def _run_reporter(program: Path, arguments: list[str], timeout: float) -> tuple[list[dict], str, str]:
    """(records, problem, program output) of one invocation with --reporters=illum-grade."""
    with tempfile.TemporaryDirectory(prefix="illum-grade-") as folder:
        out = Path(folder) / "records.jsonl"
        command = [str(program), *arguments, "--reporters=illum-grade", f"--out={out}", "--no-version"]
        problem = ""
        output = ""
        try:
            completed = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                       stdin=subprocess.DEVNULL, timeout=timeout, text=True, errors="replace")
            output = completed.stdout
            # doctest exits with 1 when a test fails; anything else is a problem.
            if completed.returncode not in (0, 1):
                problem = _describe_exit(completed.returncode)
        except subprocess.TimeoutExpired as expired:
            problem = f"the test program did not finish within {timeout:g} s (an endless loop?)"
            output = expired.stdout if isinstance(expired.stdout, str) else ""
        except OSError as error:
            return [], f"could not run {program}: {error}", ""
        text = out.read_text(encoding="utf-8", errors="replace") if out.exists() else ""
        return parse_lines(text.splitlines()), problem, output


def run_suite(program: Path, suite: str, hidden: bool = False, timeout: float | None = None) -> SuiteRun:
    """Runs ``program -ts=suite`` and returns one result per test of the suite."""
    timeout = timeout_seconds() if timeout is None else timeout
    run = SuiteRun(program, suite)
    if not program.exists():
        run.problem = f"{program} does not exist"
        return run
    listed, problem, output = _run_reporter(program, [f"-ts={suite}", "--list-test-cases"], timeout)
    if problem:
        run.problem, run.output = f"listing {program.name}: {problem}", output
        return run
    ran, problem, output = _run_reporter(program, [f"-ts={suite}"], timeout)
    # The reporter reports every skip-decorated test, whatever its suite.
    run.results = [r for r in merge(listed, ran, hidden, why_missing=problem) if r.suite == suite]
    if problem:
        run.problem = f"{program.name} -ts={suite}: {problem}"
    run.output = output
    return run


def list_suites(program: Path, timeout: float | None = None) -> list[TestResult]:
    """Every test case of a program, whatever its suite (for misplaced-suite checks)."""
    timeout = timeout_seconds() if timeout is None else timeout
    listed, _, _ = _run_reporter(program, ["--list-test-cases"], timeout)
    return [TestResult.from_json(r) for r in listed if r.get("event") == "listed"]
