"""Running the ``lessonNN`` suite of one test program through our reporter, in the sandbox (sandbox.py).

The reporter sends one JSON record per event over an inherited pipe; of the program's output only the
last 64 KB are kept. A program runs in one of three roles (``role``): ``None``, its own verdicts are
read (a student's own machine, the integrity checks, the mutants); ``"witness"``, a trusted build of the
reference that also sends every check's comparison and expected side; ``"observer"``, the student's
program built without expected sides, sending each check's left side, from which judge.py forms the
verdicts (docs/grading-defences.md, "How a test is judged").

The tests that should run come from ``expected`` (a trusted listing) or else ``--list-test-cases``. The
records must follow the reporter's order: ``started``, its checks, ``test_case`` of the same test, the
tests in listed order and each once, ``run_end`` last; a record out of order fails the running test as
tampering, and nothing after it is believed.

Limits (docs/grading-reference.md): processor time per test case (``ILLUM_GRADE_TEST_TIMEOUT``) and per
run of a program (``ILLUM_GRADE_TIMEOUT``), WALL_FACTOR times that of wall time (load does not change a
grade), and a deadline for the whole run (``ILLUM_GRADE_DEADLINE``) after which the tests left fail with
"did not run". After a crash, a time-out or an exit() inside a test, that test fails with the reason and
the program runs again from the next test (``--first=N``); each run must get further than the last, or
the tests left fail, once, with the reason.
"""
from __future__ import annotations

import json
import os
import selectors
import signal
import time
from dataclasses import dataclass, field
from pathlib import Path

from .judge import JudgeError, judge_test
from .results import TestResult, merge
from .sandbox import Sandbox, descendants_cpu_seconds

DEFAULT_TIMEOUT = 600.0       # seconds of processor time per run of a test program
DEFAULT_TEST_TIMEOUT = 60.0   # seconds of processor time per test case
WALL_FACTOR = 10.0            # wall time allowed per second of processor time (a machine at load 16 on two cores)
MAX_RECORD_BYTES = 1024 * 1024        # one record; the reporter cuts texts long before that
MAX_RECORDS_BYTES = 64 * 1024 * 1024  # all the records of one run

Key = tuple[str, str, str, int]

_deadline: float | None = None  # time.monotonic() after which no test starts
_sandbox: Sandbox | None = None


def set_deadline(seconds_from_now: float | None) -> None:
    global _deadline
    _deadline = None if seconds_from_now is None else time.monotonic() + seconds_from_now


def deadline_from_environment(start: float) -> None:
    """ILLUM_GRADE_DEADLINE seconds after ``start`` (a time.monotonic())."""
    value = os.environ.get("ILLUM_GRADE_DEADLINE")
    set_deadline(float(value) - (time.monotonic() - start) if value else None)


def set_sandbox(sandbox: Sandbox | None) -> None:
    """The sandbox every test program runs in from now on (None: a default one, as the caller)."""
    global _sandbox
    _sandbox = sandbox


def current_sandbox() -> Sandbox:
    global _sandbox
    _sandbox = _sandbox or Sandbox()
    return _sandbox


def _remaining() -> float:
    return float("inf") if _deadline is None else _deadline - time.monotonic()


def timeout_seconds() -> float:
    """Processor seconds for one run of a test program (ILLUM_GRADE_TIMEOUT)."""
    return float(os.environ.get("ILLUM_GRADE_TIMEOUT", DEFAULT_TIMEOUT))


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
    checks: dict = field(default_factory=dict)          # test key -> its check records (witness, observer)


@dataclass
class _Invocation:
    records: list[dict]
    problem: str          # why the run ended abnormally ('' when it ended normally)
    output: str
    exit_code: int | None = None
    garbage: int = 0      # complete lines that were not records
    survivors: list[str] = field(default_factory=list)


class _Tail:
    """The last ``limit`` bytes of a stream, and how many came before them."""

    def __init__(self, limit: int) -> None:
        self.limit, self.data, self.total = limit, bytearray(), 0

    def feed(self, chunk: bytes) -> bool:
        self.total += len(chunk)
        self.data += chunk
        if len(self.data) > self.limit:
            del self.data[:len(self.data) - self.limit]
        return False

    def text(self) -> str:
        text = self.data.decode("utf-8", errors="replace")
        cut = self.total - len(self.data)
        return (f"[... {cut} earlier bytes of output cut; the last {len(self.data)} are kept]\n" if cut else "") + text


