"""Running the ``lessonNN`` suite of one test program through our reporter.

The test program runs in the sandbox (sandbox.py: its own process group or
pid namespace, the student's user when there is one, resource limits). Its
reporter sends one JSON record per event over an inherited pipe (the
trusted channel: nothing can rewrite a pipe afterwards), and its output
goes through another pipe of which only the last 64 KB are kept, so that a
program printing a gigabyte costs the grader nothing.

Which tests should run comes from ``expected`` when the caller has it (the
autograder stores the list its setup got from the reference build), else
from the program's own ``--list-test-cases``. A listed test that sends no
result fails. The records of one run must follow the reporter's order
(``started`` then ``test_case`` of the same test, tests in the listed
order, each once, ``run_end`` last); a record out of that order, or a
second record for a test, is tampering: the test that was running fails
with that word, and the records after it are not believed.

Limits (Gradescope gives a whole run 10 minutes):

* each test case may run ``ILLUM_GRADE_TEST_TIMEOUT`` seconds (default 60)
  without finishing; then the program is killed;
* each run of a program may last ``ILLUM_GRADE_TIMEOUT`` seconds (default 600);
* all the tests of one ``tools/grade`` run may take ``ILLUM_GRADE_DEADLINE``
  seconds from its start (default: no limit; run_autograder sets one inside
  Gradescope's 10 minutes); the tests left when it runs out fail with
  "did not run", so that results.json is still written in time.

After a crash, a time-out or an exit() inside a test, the test that was
running fails with the reason, and the program is run again from the next
test on (doctest's ``--first=N`` counts the listed tests), so that one bad
function costs the tests that call it, not every test of the lesson.
"""
from __future__ import annotations

import json
import os
import selectors
import signal
import time
from dataclasses import dataclass, field
from pathlib import Path

from .results import TestResult, merge, normal_file
from .sandbox import Sandbox

DEFAULT_TIMEOUT = 600.0       # seconds per run of a test program
DEFAULT_TEST_TIMEOUT = 60.0   # seconds per test case
MAX_RECORD_BYTES = 1024 * 1024        # one record; the reporter cuts texts long before that
MAX_RECORDS_BYTES = 32 * 1024 * 1024  # all the records of one run

Key = tuple[str, str, str, int]

_deadline: float | None = None  # time.monotonic() after which no test starts
_sandbox: Sandbox | None = None
_trusted_run = False  # the reference's run in setup: the programs send the expected values too


def set_deadline(seconds_from_now: float | None) -> None:
    global _deadline
    _deadline = None if seconds_from_now is None else time.monotonic() + seconds_from_now


def deadline_from_environment(start: float) -> None:
    """ILLUM_GRADE_DEADLINE seconds after ``start`` (a time.monotonic())."""
    value = os.environ.get("ILLUM_GRADE_DEADLINE")
    set_deadline(float(value) - (time.monotonic() - start) if value else None)


def set_trusted_run(trusted: bool) -> None:
    """In the autograder's run of the reference only: ILLUM_CHECK_APPROX sends its expected value and
    tolerance, which setup keeps (a submission's run never sends them, so nothing in it can copy them)."""
    global _trusted_run
    _trusted_run = trusted


def set_sandbox(sandbox: Sandbox | None) -> None:
    """The sandbox every test program runs in from now on (None: a default one, as the caller)."""
    global _sandbox
    _sandbox = sandbox


def current_sandbox() -> Sandbox:
    global _sandbox
    if _sandbox is None:
        _sandbox = Sandbox()
    return _sandbox


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
    output: str = ""   # the tail of the program's own stdout and stderr, for diagnosis
    tampering: list[str] = field(default_factory=list)  # for instructors: what did not add up
    survivors: list[str] = field(default_factory=list)  # processes left behind, killed
    listed: list[dict] = field(default_factory=list)    # the tests that should report, in order
    values: dict = field(default_factory=dict)          # test key -> its ILLUM_CHECK_APPROX records


@dataclass
class _Invocation:
    records: list[dict]
    problem: str          # why the run ended abnormally ('' when it ended normally)
    output: str
    exit_code: int | None = None
    signal: int | None = None
    timed_out: bool = False
    garbage: int = 0      # complete lines that were not records
    flooded: bool = False
    survivors: list[str] = field(default_factory=list)

    @property
    def ended_normally(self) -> bool:
        return (not self.problem and self.exit_code in (0, 1)
                and any(r.get("event") == "run_end" for r in self.records))


