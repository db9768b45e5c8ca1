"""The command line of ``tools/grade`` (see docs/grading.md).

    tools/grade [--student] [--results FILE] [--junit FILE] [--hidden DIR]
                [--build-dir DIR] [NN ...]
    tools/grade --check-integrity --build-dir DIR
    tools/grade --check-alone --build-dir DIR
    tools/grade --pack-autograder FILE.zip [--hidden DIR] [NN ...]
    tools/grade --mutants [NN ...] [--sample N --seed S] [--jobs J] [--report FILE]

The autograder (run_autograder) adds --submission-info FILE (what was
installed from the upload) and --fallback-stubs DIR (pristine stubs: a
student file that does not compile is replaced by its stub, so that it
costs only its own lesson).

Exit status: 0 every test passed, 1 some failed, 2 the code could not be
built (or the command was wrong).
"""
from __future__ import annotations

import argparse
import json
import shutil
import sys
import time
import traceback
from pathlib import Path

from . import build, project, reports
from .integrity import check_build
from .reports import GradeRun
from .runner import deadline_from_environment, run_suite


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="tools/grade",
        description="Build illum with your exercise code, run the lessons' grading tests and score them.",
        epilog="Exit status: 0 all tests passed, 1 some failed, 2 could not build. See docs/grading.md.")
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
                        help="build tree (default build/grade-student or build/grade-reference)")
    parser.add_argument("--check-integrity", action="store_true",
                        help="check an already-built tree (--build-dir): every grading test passes on the "
                             "reference and fails with NotImplemented on the stubs")
    parser.add_argument("--check-alone", action="store_true",
                        help="check an already-built reference tree (--build-dir): each lesson's grading tests "
                             "pass and its program runs with every other lesson's units as stubs")
    parser.add_argument("--pack-autograder", type=Path, metavar="FILE.zip",
                        help="write Gradescope's autograder zip for the named lessons")
    parser.add_argument("--submission-info", type=Path, metavar="FILE", help=argparse.SUPPRESS)
    parser.add_argument("--fallback-stubs", type=Path, metavar="DIR", help=argparse.SUPPRESS)
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
    try:
        args.lessons = sorted(set(project.normalize_lesson(text) for text in args.lessons))
    except ValueError as error:
        parser.error(str(error))
    if args.hidden is not None and not any(args.hidden.glob("*.cpp")):
        parser.error(f"--hidden {args.hidden}: no .cpp test files there")
    return args


def output_path_problem(path: Path | None) -> str:
    """Why a file cannot be written at ``path`` (checked before anything is built), or ''."""
    if path is None:
        return ""
    if path.is_dir():
        return "is a folder; give the name of a file inside it"
    if not path.parent.is_dir():
        return f"the folder {path.parent} does not exist; create it first"
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
    if args.student or args.pack_autograder:
        if not exercises:
            raise UsageError("no lesson has exercises in exercises/NN_*/")
        unknown = [nn for nn in args.lessons if nn not in exercises]
        if unknown:
            raise UsageError(f"lesson(s) {', '.join(unknown)} have no exercises; "
                             f"lessons with exercises: {', '.join(exercises)}")
        return args.lessons or exercises
    return args.lessons or sorted(set(project.test_lessons(root)) | set(exercises))


def _build_with_fallback(args: argparse.Namespace, run: GradeRun, build_dir: Path, root: Path,
                         targets: list[str]) -> build.StepResult:
    """Builds ``targets``; with --fallback-stubs, a student file that does not
    compile is replaced by its stub and the build tried again, so that one
    broken file costs only its lesson (GradeRun.fallbacks says which)."""
    step = build.build(build_dir, targets)
    while not step.ok and args.student and args.fallback_stubs:
        blamed = [f for f in build.failed_exercise_files(step.output)
                  if f not in run.fallbacks and (args.fallback_stubs / Path(f).relative_to("exercises")).is_file()]
        if not blamed or build.error_lines_outside(step.output, blamed):
            break
        for relative in blamed:
            run.fallbacks[relative] = step.output
            target = root / relative
            shutil.copyfile(args.fallback_stubs / Path(relative).relative_to("exercises"), target)
            target.touch()
            print(f"tools/grade: {relative} did not compile; grading its lesson with the stub", file=sys.stderr)
        step = build.build(build_dir, targets)
    return step


