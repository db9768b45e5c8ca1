"""The main job's step "lessons": every BIN/lessonNN run into OUT/lessonNN, each run recorded in
OUT/run_log.json (its date, seconds, processor seconds, cores, load average and neighbours). Which run side
by side, and how a "mixed" one gets the whole machine: docs/build.md, "How the main job runs the lessons"."""

import contextlib
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import threading
import time
from collections import defaultdict
from pathlib import Path

from common.files import atomic_write_text

from . import JobError

PROGRAM = re.compile(r"^lesson(\d\d)$")


def say(message: str) -> None:
    print(f"main_job: {message}", flush=True)


def find_programs(bin_dir: Path) -> list[Path]:
    return sorted(p for p in bin_dir.glob("lesson*") if PROGRAM.match(p.name) and p.is_file() and os.access(p, os.X_OK))


def lesson_command(program: Path, out: Path, quick: bool) -> list[str]:
    return [str(program), "--out", str(out / program.name)] + (["--quick"] if quick else [])


def failure(program: Path, code: int, cmd: list[str]) -> str:
    return f"{program.name} failed (exit code {code}); its messages are above. Re-run it alone with: {' '.join(cmd)}"


def children_cpu_seconds() -> float:
    """Processor seconds of every finished child so far (all their threads, gnuplot included)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def load_average() -> list[float]:
    try:
        return [round(x, 2) for x in os.getloadavg()]
    except OSError:
        return []


def read_log(log_path: Path) -> dict:
    try:
        log = json.loads(log_path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return log if isinstance(log, dict) else {}


def record_run(log_path: Path, name: str, run: dict) -> None:
    """Adds one program's run to OUT/run_log.json (the figures' timing labels)."""
    log = read_log(log_path)
    log[name] = run
    atomic_write_text(log_path, json.dumps(log, indent=2, sort_keys=True) + "\n")


def now_utc() -> str:
    return time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())


def new_record(started: str, seconds: float, cpu: float, load_before: list[float], quick: bool) -> dict:
    return {"started": started, "seconds": round(seconds, 1), "cpu_seconds": round(cpu, 1), "cores": os.cpu_count(),
            "load_before": load_before, "load_after": load_average(), "quick": quick}


def timed_cores(program: Path) -> str:
    """"one" when every timing of the program uses one thread, "mixed" when those on more threads each ask
    for the whole machine first, else "all" (also when it cannot answer: it runs alone)."""
    try:
        answer = subprocess.run([str(program), "--timed-cores"], capture_output=True, text=True, errors="replace",
                                stdin=subprocess.DEVNULL, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return "all"
    word = answer.stdout.strip()
    return word if answer.returncode == 0 and word in ("one", "mixed") else "all"


def longest_first(programs: list[Path], log_path: Path) -> list[Path]:
    """The order that finishes a side-by-side run soonest: longest first by the last run_log.json (a
    "mixed" program's wait for the machine left out); without a record, the later lessons first."""
    log = read_log(log_path)

    def seconds(program: Path) -> float:
        run = log.get(program.name)
        value = run.get("seconds") if isinstance(run, dict) and not run.get("quick") else None
        if not isinstance(value, (int, float)):
            return -1.0
        waited = run.get("waited_seconds", 0)
        return max(0.0, value - waited) if isinstance(waited, (int, float)) else value

    if all(seconds(p) >= 0 for p in programs):
        return sorted(programs, key=lambda p: (-seconds(p), p.name))
    return sorted(programs, key=lambda p: p.name, reverse=True)


def run_lessons(bin_dir: Path, out: Path, quick: bool, alone: bool = False) -> None:
    programs = find_programs(bin_dir)
    if not programs:
        raise JobError(f"no lessonNN programs in {bin_dir} (build them first: cmake --build --preset release)")
    log_path = out / "run_log.json"
    all_start, all_cpu = time.monotonic(), children_cpu_seconds()
    numbers = {program: f"[{i}/{len(programs)}]" for i, program in enumerate(programs, 1)}
    answers = {} if alone else {p: timed_cores(p) for p in programs}
    one_core = [p for p in programs if answers.get(p) in ("one", "mixed")]
    cores = os.cpu_count() or 1
    if len(one_core) < 2 or cores < 2:
        one_core = []  # nothing to gain: every program runs alone, in order
    if one_core:
        width = min(cores, len(one_core))
        mixed = [p.name for p in one_core if answers[p] == "mixed"]
        say(f"{len(one_core)} program(s) time one thread"
            + (f" ({', '.join(mixed)} but for the studies it runs with the whole machine)" if mixed else " only")
            + f": {', '.join(p.name for p in one_core)} run side by side, {width} at once")
        SideBySide(answers, numbers, out, quick).run(longest_first(one_core, log_path), width, log_path)
    for program in programs:
        if program not in one_core:
            run_alone(program, numbers[program], out, quick, log_path)
    say(f"lessons done in {time.monotonic() - all_start:.1f} s "
        f"({children_cpu_seconds() - all_cpu:.1f} s of processor time; load average now {load_average()})")


def run_alone(program: Path, number: str, out: Path, quick: bool, log_path: Path) -> None:
    cmd = lesson_command(program, out, quick)
    say(f"{number} {' '.join(cmd)}")
    start, started, load_before, cpu_before = time.monotonic(), now_utc(), load_average(), children_cpu_seconds()
    code = subprocess.call(cmd, cwd=out, stdin=subprocess.DEVNULL)  # its output passes straight through
    if code != 0:
        raise JobError(failure(program, code, cmd))
    seconds, cpu = time.monotonic() - start, children_cpu_seconds() - cpu_before
    record_run(log_path, program.name, {**new_record(started, seconds, cpu, load_before, quick), "beside": []})
    say(f"{program.name} done in {seconds:.1f} s ({cpu:.1f} s of processor time, all its threads)")


class SideBySide:
    """Runs programs `width` at a time, each one's output kept in a file and printed whole when it ends (two
    programs' lines never mix), and records each run with the programs it overlapped. A "mixed" program asks
    for the whole machine through the pipes named in ILLUM_MAIN_JOB_FDS (docs/build.md). After a failure
    nothing new starts, the running ones finish, the runs that succeeded are recorded and the first failure
    (in lesson order) is raised."""

    def __init__(self, answers: dict[Path, str], numbers: dict[Path, str], out: Path, quick: bool):
        self.answers, self.numbers, self.out, self.quick = answers, numbers, out, quick
        self.cond = threading.Condition()
        self.todo: list[Path] = []
        self.state: dict[Path, str] = {}  # each running program: "one", "waiting" or "holding"
        self.grant_fds: dict[Path, int] = {}
        self.asked: dict[Path, float] = {}  # when a program asked for the machine, or got it
        self.waited: dict[Path, float] = defaultdict(float)
        self.held: dict[Path, float] = defaultdict(float)
        self.spans: dict[Path, tuple[float, float]] = {}
        self.runs: dict[Path, dict] = {}
        self.failures: list[tuple[Path, int, list[str]]] = []

    def run(self, queue: list[Path], width: int, log_path: Path) -> None:
        self.todo = list(queue)
        try:
            with self.cond:
                while self._schedule(width):
                    self.cond.wait()
        except BaseException:  # Ctrl-C: start nothing more (the running programs got the signal too)
            with self.cond:
                self.todo.clear()
            raise
        # Every run that finished is recorded, even when another failed: its outputs were committed.
        for program, record in sorted(self.runs.items()):
            start, end = self.spans[program]
            record["beside"] = sorted(other.name for other, (s, e) in self.spans.items()
                                      if other != program and s < end and start < e)
            record_run(log_path, program.name, record)
        if self.failures:
            raise JobError(failure(*min(self.failures, key=lambda f: f[0].name)))

    def _schedule(self, width: int) -> bool:
        """Starts what may start, grants the machine if it may be granted (the lock held); False when all is done."""
        busy = sum(1 for s in self.state.values() if s == "one")
        holder = "holding" in self.state.values()
        while self.todo and not self.failures and not holder and busy < width:
            program = self.todo.pop(0)
            self.state[program] = "one"
            busy += 1
            say(f"{self.numbers[program]} {' '.join(lesson_command(program, self.out, self.quick))} "
                "(side by side; its output when it ends)")
            threading.Thread(target=self._run_one, args=(program,)).start()
        waiting = [program for program, state in self.state.items() if state == "waiting"]
        if waiting and not holder and busy == 0 and (not self.todo or self.failures):
            program, now = min(waiting, key=self.asked.get), time.monotonic()  # the first to ask
            self.waited[program] += now - self.asked[program]
            self.asked[program] = now
            self.state[program] = "holding"
            say(f"{program.name} has the whole machine (no other program runs until it gives it back)")
            with contextlib.suppress(OSError):  # it ended meanwhile: _run_one records that
                os.write(self.grant_fds[program], b"go\n")
        return bool(self.state) or bool(self.todo and not self.failures)

    def _listen(self, program: Path, requests_fd: int) -> None:
        """Reads a mixed program's requests until it closes its end (it ended)."""
        with open(requests_fd, "r", encoding="utf-8", errors="replace") as requests:
            for line in requests:
                word = line.strip()
                with self.cond:
                    now, current = time.monotonic(), self.state.get(program)
                    if word == "machine" and current == "one":
                        self.state[program] = "waiting"
                        self.asked[program] = now
                    elif word == "release" and current == "holding":
                        self.state[program] = "one"
                        self.held[program] += now - self.asked.pop(program)
                    else:
                        say(f"warning: {program.name} sent {word[:40]!r} while {current or 'ended'}; ignored")
                    self.cond.notify_all()

    def _start(self, program: Path, cmd: list[str], log) -> subprocess.Popen | None:
        """Starts the program (a mixed one with its pipes and their listener); None when it cannot start."""
        env, pass_fds = None, ()
        if self.answers[program] == "mixed":
            from_job_r, from_job_w = os.pipe()  # the job's answers
            requests_fd, to_job_w = os.pipe()  # the program's requests
            env = dict(os.environ, ILLUM_MAIN_JOB_FDS=f"{from_job_r},{to_job_w}")
            pass_fds = (from_job_r, to_job_w)
        try:
            proc = subprocess.Popen(cmd, cwd=self.out, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                    env=env, pass_fds=pass_fds)
        except OSError as e:  # it could not start: a failure like any other, never a hang
            proc = None
            log.write(f"{program.name}: cannot start {cmd[0]}: {e}\n".encode())
        finally:
            for fd in pass_fds:
                os.close(fd)  # the program's ends: its exit then closes the requests pipe
        if pass_fds and proc is None:
            os.close(requests_fd)
            os.close(from_job_w)
        elif pass_fds:
            with self.cond:
                self.grant_fds[program] = from_job_w
            threading.Thread(target=self._listen, args=(program, requests_fd), daemon=True).start()
        return proc

    def _run_one(self, program: Path) -> None:
        """Runs one program, then records it (the lock held) and prints its output whole."""
        cmd = lesson_command(program, self.out, self.quick)
        start, started, load_before = time.monotonic(), now_utc(), load_average()
        with tempfile.TemporaryFile(mode="w+b") as log:
            proc, code = self._start(program, cmd, log), 127
            if proc is not None:  # wait4, not wait: this child's own processor time, whatever its neighbours use
                _, status, usage = os.wait4(proc.pid, 0)
                proc.returncode = code = os.waitstatus_to_exitcode(status)
            end = time.monotonic()
            log.seek(0)
            text = log.read().decode("utf-8", errors="replace")
        with self.cond:
            if self.state.pop(program, None) == "holding":
                self.held[program] += end - self.asked.pop(program)
            if program in self.grant_fds:
                os.close(self.grant_fds.pop(program))
            sys.stdout.write(text)
            sys.stdout.flush()
            self.spans[program] = (start, end)
            self.cond.notify_all()
            if code != 0:
                self.failures.append((program, code, cmd))
                return
            cpu = usage.ru_utime + usage.ru_stime
            self.runs[program] = new_record(started, end - start, cpu, load_before, self.quick)
            extra = ""
            if self.answers[program] == "mixed":
                waited, held = self.waited[program], self.held[program]
                self.runs[program].update(waited_seconds=round(waited, 1), whole_machine_seconds=round(held, 1))
                extra = f"; it waited {waited:.1f} s for the whole machine and held it {held:.1f} s"
            say(f"{program.name} done in {end - start:.1f} s ({cpu:.1f} s of processor time, all its threads{extra})")