class _Tail:
    """The last ``limit`` bytes of a stream, and how many came before them."""

    def __init__(self, limit: int) -> None:
        self.limit, self.data, self.total = limit, bytearray(), 0

    def feed(self, chunk: bytes) -> None:
        self.total += len(chunk)
        self.data += chunk
        if len(self.data) > self.limit:
            del self.data[:len(self.data) - self.limit]

    def text(self) -> str:
        text = self.data.decode("utf-8", errors="replace")
        cut = self.total - len(self.data)
        return (f"[... {cut} earlier bytes of output cut; the last {len(self.data)} are kept]\n" if cut else "") + text


class _Records:
    """Complete JSON lines of the records pipe; a half line at the end (a killed writer) is dropped."""

    def __init__(self) -> None:
        self.buffer, self.records, self.garbage, self.total, self.flooded = bytearray(), [], 0, 0, False

    def feed(self, chunk: bytes) -> bool:
        """True when at least one complete record arrived."""
        self.total += len(chunk)
        if self.total > MAX_RECORDS_BYTES:
            self.flooded = True
            return False
        self.buffer += chunk
        got = False
        while True:
            end = self.buffer.find(b"\n")
            if end < 0:
                if len(self.buffer) > MAX_RECORD_BYTES:
                    self.garbage += 1
                    self.buffer.clear()
                return got
            line = bytes(self.buffer[:end])
            del self.buffer[:end + 1]
            if not line.strip():
                continue
            try:
                record = json.loads(line) if len(line) <= MAX_RECORD_BYTES else None
            except (json.JSONDecodeError, UnicodeDecodeError):
                record = None
            if isinstance(record, dict):
                self.records.append(record)
                got = True
            else:
                self.garbage += 1


def _describe_exit(returncode: int) -> str:
    if returncode < 0:
        return _describe_signal(-returncode)
    return f"the test program exited with status {returncode}"


def _describe_signal(number: int) -> str:
    try:
        name = signal.Signals(number).name
    except ValueError:
        name = f"signal {number}"
    sandbox = current_sandbox()
    why = {
        "SIGSEGV": " (a crash: an invalid memory access, e.g. a null pointer or an index out of range)",
        "SIGABRT": " (an abort: a failed assert(), std::terminate, or a corrupted heap)",
        "SIGFPE": " (an arithmetic fault, e.g. an integer division by zero)",
        "SIGKILL": " (killed from outside: out of memory, or too many processes)",
        "SIGXCPU": " (it used up its CPU time)",
        "SIGXFSZ": f" (it wrote a file larger than {sandbox.limits.file_mb} MB)",
    }.get(name, "")
    return f"the test program was killed by {name}{why}"


