"""The command line of ``tools/grade``: its options, files and exit status are in docs/grading-reference.md.

The autograder (run_autograder) adds hidden options: --submission-info FILE (what was installed from the
upload), --fallback-stubs DIR (pristine stubs: a student file that does not compile or link is replaced by
its stub, so that it costs only its own lesson), --as-user NAME (the unprivileged user that builds and runs
the student's code) and --grader-data DIR (what setup.sh kept: the trusted list of tests, the hidden tests'
objects, which stub defines which function).
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import time
import traceback
from pathlib import Path

from . import build, project, reports, runner, suspicious
from .alone import check_alone
from .autograder import pack_autograder
from .batch import grade_batch
from .integrity import check_build
from .reports import GradeRun, OutputError
from .results import TestResult
from .runner import deadline_from_environment, run_suite
from .sandbox import Account, Limits, Sandbox, SandboxError

from common.path_options import path_argument  # tools/ is on the path (tools/grade, run_autograder's PYTHONPATH)


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = _parser()
    args = parser.parse_args(argv)
    _check_commands(parser, args)
    _check_batch(parser, args)
    _check_inputs(parser, args)
    return args


def _parser() -> argparse.ArgumentParser:
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
    parser.add_argument("--results", type=path_argument, metavar="FILE", help="write Gradescope's results.json here")
    parser.add_argument("--junit", type=path_argument, metavar="FILE", help="write JUnit XML here")
    parser.add_argument("--hidden", type=path_argument, metavar="DIR",
                        help="an instructor's folder of extra test files, reported as hidden")
    parser.add_argument("--build-dir", type=path_argument, metavar="DIR",
                        help="build tree (default: with --student, build/student, the tree of the student "
                             "commands, configured as `cmake --preset student` does; else build/grade-reference)")
    parser.add_argument("--check-integrity", action="store_true",
                        help="check an already-built tree (--build-dir): every grading test passes on the "
                             "reference and fails with NotImplemented on the stubs")
    parser.add_argument("--check-alone", action="store_true",
                        help="check an already-built reference tree (--build-dir): each lesson's grading tests "
                             "pass and its program runs with every other lesson's units as stubs")
    parser.add_argument("--pack-autograder", type=path_argument, metavar="FILE.zip",
                        help="write Gradescope's autograder zip for the named lessons")
    batch = parser.add_argument_group("grading a folder of submissions (docs/grading.md, \"Batch grading\")")
    batch.add_argument("--batch", type=path_argument, metavar="DIR",
                       help="grade every student's folder or zip in DIR, each in isolation")
    batch.add_argument("--out", type=path_argument, metavar="DIR",
                       help="with --batch: where results go (default: DIR-grades beside DIR)")
    batch.add_argument("--jobs", type=int, metavar="J", default=None,
                       help="with --batch: students graded at once (default: 1 per 2 cores)")
    batch.add_argument("--roster", type=path_argument, metavar="FILE.csv",
                       help="with --batch: the class list (an id or e-mail column); students without a "
                            "submission are listed as missing")
    batch.add_argument("--format", choices=("moodle", "canvas"),
                       help="with --batch: also write the gradebook import file of Moodle or Canvas")
    batch.add_argument("--assignment", metavar="NAME",
                       help="with --batch --format: the assignment's name in the gradebook (default: illum)")
    batch.add_argument("--work-dir", type=path_argument, metavar="DIR", help=argparse.SUPPRESS)
    for option in ("--submission-info", "--fallback-stubs", "--grader-data", "--save-tests"):  # the autograder's
        parser.add_argument(option, type=path_argument, help=argparse.SUPPRESS)
    parser.add_argument("--as-user", help=argparse.SUPPRESS)
    parser.add_argument("--build-as-grader", action="store_true", help=argparse.SUPPRESS)
    return parser


def _check_commands(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """The output paths, and the options that make a command (integrity, alone, packing) together."""
    for option, path in (("--results", args.results), ("--junit", args.junit),
                         ("--pack-autograder", args.pack_autograder)):
        problem = output_path_problem(path)
        if problem:
            parser.error(f"{option} {path}: {problem}")
    if args.check_integrity and args.pack_autograder:
        parser.error("--check-integrity and --pack-autograder are separate commands")
    for option in ("check_integrity", "check_alone"):
        if getattr(args, option) and not args.build_dir:
            parser.error(f"--{option.replace('_', '-')} needs --build-dir DIR (an already-built tree)")
    if args.build_dir is not None:
        if args.build_dir.exists() and not args.build_dir.is_dir():
            parser.error(f"--build-dir {args.build_dir}: is a file, not a folder")
        if (args.check_integrity or args.check_alone) and not args.build_dir.is_dir():
            parser.error(f"--build-dir {args.build_dir}: no such folder; build the tree first "
                         "(cmake --workflow --preset test)")


def _check_batch(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """--batch and the options that belong with it only."""
    if args.batch is not None:
        for other in ("student", "check_integrity", "check_alone", "pack_autograder", "results", "junit",
                      "build_dir", "submission_info", "fallback_stubs", "as_user", "grader_data"):
            if getattr(args, other):
                parser.error(f"--batch grades each submission itself; it does not take --{other.replace('_', '-')}")
        if not args.batch.is_dir():
            parser.error(f"--batch {args.batch}: " + ("not a folder (--batch takes the folder of the "
                                                     "submissions, each a folder or a zip)"
                                                     if args.batch.exists() else "no such folder"))
        if args.jobs is not None and args.jobs < 1:
            parser.error(f"--jobs {args.jobs}: needs at least 1")
        if args.roster is not None and not args.roster.is_file():
            parser.error(f"--roster {args.roster}: " + ("not a regular file (a roster is a CSV file)"
                                                         if args.roster.exists() else "no such file"))
    else:
        for option in ("out", "jobs", "roster", "format", "assignment", "work_dir"):
            if getattr(args, option) is not None:
                parser.error(f"--{option.replace('_', '-')} belongs with --batch DIR")


def _check_inputs(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """The submission description, the lessons' names and the hidden tests' folder, read and checked."""
    args.submission = None
    if args.submission_info is not None:
        try:
            args.submission = json.loads(args.submission_info.read_text(encoding="utf-8"))
            if not isinstance(args.submission, dict):
                raise ValueError("not a JSON object")
        except (OSError, UnicodeDecodeError, ValueError) as error:
            parser.error(f"--submission-info {args.submission_info}: not a submission description "
                         f"(JSON from the autograder): {error}")
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


def output_path_problem(path: Path | None) -> str:
    """Why a file cannot be written at ``path`` (checked before anything is built), or ''."""
    if path is None:
        return ""
    if path.is_dir():
        return "is a folder; give the name of a file inside it"
    existing = next(parent for parent in path.parents if parent.exists())  # '.' or '/' at the latest
    if not existing.is_dir():
        return f"{existing} is a file, not a folder"
    if not path.parent.is_dir():
        return f"the folder {path.parent} does not exist; create it first"
    if not os.access(path.parent, os.W_OK):
        return f"the folder {path.parent} cannot be written (read-only, or no permission)"
    if path.exists() and not path.is_file():
        return "is not a regular file"
    return ""


class UsageError(Exception):
    """A command that cannot be carried out as asked (exit status 2)."""


def choose_lessons(args: argparse.Namespace, root: Path) -> list[str]:
    """The lessons to grade; one that does not exist, or has no exercises for a student, is refused first."""
    exercises = project.exercise_lessons(root)
    known = sorted(set(project.test_lessons(root)) | set(exercises))
    unknown = [nn for nn in args.lessons if nn not in known]
    if unknown:
        raise UsageError(f"lesson {', '.join(unknown)} does not exist; the lessons are {', '.join(known)}")
    if args.student or args.pack_autograder or args.batch:
        if not exercises:
            raise UsageError("no lesson has exercises in exercises/NN_*/")
        unknown = [nn for nn in args.lessons if nn not in exercises]
        if unknown:
            raise UsageError(f"lesson(s) {', '.join(unknown)} have no exercises; "
                             f"lessons with exercises: {', '.join(exercises)}")
        return args.lessons or exercises
    return args.lessons or known


# --- what setup.sh kept (--grader-data) ----------------------------------------------------------

class GraderData:
    """The autograder's trusted data (autograder.py writes it in setup, readable by root only)."""

    def __init__(self, folder: Path | None) -> None:
        self.tests: dict[str, dict[str, list[dict]]] = {}
        self.stub_symbols: dict[str, str] = {}
        self.hidden_objects: list[Path] = []
        self.witness_dir: Path | None = None
        if folder is None:
            return
        folder = folder.resolve()  # CMake is given its objects' full paths
        if not folder.is_dir():
            raise UsageError(f"--grader-data {folder}: " + ("not a folder" if folder.exists() else
                                                           "no such folder (run setup.sh first)"))
        for name, file in (("tests", "tests.json"), ("stub_symbols", "stub-symbols.json")):
            if (folder / file).is_file():
                setattr(self, name, json.loads((folder / file).read_text(encoding="utf-8")))
        self.hidden_objects = sorted((folder / "hidden-objects").glob("*.o"))
        self.witness_dir = folder / "witness" if (folder / "witness").is_dir() else None

    def expected(self, program: str, suite: str) -> list[dict] | None:
        return self.tests.get(program, {}).get(suite, []) if self.tests else None

    def witness(self, program: str, suite: str) -> dict[runner.Key, list[dict]] | None:
        """The checks the reference's trusted run made in each test (kept by setup), or None."""
        listed = self.expected(program, suite)
        if not listed or not all("checks" in t for t in listed):
            return None
        return {TestResult.from_json(t).key: t["checks"] for t in listed}


