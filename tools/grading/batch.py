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
  columns those gradebooks import.

A student's status: ``graded``; ``partly gradable`` (a file of theirs did
not compile or link: its lesson says "not gradable", the rest is scored);
``not gradable`` (nothing of theirs compiled: no total, not a 0);
``missing`` (in the roster, no submission); ``grader error`` (not the
student's doing; the log says what).
"""
from __future__ import annotations

import csv
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import zipfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

from .autograder import RUN_LIMITS, pack_autograder
from .reports import write_text

MARKER = ".illum-grades"  # in --out: a folder this command wrote (so it may write there again)
STATUS_ORDER = ("graded", "partly gradable", "not gradable", "grader error", "missing")
ID_HEADERS = {"id", "studentid", "student", "sisuserid", "sisloginid", "username", "user", "login", "userid",
              "idnumber", "identifier", "matricula", "dni"}
EMAIL_HEADERS = {"email", "emailaddress", "mail", "correo", "correoelectronico"}


class BatchError(Exception):
    """The batch cannot be graded as asked (exit status 2)."""


def _normal(header: str) -> str:
    return re.sub(r"[\s_\-.]", "", header.strip().lower())


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


@dataclass
class Roster:
    headers: list[str]
    rows: list[dict[str, str]]
    keys: list[str]        # the columns a submission's id is matched against
    email: str | None      # the e-mail column, if any

    def match(self, submissions: list[Submission]) -> tuple[dict[int, Submission], list[Submission]]:
        """Row index -> its submission, and the submissions no row matched."""
        by_value: dict[str, set[int]] = {}
        for index, row in enumerate(self.rows):
            for key in self.keys:
                value = row.get(key, "").strip().lower()
                if value:
                    by_value.setdefault(value, set()).add(index)
                    if key == self.email and "@" in value:
                        by_value.setdefault(value.split("@", 1)[0], set()).add(index)
        matched: dict[int, Submission] = {}
        unmatched = []
        for submission in submissions:
            rows = by_value.get(submission.ident.strip().lower(), set())
            if len(rows) == 1 and next(iter(rows)) not in matched:
                matched[next(iter(rows))] = submission
            else:
                unmatched.append(submission)
        return matched, unmatched


def read_roster(path: Path) -> Roster:
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as error:
        raise BatchError(f"--roster {path}: cannot be read as UTF-8 text: {error}") from None
    try:
        dialect = csv.Sniffer().sniff(text[:4096], delimiters=",;\t")
    except csv.Error:
        dialect = csv.excel
    reader = csv.reader(io.StringIO(text), dialect)
    rows = [row for row in reader if any(cell.strip() for cell in row)]
    if not rows:
        raise BatchError(f"--roster {path}: the file is empty")
    headers = [h.strip() for h in rows[0]]
    keys = [h for h in headers if _normal(h) in ID_HEADERS | EMAIL_HEADERS]
    email = next((h for h in headers if _normal(h) in EMAIL_HEADERS), None)
    if not keys:
        raise BatchError(f"--roster {path}: no id or e-mail column (looked for headers such as id, student id, "
                         f"username, login, email, e-mail; found: {', '.join(headers)})")
    records = []
    for row in rows[1:]:
        record = {h: (row[i].strip() if i < len(row) else "") for i, h in enumerate(headers)}
        if any(v.lower() == "points possible" for v in record.values()):
            continue  # Canvas's export carries the maximum in a second row
        if any(record.get(k) for k in keys):
            records.append(record)
    return Roster(headers, records, keys, email)


@dataclass
class Outcome:
    ident: str
    status: str = "missing"
    total: float | None = None
    max_score: float = 0.0
    lessons: dict[str, dict] = field(default_factory=dict)
    tests: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0
    roster: dict[str, str] = field(default_factory=dict)

    def describe(self) -> str:
        if self.status in ("graded", "partly gradable") and self.total is not None:
            percent = 100.0 * self.total / self.max_score if self.max_score else 0.0
            text = f"{self.total:g}/{self.max_score:g} ({percent:.0f}%)"
            return text + (f", {self.status}" if self.status != "graded" else "")
        return self.status


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
    statuses = [v.get("status") for v in outcome.lessons.values()]
    gradable = [nn for nn, v in outcome.lessons.items() if v.get("status") != "not gradable"]
    outcome.max_score = sum(float(v.get("max_score", 0)) for v in outcome.lessons.values())
    if not gradable:
        outcome.status = "not gradable"
    else:
        outcome.status = "graded" if all(s != "not gradable" for s in statuses) else "partly gradable"
        outcome.total = sum(float(outcome.lessons[nn].get("score", 0)) for nn in gradable)
    outcome.notes.extend(info.get("not_gradable", []))
    for file in info.get("flagged", {}):
        outcome.notes.append(f"{file} flagged (its lesson not graded)")
    if info.get("review"):
        outcome.notes.append(f"{len(info['review'])} note(s) for review in results.json")
    if "none of your files is an exercise file" in (data or {}).get("output", ""):
        outcome.notes.append("no exercise file in the submission")
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
        env = dict(self.env, ILLUM_AUTOGRADER_ROOT=str(ag), ILLUM_GRADE_USER=self.users[k], CCACHE_BASEDIR=str(ag))
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
    env = dict(slots.env, ILLUM_AUTOGRADER_ROOT=str(ag), ILLUM_GRADE_USER=slots.users[k])
    start = time.monotonic()
    try:
        done = subprocess.run(["bash", str(ag / "source" / "run_autograder")], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, timeout=timeout, check=False)
        log = done.stdout.decode("utf-8", errors="replace")
    except subprocess.TimeoutExpired as expired:
        log = (expired.stdout or b"").decode("utf-8", errors="replace") + f"\nrun_autograder took over {timeout:g} s\n"
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
    outcome.seconds = seconds
    return outcome


def _test_columns(outcomes: list[Outcome]) -> list[str]:
    seen: dict[str, None] = {}
    for outcome in outcomes:
        for name in outcome.tests:
            seen.setdefault(name, None)
    return list(seen)


def _number(x: float | None) -> str:
    return "" if x is None else f"{x:g}"


def grades_csv(outcomes: list[Outcome], lessons: list[str], roster: Roster | None) -> str:
    tests = _test_columns(outcomes)
    extra = [h for h in (roster.headers if roster else []) if h]
    header = ["id", *[f"roster: {h}" for h in extra], "status", "total", "max", *[f"lesson{nn}" for nn in lessons],
              *tests, "notes"]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(header)
    for o in outcomes:
        lesson_cells = []
        for nn in lessons:
            info = o.lessons.get(nn)
            if info is None:
                lesson_cells.append("")
            elif info.get("status") == "not gradable":
                lesson_cells.append("not gradable")
            else:
                lesson_cells.append(_number(float(info.get("score", 0))))
        test_cells = []
        for name in tests:
            lesson = re.match(r"lesson(\d\d)", name)
            gone = lesson and o.lessons.get(lesson.group(1), {}).get("status") == "not gradable"
            test_cells.append("" if gone or name not in o.tests else _number(o.tests[name]))
        writer.writerow([o.ident, *[o.roster.get(h, "") for h in extra], o.status, _number(o.total),
                         _number(o.max_score) if o.lessons else "", *lesson_cells, *test_cells, "; ".join(o.notes)])
    return buffer.getvalue()


def _feedback(o: Outcome) -> str:
    if o.status == "missing":
        return "no submission"
    if o.status in ("not gradable", "grader error"):
        return f"{o.status}: " + ("; ".join(o.notes) or "see the grader's log")
    parts = [f"{o.total:g}/{o.max_score:g}"] + [
        f"lesson {nn}: " + (v.get("status") if v.get("status") == "not gradable" else
                            f"{float(v.get('score', 0)):g}/{float(v.get('max_score', 0)):g}")
        for nn, v in sorted(o.lessons.items())]
    return "; ".join(parts + o.notes)


def _pick(row: dict[str, str], *names: str) -> str:
    """The value of the first of ``names`` (in that order) that the row has and fills."""
    by_name = {_normal(k): v for k, v in row.items() if v}
    return next((by_name[_normal(n)] for n in names if _normal(n) in by_name), "")


def moodle_csv(outcomes: list[Outcome], roster: Roster | None) -> str:
    """Moodle's grade import (Grades > Import > CSV file): a user column to map (e-mail, id number or
    user name), "Grade" mapped to the assignment's grade item, "Feedback comments" to its feedback."""
    identity = "Email address" if roster and roster.email else "ID number" if roster else "Username"
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([identity, "Full name", "Grade", "Feedback comments"])
    for o in outcomes:
        if roster and roster.email:
            who = o.roster.get(roster.email, "") or o.ident
        elif roster:
            who = next((o.roster.get(k, "") for k in roster.keys if o.roster.get(k)), o.ident)
        else:
            who = o.ident
        name = _pick(o.roster, "full name", "name", "student", "nombre") or _pick(o.roster, "first name")
        grade = _number(o.total) if o.status in ("graded", "partly gradable") else ""
        writer.writerow([who, name, grade, _feedback(o)])
    return buffer.getvalue()