def _run_reporter(program: Path, arguments: list[str], timeout: float, test_timeout: float) -> _Invocation:
    """One invocation with --reporters=illum-grade, killed when a test case
    makes no progress for ``test_timeout`` seconds or the whole run exceeds
    ``timeout``."""
    sandbox = current_sandbox()
    command = [str(program), *arguments, "--reporters=illum-grade", "--no-version"]
    try:
        launched = sandbox.launch(command, cpu_seconds=timeout,
                                  extra_env={"ILLUM_GRADE_SEND_EXPECTED": "1"} if _trusted_run else None)
    except OSError as error:
        return _Invocation([], f"could not run {program}: {error}", "")
    tail, records, status = _Tail(sandbox.limits.output_bytes), _Records(), _Records()
    selector = selectors.DefaultSelector()
    streams = {launched.output_fd: tail.feed, launched.records_fd: records.feed, launched.status_fd: status.feed}
    for fd in streams:
        os.set_blocking(fd, False)
        selector.register(fd, selectors.EVENT_READ)
    start = last_progress = time.monotonic()
    problem, timed_out, stopping = "", False, False

    def drain(wait: float) -> None:
        for key, _ in selector.select(timeout=wait):
            try:
                chunk = os.read(key.fd, 1 << 16)
            except BlockingIOError:
                continue
            except OSError:
                chunk = b""
            if not chunk:
                selector.unregister(key.fd)
                continue
            if streams[key.fd](chunk) and key.fd == launched.records_fd:
                nonlocal last_progress
                last_progress = time.monotonic()  # a test started or finished

    while True:
        drain(0.05)
        for record in status.records:
            if "pid" in record and not sandbox.namespace and launched.program_pid is None:
                launched.program_pid = int(record["pid"])
        if launched.process.poll() is not None:
            break
        if stopping:
            continue
        now = time.monotonic()
        if records.flooded:
            problem = f"the test program sent more than {MAX_RECORDS_BYTES // (1024 * 1024)} MB of results"
        elif now - last_progress > test_timeout:
            problem, timed_out = f"the test did not finish within {test_timeout:g} s (an endless loop?)", True
        elif now - start > timeout:
            problem, timed_out = f"the test program did not finish within {timeout:g} s", True
        if problem:
            sandbox.stop(launched)
            stopping = True
    # What is still in the pipes (a process that outlived the program may keep
    # them open: a short, bounded drain, then the sandbox kills it).
    until = time.monotonic() + 0.5
    while selector.get_map() and time.monotonic() < until:
        drain(0.05)
    selector.close()
    survivors = sandbox.finish(launched)
    invocation = _Invocation(records.records, problem, tail.text(), garbage=records.garbage,
                             flooded=records.flooded, timed_out=timed_out, survivors=survivors)
    ended = [r for r in status.records if "exited" in r or "signal" in r]
    if ended and not problem:
        if "signal" in ended[-1]:
            invocation.signal = int(ended[-1]["signal"])
            invocation.problem = _describe_signal(invocation.signal)
        else:
            invocation.exit_code = int(ended[-1]["exited"])
            if invocation.exit_code not in (0, 1):
                invocation.problem = (f"the test program could not start: {tail.text().strip()[-300:]}"
                                      if invocation.exit_code == 127 and not records.records
                                      else _describe_exit(invocation.exit_code))
    elif not problem:
        invocation.problem = "the test program's launcher ended without saying how the program ended"
    return invocation


def _key(record: dict) -> Key:
    return TestResult.from_json(record).key


@dataclass
class _Checked:
    """The records of one invocation that follow the reporter's order, and what broke it."""

    accepted: list[dict]
    running: Key | None           # started, not finished when the records end
    last_recorded: Key | None     # the last test that has a started or test_case record
    violation: str = ""
    culprit: Key | None = None    # the test during which the order broke


def check_records(records: list[dict], order: dict[Key, int], first: int, garbage: int = 0) -> _Checked:
    """Accepts records while they follow the reporter's order (module doc)."""
    accepted: list[dict] = []
    running: Key | None = None
    last: Key | None = None
    seen: set[Key] = set()
    position = first - 1
    ended = False

    def broken(why: str, record_key: Key | None = None) -> _Checked:
        culprit = running or (record_key if record_key in order else None)
        return _Checked(accepted, running, last, why, culprit)

    for record in records:
        event = record.get("event")
        key = _key(record) if event in ("started", "test_case") else None
        if ended:
            return broken("a record arrived after the end of the run", key)
        if event == "started":
            if running is not None:
                return broken(f"a test started while \"{running[1]}\" was still running", key)
            if key in seen:
                return broken(f"a second record for \"{key[1]}\"", key)
            if key not in order:
                return broken(f"a record for \"{key[1]}\", which is not one of the graded tests", key)
            if order[key] <= position:
                return broken(f"\"{key[1]}\" reported out of order", key)
            position, running, last = order[key], key, key
            seen.add(key)
            accepted.append(record)
        elif event == "test_case":
            if record.get("skipped") and running is None and key in order and key not in seen:
                seen.add(key)
                last = key
                position = max(position, order[key])
                accepted.append(record)
                continue
            if key != running:
                what = f"a result for \"{key[1]}\"" if key else "a result"
                return broken(f"{what} that was not running" if key not in seen else
                              f"a second result for \"{key[1]}\"", key)
            running = None
            accepted.append(record)
        elif event == "value":  # a value the grader judges itself, of the running test
            if running is None:
                return broken("a checked value outside any test")
            accepted.append(record)
        elif event == "run_end":
            if running is not None:
                return broken("the run ended while a test was still running")
            ended = True
            accepted.append(record)
        else:
            return broken(f"a record of an unknown kind ({str(event)[:40]!r})", key)
    if garbage:
        return _Checked(accepted, running, last, f"{garbage} line(s) on the results pipe that are not records",
                        running or last)
    return _Checked(accepted, running, last)