# --- the build -----------------------------------------------------------------------------------

def _student_units(root: Path, lessons: list[str]) -> dict[str, str]:
    """File name -> ``exercises/NN_topic/name.cpp`` of every exercise unit of the graded lessons."""
    return {name: path.relative_to(root).as_posix() for name, path in project.exercise_stubs(root, lessons).items()}


def _build_with_fallback(args: argparse.Namespace, run: GradeRun, build_dir: Path, root: Path,
                         targets: list[str], data: GraderData | None = None,
                         runner: build.Runner | None = None) -> build.StepResult:
    """Builds ``targets``; with --fallback-stubs, a student file that does not compile, or that breaks the
    link (a helper defined in two files), is replaced by its stub and the build tried again, so that it
    costs only its lesson (GradeRun.fallbacks says which, with the compiler's or the linker's words)."""
    units = _student_units(root, run.lessons) if args.student else {}
    step = build.build(build_dir, targets, runner=runner)
    while not step.ok and args.student and args.fallback_stubs and not step.timed_out:
        compiled = [f for f in build.failed_exercise_files(step.output) if f in units.values()]
        linked = build.linker_blames(step.output, units, data.stub_symbols if data else None)
        blamed = [f for f in sorted(set(compiled) | set(linked)) if f not in run.fallbacks]
        if not blamed or (compiled and build.error_lines_outside(step.output, compiled)):
            break
        for relative in blamed:
            stub = args.fallback_stubs / Path(relative).relative_to("exercises")  # pristine: only setup's
            if not stub.is_file():
                return step
            shutil.copyfile(stub, root / relative)
            (root / relative).touch()
            run.fallbacks[relative] = step.output
            what = "did not link" if relative in linked and relative not in compiled else "did not compile"
            if what == "did not link":
                run.link_failures.add(relative)
            print(f"tools/grade: {relative} {what}; grading its lesson with the stub", file=sys.stderr)
        step = build.build(build_dir, targets, runner=runner)
    return step


