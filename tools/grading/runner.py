"""Running the ``lessonNN`` suite of one test program through our reporter.

Each suite is first listed (``--list-test-cases``: which tests exist, in the
order doctest runs them), then run. The reporter writes to a file of its own
(``--out``), so whatever a student's code prints on stdout cannot corrupt the
results, and it writes a ``started`` line before each test, so that when the
program crashes or hangs the driver knows which test did it.

Limits (Gradescope gives a whole run 10 minutes):

* each test case may run ``ILLUM_GRADE_TEST_TIMEOUT`` seconds (default 60)
  without finishing; then the program is killed;
* each run of a program may last ``ILLUM_GRADE_TIMEOUT`` seconds (default 600);
* all the tests of one ``tools/grade`` run may take ``ILLUM_GRADE_DEADLINE``
  seconds from its start (default: no limit; run_autograder sets one inside
  Gradescope's 10 minutes); the tests left when it runs out fail with
  "did not run", so that results.json is still written in time.

After a crash or a time-out, the test that was running fails with the
reason, and the program is run again from the next test on (doctest's
``--first=N`` counts the listed tests), so that one bad function costs the
tests that call it, not every test of the lesson.
"""
from __future__ import annotations

import os
import signal
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

from .results import TestResult, merge, parse_lines

DEFAULT_TIMEOUT = 600.0       # seconds per run of a test program
DEFAULT_TEST_TIMEOUT = 60.0   # seconds per test case


_deadline: float | None = None  # time.monotonic() after which no test starts


def set_deadline(seconds_from_now: float | None) -> None:
    global _deadline
    _deadline = None if seconds_from_now is None else time.monotonic() + seconds_from_now


def deadline_from_environment(start: float) -> None:
    """ILLUM_GRADE_DEADLINE seconds after ``start`` (a time.monotonic())."""
    value = os.environ.get("ILLUM_GRADE_DEADLINE")
    set_deadline(float(value) - (time.monotonic() - start) if value else None)


def _remaining() -> float:
    return float("inf") if _deadline is None else _deadline - time.monotonic()


def timeout_seconds() -> float:
    return float(os.environ.get("ILLUM_GRADE_TIMEOUT", DEFAULT_TIMEOUT))


def test_timeout_seconds() -> float:
    return float(os.environ.get("ILLUM_GRADE_TEST_TIMEOUT", DEFAULT_TEST_TIMEOUT))


@dataclass
class SuiteRun:
    """The results of one suite of one program, and what went wrong running it."""

    program: Path
    suite: str
    results: list[TestResult] = field(default_factory=list)
    problem: str = ""  # crashes, time-outs, a missing program (joined when several)
    output: str = ""   # the program's own stdout and stderr, for diagnosis


@dataclass
class _Invocation:
    records: list[dict]
    problem: str
    output: str


def _describe_exit(returncode: int) -> str:
    if returncode < 0:
        try:
            name = signal.Signals(-returncode).name
        except ValueError:
            name = f"signal {-returncode}"
        return f"the test program was killed by {name}"
    return f"the test program exited with status {returncode}"


def _kill(process: subprocess.Popen) -> None:
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        process.kill()
    process.wait()


def _run_reporter(program: Path, arguments: list[str], timeout: float, test_timeout: float) -> _Invocation:
    """One invocation with --reporters=illum-grade, killed when a test case
    makes no progress for ``test_timeout`` seconds or the whole run exceeds
    ``timeout``."""
    with tempfile.TemporaryDirectory(prefix="illum-grade-") as folder:
        out = Path(folder) / "records.jsonl"
        log = Path(folder) / "output.txt"
        command = [str(program), *arguments, "--reporters=illum-grade", f"--out={out}", "--no-version"]
        problem = ""
        with log.open("w+", encoding="utf-8", errors="replace") as sink:
            try:
                process = subprocess.Popen(command, stdout=sink, stderr=subprocess.STDOUT,
                                           stdin=subprocess.DEVNULL, start_new_session=True)
            except OSError as error:
                return _Invocation([], f"could not run {program}: {error}", "")
            start = last_progress = time.monotonic()
            seen = 0
            while True:
                try:
                    returncode = process.wait(timeout=0.05)
                    break
                except subprocess.TimeoutExpired:
                    pass
                now = time.monotonic()
                size = out.stat().st_size if out.exists() else 0
                if size != seen:  # a test started or finished
                    seen, last_progress = size, now
                if now - last_progress > test_timeout:
                    _kill(process)
                    problem = f"the test did not finish within {test_timeout:g} s (an endless loop?)"
                    returncode = None
                    break
                if now - start > timeout:
                    _kill(process)
                    problem = f"the test program did not finish within {timeout:g} s"
                    returncode = None
                    break
            # doctest exits with 1 when a test fails; anything else is a problem.
            if returncode is not None and returncode not in (0, 1):
                problem = _describe_exit(returncode)
            sink.seek(0)
            output = sink.read()
        text = out.read_text(encoding="utf-8", errors="replace") if out.exists() else ""
        return _Invocation(parse_lines(text.splitlines()), problem, output)