class _Records:
    """Complete JSON lines of the records pipe; a half line at the end (a killed writer) is dropped."""

    def __init__(self) -> None:
        self.buffer, self.records, self.garbage, self.total, self.flooded = bytearray(), [], 0, 0, False

    def feed(self, chunk: bytes) -> bool:
        """True when a test started or finished (progress)."""
        self.total += len(chunk)
        if self.total > MAX_RECORDS_BYTES:
            self.flooded = True
            return False
        self.buffer += chunk
        progress = False
        while True:
            end = self.buffer.find(b"\n")
            if end < 0:
                if len(self.buffer) > MAX_RECORD_BYTES:
                    self.garbage += 1
                    self.buffer.clear()
                return progress
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
                progress = progress or record.get("event") in ("started", "test_case")
            else:
                self.garbage += 1


def _describe_signal(number: int) -> str:
    try:
        name = signal.Signals(number).name
    except ValueError:
        name = f"signal {number}"
    why = {
        "SIGSEGV": " (a crash: an invalid memory access, e.g. a null pointer or an index out of range)",
        "SIGABRT": " (an abort: a failed assert(), std::terminate, or a corrupted heap)",
        "SIGILL": " (an illegal instruction: an array index the bounds check caught, or a corrupted program)",
        "SIGFPE": " (an arithmetic fault, e.g. an integer division by zero)",
        "SIGKILL": " (killed from outside: out of memory, or too many processes)",
        "SIGXCPU": " (it used up its CPU time)",
        "SIGXFSZ": f" (it wrote a file larger than {current_sandbox().limits.file_mb} MB)",
    }.get(name, "")
    return f"the test program was killed by {name}{why}"


@dataclass
class _Watch:
    """The limits of one invocation: processor time per test and per run, wall time WALL_FACTOR times that."""

    test_cpu: float
    run_cpu: float
    start: float = field(default_factory=time.monotonic)
    progress_wall: float = field(default_factory=time.monotonic)
    progress_cpu: float = 0.0
    cpu: float = 0.0
    sampled: float = 0.0
    shared: int = 0
    shared_limit: int = 0
    end: float = float("inf")  # the deadline of the whole run (ILLUM_GRADE_DEADLINE), in wall time

    def problem(self, now: float, cpu_of, shared_of) -> str:
        """Why the program must be stopped now, or ''."""
        if now - self.sampled >= 0.25:
            self.cpu, self.shared, self.sampled = max(self.cpu, cpu_of()), shared_of(), now
        if self.shared_limit and self.shared > self.shared_limit:
            return (f"your code holds {self.shared >> 20} MB of shared memory, more than the "
                    f"{self.shared_limit >> 20} MB a test program may use")
        if self.cpu - self.progress_cpu > self.test_cpu:
            return f"the test did not finish within {self.test_cpu:g} s of processor time (an endless loop?)"
        if now - self.progress_wall > WALL_FACTOR * self.test_cpu:
            return (f"the test did not finish within {WALL_FACTOR * self.test_cpu:g} s (it waited, or the "
                    "machine was very busy)")
        if self.cpu > self.run_cpu or now - self.start > WALL_FACTOR * self.run_cpu:
            return f"the test program did not finish within {self.run_cpu:g} s of processor time"
        if now > self.end:
            return "the time for the whole run (ILLUM_GRADE_DEADLINE) ran out during this test"
        return ""

    def moved(self, now: float) -> None:
        self.progress_wall, self.progress_cpu = now, self.cpu