def _make_sandbox(args: argparse.Namespace, root: Path) -> Sandbox:
    """The student's code runs apart from the grader's folder and the test sources (a program that
    could read the visible tests while it runs could copy their expected values)."""
    limits = Limits.from_environment()
    if not args.as_user:
        return Sandbox(None, limits)
    account = Account.lookup(args.as_user)
    if account is None:
        raise UsageError(f"--as-user {args.as_user}: no such user (setup.sh creates it)")
    if os.geteuid() != 0:
        raise UsageError(f"--as-user {args.as_user}: running code as another user needs root")
    hide = [str(root / "tests")] + ([str(args.grader_data.resolve())] if args.grader_data else [])
    return Sandbox(account, limits, hide=hide)


def _save_tests(path: Path, suites: list[tuple[str, runner.SuiteRun, dict | None]]) -> None:
    """The trusted list of tests (setup's reference run): program -> suite -> the tests in doctest's order,
    each with the witness's checks (visible tests only: hidden ones are witnessed in every run, new seed)."""
    saved: dict[str, dict[str, list[dict]]] = {}
    for _lesson, suite, witness in suites:
        tests = []
        for record in suite.listed:
            entry = {k: record.get(k) for k in ("suite", "name", "file", "line", "description")}
            key = TestResult.from_json(record).key
            if witness is not None and key in witness and "tests_hidden" not in suite.program.name:
                entry["checks"] = witness[key]
            tests.append(entry)
        name = suite.program.name.removesuffix("_observer")
        saved.setdefault(name, {})[suite.suite] = tests
    reports.write_text(path, json.dumps(saved, indent=1) + "\n")


