"""``tools/grade --batch DIR``: a folder of submissions graded as the autograder grades one.

The pattern of otter-grader's ``otter grade``, without Gradescope: DIR holds
one folder or one zip per student (named by the student's id, user name or
e-mail). The grader is prepared once per worker exactly as on Gradescope:
the autograder zip is packed, unpacked and its setup.sh run (the reference
proved at full marks, hidden tests compiled and their sources removed, the
trusted test list kept). Each submission is then graded by
``run_autograder`` in a fresh copy of that prepared tree, as its own
unprivileged user, with the run limits of Gradescope. Several at once with
``--jobs``; progress on stderr.

Written to ``--out`` (default ``DIR-grades``):

* ``<id>/results.json``  Gradescope's results (what the student would read),
  ``<id>/grader.log`` the grader's log (for the instructor);
* ``grades.csv``  one row per student: id, status, total, maximum, one
  column per lesson and one per test; with ``--roster FILE.csv`` the
  roster's rows in its order, joined on an id or e-mail column, students
  without a submission listed as ``missing``;
* ``grades-moodle.csv`` / ``grades-canvas.csv`` with ``--format``: the
  columns those gradebooks import (tools/grading/gradebook.py).

The roster is read, and every submission matched to its row, before
anything is built: a roster that cannot be trusted (an id on two rows, a
submission matching two rows) stops the command with exit status 2.

Setup (the reference's build and proof) runs without the limits of a
student's run, as on Gradescope: its builds have no time limit unless
``ILLUM_GRADE_SETUP_BUILD_TIMEOUT`` sets one. A student's run keeps
Gradescope's (``ILLUM_GRADE_BUILD_TIMEOUT``, 300 s, for their rebuild), and
the whole of it ``ILLUM_GRADE_BATCH_TIMEOUT`` (1200 s). A limit that is hit
is named, with its variable, in the log and on stderr.

A student's status: ``graded``; ``partly gradable`` (a file of theirs did
not compile or link: its lesson says "not gradable", the rest is scored);
``not gradable`` (nothing of theirs compiled: no total, not a 0);
``missing`` (in the roster, no submission); ``grader error`` (not the
student's doing; the log says what).
"""
from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import zipfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from .autograder import RUN_LIMITS, pack_autograder
from .gradebook import (Outcome, Roster, RosterError, canvas_rows, csv_text, grades_rows, moodle_rows,
                        read_roster)
from .reports import write_text

MARKER = ".illum-grades"  # in --out: a folder this command wrote (so it may write there again)
STATUS_ORDER = ("graded", "partly gradable", "not gradable", "grader error", "missing")
BATCH_TIMEOUT = 1200.0  # seconds for one submission's run_autograder (ILLUM_GRADE_BATCH_TIMEOUT)


class BatchError(Exception):
    """The batch cannot be graded as asked (exit status 2)."""


@dataclass
class Submission:
    ident: str
    path: Path


def discover(folder: Path) -> tuple[list[Submission], list[str]]:
    """The submissions of ``folder`` and the entries that are not one (with why)."""
    found: dict[str, Submission] = {}
    skipped: list[str] = []
    for entry in sorted(folder.iterdir()):
        if entry.name.startswith(".") or entry.name == "__MACOSX":
            continue
        if entry.is_symlink():
            skipped.append(f"{entry.name}: a symbolic link (give the folder or zip itself)")
            continue
        if entry.is_dir():
            ident = entry.name
        elif entry.is_file() and entry.suffix.lower() == ".zip":
            ident = entry.stem
        else:
            skipped.append(f"{entry.name}: neither a folder nor a .zip (each student's work goes in a folder "
                           "or zip named after them)")
            continue
        if ident in found:
            raise BatchError(f"two submissions for {ident}: {found[ident].path.name} and {entry.name}")
        found[ident] = Submission(ident, entry)
    return list(found.values()), skipped