def _key(record: dict) -> tuple[str, str, str, int]:
    return TestResult.from_json(record).key


def _interrupted_test(records: list[dict]) -> dict | None:
    """The test that started and never finished (the one running at a crash)."""
    finished = {_key(r) for r in records if r.get("event") == "test_case"}
    started = [r for r in records if r.get("event") == "started"]
    if started and _key(started[-1]) not in finished:
        return started[-1]
    return None


def run_suite(program: Path, suite: str, hidden: bool = False, timeout: float | None = None,
              test_timeout: float | None = None) -> SuiteRun:
    """Runs ``program -ts=suite`` and returns one result per test of the suite."""
    timeout = timeout_seconds() if timeout is None else timeout
    test_timeout = test_timeout_seconds() if test_timeout is None else test_timeout
    run = SuiteRun(program, suite)
    if not program.exists():
        run.problem = f"{program} does not exist"
        return run
    listing = _run_reporter(program, [f"-ts={suite}", "--list-test-cases"], timeout, test_timeout)
    if listing.problem:
        run.problem, run.output = f"listing {program.name}: {listing.problem}", listing.output
        return run
    listed = [r for r in listing.records if r.get("event") == "listed"]
    position = {_key(r): number for number, r in enumerate(listed, start=1)}

    ran: list[dict] = []
    problems: list[str] = []
    outputs: list[str] = []
    notes: dict[tuple[str, str, str, int], str] = {}
    first = 1
    while first <= max(len(listed), 1):
        if _remaining() <= 0:
            problems.append(f"{program.name} -ts={suite}: the time for the whole run (ILLUM_GRADE_DEADLINE) "
                            "ran out before these tests")
            break
        arguments = [f"-ts={suite}"] + ([f"--first={first}"] if first > 1 else [])
        invocation = _run_reporter(program, arguments, min(timeout, max(_remaining(), 1.0)), test_timeout)
        ran.extend(r for r in invocation.records if r.get("event") == "test_case")
        outputs.append(invocation.output)
        if not invocation.problem:
            break
        culprit = _interrupted_test(invocation.records)
        if culprit is None or _key(culprit) not in position:
            problems.append(f"{program.name} -ts={suite}: {invocation.problem}")
            break
        notes[_key(culprit)] = f"did not finish: {invocation.problem}"
        problems.append(f"{program.name}: test \"{culprit.get('name', '')}\": {invocation.problem}")
        first = position[_key(culprit)] + 1  # go on with the tests after it
    why_missing = problems[-1] if problems else ""
    # The reporter reports every skip-decorated test, whatever its suite.
    results = [r for r in merge(listed, ran, hidden, why_missing=why_missing) if r.suite == suite]
    for result in results:
        if result.key in notes:  # it ran, and crashed or hung
            result.note, result.ran = notes[result.key], True
    run.results = results
    run.problem = "; ".join(problems)
    run.output = "".join(outputs)
    return run


def list_suites(program: Path, timeout: float | None = None) -> list[TestResult]:
    """Every test case of a program, whatever its suite (for misplaced-suite checks)."""
    timeout = timeout_seconds() if timeout is None else timeout
    listing = _run_reporter(program, ["--list-test-cases"], timeout, timeout)
    return [TestResult.from_json(r) for r in listing.records if r.get("event") == "listed"]