def build_tree(args: argparse.Namespace, root: Path, lessons: list[str]) -> tuple[Path, list[str]]:
    """The tree to build in and the ILLUM_EXERCISES it is configured with: a student's own tree,
    build/student, as the `student` preset configures it (one cold build, not two); any other --build-dir
    (the autograder's) with the graded lessons from exercises/; the reference with none."""
    student_tree = root / "build" / "student"
    build_dir = args.build_dir or (student_tree if args.student else root / "build" / "grade-reference")
    if not args.student:
        return build_dir, []
    if build_dir.resolve() == student_tree.resolve():
        return build_dir, ["all"]
    return build_dir, list(lessons)


def _build_student_code(args: argparse.Namespace, run: GradeRun, root: Path, build_dir: Path, exercises: list[str],
                        targets: list[str], sandbox: Sandbox, data: GraderData) -> build.StepResult:
    """Configures and builds; a student's build runs as the student's user (the tree is theirs while it
    compiles, and root's after)."""
    build_home, runner = None, build.Runner(timeout=build.build_timeout_from_environment())
    if sandbox.account is not None and not args.build_as_grader:
        build_dir.mkdir(parents=True, exist_ok=True)
        sandbox.give_tree(build_dir)
        build_home = sandbox.make_scratch()
        runner = build.Runner(preexec=sandbox.build_preexec(), env=sandbox.build_environment(build_home / "home"),
                              timeout=runner.timeout)
    try:
        step = build.configure(root, build_dir, exercises, None if data.hidden_objects else args.hidden,
                               data.hidden_objects, runner=runner)
        if step.ok:
            # The visible tests first: an instructor's hidden tests that do not
            # build must not cost the student the visible ones (nor blame them).
            step = _build_with_fallback(args, run, build_dir, root, targets, data, runner)
    finally:
        if build_home is not None:
            sandbox.reap()
            sandbox.take_tree(build_dir)
            shutil.rmtree(build_home, ignore_errors=True)
    return step


