"""The command line of ``tools/grade`` (see docs/grading.md).

    tools/grade [--student] [--results FILE] [--junit FILE] [--hidden DIR]
                [--build-dir DIR] [NN ...]
    tools/grade --check-integrity --build-dir DIR
    tools/grade --check-alone --build-dir DIR
    tools/grade --pack-autograder FILE.zip [--hidden DIR] [NN ...]
    tools/grade --batch DIR [--out DIR] [--jobs J] [--roster FILE.csv] [--format moodle|canvas] [NN ...]
    tools/grade --mutants [NN ...] [--sample N --seed S] [--jobs J] [--report FILE]

The autograder (run_autograder) adds --submission-info FILE (what was
installed from the upload), --fallback-stubs DIR (pristine stubs: a
student file that does not compile, link or pass the suspicious-code
checks is replaced by its stub, so that it costs only its own lesson),
--as-user NAME (the unprivileged user that builds and runs the student's
code) and --grader-data DIR (what setup.sh kept: the trusted list of
tests, the hidden tests' objects, which stub defines which function).

Exit status: 0 every test passed, 1 some failed, 2 the code could not be
built, an output could not be written, or the command was wrong.
"""
from __future__ import annotations

import argparse
import errno
import json
import os
import shutil
import sys
import time
import traceback
from pathlib import Path

