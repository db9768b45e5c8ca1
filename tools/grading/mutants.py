"""`tools/grade --mutants`: how many plausible student bugs do the grading tests catch? (docs/grading-reference.md,
"Grading power: measuring it with mutants"). Each mutant (cpp_mutants.py) or hand-written student bug
(tests/mutants/student_bugs/*.bug) is built in a worker's copy of the tree, build/mutants/wK/, and the lesson's
grading suite run on it."""
from __future__ import annotations

import argparse
import os
import queue
import random
import re
import shlex
import shutil
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from . import project
from .cpp_mutants import Mutant, code_only, generate

EQUIVALENT_FILE = Path("tests") / "mutants" / "equivalent.txt"
BUGS_FOLDER = Path("tests") / "mutants" / "student_bugs"
WORK_DIR = Path("build") / "mutants"
_COPY_IGNORE = {"build", ".git", "node_modules", "out", "__pycache__"}
_TEST_CASE_LINE = re.compile(r"^TEST CASE:\s+(.*)$", re.M)


def all_mutants(root: Path, lesson: str) -> list[Mutant]:
    """The mutants of every reference unit under lib/ of the lesson's stubs, on the lines not in the stub."""
    mutants = []
    for stub in sorted((root / "exercises").glob(f"{lesson}_*/*.cpp")):
        if found := sorted((root / "lib").rglob(stub.name)):
            stub_lines = {line.strip() for line in stub.read_text(encoding="utf-8").splitlines()} - {""}
            mutants += generate(lesson, found[0].relative_to(root), found[0].read_text(encoding="utf-8"), stub_lines)
    return mutants


@dataclass
class Equivalents:
    reasons: dict[str, str] = field(default_factory=dict)  # key -> reason
    problems: list[str] = field(default_factory=list)

    def reason(self, mutant: Mutant) -> str | None:
        return self.reasons.get(mutant.equivalence_key())


def read_equivalents(path: Path) -> Equivalents:
    """``file: original line => mutated line  -- reason``, one a line; # comments."""
    result = Equivalents()
    if not path.exists():
        return result
    for number, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        key, sep, reason = line.rpartition(" -- ")
        if not sep or " => " not in key or ": " not in key or not reason.strip():
            result.problems.append(f"{path}:{number}: expected 'file: original => mutated -- reason'")
            continue
        unit, _, lines = key.partition(": ")
        original, _, mutated = lines.partition(" => ")
        result.reasons[f"{unit.strip()}: {code_only(original)} => {code_only(mutated)}"] = reason.strip()
    return result


@dataclass
class BugFile:
    path: Path
    lesson: str = ""
    unit: Path = Path()
    title: str = ""
    caught_by: str = ""  # the test the bug's author expects to fail first (for the reader; not enforced)
    edits: list[tuple[str, str]] = field(default_factory=list)  # (find, replace), each found exactly once


def read_bug(path: Path) -> BugFile:
    """A `.bug` file: `key: value` lines (lesson, unit, title, caught-by; # comments), then one or more
    `--- find` / `+++ replace` pairs, each followed by its lines verbatim."""
    header, *pairs = re.split(r"^--- find\n", path.read_text(encoding="utf-8"), flags=re.M)
    bug = BugFile(path)
    for line in (raw.strip() for raw in header.splitlines()):
        if "+++ replace" == line:
            raise ValueError(f"{path}: '+++ replace' without a '--- find' before it")
        if not line or line.startswith("#"):
            continue
        key, sep, value = (part.strip() for part in line.partition(":"))
        if not sep:
            raise ValueError(f"{path}: expected 'key: value', got {line!r}")
        if key not in ("lesson", "unit", "title", "caught-by"):
            raise ValueError(f"{path}: unknown key {key!r} (lesson, unit, title, caught-by)")
        setattr(bug, key.replace("-", "_"), Path(value) if key == "unit" else value)
    for pair in pairs:
        find, *replace = re.split(r"^\+\+\+ replace$\n?", pair, flags=re.M)
        if len(replace) > 1:
            raise ValueError(f"{path}: '+++ replace' without a '--- find' before it")
        if replace:
            bug.edits.append((find.removesuffix("\n"), replace[0].removesuffix("\n")))
    if not (bug.lesson and str(bug.unit) != "." and bug.title and bug.edits):
        raise ValueError(f"{path}: needs lesson, unit, title and at least one --- find / +++ replace pair")
    return bug