def _run_reporter(program: Path, arguments: list[str], timeout: float, test_timeout: float,
                  env: dict[str, str] | None = None, sandbox: Sandbox | None = None) -> _Invocation:
    """One invocation with --reporters=illum-grade, killed when it goes beyond a limit (``_Watch``)."""
    sandbox = sandbox or current_sandbox()
    command = [str(program), *arguments, "--reporters=illum-grade", "--no-version"]
    try:
        launched = sandbox.launch(command, cpu_seconds=timeout, extra_env=env)
    except OSError as error:
        return _Invocation([], f"could not run {program}: {error}", "")
    tail, records, status = _Tail(sandbox.limits.output_bytes), _Records(), _Records()
    selector = selectors.DefaultSelector()
    streams = {launched.output_fd: tail.feed, launched.records_fd: records.feed, launched.status_fd: status.feed}
    for fd in streams:
        os.set_blocking(fd, False)
        selector.register(fd, selectors.EVENT_READ)
    listing = "--list-test-cases" in arguments  # a listing runs no test: the deadline is for tests
    watch = _Watch(test_timeout, timeout, shared_limit=sandbox.limits.memory_mb << 20,
                   end=float("inf") if listing else time.monotonic() + _remaining())
    problem, stopping = "", False
    while True:
        if _drain(selector, streams, 0.05):
            watch.moved(time.monotonic())
        for record in status.records:
            if "pid" in record and not sandbox.namespace and launched.program_pid is None:
                launched.program_pid = int(record["pid"])
        if launched.process.poll() is not None:
            break
        if stopping:
            continue
        if records.flooded:
            problem = f"the test program sent more than {MAX_RECORDS_BYTES // (1024 * 1024)} MB of results"
        else:
            problem = watch.problem(time.monotonic(), lambda: descendants_cpu_seconds(launched.process.pid),
                                    sandbox.shared_memory_bytes)
        if problem:
            sandbox.stop(launched)
            stopping = True
    # What is still in the pipes (a process that outlived the program may keep
    # them open: a short, bounded drain, then the sandbox kills it).
    until = time.monotonic() + 0.5
    while selector.get_map() and time.monotonic() < until:
        _drain(selector, streams, 0.05)
    selector.close()
    survivors = sandbox.finish(launched)
    invocation = _Invocation(records.records, problem, tail.text(), garbage=records.garbage, survivors=survivors)
    _how_it_ended(invocation, status.records, bool(records.records), tail)
    return invocation


def _drain(selector: selectors.BaseSelector, streams: dict, wait: float) -> bool:
    """Reads what the pipes hold; True when a test started or finished (only the records' feed says so)."""
    progress = False
    for key, _ in selector.select(timeout=wait):
        try:
            chunk = os.read(key.fd, 1 << 16)
        except BlockingIOError:
            continue
        except OSError:
            chunk = b""
        if chunk:
            progress = streams[key.fd](chunk) or progress
        else:
            selector.unregister(key.fd)
    return progress


def _how_it_ended(invocation: _Invocation, status: list[dict], any_records: bool, tail: _Tail) -> None:
    """The exit status or signal the sandbox's first process reported (the program cannot forge it)."""
    ended = [r for r in status if "exited" in r or "signal" in r]
    if invocation.problem:
        return
    if not ended:
        invocation.problem = "the test program's launcher ended without saying how the program ended"
    elif "signal" in ended[-1]:
        invocation.problem = _describe_signal(int(ended[-1]["signal"]))
    else:
        invocation.exit_code = int(ended[-1]["exited"])
        if invocation.exit_code not in (0, 1):
            invocation.problem = (f"the test program could not start: {tail.text().strip()[-300:]}"
                                  if invocation.exit_code == 127 and not any_records
                                  else f"the test program exited with status {invocation.exit_code}")


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
        elif event == "test_case" and record.get("skipped") and running is None and key in order and key not in seen:
            seen.add(key)
            last, position = key, max(position, order[key])
        elif event == "test_case":
            if key != running:
                what = f"a result for \"{key[1]}\"" if key else "a result"
                return broken(f"{what} that was not running" if key not in seen else
                              f"a second result for \"{key[1]}\"", key)
            running = None
        elif event == "check" and running is None:  # a check belongs to the running test (witness, observer)
            return broken("a check outside any test")
        elif event == "run_end" and running is not None:
            return broken("the run ended while a test was still running")
        elif event not in ("check", "run_end"):
            return broken(f"a record of an unknown kind ({str(event)[:40]!r})", key)
        ended = event == "run_end"
        accepted.append(record)
    why = f"{garbage} line(s) on the results pipe that are not records" if garbage else ""
    return _Checked(accepted, running, last, why, (running or last) if garbage else None)


@dataclass
class _Progress:
    """What the invocations of one suite have established so far."""

    position: dict[Key, int]
    ran: dict[Key, dict] = field(default_factory=dict)
    notes: dict[Key, str] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)
    why_missing: str = ""


def _take(run: SuiteRun, progress: _Progress, checked: _Checked) -> None:
    """The accepted records of one invocation: each test's checks and result."""
    current: Key | None = None
    for record in checked.accepted:
        event = record.get("event")
        if event == "started":
            current = _key(record)
            run.checks[current] = []
        elif event == "check" and current is not None:
            run.checks[current].append(record)
        if event != "test_case":
            continue
        key = _key(record)
        if key in progress.ran:  # already reported by an earlier run of the program
            if record.get("skipped") and progress.ran[key].get("skipped"):
                continue  # doctest reports a skipped test again in every run
            checked.violation, checked.culprit = f"a second result for \"{key[1]}\"", key
            return
        progress.ran[key] = record