from . import build, project, reports, runner, suspicious
from .integrity import check_build
from .reports import GradeRun, OutputError
from .results import TestResult
from .runner import deadline_from_environment, run_suite
from .sandbox import Account, Limits, Sandbox, SandboxError


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="tools/grade",
        description="Build illum with your exercise code, run the lessons' grading tests and score them.",
        epilog="Exit status: 0 all tests passed, 1 some failed, 2 could not build (or a wrong command). "
               "See docs/grading.md.")
    parser.add_argument("lessons", nargs="*", metavar="NN",
                        help="lessons to grade (default: every lesson with exercises for --student, "
                             "every lesson with tests otherwise)")
    parser.add_argument("--student", action="store_true",
                        help="build the named lessons' exercise units from exercises/ (your code)")
    parser.add_argument("--results", type=Path, metavar="FILE", help="write Gradescope's results.json here")
    parser.add_argument("--junit", type=Path, metavar="FILE", help="write JUnit XML here")
    parser.add_argument("--hidden", type=Path, metavar="DIR",
                        help="an instructor's folder of extra test files, reported as hidden")
    parser.add_argument("--build-dir", type=Path, metavar="DIR",
                        help="build tree (default: with --student, build/student, the tree of the student "
                             "commands, configured as `cmake --preset student` does; else build/grade-reference)")
    parser.add_argument("--check-integrity", action="store_true",
                        help="check an already-built tree (--build-dir): every grading test passes on the "
                             "reference and fails with NotImplemented on the stubs")
    parser.add_argument("--check-alone", action="store_true",
                        help="check an already-built reference tree (--build-dir): each lesson's grading tests "
                             "pass and its program runs with every other lesson's units as stubs")
    parser.add_argument("--pack-autograder", type=Path, metavar="FILE.zip",
                        help="write Gradescope's autograder zip for the named lessons")
    batch = parser.add_argument_group("grading a folder of submissions (docs/grading.md, \"Batch grading\")")
    batch.add_argument("--batch", type=Path, metavar="DIR",
                       help="grade every student's folder or zip in DIR, each in isolation")
    batch.add_argument("--out", type=Path, metavar="DIR",
                       help="with --batch: where results go (default: DIR-grades beside DIR)")
    batch.add_argument("--jobs", type=int, metavar="J", default=None,
                       help="with --batch: students graded at once (default: 1 per 2 cores)")
    batch.add_argument("--roster", type=Path, metavar="FILE.csv",
                       help="with --batch: the class list (an id or e-mail column); students without a "
                            "submission are listed as missing")
    batch.add_argument("--format", choices=("moodle", "canvas"),
                       help="with --batch: also write the gradebook import file of Moodle or Canvas")
    batch.add_argument("--assignment", metavar="NAME", default="illum",
                       help="with --batch --format: the assignment's name in the gradebook (default: illum)")
    batch.add_argument("--work-dir", type=Path, metavar="DIR", help=argparse.SUPPRESS)
    parser.add_argument("--submission-info", type=Path, metavar="FILE", help=argparse.SUPPRESS)
    parser.add_argument("--fallback-stubs", type=Path, metavar="DIR", help=argparse.SUPPRESS)
    parser.add_argument("--as-user", metavar="NAME", help=argparse.SUPPRESS)
    parser.add_argument("--grader-data", type=Path, metavar="DIR", help=argparse.SUPPRESS)
    parser.add_argument("--save-tests", type=Path, metavar="FILE", help=argparse.SUPPRESS)
    parser.add_argument("--build-as-grader", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    for option, path in (("--results", args.results), ("--junit", args.junit),
                         ("--pack-autograder", args.pack_autograder)):
        problem = output_path_problem(path)
        if problem:
            parser.error(f"{option} {path}: {problem}")
    if args.check_integrity and args.pack_autograder:
        parser.error("--check-integrity and --pack-autograder are separate commands")
    if args.check_integrity and not args.build_dir:
        parser.error("--check-integrity needs --build-dir DIR (an already-built tree)")
    if args.check_alone and not args.build_dir:
        parser.error("--check-alone needs --build-dir DIR (an already-built tree)")
    if args.build_dir is not None:
        if args.build_dir.exists() and not args.build_dir.is_dir():
            parser.error(f"--build-dir {args.build_dir}: is a file, not a folder")
        if (args.check_integrity or args.check_alone) and not args.build_dir.is_dir():
            parser.error(f"--build-dir {args.build_dir}: no such folder; build the tree first "
                         "(cmake --workflow --preset test)")
    if args.batch is not None:
        for other in ("student", "check_integrity", "check_alone", "pack_autograder", "results", "junit",
                      "build_dir", "submission_info", "fallback_stubs", "as_user", "grader_data"):
            if getattr(args, other):
                parser.error(f"--batch grades each submission itself; it does not take --{other.replace('_', '-')}")
        if not args.batch.is_dir():
            parser.error(f"--batch {args.batch}: " + ("not a folder (--batch takes the folder of the "
                                                     "submissions, each a folder or a zip)"
                                                     if args.batch.exists() else _no_folder(args.batch)))
        if args.jobs is not None and args.jobs < 1:
            parser.error(f"--jobs {args.jobs}: needs at least 1")
        if args.roster is not None and not args.roster.is_file():
            parser.error(f"--roster {args.roster}: " + ("not a regular file (a roster is a CSV file)"
                                                         if args.roster.exists() else "no such file"))
    else:
        for option in ("out", "jobs", "roster", "format", "work_dir"):
            if getattr(args, option) is not None:
                parser.error(f"--{option.replace('_', '-')} belongs with --batch DIR")
    if args.submission_info is not None:
        try:
            info = json.loads(args.submission_info.read_text(encoding="utf-8"))
            if not isinstance(info, dict):
                raise ValueError("not a JSON object")
            args.submission = info
        except (OSError, UnicodeDecodeError, ValueError) as error:
            parser.error(f"--submission-info {args.submission_info}: not a submission description "
                         f"(JSON from the autograder): {error}")
    else:
        args.submission = None
    try:
        args.lessons = sorted(set(project.normalize_lesson(text) for text in args.lessons))
    except ValueError as error:
        parser.error(str(error))
    if args.hidden is not None:
        if not args.hidden.is_dir():
            parser.error(f"--hidden {args.hidden}: " + ("not a folder (it takes the folder of the hidden test "
                                                       "files)" if args.hidden.exists() else "no such folder"))
        if not any(args.hidden.glob("*.cpp")):
            parser.error(f"--hidden {args.hidden}: no .cpp test files there")
    return args


def _no_folder(path: Path) -> str:
    """Why nothing is at `path`: 'no such folder', or a link that leads back to itself (ELOOP)."""
    try:
        os.stat(path)
    except OSError as error:
        if error.errno == errno.ELOOP:
            return "a symbolic link that leads back to itself (a link loop)"
    return "no such folder"


def output_path_problem(path: Path | None) -> str:
    """Why a file cannot be written at ``path`` (checked before anything is built), or ''."""
    if path is None:
        return ""
    if path.is_dir():
        return "is a folder; give the name of a file inside it"
    for parent in [path.parent, *path.parent.parents]:
        if parent.exists() and not parent.is_dir():
            return f"{parent} is a file, not a folder"
        if parent.exists():
            break
    if not path.parent.is_dir():
        return f"the folder {path.parent} does not exist; create it first"
    if not os.access(path.parent, os.W_OK):
        return f"the folder {path.parent} cannot be written (read-only, or no permission)"
    if path.exists() and not path.is_file():
        return "is not a regular file"
    return ""


class UsageError(Exception):
    """A command that cannot be carried out as asked (exit status 2)."""


def check_lessons_exist(args: argparse.Namespace, root: Path) -> None:
    """Refuses a lesson that does not exist, before anything is built."""
    known = sorted(set(project.test_lessons(root)) | set(project.exercise_lessons(root)))
    unknown = [nn for nn in args.lessons if nn not in known]
    if unknown:
        raise UsageError(f"lesson {', '.join(unknown)} does not exist; the lessons are {', '.join(known)}")


def choose_lessons(args: argparse.Namespace, root: Path) -> list[str]:
    """The lessons to grade; a student can only be graded on lessons with exercises."""
    exercises = project.exercise_lessons(root)
    if args.student or args.pack_autograder or args.batch:
        if not exercises:
            raise UsageError("no lesson has exercises in exercises/NN_*/")
        unknown = [nn for nn in args.lessons if nn not in exercises]
        if unknown:
            raise UsageError(f"lesson(s) {', '.join(unknown)} have no exercises; "
                             f"lessons with exercises: {', '.join(exercises)}")
        return args.lessons or exercises
    return args.lessons or sorted(set(project.test_lessons(root)) | set(exercises))


# --- what setup.sh kept (--grader-data) ----------------------------------------------------------

class GraderData:
    """The autograder's trusted data (autograder.py writes it in setup, readable by root only)."""

    def __init__(self, folder: Path | None) -> None:
        folder = folder.resolve() if folder is not None else None  # CMake is given its objects' full paths
        self.folder = folder
        self.tests: dict[str, dict[str, list[dict]]] = {}
        self.stub_symbols: dict[str, str] = {}
        self.hidden_objects: list[Path] = []
        if folder is None:
            return
        if not folder.is_dir():
            raise UsageError(f"--grader-data {folder}: " + ("not a folder" if folder.exists() else
                                                           "no such folder (run setup.sh first)"))
        tests, symbols = folder / "tests.json", folder / "stub-symbols.json"
        if tests.is_file():
            self.tests = json.loads(tests.read_text(encoding="utf-8"))
        if symbols.is_file():
            self.stub_symbols = json.loads(symbols.read_text(encoding="utf-8"))
        self.hidden_objects = sorted((folder / "hidden-objects").glob("*.o"))

    def expected(self, program: str, suite: str) -> list[dict] | None:
        if not self.tests:
            return None
        return self.tests.get(program, {}).get(suite, [])


# --- the build -----------------------------------------------------------------------------------

def _student_units(root: Path, lessons: list[str]) -> dict[str, str]:
    """File name -> ``exercises/NN_topic/name.cpp`` of every exercise unit of the graded lessons."""
    return {name: path.relative_to(root).as_posix() for name, path in project.exercise_stubs(root).items()
            if path.parent.name[:2] in lessons}


def _fall_back(args: argparse.Namespace, root: Path, relative: str, compiled: bool = True) -> bool:
    """Replaces a student's file by its pristine stub (only the autograder has them). True if done.

    ``compiled``: whether the student's file was compiled in this tree; if not (flagged by its text),
    the stub keeps its own date, so that make reuses the stub's object of the warm build."""
    if not (args.student and args.fallback_stubs):
        return False
    stub = args.fallback_stubs / Path(relative).relative_to("exercises")
    if not stub.is_file():
        return False
    target = root / relative
    if compiled:
        shutil.copyfile(stub, target)
        target.touch()
    else:
        shutil.copy2(stub, target)
    return True


def _build_with_fallback(args: argparse.Namespace, run: GradeRun, build_dir: Path, root: Path,
                         targets: list[str], data: GraderData | None = None) -> build.StepResult:
    """Builds ``targets``; with --fallback-stubs, a student file that does not
    compile, or that breaks the link (a helper defined in two files), is
    replaced by its stub and the build tried again, so that one broken file
    costs only its lesson (GradeRun.fallbacks says which, with the compiler's
    or the linker's words)."""
    units = _student_units(root, run.lessons) if args.student else {}
    step = build.build(build_dir, targets)
    while not step.ok and args.student and args.fallback_stubs and not step.timed_out:
        compiled = [f for f in build.failed_exercise_files(step.output) if f in units.values()]
        linked = build.linker_blames(step.output, units, data.stub_symbols if data else None)
        blamed = [f for f in sorted(set(compiled) | set(linked)) if f not in run.fallbacks]
        if not blamed or (compiled and build.error_lines_outside(step.output, compiled)):
            break
        for relative in blamed:
            if not _fall_back(args, root, relative):
                return step
            run.fallbacks[relative] = step.output
            what = "did not link" if relative in linked and relative not in compiled else "did not compile"
            if what == "did not link":
                run.link_failures.add(relative)
            print(f"tools/grade: {relative} {what}; grading its lesson with the stub", file=sys.stderr)
        step = build.build(build_dir, targets)
    return step


def _scan_sources(args: argparse.Namespace, run: GradeRun, root: Path) -> None:
    """The suspicious-code check of the student's files' text (suspicious.py), before anything compiles."""
    for name, relative in _student_units(root, run.lessons).items():
        path = root / relative
        if not path.is_file():
            continue
        findings = suspicious.scan_source(path.read_text(encoding="utf-8", errors="replace"), relative)
        if findings:
            run.flagged[relative] = [f.describe() for f in findings]
            if _fall_back(args, root, relative, compiled=False):
                print(f"tools/grade: {relative} was flagged; grading its lesson with the stub", file=sys.stderr)


def _scan_objects(args: argparse.Namespace, run: GradeRun, root: Path, build_dir: Path) -> list[str]:
    """The suspicious-code check of the student's compiled files; returns the files flagged now."""
    units = _student_units(root, run.lessons)
    archive = next(iter(sorted(build_dir.glob("libillum.a"))), None)
    library = suspicious.library_definitions(archive, {f"{n}.o" for n in units}) if archive else {}
    newly = []
    for name, relative in units.items():
        if relative in run.flagged or relative in run.fallbacks:
            continue
        obj = suspicious.object_of(build_dir, relative)
        if obj is None:
            continue
        try:
            findings = suspicious.scan_object(obj, relative, library)
        except OSError as error:
            run.review.append(f"{relative}: the object file could not be checked: {error}")
            continue
        run.review.extend(f"{f.describe()}" for f in findings if not f.serious)
        serious = [f.describe() for f in findings if f.serious]
        if serious:
            run.flagged[relative] = serious
            newly.append(relative)
            if _fall_back(args, root, relative):
                print(f"tools/grade: {relative} was flagged; grading its lesson with the stub", file=sys.stderr)
    return newly


def _make_sandbox(args: argparse.Namespace) -> Sandbox:
    limits = Limits.from_environment()
    if not args.as_user:
        return Sandbox(None, limits)
    account = Account.lookup(args.as_user)
    if account is None:
        raise UsageError(f"--as-user {args.as_user}: no such user (setup.sh creates it)")
    if os.geteuid() != 0:
        raise UsageError(f"--as-user {args.as_user}: running code as another user needs root")
    return Sandbox(account, limits)


def _save_tests(path: Path, suites: list[tuple[str, runner.SuiteRun]]) -> None:
    """The trusted list of tests (from the reference, in setup): program -> suite -> the tests in
    doctest's order, each with the values its ILLUM_CHECK_APPROX checks expect (grade_values.hpp)."""
    saved: dict[str, dict[str, list[dict]]] = {}
    for _lesson, suite in suites:
        tests = []
        for record in suite.listed:
            entry = {k: record.get(k) for k in ("suite", "name", "file", "line", "description")}
            values = [v for v in suite.values.get(TestResult.from_json(record).key, [])
                      if isinstance(v.get("expected"), (int, float)) and isinstance(v.get("epsilon"), (int, float))]
            if values:
                entry["values"] = [{"file": v.get("at_file"), "line": v.get("at_line"), "expected": v.get("expected"),
                                    "epsilon": v.get("epsilon")} for v in values]
            tests.append(entry)
        saved.setdefault(suite.program.name, {})[suite.suite] = tests
    reports.write_text(path, json.dumps(saved, indent=1) + "\n")


def build_tree(args: argparse.Namespace, root: Path, lessons: list[str]) -> tuple[Path, list[str]]:
    """The tree to build in and the ILLUM_EXERCISES it is configured with.

    A student's code is built in the student's own tree, build/student (the `student` preset's),
    configured as the preset does (every exercise from exercises/), so that grading reuses the
    student's build and their next `cmake --build --preset student` finds the tree as they left it:
    one cold build, not two. Any other --build-dir (the autograder's build/grade-student) builds the
    graded lessons from exercises/ and the rest from the library; the reference, nothing."""
    student_tree = root / "build" / "student"
    build_dir = args.build_dir or (student_tree if args.student else root / "build" / "grade-reference")
    if not args.student:
        return build_dir, []
    if build_dir.resolve() == student_tree.resolve():
        return build_dir, ["all"]
    return build_dir, list(lessons)


def grade(args: argparse.Namespace, root: Path) -> int:
    start = time.monotonic()
    check_lessons_exist(args, root)
    lessons = choose_lessons(args, root)
    data = GraderData(args.grader_data)  # a wrong folder is refused before the build writes anything
    build_dir, exercises = build_tree(args, root, lessons)
    if not (build_dir / "libillum.a").exists():
        print(f"tools/grade: the first build of {build_dir} compiles the whole library: 1 to 3 minutes on two "
              "cores, about twice that on a slower machine (less when ccache has the objects); later runs rebuild only what changed",
              file=sys.stderr, flush=True)
    run = GradeRun(lessons=lessons, student=args.student)
    run.submission = args.submission
    try:
        sandbox = _make_sandbox(args)
    except SandboxError as error:
        raise UsageError(str(error)) from error
    runner.set_sandbox(sandbox)
    runner.set_trusted_run(bool(args.save_tests))
    if sandbox.account is not None:  # for the instructor's log: how far the separation goes here
        print(f"tools/grade: the student's code runs as {sandbox.account.name}, "
              + ("each test program in a pid namespace of its own" if sandbox.namespace else
                 "each test program in a process group of its own (no pid namespace here: unshare is not "
                 "allowed, or ILLUM_GRADE_NO_PID_NAMESPACE=1); every process of the user is killed after it"),
              file=sys.stderr)
    tested = set(project.test_lessons(root))
    hidden_objects = data.hidden_objects
    has_hidden = bool(hidden_objects) or bool(project.hidden_sources(root, args.hidden))
    run.has_hidden = has_hidden

    # The student's files: their text checked before anything compiles. ILLUM_GRADE_NO_SCAN=1 switches the
    # checks off, for the grader's own tests of what the sandbox alone defends (never on a real autograder).
    scanning = args.student and os.environ.get("ILLUM_GRADE_NO_SCAN") != "1"
    if args.student and not scanning:
        run.review.append("the suspicious-code checks were switched off (ILLUM_GRADE_NO_SCAN=1)")
    if scanning:
        _scan_sources(args, run, root)

    build_home = None
    if sandbox.account is not None and not args.build_as_grader:
        # The build runs as the student's user: the tree is theirs while it compiles, and root's after.
        build_dir.mkdir(parents=True, exist_ok=True)
        sandbox.give_tree(build_dir)
        build_home = sandbox.make_scratch()
        build.set_runner(build.Runner(preexec=sandbox.build_preexec(),
                                      env=sandbox.build_environment(build_home / "home"),
                                      timeout=build.build_timeout_from_environment()))
    else:
        build.set_runner(build.Runner(timeout=build.build_timeout_from_environment()))
    try:
        step = build.configure(root, build_dir, exercises, None if hidden_objects else args.hidden,
                               extra=build.hidden_objects_arguments(hidden_objects))
        if step.ok:
            # The visible tests first: an instructor's hidden tests that do not
            # build must not cost the student the visible ones (nor blame them).
            targets = ["illum"] + [f"tests_lesson{nn}" for nn in lessons if nn in tested]
            step = _build_with_fallback(args, run, build_dir, root, targets, data)
            if step.ok and scanning and _scan_objects(args, run, root, build_dir) and args.fallback_stubs:
                step = _build_with_fallback(args, run, build_dir, root, targets, data)
    finally:
        build.set_runner(build.Runner())
        if build_home is not None:
            sandbox.reap()
            sandbox.take_tree(build_dir)
            sandbox.remove_scratch(build_home)
    if step.ok and has_hidden:
        # Linked by the grader itself: the hidden tests' objects are readable by root only.
        hidden_step = build.build(build_dir, ["tests_hidden"])
        if not hidden_step.ok:
            run.hidden_build_failed, run.hidden_build_output = True, hidden_step.output
            has_hidden = False
        elif sandbox.account is not None:
            (build_dir / "bin" / "tests_hidden").chmod(0o711)  # run by the student's user, never read
    if not step.ok:
        run.build_failed, run.build_output = True, step.output
        # Blame the student only for errors in their own files.
        units = _student_units(root, lessons) if args.student else {}
        run.blame_student = bool(args.student and (build.failed_exercise_files(step.output)
                                                   or build.linker_blames(step.output, units, data.stub_symbols)
                                                   or step.timed_out))
    else:
        deadline_from_environment(start)
        bin_dir = build_dir / "bin"
        planned = [(lesson, f"tests_lesson{lesson}", False) for lesson in lessons if lesson in tested]
        # The hidden tests last: nothing a student's code learns while they run can reach a visible result.
        planned += [(lesson, "tests_hidden", True) for lesson in lessons] if has_hidden else []
        ran_suites = []
        for lesson, program, hidden in planned:
            expected = data.expected(program, f"lesson{lesson}")
            if expected == [] and hidden:
                continue  # setup found no hidden test of this lesson
            suite = run_suite(bin_dir / program, f"lesson{lesson}", hidden=hidden, expected=expected)
            ran_suites.append((lesson, suite))
            # A doctest::skip() test is switched off by its author: it neither scores nor costs.
            for skipped in (r for r in suite.results if r.skipped):
                print(f"skipped, not graded: lesson{lesson}: {skipped.name}", file=sys.stderr)
            run.results.extend(r for r in suite.results if not r.skipped)
            run.review.extend(f"tampering: {t}" for t in suite.tampering)
            if suite.problem:
                run.problems.append(suite.problem)
                if suite.output.strip():
                    print(suite.output[-4000:], file=sys.stderr)
        if args.save_tests:
            _save_tests(args.save_tests, ran_suites)
    # Nothing of the student's may be alive, or left in the shared folders, when results are written.
    survivors = sandbox.reap()
    sandbox.clean_shared_folders()
    if survivors:
        run.review.append("processes of the student's user still alive at the end were killed: "
                          + ", ".join(survivors[:10]))
    _fail_flagged_lessons(run)
    run.seconds = time.monotonic() - start

    details = reports.failure_report(run, root)
    if details:
        print(details + "\n")
    if run.hidden_build_failed:
        print("tools/grade: the hidden tests did not build (the grader is misconfigured); the visible tests "
              "were graded. The linker's or compiler's messages are above.", file=sys.stderr)
    for file, findings in run.flagged.items():
        print(f"tools/grade: {file} was flagged, so its lesson was not graded:\n  " + "\n  ".join(findings),
              file=sys.stderr)
    print(reports.score_table(run))
    summary = reports.failure_summary(run, root)
    if summary:
        print("\n" + summary)
    if args.results:
        reports.write_results_json(args.results, run, root)
    if args.junit:
        reports.write_junit(args.junit, run, root)
    return reports.exit_code(run)


def _fail_flagged_lessons(run: GradeRun) -> None:
    """Every test of a flagged file's lesson fails, with the reason (suspicious.py)."""
    for file, findings in run.flagged.items():
        lesson = run.lesson_of(file)
        reason = (f"not graded: {file} was flagged by the grader's checks ({findings[0]}"
                  + (f"; and {len(findings) - 1} more" if len(findings) > 1 else "") + ")")
        for result in run.results:
            if result.lesson == lesson:
                result.passed = False
                result.note = reason


def check_integrity(args: argparse.Namespace, root: Path) -> int:
    if project.is_student_edition(root):
        print("tools/grade: --check-integrity needs the reference solutions, which the student edition "
              "does not have", file=sys.stderr)
        return reports.EXIT_NOT_BUILT
    report = check_build(args.build_dir)
    for line in report.checked:
        print(f"ok       {line}")
    for line in report.offenders:
        print(f"OFFENDER {line}")
    print("grading integrity: " + ("passed" if report.ok else f"FAILED ({len(report.offenders)} problem(s))"))
    if not report.ok:
        print(f"tools/grade: grading integrity FAILED: {len(report.offenders)} problem(s), the OFFENDER lines above",
              file=sys.stderr)
    return reports.EXIT_PASSED if report.ok else reports.EXIT_FAILED


def check_alone(args: argparse.Namespace, root: Path) -> int:
    from .alone import check_alone as run_check

    if project.is_student_edition(root):
        print("tools/grade: --check-alone needs the reference solutions, which the student edition "
              "does not have", file=sys.stderr)
        return reports.EXIT_NOT_BUILT
    report = run_check(args.build_dir, root)
    for line in report.checked:
        print(f"ok       {line}")
    for line in report.offenders:
        print(f"OFFENDER {line}")
    print("each lesson alone: " + ("passed" if report.ok else f"FAILED ({len(report.offenders)} problem(s))"))
    if not report.ok:
        print(f"tools/grade: each lesson alone FAILED: {len(report.offenders)} problem(s), the OFFENDER lines above",
              file=sys.stderr)
    return reports.EXIT_PASSED if report.ok else reports.EXIT_FAILED


def pack(args: argparse.Namespace, root: Path) -> int:
    from .autograder import pack_autograder

    if project.is_student_edition(root):
        print("tools/grade: pack the autograder from the instructors' tree, not the student edition",
              file=sys.stderr)
        return reports.EXIT_NOT_BUILT
    check_lessons_exist(args, root)
    lessons = choose_lessons(args, root)
    try:
        names = pack_autograder(root, args.pack_autograder, lessons, args.hidden)
    except ValueError as error:
        raise UsageError(str(error)) from error
    hidden = [n for n in names if n.startswith("hidden-tests/")]
    print(f"wrote {args.pack_autograder}: {len(names)} files, lessons {', '.join(lessons)}, "
          f"{len(hidden)} hidden test file(s)")
    return reports.EXIT_PASSED


def batch(args: argparse.Namespace, root: Path) -> int:
    from .batch import grade_batch

    if project.is_student_edition(root):
        raise UsageError("--batch packs the autograder from the instructors' tree, not the student edition")
    check_lessons_exist(args, root)
    lessons = choose_lessons(args, root)
    return grade_batch(root, args, lessons)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if "--mutants" in argv:  # the mutation report has options of its own (tools/grading/mutants.py)
        from .mutants import main as mutants_main

        return mutants_main(argv)
    args = parse_arguments(argv)
    root = project.ROOT
    try:
        if args.check_integrity:
            return check_integrity(args, root)
        if args.check_alone:
            return check_alone(args, root)
        if args.pack_autograder:
            return pack(args, root)
        if args.batch:
            return batch(args, root)
        return grade(args, root)
    except UsageError as error:  # a wrong command: say so, write nothing
        print(f"tools/grade: {error}", file=sys.stderr)
        return reports.EXIT_NOT_BUILT
    except OutputError as error:  # the grading ran, its results could not be kept
        print(f"tools/grade: {error}", file=sys.stderr)
        return reports.EXIT_NOT_BUILT
    except Exception as error:  # noqa: BLE001 -- the autograder must still get a results.json
        text = traceback.format_exc()
        print(text, file=sys.stderr)
        if args.results and not args.check_integrity and not args.check_alone and not args.pack_autograder:
            failed = GradeRun(lessons=args.lessons, build_failed=True, blame_student=False,
                              build_output="The grader itself failed (not your code):\n" + text)
            try:
                reports.write_results_json(args.results, failed)
            except OutputError as output_error:
                print(f"tools/grade: {output_error}", file=sys.stderr)
        return reports.EXIT_NOT_BUILT