def bug_mutant(root: Path, bug: BugFile) -> Mutant:
    """The bug as a mutant of its unit: the whole file replaced by the edited one."""
    source = (root / bug.unit).read_text(encoding="utf-8")
    edited = source
    for find, replace in bug.edits:
        count = edited.count(find)
        if count != 1:
            raise ValueError(f"{bug.path.name}: the text to find occurs {count} times in {bug.unit} "
                             f"(expected once):\n{find}")
        edited = edited.replace(find, replace)
    line = source.count("\n", 0, len(os.path.commonprefix([source, edited]))) + 1
    return Mutant(bug.lesson, bug.unit, line, f"student bug {bug.path.stem}", 0, len(source), source, edited,
                  source_line=bug.title, mutated_line=bug.caught_by, source=source)


def read_bugs(root: Path, folder: Path) -> tuple[list[tuple[BugFile, Mutant]], list[str]]:
    """Every bug of ``folder`` with its mutant, and the problems of the files that could not be read."""
    found, problems = [], []
    for path in sorted(folder.glob("*.bug")):
        try:
            bug = read_bug(path)
            found.append((bug, bug_mutant(root, bug)))
        except (ValueError, OSError) as error:
            problems.append(str(error))
    return found, problems


def sync_tree(source: Path, destination: Path) -> None:
    """Mirrors source into destination, rewriting only changed files (the others keep their time stamps: no rebuild)."""
    seen: set[Path] = set()
    for folder, dirs, files in os.walk(source):
        here = Path(folder)
        target = destination / here.relative_to(source)
        dirs[:] = [d for d in dirs if d not in (_COPY_IGNORE if here == source else {"__pycache__"})]
        target.mkdir(parents=True, exist_ok=True)
        seen.add(target)
        for name in files:
            if here == source and name in _COPY_IGNORE:
                continue  # e.g. a node_modules symlink
            src, dst = here / name, target / name
            seen.add(dst)
            if src.is_symlink():  # copied as a link, never followed (it may point anywhere, or nowhere)
                if not dst.is_symlink() or os.readlink(dst) != os.readlink(src):
                    dst.unlink(missing_ok=True)
                    os.symlink(os.readlink(src), dst)
                continue
            if dst.is_symlink():
                dst.unlink()
            if not dst.exists() or dst.read_bytes() != src.read_bytes():
                shutil.copy(src, dst)  # the content and the mode
    for folder, _, files in os.walk(destination, topdown=False):
        here = Path(folder)
        if here.is_relative_to(destination / "build"):
            continue
        for name in files:
            if here / name not in seen:
                (here / name).unlink()
        if here not in seen and here != destination:
            shutil.rmtree(here, ignore_errors=True)


def _run(command: list[str], timeout: float | None = None) -> tuple[bool, str]:
    """(whether ``command`` succeeded, its output and errors together); a time-out fails, saying so."""
    try:
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              errors="replace", timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, f"the build did not finish within {timeout:g} s"
    return done.returncode == 0, done.stdout