def outcome_of(ident: str, data: dict | None, log: str) -> Outcome:
    """A student's row, read from their results.json (its extra_data, written by tools/grade)."""
    outcome = Outcome(ident)
    info = (data or {}).get("extra_data", {}).get("illum") if isinstance(data, dict) else None
    if not info:
        outcome.status = "grader error"
        outcome.notes.append("no results from the grader" if data is None else "the grader itself failed")
        return outcome
    if info.get("grader_error"):
        outcome.status = "grader error"
        outcome.notes.append("the grader could not build the tree (see grader.log)")
        return outcome
    outcome.lessons = info.get("lessons", {})
    outcome.tests = {t["name"]: float(t["score"]) for t in info.get("tests", [])}
    for test in info.get("tests", []):
        if test.get("hidden"):
            outcome.has_hidden = True
        else:  # what the student may see: the visible tests' scores
            score, top = outcome.visible.get(test.get("lesson", ""), (0.0, 0.0))
            outcome.visible[test.get("lesson", "")] = (score + float(test["score"]),
                                                       top + float(test.get("max_score", 0)))
    statuses = [v.get("status") for v in outcome.lessons.values()]
    gradable = [nn for nn, v in outcome.lessons.items() if v.get("status") != "not gradable"]
    outcome.max_score = sum(float(v.get("max_score", 0)) for v in outcome.lessons.values())
    if not gradable:
        outcome.status = "not gradable"
    else:
        outcome.status = "graded" if all(s != "not gradable" for s in statuses) else "partly gradable"
        outcome.total = sum(float(outcome.lessons[nn].get("score", 0)) for nn in gradable)
    shared = list(info.get("not_gradable", []))
    if "none of your files is an exercise file" in (data or {}).get("output", ""):
        shared.append("no exercise file in the submission")
    outcome.notes.extend(shared)
    outcome.student_notes.extend(shared)
    if info.get("review"):
        outcome.notes.append(f"{len(info['review'])} note(s) for review in results.json")
    return outcome


