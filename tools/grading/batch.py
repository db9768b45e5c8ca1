"""`tools/grade --batch DIR` (docs/grading.md, "Batch grading"): each worker prepares the autograder as on
Gradescope, then grades each submission (a folder or a zip per student) in a fresh copy of it as its own
user, with Gradescope's limits; grades.csv and the gradebooks' files (gradebook.py) go to --out."""
from __future__ import annotations

import itertools
import json
import os
import pwd
import queue
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import zipfile
from concurrent.futures import ThreadPoolExecutor
from contextlib import suppress
from dataclasses import dataclass
from pathlib import Path

from .autograder import RUN_LIMITS, pack_autograder
from .gradebook import Outcome, Roster, RosterError, canvas_rows, csv_text, grades_rows, moodle_rows, read_roster
from .reports import EXIT_NOT_BUILT, write_text
from .sandbox import kill_group

MARKER = ".illum-grades"  # in --out: a folder this command wrote (so it may write there again)
STATUS_ORDER = ("graded", "partly gradable", "not gradable", "grader error", "missing")
BATCH_TIMEOUT = 1200.0  # seconds for one submission's run_autograder (ILLUM_GRADE_BATCH_TIMEOUT)


class BatchError(Exception):
    """The batch cannot be graded as asked (exit status 2)."""


@dataclass
class Submission:
    ident: str
    path: Path


def say(text: str) -> None:
    print(f"tools/grade --batch: {text}", file=sys.stderr, flush=True)


def discover(folder: Path) -> tuple[list[Submission], list[str]]:
    """The submissions of `folder` and the entries that are not one (with why)."""
    found, skipped = {}, []
    for entry in sorted(folder.iterdir()):
        if entry.name.startswith(".") or entry.name == "__MACOSX":
            continue
        if entry.is_symlink():
            skipped.append(f"{entry.name}: a symbolic link (give the folder or zip itself)")
            continue
        if not entry.is_dir() and not (entry.is_file() and entry.suffix.lower() == ".zip"):
            skipped.append(f"{entry.name}: neither a folder nor a .zip (each student's work goes in a folder "
                           "or zip named after them)")
            continue
        ident = entry.name if entry.is_dir() else entry.stem
        if ident in found:
            raise BatchError(f"two submissions for {ident}: {found[ident].path.name} and {entry.name}")
        found[ident] = Submission(ident, entry)
    return list(found.values()), skipped


def outcome_of(ident: str, data: dict | None) -> Outcome:
    """A student's row, read from their results.json (its extra_data, written by tools/grade)."""
    outcome = Outcome(ident)
    info = data.get("extra_data", {}).get("illum") if isinstance(data, dict) else None
    if not info or info.get("grader_error"):
        outcome.status = "grader error"
        outcome.notes.append("the grader could not build the tree (see grader.log)" if info else
                             "no results from the grader" if data is None else "the grader itself failed")
        return outcome
    tests = info.get("tests", [])
    outcome.lessons, outcome.tests = info.get("lessons", {}), {t["name"]: float(t["score"]) for t in tests}
    outcome.has_hidden = any(t.get("hidden") for t in tests)
    for test in (t for t in tests if not t.get("hidden")):  # what the student may see: the visible tests' scores
        score, top = outcome.visible.get(lesson := test.get("lesson", ""), (0.0, 0.0))
        outcome.visible[lesson] = (score + float(test["score"]), top + float(test.get("max_score", 0)))
    gradable = [nn for nn, v in outcome.lessons.items() if v.get("status") != "not gradable"]
    outcome.max_score = sum(float(v.get("max_score", 0)) for v in outcome.lessons.values())
    outcome.status = ("not gradable" if not gradable else "graded" if len(gradable) == len(outcome.lessons)
                      else "partly gradable")
    outcome.total = sum(float(outcome.lessons[nn].get("score", 0)) for nn in gradable) if gradable else None
    shared = list(info.get("not_gradable", []))
    if "none of your files is an exercise file" in data.get("output", ""):
        shared.append("no exercise file in the submission")
    outcome.notes, outcome.student_notes = list(shared), shared
    if info.get("review"):
        outcome.notes.append(f"{len(info['review'])} note(s) for review in results.json")
    return outcome