def grade(args: argparse.Namespace, root: Path) -> int:
    start = time.monotonic()
    check_lessons_exist(args, root)
    lessons = choose_lessons(args, root)
    build_dir = args.build_dir or root / "build" / ("grade-student" if args.student else "grade-reference")
    run = GradeRun(lessons=lessons, student=args.student)
    if args.submission_info and args.submission_info.is_file():
        run.submission = json.loads(args.submission_info.read_text(encoding="utf-8"))
    tested = set(project.test_lessons(root))
    has_hidden = bool(project.hidden_sources(root, args.hidden))
    run.has_hidden = has_hidden

    step = build.configure(root, build_dir, lessons if args.student else [], args.hidden)
    if step.ok:
        # The visible tests first: an instructor's hidden tests that do not
        # compile must not cost the student the visible ones (nor blame them).
        targets = ["illum"] + [f"tests_lesson{nn}" for nn in lessons if nn in tested]
        step = _build_with_fallback(args, run, build_dir, root, targets)
        if step.ok and has_hidden:
            hidden_step = build.build(build_dir, ["tests_hidden"])
            if not hidden_step.ok:
                run.hidden_build_failed, run.hidden_build_output = True, hidden_step.output
                has_hidden = False
    if not step.ok:
        run.build_failed, run.build_output = True, step.output
        # Blame the student only for errors in their own files.
        run.blame_student = bool(args.student and build.failed_exercise_files(step.output))
    else:
        deadline_from_environment(start)
        bin_dir = build_dir / "bin"
        for lesson in lessons:
            suites = [run_suite(bin_dir / f"tests_lesson{lesson}", f"lesson{lesson}")] if lesson in tested else []
            if has_hidden:
                suites.append(run_suite(bin_dir / "tests_hidden", f"lesson{lesson}", hidden=True))
            for suite in suites:
                # A doctest::skip() test is switched off by its author: it neither scores nor costs.
                for skipped in (r for r in suite.results if r.skipped):
                    print(f"skipped, not graded: lesson{lesson}: {skipped.name}", file=sys.stderr)
                run.results.extend(r for r in suite.results if not r.skipped)
                if suite.problem:
                    run.problems.append(suite.problem)
                    if suite.output.strip():
                        print(suite.output[-4000:], file=sys.stderr)
    run.seconds = time.monotonic() - start

    details = reports.failure_report(run, root)
    if details:
        print(details + "\n")
    if run.hidden_build_failed:
        print("tools/grade: the hidden tests did not compile (the grader is misconfigured); the visible tests "
              "were graded. The compiler's messages are above.", file=sys.stderr)
    print(reports.score_table(run))
    if args.results:
        reports.write_results_json(args.results, run, root)
    if args.junit:
        reports.write_junit(args.junit, run, root)
    return reports.exit_code(run)


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
        return grade(args, root)
    except UsageError as error:  # a wrong command: say so, write nothing
        print(f"tools/grade: {error}", file=sys.stderr)
        return reports.EXIT_NOT_BUILT
    except Exception as error:  # noqa: BLE001 -- the autograder must still get a results.json
        text = traceback.format_exc()
        print(text, file=sys.stderr)
        if args.results and not args.check_integrity and not args.check_alone and not args.pack_autograder:
            failed = GradeRun(lessons=args.lessons, build_failed=True, blame_student=False,
                              build_output="The grader itself failed (not your code):\n" + text)
            reports.write_results_json(args.results, failed)
        return reports.EXIT_NOT_BUILT