def _next_first(run: SuiteRun, progress: _Progress, checked: _Checked, invocation: _Invocation,
                first: int) -> int | None:
    """Where the next invocation starts after one that ended early, or None to stop."""
    program = run.program.name
    if checked.violation:
        run.tampering.append(f"{program} -ts={run.suite}: {checked.violation}")
        if checked.culprit is None:
            progress.why_missing = (f"the results of this run could not be trusted ({checked.violation}); "
                                    "nothing after that point was believed")
            progress.problems.append(f"{program} -ts={run.suite}: {progress.why_missing}")
            return None
        progress.ran.pop(checked.culprit, None)
        progress.notes[checked.culprit] = (f"failed as tampering: {checked.violation} (the grader accepts one result "
                                           "per test, in order, from the test program's reporter only)")
        progress.problems.append(f"{program}: test \"{checked.culprit[1]}\": tampering: {checked.violation}")
        return progress.position[checked.culprit] + 1
    exited = invocation.exit_code in (0, 1) and not invocation.problem
    if exited:
        how = f"exit({invocation.exit_code})"
        reason = (f"your code ended the program with {how} (or a similar call) during this test: "
                  "the tests after it were run again in a new program")
    else:
        how = invocation.problem
        reason = f"did not finish: {invocation.problem}"
    culprit = checked.running
    last = progress.ran.get(checked.last_recorded) if checked.last_recorded else None
    if culprit is None and last is not None and any(f.get("kind") == "crash" for f in last.get("failures", [])):
        # doctest reported the crash inside the test (its signal handler), then the program died.
        progress.problems.append(f"{program}: test \"{checked.last_recorded[1]}\": {how}")
        return progress.position[checked.last_recorded] + 1
    if culprit is not None:
        progress.notes[culprit] = reason
        progress.problems.append(f"{program}: test \"{culprit[1]}\": {how}")
        return progress.position[culprit] + 1
    if checked.last_recorded is not None and progress.position[checked.last_recorded] >= first:
        progress.problems.append(f"{program} -ts={run.suite}: after test \"{checked.last_recorded[1]}\": {how}")
        return progress.position[checked.last_recorded] + 1
    progress.why_missing = f"{program} -ts={run.suite}: {how}" + (" before running a test" if exited else "")
    progress.problems.append(progress.why_missing)
    return None


def run_suite(program: Path, suite: str, hidden: bool = False, timeout: float | None = None,
              test_timeout: float | None = None, expected: list[dict] | None = None, role: str | None = None,
              env: dict[str, str] | None = None, sandbox: Sandbox | None = None) -> SuiteRun:
    """One result per test of ``program -ts=suite``. ``expected``: the tests that must report ("listed" records,
    in doctest's order) from a trusted listing, or None to list them from the program. ``role``: None,
    "witness" or "observer" (module doc); an observer's results are judged by ``judge_suite`` afterwards."""
    timeout = timeout_seconds() if timeout is None else timeout
    if test_timeout is None:
        test_timeout = float(os.environ.get("ILLUM_GRADE_TEST_TIMEOUT", DEFAULT_TEST_TIMEOUT))
    env = dict(env or {}, **({"ILLUM_GRADE_ROLE": role} if role else {}))
    run = SuiteRun(program, suite)
    if not program.exists():
        run.problem = f"{program} does not exist"
        return run
    if expected is not None:
        listed = [dict(r, event="listed") for r in expected]
    else:
        listing = _run_reporter(program, [f"-ts={suite}", "--list-test-cases"], timeout, timeout, env, sandbox)
        if listing.problem:
            run.problem, run.output = f"listing {program.name}: {listing.problem}", listing.output
            return run
        listed = [r for r in listing.records if r.get("event") == "listed" and r.get("suite") == suite]
    run.listed = listed
    progress = _Progress({})
    for number, record in enumerate(listed, start=1):
        progress.position.setdefault(_key(record), number)
    outputs: list[str] = []
    first: int | None = 1
    while first is not None and first <= max(len(listed), 1):
        if _remaining() <= 0:
            progress.why_missing = (f"{program.name} -ts={suite}: the time for the whole run (ILLUM_GRADE_DEADLINE) "
                                    "ran out before these tests")
            progress.problems.append(progress.why_missing)
            break
        arguments = [f"-ts={suite}"] + ([f"--first={first}"] if first > 1 else [])
        invocation = _run_reporter(program, arguments, min(timeout, max(_remaining(), 1.0)), test_timeout, env,
                                   sandbox)
        outputs.append(invocation.output)
        run.survivors.extend(invocation.survivors)
        checked = check_records(invocation.records, progress.position, first, invocation.garbage)
        _take(run, progress, checked)
        if not (checked.violation or invocation.problem) and invocation.exit_code in (0, 1) \
                and any(r.get("event") == "run_end" for r in invocation.records):
            break  # it ended normally
        after = _next_first(run, progress, checked, invocation, first)
        if after is not None and after <= first:  # no progress: the program dies before the test it starts at
            progress.why_missing = (f"{program.name} -ts={suite}: run again from test {first}, the program ended "
                                    f"before reaching it ({invocation.problem or checked.violation or 'no result'})")
            progress.problems.append(progress.why_missing)
            break
        first = after
    _finish(run, progress, hidden, outputs)
    return run