def _hand_back(path: Path) -> None:
    """Under sudo, the outputs belong to the instructor who ran it, not to root."""
    uid, gid = os.environ.get("SUDO_UID"), os.environ.get("SUDO_GID")
    if os.geteuid() != 0 or not uid or not gid:
        return
    for item in [path, *path.rglob("*")]:
        if ".work" not in item.relative_to(path).parts[:1]:
            with suppress(OSError):
                os.chown(item, int(uid), int(gid), follow_symlinks=False)


def run_environment(base: dict[str, str]) -> dict[str, str]:
    """A student's run: Gradescope's limits (RUN_LIMITS) where the instructor set none."""
    return {**RUN_LIMITS, **base}


def setup_environment(base: dict[str, str]) -> dict[str, str]:
    """setup.sh's, as on Gradescope: without a student run's limits; its builds (the library, cold) get
    ILLUM_GRADE_SETUP_BUILD_TIMEOUT seconds if set, else none (not a student rebuild's limit)."""
    env = {k: v for k, v in base.items() if k != "ILLUM_GRADE_BUILD_TIMEOUT"}
    if limit := base.get("ILLUM_GRADE_SETUP_BUILD_TIMEOUT", "").strip():
        env["ILLUM_GRADE_BUILD_TIMEOUT"] = limit
    return env


def explain_setup_failure(log: str, env: dict[str, str]) -> str:
    """A sentence naming the time limit setup hit and the variable that changes it ("" if none was hit)."""
    limit = env.get("ILLUM_GRADE_SETUP_BUILD_TIMEOUT", "").strip()
    if limit and "the time limit of a build" in log:
        return (f"setup's build was stopped by its time limit, {limit} s (ILLUM_GRADE_SETUP_BUILD_TIMEOUT); "
                "raise it, or unset it for no limit")
    if "did not finish within" in log or "ILLUM_GRADE_DEADLINE" in log:
        return ("a test of the reference's proof ran out of time on this machine: the limits are "
                "ILLUM_GRADE_TEST_TIMEOUT (seconds per test), ILLUM_GRADE_TIMEOUT (per test program) and "
                "ILLUM_GRADE_DEADLINE (the whole run); raise the one the log names")
    return ""


class Slots:
    """Prepared trees, one per worker, each at the path where it grades (a CMake build tree cannot move)."""

    def __init__(self, work: Path, count: int, zip_path: Path, env: dict[str, str]) -> None:
        self.zip_path, self.env = zip_path, env
        self.folders = [work / f"slot-{k}" for k in range(1, count + 1)]
        base = os.environ.get("ILLUM_GRADE_USER") or "illum-student"
        self.users = [base] + [f"{base}-{k}" for k in range(2, count + 1)]
        self.free: queue.SimpleQueue[int] = queue.SimpleQueue()  # the slots no worker grades in now
        for k in range(count):
            self.free.put(k)

    def prepare(self, k: int) -> tuple[int, str]:
        folder, ag = self.folders[k], self.folders[k] / "autograder"
        if folder.exists():
            shutil.rmtree(folder)
        folder.mkdir(parents=True)
        unpack(self.zip_path, ag)
        env = dict(setup_environment(self.env), ILLUM_AUTOGRADER_ROOT=str(ag), ILLUM_GRADE_USER=self.users[k],
                   CCACHE_BASEDIR=str(ag))
        done = subprocess.run(["bash", str(ag / "source" / "setup.sh")], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, errors="replace", check=False)
        if done.returncode == 0:
            subprocess.run(["cp", "-a", "--reflink=auto", str(ag), str(folder / "snapshot")], check=True)
            self._close(k)
        return done.returncode, done.stdout

    def _close(self, k: int) -> None:
        """Only root and the slot's own user may enter a slot (another student's files are in the others)."""
        if os.geteuid() != 0:
            return
        try:
            gid = pwd.getpwnam(self.users[k]).pw_gid
        except KeyError:  # setup ran without a separate user (it said why)
            return
        os.chown(self.folders[k], 0, gid)
        self.folders[k].chmod(0o750)