def _build_hidden(run: GradeRun, build_dir: Path, judged: bool, witness_here: bool, sandbox: Sandbox) -> bool:
    """Links the hidden tests' program(s), as the grader: their objects are readable by root only."""
    targets = ["tests_hidden_observer"] + (["tests_hidden"] if witness_here else []) if judged else ["tests_hidden"]
    step = build.build(build_dir, targets)
    if not step.ok:
        run.hidden_build_failed, run.hidden_build_output = True, step.output
        return False
    if sandbox.account is not None:
        for name in targets:
            (build_dir / "bin" / name).chmod(0o711)  # run by the student's user, never read
    return True


def _witness_run(data: GraderData, bin_dir: Path, program: str, suite: str, seed_env: dict[str, str],
                 hidden: bool) -> tuple[runner.SuiteRun | None, dict | None, str]:
    """The witness's checks for one suite: kept by setup (visible tests), or from running the trusted
    build of the reference now, outside the student's sandbox, with this run's seed (hidden tests)."""
    kept = data.witness(program, suite)
    if kept is not None and not hidden:
        return None, kept, ""
    folder = data.witness_dir or bin_dir
    trusted = Sandbox(None, Limits.from_environment(), private=False)
    run = run_suite(folder / program, suite, hidden=hidden, role="witness", env=seed_env, sandbox=trusted,
                    expected=data.expected(program, suite))
    failed = [r.name for r in run.results if not r.passed]
    if run.problem or failed:
        return run, None, (f"the reference's run of {program} -ts={suite} failed (the grader's fault): "
                           f"{run.problem or ', '.join(failed[:5])}")
    return run, runner.witness_checks(run), ""


def _run_planned(run: GradeRun, data: GraderData, bin_dir: Path,
                 planned: list[tuple[str, str, bool]], judged: bool) -> list:
    """Runs every planned suite; with the judge, the witness first and then the student's observer."""
    seed_env = {"ILLUM_GRADE_SEED": os.environ.get("ILLUM_GRADE_SEED") or str(int.from_bytes(os.urandom(4), "big"))}
    ran = []
    for lesson, program, hidden in planned:
        suite_name = f"lesson{lesson}"
        expected = data.expected(program, suite_name)
        if expected == [] and hidden:
            continue  # setup found no hidden test of this lesson
        witness = None
        if judged:
            witness_suite, witness, problem = _witness_run(data, bin_dir, program, suite_name, seed_env, hidden)
            if problem:
                run.problems.append(problem)
                run.review.append(problem)
                continue
            expected = witness_suite.listed if witness_suite is not None else expected
            suite = run_suite(bin_dir / f"{program}_observer", suite_name, hidden=hidden, expected=expected,
                              role="observer", env=seed_env if hidden else None)
            run.review.extend(runner.judge_suite(suite, witness, hidden))
        else:
            suite = run_suite(bin_dir / program, suite_name, hidden=hidden, expected=expected)
        ran.append((lesson, suite, witness))
        _collect(run, lesson, suite)
    return ran


def _collect(run: GradeRun, lesson: str, suite: runner.SuiteRun) -> None:
    # A doctest::skip() test is switched off by its author: it neither scores nor costs.
    for skipped in (r for r in suite.results if r.skipped):
        print(f"skipped, not graded: lesson{lesson}: {skipped.name}", file=sys.stderr)
    run.results.extend(r for r in suite.results if not r.skipped)
    run.review.extend(f"tampering: {t}" for t in suite.tampering)
    if suite.problem:
        run.problems.append(suite.problem)
        if suite.output.strip():
            print(suite.output[-4000:], file=sys.stderr)