def run_suite(program: Path, suite: str, hidden: bool = False, timeout: float | None = None,
              test_timeout: float | None = None, expected: list[dict] | None = None) -> SuiteRun:
    """Runs ``program -ts=suite`` and returns one result per test of the suite.

    ``expected``: the tests that must report (records of kind "listed", in
    doctest's order), from a trusted listing; None lists them from the program.
    """
    timeout = timeout_seconds() if timeout is None else timeout
    test_timeout = test_timeout_seconds() if test_timeout is None else test_timeout
    run = SuiteRun(program, suite)
    if not program.exists():
        run.problem = f"{program} does not exist"
        return run
    if expected is None:
        listing = _run_reporter(program, [f"-ts={suite}", "--list-test-cases"], timeout, test_timeout)
        if listing.problem:
            run.problem, run.output = f"listing {program.name}: {listing.problem}", listing.output
            return run
        listed = [r for r in listing.records if r.get("event") == "listed" and r.get("suite") == suite]
    else:
        listed = [dict(r, event="listed") for r in expected]
    position = {}
    for number, record in enumerate(listed, start=1):
        position.setdefault(_key(record), number)
    stored_values = {_key(r): r["values"] for r in listed if r.get("values")}
    run.listed = listed

    ran: dict[Key, dict] = {}
    problems: list[str] = []
    outputs: list[str] = []
    notes: dict[Key, str] = {}
    first = 1
    why_missing = ""
    while first <= max(len(listed), 1):
        if _remaining() <= 0:
            why_missing = (f"{program.name} -ts={suite}: the time for the whole run (ILLUM_GRADE_DEADLINE) "
                           "ran out before these tests")
            problems.append(why_missing)
            break
        arguments = [f"-ts={suite}"] + ([f"--first={first}"] if first > 1 else [])
        invocation = _run_reporter(program, arguments, min(timeout, max(_remaining(), 1.0)), test_timeout)
        outputs.append(invocation.output)
        run.survivors.extend(invocation.survivors)
        checked = check_records(invocation.records, position, first, invocation.garbage)
        current: Key | None = None
        for record in checked.accepted:
            event = record.get("event")
            if event == "started":
                current = _key(record)
                run.values[current] = []
            elif event == "value" and current is not None:
                run.values[current].append(record)
            if event != "test_case":
                continue
            key = _key(record)
            if key in ran:  # already reported by an earlier run of the program
                if record.get("skipped") and ran[key].get("skipped"):
                    continue  # doctest reports a skipped test again in every run
                checked.violation, checked.culprit = f"a second result for \"{key[1]}\"", key
                break
            ran[key] = record
        if checked.violation:
            run.tampering.append(f"{program.name} -ts={suite}: {checked.violation}")
            if checked.culprit is None:
                why_missing = (f"the results of this run could not be trusted ({checked.violation}); "
                               "nothing after that point was believed")
                problems.append(f"{program.name} -ts={suite}: {why_missing}")
                break
            ran.pop(checked.culprit, None)
            notes[checked.culprit] = (f"failed as tampering: {checked.violation} (the grader accepts one result "
                                      "per test, in order, from the test program's reporter only)")
            problems.append(f"{program.name}: test \"{checked.culprit[1]}\": tampering: {checked.violation}")
            first = position[checked.culprit] + 1
            continue
        if invocation.ended_normally:
            break
        if invocation.exit_code in (0, 1) and not invocation.problem:
            how = f"exit({invocation.exit_code})"
            reason = (f"your code ended the program with {how} (or a similar call) during this test: "
                      "the tests after it were run again in a new program")
        else:
            how = invocation.problem
            reason = f"did not finish: {invocation.problem}"
        culprit = checked.running
        last = ran.get(checked.last_recorded) if checked.last_recorded else None
        if culprit is None and last is not None and any(f.get("kind") == "crash" for f in last.get("failures", [])):
            # doctest reported the crash inside the test (its signal handler), then the program died.
            problems.append(f"{program.name}: test \"{checked.last_recorded[1]}\": {how}")
            first = position[checked.last_recorded] + 1
            continue
        if culprit is not None:
            notes[culprit] = reason
            problems.append(f"{program.name}: test \"{culprit[1]}\": {how}")
            first = position[culprit] + 1
        elif checked.last_recorded is not None and position[checked.last_recorded] >= first:
            # Between tests (doctest reports a crash inside a test itself, then the program dies).
            problems.append(f"{program.name} -ts={suite}: after test \"{checked.last_recorded[1]}\": {how}")
            first = position[checked.last_recorded] + 1
        else:
            why_missing = f"{program.name} -ts={suite}: {how}"
            if invocation.exit_code in (0, 1) and not invocation.problem:
                why_missing += " before running a test"
            problems.append(why_missing)
            break
    if not why_missing and problems:
        why_missing = problems[-1]
    # The reporter reports every skip-decorated test, whatever its suite.
    results = [r for r in merge(listed, list(ran.values()), hidden, why_missing=why_missing) if r.suite == suite]
    for result in results:
        if result.key in notes:  # it ran, and crashed, hung, exited or lied
            result.note, result.ran, result.passed = notes[result.key], True, False
        elif not result.ran and not why_missing:
            result.note = "no result was received for this test (the program never reported it)"
        stored = stored_values.get(result.key)
        if stored and result.passed:
            problem = judge_values(stored, run.values.get(result.key, []))
            if problem:
                result.passed = False
                result.note = f"checked by the grader outside your program: {problem}"
        if any("bad_alloc" in f.exception or "bad_alloc" in f.message for f in result.failures):
            result.note = (f"out of memory: your code asked for more than the {current_sandbox().limits.memory_mb} MB "
                           "a test program may use" + (f"; {result.note}" if result.note else ""))
    run.results = results
    if run.survivors:
        problems.append(f"{program.name} -ts={suite}: processes your code started were still running after the "
                        f"test program ended; they were killed ({len(run.survivors)})")
    run.problem = "; ".join(problems)
    run.output = "".join(outputs)
    return run