def unpack(zip_path: Path, ag: Path) -> None:
    """The autograder zip unpacked as Gradescope does: into source/ (its scripts executable), with results/."""
    with zipfile.ZipFile(zip_path) as archive:
        archive.extractall(ag / "source")
    for name in ("setup.sh", "run_autograder", "illum/tools/grade"):
        (ag / "source" / name).chmod(0o755)
    (ag / "results").mkdir()


def fresh_copy(snapshot: Path, ag: Path, submission: Path | None = None) -> None:
    """The prepared autograder copied afresh to `ag`, `submission` (a folder, or a file such as a zip) its upload."""
    if ag.exists():
        shutil.rmtree(ag)
    subprocess.run(["cp", "-a", "--reflink=auto", str(snapshot), str(ag)], check=True)
    upload = ag / "submission"
    if upload.exists():
        shutil.rmtree(upload)
    if submission is not None and submission.is_dir():
        shutil.copytree(submission, upload, symlinks=True)
    else:
        upload.mkdir()
        if submission is not None:
            shutil.copyfile(submission, upload / submission.name)


def grade_one(slots: Slots, k: int, submission: Submission, out: Path, timeout: float) -> Outcome:
    ag = slots.folders[k] / "autograder"
    fresh_copy(slots.folders[k] / "snapshot", ag, submission.path)
    env = dict(run_environment(slots.env), ILLUM_AUTOGRADER_ROOT=str(ag), ILLUM_GRADE_USER=slots.users[k])
    start = time.monotonic()
    log, stopped = run_limited(["bash", str(ag / "source" / "run_autograder")], env, timeout)
    log += f"\n{stopped}\n" if stopped else ""
    seconds = time.monotonic() - start
    target = out / submission.ident
    target.mkdir(parents=True, exist_ok=True)
    target.chmod(0o700)
    results, data = ag / "results" / "results.json", None
    if results.is_file():
        text = results.read_text(encoding="utf-8", errors="replace")
        write_text(target / "results.json", text)
        with suppress(ValueError):
            data = json.loads(text)
    write_text(target / "grader.log", log[-2_000_000:])
    outcome = outcome_of(submission.ident, data)
    outcome.notes += [stopped] if stopped else []
    outcome.seconds = seconds
    return outcome


def run_limited(command: list[str], env: dict[str, str], timeout: float) -> tuple[str, str]:
    """(output, "" or why it was stopped): `command` in a session of its own, so that at the limit all it
    started is stopped with it (killing bash alone would leave tools/grade running, the pipe open)."""
    process = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               stdin=subprocess.DEVNULL, start_new_session=True)
    try:
        return process.communicate(timeout=timeout)[0].decode("utf-8", errors="replace"), ""
    except subprocess.TimeoutExpired:
        kill_group(process.pid)
        return (process.communicate()[0].decode("utf-8", errors="replace"),
                f"run_autograder did not finish within {timeout:g} s, the time limit of one submission "
                "(ILLUM_GRADE_BATCH_TIMEOUT), and was stopped")


def grade_batch(root: Path, args, lessons: list[str]) -> int:
    try:
        return Batch(root, args, lessons).run()
    except (BatchError, RosterError) as error:  # a wrong command, as the driver says it
        print(f"tools/grade: {error}", file=sys.stderr)
        return EXIT_NOT_BUILT


def _seconds(name: str, default: float | None) -> float | None:
    """A time limit from the environment, checked before anything is built."""
    text = os.environ.get(name, "").strip()
    if not text:
        return default
    value = 0.0
    with suppress(ValueError):
        value = float(text)
    if not value > 0 or value == float("inf"):
        raise BatchError(f"{name}={text}: not a number of seconds above 0 (unset it for the default)")
    return value