def _announce(sandbox: Sandbox, judged: bool) -> None:
    """For the instructor's log: how far the separation goes here, and who forms the verdicts."""
    if sandbox.account is not None:
        print(f"tools/grade: the student's code runs as {sandbox.account.name}, "
              + ("each test program in pid, mount and IPC namespaces of its own" if sandbox.private else
                 "each test program in a pid namespace of its own" if sandbox.namespace else
                 "each test program in a process group of its own (no namespaces here: unshare is not "
                 "allowed, or ILLUM_GRADE_NO_PID_NAMESPACE=1); every process of the user is killed after it"),
              file=sys.stderr)
    print("tools/grade: " + ("verdicts by the judge, outside the programs that run the code graded (docs/grading.md)"
                             if judged else "verdicts from the test programs themselves (your own machine)"),
          file=sys.stderr)


def grade(args: argparse.Namespace, root: Path) -> int:
    start = time.monotonic()
    lessons = choose_lessons(args, root)
    data = GraderData(args.grader_data)  # a wrong folder is refused before the build writes anything
    build_dir, exercises = build_tree(args, root, lessons)
    if not (build_dir / "libillum.a").exists():
        print(f"tools/grade: the first build of {build_dir} compiles the whole library: 1 to 3 minutes on two "
              "cores, about twice that on a slower machine (less when ccache has the objects); later runs rebuild "
              "only what changed", file=sys.stderr, flush=True)
    run = GradeRun(lessons=lessons, submission=args.submission)
    try:
        sandbox = _make_sandbox(args, root)
    except SandboxError as error:
        raise UsageError(str(error)) from error
    runner.set_sandbox(sandbox)
    # Verdicts come from the judge where a witness exists (the reference is in this tree, or setup kept its
    # records), from the student's own program only on their own machine.
    judged = not args.student or bool(data.tests) or data.witness_dir is not None
    witness_here = judged and data.witness_dir is None  # the reference is this tree's own library
    _announce(sandbox, judged)
    tested = set(project.test_lessons(root))
    has_hidden = bool(data.hidden_objects) or bool(project.hidden_sources(root, args.hidden))
    _advise(args, run, root)
    programs = [f"tests_lesson{nn}" for nn in lessons if nn in tested]
    targets = ["illum"] + ([f"{p}_observer" for p in programs] + (programs if witness_here else []) if judged
                           else programs)
    step = _build_student_code(args, run, root, build_dir, exercises, targets, sandbox, data)
    if not step.ok:
        _build_failed(args, run, root, lessons, step, data)
    else:
        _advise(args, run, root, build_dir=build_dir)
        has_hidden = has_hidden and _build_hidden(run, build_dir, judged, witness_here, sandbox)
        deadline_from_environment(start)
        planned = [(lesson, f"tests_lesson{lesson}", False) for lesson in lessons if lesson in tested]
        # The hidden tests last: nothing a student's code learns while they run can reach a visible result.
        planned += [(lesson, "tests_hidden", True) for lesson in lessons] if has_hidden else []
        with sandbox.hidden_folders():
            ran_suites = _run_planned(run, data, build_dir / "bin", planned, judged)
        if args.save_tests:
            _save_tests(args.save_tests, ran_suites)
    # Nothing of the student's may be alive, or left in the shared folders, when results are written.
    survivors = sandbox.reap()
    sandbox.clean_shared_folders()
    if survivors:
        run.review.append("processes of the student's user still alive at the end were killed: "
                          + ", ".join(survivors[:10]))
    run.seconds = time.monotonic() - start
    return _report(args, run, root)


def _build_failed(args: argparse.Namespace, run: GradeRun, root: Path, lessons: list[str], step: build.StepResult,
                  data: GraderData) -> None:
    run.build_failed, run.build_output = True, step.output
    # Blame the student only for errors in their own files.
    units = _student_units(root, lessons) if args.student else {}
    run.blame_student = bool(args.student and (build.failed_exercise_files(step.output)
                                               or build.linker_blames(step.output, units, data.stub_symbols)
                                               or step.timed_out))