def canvas_csv(outcomes: list[Outcome], roster: Roster | None, assignment: str) -> str:
    """Canvas's gradebook import: Student, ID, SIS User ID, SIS Login ID, Section, then the assignment's
    column (Canvas matches students on these; a "Points Possible" row gives the maximum)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["Student", "ID", "SIS User ID", "SIS Login ID", "Section", assignment])
    maximum = max((o.max_score for o in outcomes), default=0.0)
    writer.writerow(["Points Possible", "", "", "", "", _number(maximum)])
    for o in outcomes:
        row = o.roster
        grade = _number(o.total) if o.status in ("graded", "partly gradable") else ""
        writer.writerow([_pick(row, "student", "name") or o.ident, _pick(row, "id"), _pick(row, "sis user id"),
                         _pick(row, "sis login id", "login", "username") or (o.ident if not row else ""),
                         _pick(row, "section"), grade])
    return buffer.getvalue()


def grade_batch(root: Path, args, lessons: list[str]) -> int:
    from .driver import UsageError

    try:
        return _grade_batch(root, args, lessons)
    except BatchError as error:
        raise UsageError(str(error)) from error


def _grade_batch(root: Path, args, lessons: list[str]) -> int:
    submissions_dir = args.batch.resolve()
    out = (args.out or submissions_dir.with_name(submissions_dir.name + "-grades")).resolve()
    if out == submissions_dir or submissions_dir in out.parents:
        raise BatchError(f"--out {out} is inside the submissions folder; put the grades elsewhere")
    if out.exists() and (not out.is_dir() or (any(out.iterdir()) and not (out / MARKER).exists())):
        raise BatchError(f"--out {out} exists and was not written by tools/grade --batch; choose another folder")
    roster = read_roster(args.roster) if args.roster else None
    submissions, skipped = discover(submissions_dir)
    if not submissions and roster is None:
        raise BatchError(f"--batch {submissions_dir}: no submission (a folder or a .zip per student)")
    jobs = _jobs(args.jobs, len(submissions))
    privileged = os.geteuid() == 0
    say = lambda text: print(f"tools/grade --batch: {text}", file=sys.stderr, flush=True)  # noqa: E731
    for line in skipped:
        say(f"skipped {line}")
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
        pack_autograder(root, zip_path, lessons, args.hidden)
        cores = os.cpu_count() or 1
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1",
                   CMAKE_BUILD_PARALLEL_LEVEL=os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(max(1, cores // jobs))))
        for key, value in RUN_LIMITS.items():
            env.setdefault(key, value)
        if shutil.which("ccache"):  # each worker's tree at the same place under its base: they share objects
            env["CCACHE_NOHASHDIR"] = "1"
        slots = Slots(work, jobs, zip_path, env)
        say(f"preparing the grader for lessons {', '.join(lessons)} in {jobs} worker(s): setup.sh builds and "
            "proves the reference, as on Gradescope")
        # The first worker alone: the others then find the library's objects in ccache, where it is installed.
        prepared = [slots.prepare(0)]
        if prepared[0][0] == 0 and jobs > 1:
            with ThreadPoolExecutor(max_workers=jobs - 1) as pool:
                prepared += list(pool.map(slots.prepare, range(1, jobs)))
        write_text(out / "setup.log", prepared[0][1])
        (out / "setup.log").chmod(0o600)
        for k, (status, log) in enumerate(prepared):
            if status != 0:
                say(f"setup.sh failed in worker {k + 1} (its log: {out / 'setup.log'}):\n{log[-3000:]}")
                write_text(out / "setup.log", log)
                return 2
        say(f"ready in {time.monotonic() - start:.0f} s; grading {len(submissions)} submission(s)")
        timeout = float(os.environ.get("ILLUM_GRADE_BATCH_TIMEOUT", "1200"))
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

    rows: list[Outcome] = []
    if roster is not None:
        matched, unmatched = roster.match(submissions)
        by_ident = {o.ident: o for o in outcomes}
        for index, row in enumerate(roster.rows):
            if index in matched:
                outcome = by_ident[matched[index].ident]
            else:
                outcome = Outcome(_pick(row, "sis login id", "login", "username", "user", "email", "e-mail", "id",
                                        "student id", *roster.keys) or f"row {index + 2}", status="missing")
            outcome.roster = row
            rows.append(outcome)
        for submission in unmatched:
            outcome = by_ident[submission.ident]
            outcome.notes.append("not in the roster")
            rows.append(outcome)
            say(f"{submission.ident}: no row of the roster matches this submission")
    else:
        rows = outcomes
    write_text(out / "grades.csv", grades_csv(rows, lessons, roster))
    written = [out / "grades.csv"]
    if args.format == "moodle":
        write_text(out / "grades-moodle.csv", moodle_csv(rows, roster))
        written.append(out / "grades-moodle.csv")
    elif args.format == "canvas":
        write_text(out / "grades-canvas.csv", canvas_csv(rows, roster, args.assignment))
        written.append(out / "grades-canvas.csv")
    for path in written:
        path.chmod(0o600)
    _hand_back(out)
    counts = {status: sum(o.status == status for o in rows) for status in STATUS_ORDER}
    say(f"{len(submissions)} submission(s) in {time.monotonic() - start:.0f} s: "
        + ", ".join(f"{n} {status}" for status, n in counts.items() if n) + f"; wrote {', '.join(map(str, written))}")
    return 1 if counts["grader error"] else 0