def _roster_rows(roster: Roster, outcomes: list[Outcome], matched: dict, unmatched: list[Submission]) -> list[Outcome]:
    """The roster's rows in its order (without a submission: `missing`), then the submissions no row matches."""
    by_ident = {o.ident: o for o in outcomes}
    rows = []
    for index, row in enumerate(roster.rows):
        outcome = by_ident[matched[index].ident] if index in matched else Outcome(next(
            (v for r in ("username", "email", "idnumber", "id") if (v := roster.value(row, r))),
            f"line {roster.lines[index]}"), status="missing")
        outcome.roster, outcome.line = row, roster.lines[index]
        rows.append(outcome)
    for submission in unmatched:
        by_ident[submission.ident].notes.append("not in the roster")
    return rows + [by_ident[s.ident] for s in unmatched]


class Batch:
    """One `tools/grade --batch` run: checked whole (folders, limits, roster) before anything is built."""

    def __init__(self, root: Path, args, lessons: list[str]):
        self.root, self.args, self.lessons = root, args, lessons
        self.submissions_dir = args.batch.resolve()
        self.out = (args.out or self.submissions_dir.with_name(self.submissions_dir.name + "-grades")).resolve()
        if self.out == self.submissions_dir or self.submissions_dir in self.out.parents:
            raise BatchError(f"--out {self.out} is inside the submissions folder; put the grades elsewhere")
        if self.out.exists() and (not self.out.is_dir() or (any(self.out.iterdir())
                                                            and not (self.out / MARKER).exists())):
            raise BatchError(f"--out {self.out} exists and was not written by tools/grade --batch; choose another "
                             "folder")
        self.timeout = _seconds("ILLUM_GRADE_BATCH_TIMEOUT", BATCH_TIMEOUT)
        _seconds("ILLUM_GRADE_SETUP_BUILD_TIMEOUT", None)
        self.roster = read_roster(args.roster) if args.roster else None
        self.submissions, self.skipped = discover(self.submissions_dir)
        if not self.submissions and self.roster is None:
            raise BatchError(f"--batch {self.submissions_dir}: no submission (a folder or a .zip per student)")
        # Matched now, not after an hour of grading: a roster that would lose a grade stops the command here.
        self.matched, self.unmatched = self.roster.match(self.submissions) if self.roster else ({}, [])
        self.jobs = max(1, min(args.jobs or max(1, (os.cpu_count() or 1) // 2), len(self.submissions)))

    def run(self) -> int:
        self._announce()
        self.out.mkdir(parents=True, exist_ok=True)
        self.out.chmod(0o711)  # the students' users may pass through, never list or read
        (self.out / MARKER).write_text("written by tools/grade --batch\n", encoding="utf-8")
        work = self.args.work_dir.resolve() if self.args.work_dir else Path(tempfile.mkdtemp(prefix="illum-batch-"))
        if work.exists() and self.args.work_dir:
            shutil.rmtree(work)
        work.mkdir(parents=True, exist_ok=True)
        work.chmod(0o711)
        start = time.monotonic()
        try:
            slots = self._prepare(work)
            if slots is None:
                return 2
            say(f"ready in {time.monotonic() - start:.0f} s; grading {len(self.submissions)} submission(s)")
            outcomes = self._grade_all(slots)
        finally:
            if not self.args.work_dir:
                shutil.rmtree(work, ignore_errors=True)
        return self._write(outcomes, start)

    def _announce(self) -> None:
        for line in self.skipped:
            say(f"skipped {line}")
        for submission in self.unmatched:
            say(f"{submission.ident}: no row of the roster matches this submission; it is graded and listed last in "
                "grades.csv" + (f", and left out of grades-{self.args.format}.csv" if self.args.format else ""))
        if os.geteuid() != 0:
            say("WARNING: not running as root, so each submission runs as you, not as a user of its own: a hostile "
                "submission could read or change your files. Grade untrusted work with sudo "
                "(docs/grading-defences.md, \"What is left\").")

    def _prepare(self, work: Path) -> Slots | None:
        """Packs the autograder and runs its setup in every worker's slot; None (setup.log says why) on a failure."""
        zip_path = work / "autograder.zip"
        try:
            pack_autograder(self.root, zip_path, self.lessons, self.args.hidden)
        except (ValueError, OSError) as error:
            raise BatchError(f"the autograder could not be packed: {error}") from None
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", CMAKE_BUILD_PARALLEL_LEVEL=os.environ.get(
            "CMAKE_BUILD_PARALLEL_LEVEL", str(max(1, (os.cpu_count() or 1) // self.jobs))))
        if shutil.which("ccache"):  # each worker's tree at the same place under its base: they share objects
            env["CCACHE_NOHASHDIR"] = "1"
        slots = Slots(work, self.jobs, zip_path, env)
        limit = env.get("ILLUM_GRADE_SETUP_BUILD_TIMEOUT", "").strip()
        say(f"preparing the grader for lessons {', '.join(self.lessons)} in {self.jobs} worker(s): setup.sh builds "
            "and proves the reference, as on Gradescope (its builds: "
            + (f"{limit} s each, ILLUM_GRADE_SETUP_BUILD_TIMEOUT)" if limit else
               "no time limit; ILLUM_GRADE_SETUP_BUILD_TIMEOUT sets one)"))
        # The first worker alone: the others then find the library's objects in ccache, where it is installed.
        prepared = [slots.prepare(0)]
        if prepared[0][0] == 0 and self.jobs > 1:
            with ThreadPoolExecutor(max_workers=self.jobs - 1) as pool:
                prepared += list(pool.map(slots.prepare, range(1, self.jobs)))
        # setup.log: the first worker's log, or the first failed one's with the limit it hit
        k, (status, log) = next(((k, p) for k, p in enumerate(prepared) if p[0] != 0), (0, prepared[0]))
        why = explain_setup_failure(log, env) if status != 0 else ""
        write_text(setup_log := self.out / "setup.log", log + (f"\n{why}\n" if why else ""), mode=0o600)
        if status != 0:
            say(f"setup.sh failed in worker {k + 1} (its log: {setup_log}):\n{log[-3000:]}"
                + (f"\ntools/grade --batch: {why}" if why else ""))
            return None
        return slots

    def _grade_all(self, slots: Slots) -> list[Outcome]:
        done, lock = itertools.count(1), threading.Lock()

        def work_on(submission: Submission) -> Outcome:
            k = slots.free.get()
            try:
                outcome = grade_one(slots, k, submission, self.out, self.timeout)
            except Exception as error:  # noqa: BLE001 -- one student's trouble must not stop the others
                outcome = Outcome(submission.ident, status="grader error", notes=[f"the batch failed: {error}"])
            finally:
                slots.free.put(k)
            with lock:
                say(f"[{next(done)}/{len(self.submissions)}] {submission.ident}: {outcome.describe()}"
                    + (f" ({'; '.join(outcome.notes)})" if outcome.notes and outcome.status != "graded" else "")
                    + f", {outcome.seconds:.0f} s")
            return outcome

        with ThreadPoolExecutor(max_workers=self.jobs) as pool:
            return list(pool.map(work_on, self.submissions))

    def _write(self, outcomes: list[Outcome], start: float) -> int:
        """grades.csv and the gradebook's file; 1 when a submission met a grader error."""
        rows = _roster_rows(self.roster, outcomes, self.matched, self.unmatched) if self.roster else outcomes
        files, left_out = {"grades.csv": grades_rows(rows, self.lessons, self.roster)}, []
        if self.args.format:
            make = moodle_rows if self.args.format == "moodle" else canvas_rows
            files[f"grades-{self.args.format}.csv"], left_out = make(rows, self.roster, self.args.assignment or "illum")
        for name, table in files.items():
            write_text(self.out / name, csv_text(table), mode=0o600)
        for line in left_out:
            say(f"left out of grades-{self.args.format}.csv: {line}")
        _hand_back(self.out)
        counts = {status: sum(o.status == status for o in rows) for status in STATUS_ORDER}
        say(f"{len(self.submissions)} submission(s) in {time.monotonic() - start:.0f} s: "
            + ", ".join(f"{n} {status}" for status, n in counts.items() if n)
            + f"; wrote {', '.join(str(self.out / name) for name in files)}")
        return 1 if counts["grader error"] else 0