def _advise(args: argparse.Namespace, run: GradeRun, root: Path, build_dir: Path | None = None) -> None:
    """The suspicious-code checks (suspicious.py) of the student's files' text, or with ``build_dir`` of their
    objects: advice for the instructor's review, never a verdict. ILLUM_GRADE_NO_SCAN=1 switches them off."""
    if not args.student or os.environ.get("ILLUM_GRADE_NO_SCAN") == "1":
        return
    units = _student_units(root, run.lessons)
    findings = []
    if build_dir is None:
        for relative in units.values():
            if (root / relative).is_file():
                text = (root / relative).read_text(encoding="utf-8", errors="replace")
                findings += [finding.describe() for finding in suspicious.scan_source(text, relative)]
    else:
        library = suspicious.library_definitions(build_dir / "libillum.a", {f"{n}.o" for n in units})
        for relative in units.values():
            obj = None if relative in run.fallbacks else suspicious.object_of(build_dir, relative)
            try:
                findings += [f.describe() for f in suspicious.scan_object(obj, relative, library)] if obj else []
            except OSError as error:
                findings.append(f"{relative}: the object file could not be checked: {error}")
    run.review.extend(findings)
    if findings and not args.grader_data:  # the student's own machine: worth knowing before submitting
        print("tools/grade: worth a second look (the autograder shows these to your instructor; they change no "
              "score):\n  " + "\n  ".join(findings), file=sys.stderr)


def _report(args: argparse.Namespace, run: GradeRun, root: Path) -> int:
    details = reports.failure_report(run, root)
    if details:
        print(details + "\n")
    if run.hidden_build_failed:
        print("tools/grade: the hidden tests did not build (the grader is misconfigured); the visible tests "
              "were graded. The linker's or compiler's messages are above.", file=sys.stderr)
    print(reports.score_table(run))
    summary = reports.failure_summary(run, root)
    if summary:
        print("\n" + summary)
    if args.results:
        reports.write_results_json(args.results, run, root)
    if args.junit:
        reports.write_junit(args.junit, run, root)
    return reports.exit_code(run)


def _needs_reference(root: Path, why: str) -> None:
    """Refuses a command that needs the reference solutions in the student edition, which has none."""
    if project.is_student_edition(root):
        raise UsageError(why)


def check_tree(args: argparse.Namespace, root: Path) -> int:
    """--check-integrity (integrity.py) or --check-alone (alone.py) on an already-built tree."""
    option, title = ("--check-integrity", "grading integrity") if args.check_integrity else \
        ("--check-alone", "each lesson alone")
    _needs_reference(root, f"{option} needs the reference solutions, which the student edition does not have")
    report = check_build(args.build_dir) if args.check_integrity else check_alone(args.build_dir, root)
    for line in report.checked:
        print(f"ok       {line}")
    for line in report.offenders:
        print(f"OFFENDER {line}")
    print(f"{title}: " + ("passed" if report.ok else f"FAILED ({len(report.offenders)} problem(s))"))
    if not report.ok:
        print(f"tools/grade: {title} FAILED: {len(report.offenders)} problem(s), the OFFENDER lines above",
              file=sys.stderr)
    return reports.EXIT_PASSED if report.ok else reports.EXIT_FAILED


def pack(args: argparse.Namespace, root: Path) -> int:
    _needs_reference(root, "pack the autograder from the instructors' tree, not the student edition")
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
    _needs_reference(root, "--batch packs the autograder from the instructors' tree, not the student edition")
    return grade_batch(root, args, choose_lessons(args, root))


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if "--mutants" in argv:  # the mutation report has options of its own (tools/grading/mutants.py)
        from .mutants import main as mutants_main

        return mutants_main(argv)
    args = parse_arguments(argv)
    root = project.ROOT
    try:
        if args.check_integrity or args.check_alone:
            return check_tree(args, root)
        if args.pack_autograder:
            return pack(args, root)
        if args.batch:
            return batch(args, root)
        return grade(args, root)
    except (UsageError, OutputError) as error:  # a wrong command (nothing written), or results not kept
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