def _finish(run: SuiteRun, progress: _Progress, hidden: bool, outputs: list[str]) -> None:
    why_missing = progress.why_missing or (progress.problems[-1] if progress.problems else "")
    # The reporter reports every skip-decorated test, whatever its suite.
    results = [r for r in merge(run.listed, list(progress.ran.values()), hidden, why_missing=why_missing)
               if r.suite == run.suite]
    for result in results:
        if result.key in progress.notes:  # it ran, and crashed, hung, exited or lied
            result.note, result.ran, result.passed = progress.notes[result.key], True, False
        elif not result.ran and not progress.why_missing:
            result.note = "no result was received for this test (the program never reported it)"
        if any("bad_alloc" in f.exception or "bad_alloc" in f.message for f in result.failures):
            result.note = (f"out of memory: your code asked for more than the {current_sandbox().limits.memory_mb} MB "
                           "a test program may use" + (f"; {result.note}" if result.note else ""))
    run.results = results
    if run.survivors:
        progress.problems.append(f"{run.program.name} -ts={run.suite}: processes your code started were still "
                                 f"running after the test program ended; they were killed ({len(run.survivors)})")
    run.problem = "; ".join(progress.problems)
    run.output = "".join(outputs)


def _stopped(result: TestResult) -> str:
    """Why the observer's run of a test ended early, for the judge ('' when it ended normally)."""
    if result.note:
        return result.note
    for failure in result.failures:
        if failure.kind in ("exception", "crash", "timeout", "aborted"):
            return failure.exception or failure.message
    return ""


def judge_suite(run: SuiteRun, witness: dict[Key, list[dict]], hidden: bool) -> list[str]:
    """Replaces each observed test's verdict by the judge's (judge.py); returns the grader's own
    problems (a test the witness cannot judge), which are not the student's fault."""
    problems = []
    for result in run.results:
        checks = witness.get(result.key)
        if checks is None:
            problems.append(f"{run.program.name}: no trusted record of \"{result.name}\"")
            result.passed, result.note = False, "the grader has no trusted record of this test (not your fault)"
            continue
        if not result.ran:
            continue
        try:
            verdict = judge_test(checks, run.checks.get(result.key, []), _stopped(result), hidden)
        except JudgeError as error:
            problems.append(f"{run.program.name}: \"{result.name}\": {error}")
            result.passed, result.note = False, f"the grader cannot judge this test: {error} (not your fault)"
            continue
        crashes = [] if verdict.passed else [f for f in result.failures if f.kind == "crash"]
        result.passed, result.failures = verdict.passed, verdict.failures + crashes
        result.not_implemented_only = verdict.not_implemented_only
        if verdict.passed:
            result.note = ""
    return problems


def witness_checks(run: SuiteRun) -> dict[Key, list[dict]]:
    """The witness's check records of every test that passed there (the trusted expected sides)."""
    return {r.key: run.checks.get(r.key, []) for r in run.results if r.passed}


def list_suites(program: Path) -> list[TestResult]:
    """Every test case of a program, whatever its suite (for misplaced-suite checks)."""
    listing = _run_reporter(program, ["--list-test-cases"], timeout_seconds(), timeout_seconds())
    return [TestResult.from_json(r) for r in listing.records if r.get("event") == "listed"]