def _jobs(requested: int | None, count: int) -> int:
    cores = os.cpu_count() or 1
    return max(1, min(requested or max(1, cores // 2), max(count, 1)))


def _hand_back(path: Path) -> None:
    """Under sudo, the outputs belong to the instructor who ran it, not to root."""
    uid, gid = os.environ.get("SUDO_UID"), os.environ.get("SUDO_GID")
    if os.geteuid() != 0 or not uid or not gid:
        return
    for item in [path, *path.rglob("*")]:
        if ".work" in item.relative_to(path).parts[:1]:
            continue
        try:
            os.chown(item, int(uid), int(gid), follow_symlinks=False)
        except OSError:
            pass


def run_environment(base: dict[str, str]) -> dict[str, str]:
    """A student's run: Gradescope's limits (RUN_LIMITS) where the instructor set none."""
    env = dict(base)
    for key, value in RUN_LIMITS.items():
        env.setdefault(key, value)
    return env


def setup_environment(base: dict[str, str]) -> dict[str, str]:
    """setup.sh's environment. As on Gradescope, where setup.sh runs without a student run's limits,
    RUN_LIMITS' defaults are not added (the limits you set yourself apply), and its builds (the whole
    library, cold) get ILLUM_GRADE_SETUP_BUILD_TIMEOUT seconds if it is set, else no limit:
    ILLUM_GRADE_BUILD_TIMEOUT (300 s) is the limit of a student's rebuild."""
    env = {k: v for k, v in base.items() if k != "ILLUM_GRADE_BUILD_TIMEOUT"}
    limit = base.get("ILLUM_GRADE_SETUP_BUILD_TIMEOUT", "").strip()
    if limit:
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
        self.work, self.zip_path, self.env = work, zip_path, env
        self.folders = [work / f"slot-{k}" for k in range(1, count + 1)]
        base = os.environ.get("ILLUM_GRADE_USER") or "illum-student"
        self.users = [base] + [f"{base}-{k}" for k in range(2, count + 1)]
        self.free = list(range(count))
        self.lock = threading.Lock()

    def prepare(self, k: int) -> tuple[int, str]:
        folder, ag = self.folders[k], self.folders[k] / "autograder"
        if folder.exists():
            shutil.rmtree(folder)
        folder.mkdir(parents=True)
        with zipfile.ZipFile(self.zip_path) as archive:
            archive.extractall(ag / "source")
        for name in ("setup.sh", "run_autograder", "illum/tools/grade"):
            (ag / "source" / name).chmod(0o755)
        (ag / "results").mkdir()
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
        import pwd

        try:
            gid = pwd.getpwnam(self.users[k]).pw_gid
        except KeyError:  # setup ran without a separate user (it said why)
            return
        os.chown(self.folders[k], 0, gid)
        self.folders[k].chmod(0o750)

    def take(self) -> int:
        with self.lock:
            return self.free.pop(0)

    def give(self, k: int) -> None:
        with self.lock:
            self.free.append(k)


def grade_one(slots: Slots, k: int, submission: Submission, out: Path, timeout: float) -> Outcome:
    folder = slots.folders[k]
    ag = folder / "autograder"
    if ag.exists():
        shutil.rmtree(ag)
    subprocess.run(["cp", "-a", "--reflink=auto", str(folder / "snapshot"), str(ag)], check=True)
    upload = ag / "submission"
    if upload.exists():
        shutil.rmtree(upload)
    if submission.path.is_dir():
        shutil.copytree(submission.path, upload, symlinks=True)
    else:
        upload.mkdir()
        shutil.copyfile(submission.path, upload / submission.path.name)
    env = dict(run_environment(slots.env), ILLUM_AUTOGRADER_ROOT=str(ag), ILLUM_GRADE_USER=slots.users[k])
    start = time.monotonic()
    log, stopped = run_limited(["bash", str(ag / "source" / "run_autograder")], env, timeout)
    if stopped:
        log += f"\n{stopped}\n"
    seconds = time.monotonic() - start
    target = out / submission.ident
    target.mkdir(parents=True, exist_ok=True)
    target.chmod(0o700)
    results = ag / "results" / "results.json"
    data = None
    if results.is_file():
        text = results.read_text(encoding="utf-8", errors="replace")
        write_text(target / "results.json", text)
        try:
            data = json.loads(text)
        except ValueError:
            data = None
    write_text(target / "grader.log", log[-2_000_000:])
    outcome = outcome_of(submission.ident, data, log)
    if stopped:
        outcome.notes.append(stopped)
    outcome.seconds = seconds
    return outcome


def run_limited(command: list[str], env: dict[str, str], timeout: float) -> tuple[str, str]:
    """(output, "" or why it was stopped): ``command`` in a session of its own, so that at the limit
    everything it started is stopped with it (killing bash alone would leave tools/grade running and
    the output pipe open)."""
    process = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               stdin=subprocess.DEVNULL, start_new_session=True)
    stopped = ""
    try:
        output, _ = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        stopped = (f"run_autograder did not finish within {timeout:g} s, the time limit of one submission "
                   "(ILLUM_GRADE_BATCH_TIMEOUT), and was stopped")
        try:
            os.killpg(process.pid, signal.SIGKILL)
        except OSError:
            pass
        output, _ = process.communicate()
    return output.decode("utf-8", errors="replace"), stopped


def grade_batch(root: Path, args, lessons: list[str]) -> int:
    from .driver import UsageError

    try:
        return _grade_batch(root, args, lessons)
    except (BatchError, RosterError) as error:
        raise UsageError(str(error)) from error


def _seconds(name: str, default: float | None) -> float | None:
    """A time limit from the environment, checked before anything is built."""
    text = os.environ.get(name, "").strip()
    if not text:
        return default
    try:
        value = float(text)
    except ValueError:
        value = 0.0
    if not value > 0 or value == float("inf"):
        raise BatchError(f"{name}={text}: not a number of seconds above 0 (unset it for the default)")
    return value


def _roster_rows(roster: Roster, outcomes: list[Outcome], matched: dict, unmatched: list[Submission]) -> list[Outcome]:
    """The roster's rows in its order (a student without a submission is ``missing``), then the
    submissions no row matches."""
    by_ident = {o.ident: o for o in outcomes}
    rows = []
    for index, row in enumerate(roster.rows):
        if index in matched:
            outcome = by_ident[matched[index].ident]
        else:
            outcome = Outcome(next((v for r in ("username", "email", "idnumber", "id") if (v := roster.value(row, r))),
                                   f"line {roster.lines[index]}"), status="missing")
        outcome.roster, outcome.line = row, roster.lines[index]
        rows.append(outcome)
    for submission in unmatched:
        outcome = by_ident[submission.ident]
        outcome.notes.append("not in the roster")
        rows.append(outcome)
    return rows


def _grade_batch(root: Path, args, lessons: list[str]) -> int:
    submissions_dir = args.batch.resolve()
    out = (args.out or submissions_dir.with_name(submissions_dir.name + "-grades")).resolve()
    if out == submissions_dir or submissions_dir in out.parents:
        raise BatchError(f"--out {out} is inside the submissions folder; put the grades elsewhere")
    if out.exists() and (not out.is_dir() or (any(out.iterdir()) and not (out / MARKER).exists())):
        raise BatchError(f"--out {out} exists and was not written by tools/grade --batch; choose another folder")
    timeout = _seconds("ILLUM_GRADE_BATCH_TIMEOUT", BATCH_TIMEOUT)
    _seconds("ILLUM_GRADE_SETUP_BUILD_TIMEOUT", None)
    roster = read_roster(args.roster) if args.roster else None
    submissions, skipped = discover(submissions_dir)
    if not submissions and roster is None:
        raise BatchError(f"--batch {submissions_dir}: no submission (a folder or a .zip per student)")
    # Matched now, not after an hour of grading: a roster that would lose a grade stops the command here.
    matched, unmatched = roster.match(submissions) if roster is not None else ({}, [])
    jobs = _jobs(args.jobs, len(submissions))
    privileged = os.geteuid() == 0
    say = lambda text: print(f"tools/grade --batch: {text}", file=sys.stderr, flush=True)  # noqa: E731
    for line in skipped:
        say(f"skipped {line}")
    for submission in unmatched:
        say(f"{submission.ident}: no row of the roster matches this submission; it is graded and listed last in "
            "grades.csv" + (f", and left out of grades-{args.format}.csv" if args.format else ""))
    if not privileged:
        say("WARNING: not running as root, so each submission runs as you, not as a user of its own: a hostile "
            "submission could read or change your files. Grade untrusted work with sudo (docs/grading.md, "
            "\"Threat model\").")
    out.mkdir(parents=True, exist_ok=True)
    out.chmod(0o711)  # the students' users may pass through, never list or read
    (out / MARKER).write_text("written by tools/grade --batch\n", encoding="utf-8")
    work = (args.work_dir.resolve() if args.work_dir else Path(tempfile.mkdtemp(prefix="illum-batch-")))
    if work.exists() and args.work_dir:
        shutil.rmtree(work)
    work.mkdir(parents=True, exist_ok=True)
    work.chmod(0o711)
    start = time.monotonic()
    try:
        zip_path = work / "autograder.zip"
        try:
            pack_autograder(root, zip_path, lessons, args.hidden)
        except (ValueError, OSError) as error:
            raise BatchError(f"the autograder could not be packed: {error}") from None
        cores = os.cpu_count() or 1
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1",
                   CMAKE_BUILD_PARALLEL_LEVEL=os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(max(1, cores // jobs))))
        if shutil.which("ccache"):  # each worker's tree at the same place under its base: they share objects
            env["CCACHE_NOHASHDIR"] = "1"
        slots = Slots(work, jobs, zip_path, env)
        limit = env.get("ILLUM_GRADE_SETUP_BUILD_TIMEOUT", "").strip()
        say(f"preparing the grader for lessons {', '.join(lessons)} in {jobs} worker(s): setup.sh builds and "
            "proves the reference, as on Gradescope (its builds: "
            + (f"{limit} s each, ILLUM_GRADE_SETUP_BUILD_TIMEOUT)" if limit else
               "no time limit; ILLUM_GRADE_SETUP_BUILD_TIMEOUT sets one)"))
        # The first worker alone: the others then find the library's objects in ccache, where it is installed.
        prepared = [slots.prepare(0)]
        if prepared[0][0] == 0 and jobs > 1:
            with ThreadPoolExecutor(max_workers=jobs - 1) as pool:
                prepared += list(pool.map(slots.prepare, range(1, jobs)))
        write_text(out / "setup.log", prepared[0][1])
        (out / "setup.log").chmod(0o600)
        for k, (status, log) in enumerate(prepared):
            if status != 0:
                why = explain_setup_failure(log, env)
                say(f"setup.sh failed in worker {k + 1} (its log: {out / 'setup.log'}):\n{log[-3000:]}"
                    + (f"\ntools/grade --batch: {why}" if why else ""))
                write_text(out / "setup.log", log + (f"\n{why}\n" if why else ""))
                return 2
        say(f"ready in {time.monotonic() - start:.0f} s; grading {len(submissions)} submission(s)")
        done_count = 0
        count_lock = threading.Lock()

        def work_on(submission: Submission) -> Outcome:
            nonlocal done_count
            k = slots.take()
            try:
                outcome = grade_one(slots, k, submission, out, timeout)
            except Exception as error:  # noqa: BLE001 -- one student's trouble must not stop the others
                outcome = Outcome(submission.ident, status="grader error", notes=[f"the batch failed: {error}"])
            finally:
                slots.give(k)
            with count_lock:
                done_count += 1
                say(f"[{done_count}/{len(submissions)}] {submission.ident}: {outcome.describe()}"
                    + (f" ({'; '.join(outcome.notes)})" if outcome.notes and outcome.status != "graded" else "")
                    + f", {outcome.seconds:.0f} s")
            return outcome

        with ThreadPoolExecutor(max_workers=jobs) as pool:
            outcomes = list(pool.map(work_on, submissions))
    finally:
        if not args.work_dir:
            shutil.rmtree(work, ignore_errors=True)

    rows = _roster_rows(roster, outcomes, matched, unmatched) if roster is not None else outcomes
    files = {"grades.csv": grades_rows(rows, lessons, roster)}
    left_out: list[str] = []
    if args.format == "moodle":
        files["grades-moodle.csv"], left_out = moodle_rows(rows, roster, args.assignment)
    elif args.format == "canvas":
        files["grades-canvas.csv"], left_out = canvas_rows(rows, roster, args.assignment)
    for name, table in files.items():
        write_text(out / name, csv_text(table))
        (out / name).chmod(0o600)
    for line in left_out:
        say(f"left out of grades-{args.format}.csv: {line}")
    _hand_back(out)
    counts = {status: sum(o.status == status for o in rows) for status in STATUS_ORDER}
    say(f"{len(submissions)} submission(s) in {time.monotonic() - start:.0f} s: "
        + ", ".join(f"{n} {status}" for status, n in counts.items() if n)
        + f"; wrote {', '.join(str(out / name) for name in files)}")
    return 1 if counts["grader error"] else 0