class Workspace:
    """One worker's copy of the tree (``build/mutants/wK``) and its build tree, at the depth of build/release
    so that ccache's base_dir makes paths identical."""

    def __init__(self, root: Path, base: Path, number: int):
        self.root, self.src = root, base / f"w{number}"
        self.build = self.src / "build" / "release"
        self.current: Path | None = None  # the unit rewritten now, if any

    def prepare(self) -> tuple[bool, str]:
        sync_tree(self.root, self.src)
        command = ["cmake", "-S", str(self.src), "-B", str(self.build), "-DCMAKE_BUILD_TYPE=Release",
                   "-DILLUM_BUILD_TESTS=ON", "-DILLUM_WERROR=ON", "-DILLUM_EXERCISES=", "-DILLUM_HIDDEN_TESTS="]
        return _run(command + (["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []))

    def build_targets(self, targets: list[str], timeout: float, jobs: int = 1) -> tuple[bool, str]:
        return _run(["cmake", "--build", str(self.build), "-j", str(jobs), "--target", *targets], timeout)

    def write_unit(self, unit: Path, text: str) -> None:
        # One mutant at a time: a worker that moves on to another unit puts the previous one back first, or every
        # later mutant would also carry the last mutation of that unit (and be killed by it, not by its own).
        if self.current != unit:
            self.restore()
        (self.src / unit).write_text(text, encoding="utf-8")
        self.current = unit

    def restore(self) -> None:
        if self.current is not None:
            shutil.copyfile(self.root / self.current, self.src / self.current)
            self.current = None


def lesson_targets(root: Path, lesson: str) -> list[str]:
    targets = [f"tests_lesson{lesson}"]
    # The hidden program only when it holds this lesson's suite: linking it costs as much as the lesson's own.
    if any(f'"lesson{lesson}"' in path.read_text(encoding="utf-8", errors="replace")
           for path in project.hidden_sources(root)):
        targets.append("tests_hidden")
    return targets


def run_grading(workspace: Workspace, lesson: str, timeout: float, extra: tuple[str, ...] = ()) -> tuple[str, str]:
    """('killed' | 'survived' | 'timed out', first failing test) for the built tree. One failing test kills a
    mutant, so the suite runs with --abort-after=1: a wrong program stops at its first failed assertion instead
    of failing thousands (minutes), and a time-out then really means a program that does not finish."""
    for program in (workspace.build / "bin" / target for target in lesson_targets(workspace.root, lesson)):
        command = [str(program), f"-ts=lesson{lesson}", "--abort-after=1", "--no-version", "--no-colors", *extra]
        try:
            # One process: a mutant that crashes a test is killed there; the tests after it need not run.
            done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                  text=True, errors="replace", timeout=timeout,
                                  env=dict(os.environ, ILLUM_TEST_ONE_PROCESS="1"))
        except subprocess.TimeoutExpired:
            return "timed out", ""
        if done.returncode == 124 and "(an endless loop?)" in done.stdout:
            return "timed out", ""  # the test program's own per-test limit (tests/support/test_main.cpp)
        if done.returncode != 0:
            found = _TEST_CASE_LINE.search(done.stdout)
            return "killed", found.group(1).strip() if found else f"{program.name} exited with status {done.returncode}"
        if not extra and ("test cases:" not in done.stdout or re.search(r"test cases:\s+0 \|", done.stdout)):
            return "killed", f"{program.name} ran no lesson{lesson} test"
    return "survived", ""


@dataclass
class LessonReport:
    lesson: str
    generated: int = 0          # every mutant of the lesson
    equivalent: int = 0         # of them listed as equivalent
    mutants: list[Mutant] = field(default_factory=list)  # the ones run
    seconds: float = 0.0
    baseline_seconds: float = 0.0
    problem: str = ""

    def count(self, status: str, without: bool = False) -> int:
        return sum((m.status_without if without else m.status) == status for m in self.mutants)

    def detected(self, without: bool = False) -> int:
        return self.count("killed", without) + self.count("timed out", without)

    def scored(self, without: bool = False) -> int:
        return self.detected(without) + self.count("survived", without)

    def score(self, without: bool = False) -> float | None:
        scored = self.scored(without)
        return 100.0 * self.detected(without) / scored if scored else None


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="tools/grade --mutants",
        description="Mutation report: build small plausible bugs of the lessons' exercise units and count how "
                    "many the grading tests catch (see docs/grading-reference.md).")
    parser.add_argument("--mutants", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("lessons", nargs="*", metavar="NN", help="lessons (default: every lesson with exercises)")
    parser.add_argument("--sample", type=int, metavar="N",
                        help="a seeded random sample of N mutants per lesson (those listed as equivalent are then "
                             "left out of it)")
    parser.add_argument("--seed", type=int, default=1, metavar="S", help="seed of --sample (default 1)")
    parser.add_argument("--jobs", "-j", type=int, default=max(1, (os.cpu_count() or 2) // 2), metavar="J",
                        help="parallel workers, each with its own build tree (default: half the cores)")
    parser.add_argument("--report", type=Path, metavar="FILE", help="write the Markdown report here")
    parser.add_argument("--timeout", type=float, metavar="SECONDS",
                        help="seconds per suite run (default: 10 × the unmutated run, at least 20)")
    parser.add_argument("--list", action="store_true", help="list the mutants (after --sample) and stop")
    parser.add_argument("--only", action="append", default=[], metavar="ID",
                        help="run only the mutant with this id (from --list or a report); repeatable")
    parser.add_argument("--compare-without", metavar="GLOB",
                        help="also score every mutant against the suite without the test files matching GLOB "
                             "(doctest --source-file-exclude), e.g. to show what new tests add")
    parser.add_argument("--work-dir", type=Path, metavar="DIR", help=f"workers' trees (default {WORK_DIR})")
    parser.add_argument("--fail-under", type=float, metavar="PERCENT",
                        help="exit 1 if a lesson scores below PERCENT")
    parser.add_argument("--bugs", nargs="?", const=str(BUGS_FOLDER), metavar="DIR",
                        help="run the hand-written student bugs of DIR (default tests/mutants/student_bugs, "
                             "*.bug files) instead of generated mutants")
    args = parser.parse_args(argv)
    try:
        args.lessons = sorted(set(project.normalize_lesson(text) for text in args.lessons))
    except ValueError as error:
        parser.error(str(error))
    if args.sample is not None and args.sample < 1:
        parser.error("--sample N needs N ≥ 1")
    if args.jobs < 1:
        parser.error("--jobs J needs J ≥ 1")
    return args


def _bug_reports(root: Path, args: argparse.Namespace, lessons: list[str]) -> list[LessonReport]:
    folder = Path(args.bugs) if Path(args.bugs).is_absolute() else root / args.bugs
    bugs, problems = read_bugs(root, folder)
    for problem in problems:
        print(f"tools/grade --mutants --bugs: {problem}", file=sys.stderr)
    if problems:
        raise SystemExit(2)
    reports = [LessonReport(lesson, mutants=[m for bug, m in bugs if bug.lesson == lesson]) for lesson in lessons]
    for report in reports:
        report.generated = len(report.mutants)
        report.mutants = [m for m in report.mutants if not args.only or m.ident in args.only]
    return [report for report in reports if report.generated]


def choose(root: Path, args: argparse.Namespace, equivalents: Equivalents) -> list[LessonReport]:
    exercises = project.exercise_lessons(root)
    unknown = [nn for nn in args.lessons if nn not in exercises]
    if unknown:  # a wrong command: exit status 2, as every tools/grade command
        print(f"tools/grade --mutants: lesson(s) {', '.join(unknown)} have no exercise units; "
              f"lessons with exercises: {', '.join(exercises)}", file=sys.stderr)
        raise SystemExit(2)
    if getattr(args, "bugs", None):
        return _bug_reports(root, args, args.lessons or exercises)
    reports = []
    for lesson in args.lessons or exercises:
        chosen = every = all_mutants(root, lesson)
        if args.sample is not None and args.sample < len(every):
            # Drawn from every mutant, equivalent or not, so that listing an equivalent mutant later leaves
            # the rest of a seed's sample as it was (fair before/after runs).
            chosen = sorted(random.Random(f"{args.seed}:{lesson}").sample(every, args.sample),
                            key=lambda m: (str(m.unit), m.start))
        reports.append(LessonReport(lesson, len(every), sum(equivalents.reason(m) is not None for m in every),
                                    [m for m in chosen if equivalents.reason(m) is None
                                     and (not args.only or m.ident in args.only)]))
    return reports


class Progress:
    def __init__(self, total: int):
        self.total, self.done, self.start = total, 0, time.monotonic()
        self.lock = threading.Lock()

    def report(self, mutant: Mutant) -> None:
        with self.lock:
            self.done += 1
            elapsed = time.monotonic() - self.start
            left = elapsed / self.done * (self.total - self.done)
            what = (mutant.source_line if mutant.operator.startswith("student bug") else
                    f"{mutant.original!r} -> {mutant.replacement!r}")
            print(f"[{self.done}/{self.total} {elapsed:5.0f} s, ~{left:4.0f} s left] {mutant.status:13} "
                  f"{mutant.unit.name}:{mutant.line} {mutant.operator}: {what}"
                  + (f"  ({mutant.failed_test})" if mutant.failed_test else ""),
                  file=sys.stderr, flush=True)


def run_lesson(report: LessonReport, workspaces: list[Workspace], timeout_arg: float | None,
               compare_without: str | None = None) -> None:
    root = workspaces[0].root
    start = time.monotonic()
    targets = lesson_targets(root, report.lesson)
    # Baseline: each worker builds the unmutated tree; the suite must pass on it.
    # The first build of a tree compiles the whole library: share the cores among the workers.
    build_jobs = max(1, (os.cpu_count() or 1) // len(workspaces))
    for workspace in workspaces:
        workspace.restore()
        ok, output = workspace.build_targets(targets, timeout=3600, jobs=build_jobs)
        if not ok:
            report.problem = f"the unmutated tree does not build in {workspace.build}:\n{output[-3000:]}"
            return
    t0 = time.monotonic()
    status, failed = run_grading(workspaces[0], report.lesson, timeout=timeout_arg or 600)
    report.baseline_seconds = time.monotonic() - t0
    if status != "survived":
        report.problem = f"the grading suite does not pass on the reference ({status}: {failed}); fix that first"
        return
    timeout = timeout_arg or max(20.0, 10 * report.baseline_seconds)
    progress = Progress(len(report.mutants))
    # Mutants of one unit go to one worker in turn, so it rewrites the file in place.
    work: queue.Queue[Mutant] = queue.Queue()
    for mutant in sorted(report.mutants, key=lambda m: (str(m.unit), m.start)):
        work.put(mutant)

    def worker(workspace: Workspace) -> None:
        while True:
            try:
                mutant = work.get_nowait()
            except queue.Empty:
                break
            workspace.write_unit(mutant.unit, mutant.apply())
            ok, _ = workspace.build_targets(targets, timeout=max(300.0, timeout))
            if not ok:
                mutant.status = mutant.status_without = "did not build"
            else:
                mutant.status, mutant.failed_test = run_grading(workspace, report.lesson, timeout)
                mutant.status_without = mutant.status
                if compare_without and mutant.status != "survived":
                    # Fewer tests cannot kill what the whole suite lets through: run only if it matters.
                    mutant.status_without, _ = run_grading(workspace, report.lesson, timeout,
                                                           (f"--source-file-exclude={compare_without}",))
            progress.report(mutant)

    threads = [threading.Thread(target=worker, args=(w,)) for w in workspaces]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    # Leave every tree with the unmutated sources (a worker that stopped on an error did not restore its own).
    for workspace in workspaces:
        workspace.restore()
    report.seconds = time.monotonic() - start


def summary_table(reports: list[LessonReport], compare_without: str | None = None) -> str:
    extra = f" score without `{compare_without}` |" if compare_without else ""
    lines = ["| lesson | mutants (equivalent) | run | killed | timed out | survived | did not build | score |"
             + extra + " time |",
             "|---|---|---|---|---|---|---|---|" + ("---|" if compare_without else "") + "---|"]
    for r in reports:
        score = "error" if r.problem else "n/a" if r.score() is None else f"**{r.score():.1f}%**"
        row = (f"| {r.lesson} | {r.generated} ({r.equivalent}) | {len(r.mutants)} | {r.count('killed')} | "
               f"{r.count('timed out')} | {r.count('survived')} | {r.count('did not build')} | {score} |")
        if compare_without:
            before = r.score(without=True)
            row += (" n/a |" if before is None or r.problem else
                    f" {before:.1f}% ({r.count('survived', True)} survived) |")
        lines.append(row + f" {r.seconds:.0f} s |")
    return "\n".join(lines)


def markdown_report(reports: list[LessonReport], command: str, compare_without: str | None = None) -> str:
    parts = [
        "# Grading power: the mutation report", "",
        "Produced by `tools/grade --mutants` (docs/grading-reference.md explains how to read it). Regenerate with:",
        "", "```sh", command, "```", "",
        "A *mutant* is a reference exercise unit with one plausible student mistake. **score** = "
        "(killed + timed out) / (killed + timed out + survived): the share of those mistakes the lesson's "
        "grading suite catches. Mutants listed in `tests/mutants/equivalent.txt` (no test could detect them) "
        "are left out; *did not build* mutants do not compile and are not scored. *time* is the whole "
        "lesson's run on this machine (two cores, shared).", "", summary_table(reports, compare_without), "",
    ]
    if compare_without:
        parts[-1:-1] = ["", f"*score without `{compare_without}`*: the same mutants against the suite without "
                        f"the test files matching `{compare_without}` (what the score was before those tests)."]
    for r in reports:
        parts += [f"## Lesson {r.lesson}", ""]
        if r.problem:
            parts += ["Not run: " + r.problem.splitlines()[0], ""]
            continue
        parts += [f"{len(r.mutants)} mutant(s) run of {r.generated} ({r.equivalent} equivalent left out); "
                  f"unmutated suite {r.baseline_seconds:.1f} s.", ""]
        survivors = [m for m in r.mutants if m.status == "survived"]
        if not survivors:
            parts += ["No survivor.", ""]
        for m in survivors:
            parts += [f"- survived: `{m.unit.as_posix()}:{m.line}` ({m.operator}, id `{m.ident}`)", "", "  ```diff"]
            parts += ["  " + line for line in m.diff().rstrip("\n").splitlines()]
            parts += ["  ```", ""]
    return "\n".join(parts).rstrip("\n") + "\n"


def bugs_report(reports: list[LessonReport], command: str) -> str:
    """Markdown: every hand-written student bug, whether the grading suite catches it, and by which test."""
    lines = ["# Student bugs: does the grading suite catch them?", "",
             "Produced by `tools/grade --mutants --bugs` (docs/grading-power.md). Regenerate with:", "", "```sh",
             command, "```", "",
             "Each bug is a mistake written by hand into a copy of a reference exercise unit "
             "(`tests/mutants/student_bugs/*.bug`), built and graded like a mutant.", "",
             "| lesson | bug | what the student did | status | first test that fails |", "|---|---|---|---|---|"]
    for r in reports:
        for m in r.mutants:
            name = m.operator.removeprefix("student bug ")
            test = m.failed_test.replace("|", "\\|") or "—"
            title = m.source_line.replace("|", "\\|")
            lines.append(f"| {r.lesson} | `{name}` | {title} | {m.status} | {test} |")
    caught = sum(r.detected() for r in reports)
    scored = sum(r.scored() for r in reports)
    lines += ["", f"Caught: {caught} of {scored}" + (f" ({100.0 * caught / scored:.0f}%)." if scored else "."), ""]
    return "\n".join(lines)


def _prepared_workspaces(root: Path, args: argparse.Namespace, reports: list[LessonReport]) -> list[Workspace] | None:
    """One configured tree per worker (as many as the largest lesson has mutants, at most --jobs)."""
    base = (args.work_dir or root / WORK_DIR).resolve()
    jobs = max(1, min(args.jobs, max(len(r.mutants) for r in reports) if reports else 1))
    workspaces = [Workspace(root, base, k) for k in range(jobs)]
    for workspace in workspaces:
        print(f"tools/grade --mutants: preparing {workspace.src}", file=sys.stderr, flush=True)
        ok, output = workspace.prepare()
        if not ok:
            print(output[-4000:], file=sys.stderr)
            print(f"tools/grade --mutants: could not configure {workspace.build}", file=sys.stderr)
            return None
    return workspaces


def main(argv: list[str]) -> int:
    args = parse_arguments(argv)
    root = project.ROOT
    if project.is_student_edition(root):
        print("tools/grade --mutants: mutants are made from the reference solutions, which the student edition "
              "does not have", file=sys.stderr)
        return 2
    equivalents = read_equivalents(root / EQUIVALENT_FILE)
    for problem in equivalents.problems:
        print(f"tools/grade --mutants: {problem}", file=sys.stderr)
    if equivalents.problems:
        return 2
    reports = choose(root, args, equivalents)
    if args.list:
        for r, m in ((r, m) for r in reports for m in r.mutants):
            where = f"{m.unit.as_posix()}:{m.line}"
            print(f"{m.ident} lesson{r.lesson} {m.operator.removeprefix('student bug ')} {where}: {m.source_line}"
                  if args.bugs else f"{m.ident} lesson{r.lesson} {where} {m.operator}: {m.source_line}  =>  "
                  f"{m.mutated_line}")
        return 0
    workspaces = _prepared_workspaces(root, args, reports)
    if workspaces is None:
        return 2
    for report in reports:
        print(f"tools/grade --mutants: lesson {report.lesson}: {len(report.mutants)} mutant(s) of "
              f"{report.generated}, {len(workspaces)} worker(s)", file=sys.stderr, flush=True)
        run_lesson(report, workspaces, args.timeout, args.compare_without)
        if report.problem:
            print(f"tools/grade --mutants: lesson {report.lesson}: {report.problem}", file=sys.stderr)
    command = "tools/grade " + shlex.join(argv if "--mutants" in argv else ["--mutants", *argv])
    if args.bugs:
        print(text := bugs_report(reports, command))
    else:
        print(summary_table(reports, args.compare_without))
        for m in (m for r in reports for m in r.mutants if m.status == "survived"):
            print(f"survived: {m.ident} {m.unit.as_posix()}:{m.line} {m.operator}: {m.source_line}  =>  "
                  f"{m.mutated_line}")
        text = markdown_report(reports, command, args.compare_without)
    if args.report:
        args.report.parent.mkdir(parents=True, exist_ok=True)
        args.report.write_text(text, encoding="utf-8")
        print(f"wrote {args.report}", file=sys.stderr)
    return 2 if any(r.problem for r in reports) else 1 if args.fail_under is not None and any(
        r.score() is not None and r.score() < args.fail_under for r in reports) else 0