def approx_equal(actual: float, expected: float, epsilon: float, scale: float = 1.0) -> bool:
    """doctest's Approx: |a − e| < ε·(scale + max(|a|, |e|))."""
    return abs(actual - expected) < epsilon * (scale + max(abs(actual), abs(expected)))


def judge_values(stored: list[dict], sent: list[dict]) -> str:
    """Why the values a test sent do not match what the trusted run kept, or ''.

    ``stored``: [{"file", "line", "expected", "epsilon"}] in the order the
    reference sent them; ``sent``: the "value" records of this run."""
    counts: dict[tuple[str, int], int] = {}
    mine: dict[tuple[str, int, int], object] = {}
    for record in sent:
        at = (normal_file(str(record.get("at_file", ""))), int(record.get("at_line", 0) or 0))
        counts[at] = counts.get(at, 0) + 1
        mine[(*at, counts[at])] = record.get("actual")
    seen: dict[tuple[str, int], int] = {}
    for check in stored:
        at = (normal_file(str(check["file"])), int(check["line"]))
        seen[at] = seen.get(at, 0) + 1
        where = f"{at[0]}:{at[1]}"
        actual = mine.get((*at, seen[at]))
        if actual is None:
            return f"the value checked at {where} was never computed (expected {float(check['expected'])!r})"
        try:
            ok = approx_equal(float(actual), float(check["expected"]), float(check["epsilon"]))
        except (TypeError, ValueError):
            ok = False
        if not ok:
            return (f"the value checked at {where} is {actual!r}, expected {float(check['expected'])!r} "
                    f"(within a relative {check['epsilon']:g})")
    extra = sum(counts.values()) - len(stored)
    if extra > 0:
        return f"{extra} more checked value(s) than the test makes"
    return ""


def list_suites(program: Path, timeout: float | None = None) -> list[TestResult]:
    """Every test case of a program, whatever its suite (for misplaced-suite checks)."""
    timeout = timeout_seconds() if timeout is None else timeout
    listing = _run_reporter(program, ["--list-test-cases"], timeout, timeout)
    return [TestResult.from_json(r) for r in listing.records if r.get("event") == "listed"]
