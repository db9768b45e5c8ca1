#!/usr/bin/env python3
"""CI check of the student edition: what students get must build, must not
contain the answers, and must make every grading test fail with
NotImplemented (so a student starts at 0 and every failure names the
function still to write).

Steps: build the ``student-edition`` target of a configured tree; check the
edition holds no reference unit and no hidden test; configure it in a
temporary folder and build what a student builds there (the lesson programs,
the illum command, every ``tests_lessonNN``); run each ``tests_lessonNN`` on suite ``lessonNN``
through the illum-grade reporter (every test of a lesson handed out must fail
with NotImplemented, every test of a lesson shipped as reference code must
pass); check that the grading_integrity test is
not registered there.

With ``--lesson NN`` (an instructor's re-verification, too slow for CI: two
builds of the library and the lesson program's full run), it checks instead
what a student handed out only lesson NN gets: the edition of that lesson
alone (tools/student_edition.py --lessons NN) is written to the work folder,
and the student commands of *the edition's own README* (its "Build, test and
grade your code" block, NN replaced) are run in it: ``cmake --preset
student`` and the build of the lesson's tests and program; the test command
(``build/student/bin/tests_lessonNN -ts=lessonNN``) fails naming
NotImplemented and ``tools/grade --student NN`` scores 0 on the untouched
stubs; the reference units of lesson NN (``lib/illum/<area>/<unit>.cpp`` of
this tree) are copied over the stubs as the student's files; then the build
succeeds, the test command passes, the lesson program runs to completion
(``--quick`` with ``--quick``) and ``tools/grade --student NN`` scores 100%.

    tools/check_student_edition.py --lesson 07 --work-dir /tmp/ed07
"""
from __future__ import annotations

import argparse
import json
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import figures  # noqa: E402
from grading import build, project  # noqa: E402
from grading.integrity import grading_programs  # noqa: E402
from grading.edition import broken_links  # noqa: E402
from grading.runner import run_suite  # noqa: E402


def content_problems(edition: Path) -> list[str]:
    """What must not be in the edition: reference units, hidden tests; what must: the marker, the errata."""
    problems = []
    if not (edition / project.STUDENT_EDITION_MARKER).is_file():
        problems.append(f"{edition} has no {project.STUDENT_EDITION_MARKER} marker")
    if (edition / "tests" / "hidden").exists():
        problems.append("tests/hidden/ is in the student edition")
    # The texts cite "erratum N" of the notes: the list must travel with them.
    if not (edition / "docs" / "errata.md").is_file():
        problems.append("docs/errata.md (the errata the lessons cite) is missing from the student edition")
    # The lesson texts' images show before anything has run (tools/figures.py, "Images").
    for text in figures.lesson_texts(edition):
        links, _ = figures.image_links(text.relative_to(edition), text.read_text(encoding="utf-8").splitlines())
        for link in links:
            if link.kept and not (text.parent / figures.FIGURES_FOLDER / link.name).is_file():
                problems.append(f"{text.relative_to(edition)}:{link.line + 1} shows "
                                f"{figures.FIGURES_FOLDER}/{link.name}, which the student edition lacks")
    # Every link of every Markdown file resolves in the edition (its own README included): a
    # student never follows a link to a reference unit, a hidden test or an exercise not handed out.
    problems += [f"dead link: {problem}" for problem in broken_links(edition)]
    readme = (edition / "README.md").read_text(encoding="utf-8") if (edition / "README.md").is_file() else ""
    if "student edition" not in readme.splitlines()[0] if readme else True:
        problems.append("README.md is not the student edition's own README")
    for instructors_only in ("## For instructors", "--pack-autograder", "--batch", "--check-integrity"):
        if instructors_only in readme:
            problems.append(f"README.md holds instructors' material ({instructors_only!r})")
    stubs = project.exercise_stubs(edition)
    for reference in sorted((edition / "lib").rglob("*.cpp")):
        if reference.name in stubs:
            problems.append(f"{reference.relative_to(edition)} is the reference of the exercise "
                            f"{stubs[reference.name].relative_to(edition)}")
    return problems


def readme_commands(edition: Path, lesson: str) -> tuple[dict[str, list[str]], list[str]]:
    """The student commands of the edition's own README (its "Build, test and grade your code"
    block), with NN replaced by the lesson, by what each does: configure, build, test, program,
    grade. Returns them and the problems found (a command missing, a block missing)."""
    readme = edition / "README.md"
    text = readme.read_text(encoding="utf-8") if readme.is_file() else ""
    section = text.split("## Build, test and grade your code", 1)
    block = re.search(r"```sh\n(.*?)```", section[1], re.S) if len(section) == 2 else None
    if block is None:
        return {}, ["the edition's README.md has no ```sh block under \"Build, test and grade your code\""]
    commands: dict[str, list[str]] = {}
    for line in block.group(1).splitlines():
        words = shlex.split(line.split("#", 1)[0].replace("NN", lesson))
        if not words:
            continue
        kind = ("configure" if words[:2] == ["cmake", "--preset"] else
                "build" if words[:2] == ["cmake", "--build"] else
                "test" if words[0].endswith(f"/tests_lesson{lesson}") else
                "program" if words[0].endswith(f"/lesson{lesson}") else
                "grade" if words[0] == "tools/grade" else "other")
        commands.setdefault(kind, words)
    missing = [k for k in ("configure", "build", "test", "program", "grade") if k not in commands]
    return commands, [f"the edition's README.md has no {k} command in its student block" for k in missing]


def _grade(edition: Path, command: list[str], results: Path) -> tuple[int, float | None, int]:
    """Runs the README's grade command (``tools/grade --student NN``) with a results file:
    (exit status, score %, grading tests)."""
    results.unlink(missing_ok=True)
    step = build.run_streaming([sys.executable, str(edition / command[0]), *command[1:], "--results", str(results)],
                               cwd=edition)
    status = 0 if step.ok else 1
    if not results.is_file():
        return 2, None, 0
    report = json.loads(results.read_text(encoding="utf-8"))
    score = 100.0 * report["score"] / report["max_score"] if report.get("max_score") else None
    return status, score, len(report.get("tests", []))


def check_one_lesson(lesson: str, work: Path, quick: bool) -> list[str]:
    """The student's path for one lesson handed out alone, by the commands of the edition's own
    README; the problems found."""
    from grading.edition import make_student_edition

    problems: list[str] = []
    edition = work / f"student-edition-{lesson}"
    made = make_student_edition(project.ROOT, edition, [lesson])
    problems += content_problems(edition)
    stubs = sorted((edition / "exercises").glob(f"{lesson}_*/*.cpp"))
    print(f"lesson {lesson}: edition in {edition} ({made.copied} files); exercise units: "
          f"{', '.join(s.name for s in stubs)}")
    commands, missing = readme_commands(edition, lesson)
    if missing:
        return problems + [f"lesson {lesson}: {problem}" for problem in missing]
    print(f"lesson {lesson}: the edition's README says: " + "; ".join(" ".join(c) for c in commands.values()))
    for kind in ("configure", "build"):
        if not build.run_streaming(commands[kind], cwd=edition).ok:
            return problems + [f"lesson {lesson}: `{' '.join(commands[kind])}` (the README's) fails in the edition "
                               "on the stubs"]
    # The README's test command on the stubs: it runs, fails, and says which functions are not written.
    tested = build.run_streaming(commands["test"], cwd=edition)
    print(f"lesson {lesson}: on the untouched stubs, `{' '.join(commands['test'])}` "
          + ("passes" if tested.ok else "fails") + (", naming NotImplemented" if "NotImplemented" in tested.output
                                                    else ""))
    if tested.ok or "NotImplemented" not in tested.output:
        problems.append(f"lesson {lesson}: on the stubs `{' '.join(commands['test'])}` should fail with "
                        "NotImplemented")
    results = work / f"grade-{lesson}.json"
    status, score, tests = _grade(edition, commands["grade"], results)
    print(f"lesson {lesson}: on the untouched stubs, {' '.join(commands['grade'])} exits {status}, "
          f"score {score}% over {tests} grading test(s)")
    if status != 1 or score != 0 or not tests:
        problems.append(f"lesson {lesson}: the stubs score {score}% (exit {status}, {tests} tests); expected 0%")
    for stub in stubs:
        references = sorted((project.ROOT / "lib").rglob(stub.name))
        if len(references) != 1:
            problems.append(f"lesson {lesson}: {stub.name} has {len(references)} reference(s) under lib/")
            continue
        shutil.copyfile(references[0], stub)
        print(f"lesson {lesson}: {references[0].relative_to(project.ROOT)} copied over "
              f"{stub.relative_to(edition)}")
    if not build.run_streaming(commands["build"], cwd=edition).ok:
        return problems + [f"lesson {lesson}: the edition does not build with the reference units as "
                           "the student's files"]
    tested = build.run_streaming(commands["test"], cwd=edition)
    print(f"lesson {lesson}: with the reference units, `{' '.join(commands['test'])}` "
          + ("passes" if tested.ok else "FAILS"))
    if not tested.ok:
        problems.append(f"lesson {lesson}: with the reference units as the student's files "
                        f"`{' '.join(commands['test'])}` fails: "
                        f"{(tested.output.strip().splitlines() or ['(no output)'])[-1]}")
    out = work / f"out-{lesson}"
    shutil.rmtree(out, ignore_errors=True)
    program = [str(edition / commands["program"][0]), *(["--quick"] if quick else []), "--out",
               str(out / f"lesson{lesson}")]
    run = build.run_streaming(program, echo=True, cwd=edition)
    print(f"lesson {lesson}: `lesson{lesson}{' --quick' if quick else ''}` "
          + ("runs to completion" if run.ok else "FAILS"))
    if not run.ok:
        problems.append(f"lesson {lesson}: the lesson program stops on the reference units placed as the "
                        f"student's: {(run.output.strip().splitlines() or ['(no output)'])[-1]}")
    status, score, tests = _grade(edition, commands["grade"], results)
    print(f"lesson {lesson}: with the reference units as the student's files, {' '.join(commands['grade'])} "
          f"exits {status}, score {score}% over {tests} grading test(s)")
    if status != 0 or score != 100.0:
        problems.append(f"lesson {lesson}: the reference units score {score}% (exit {status}); expected 100%")
    return problems


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", type=Path, default=project.ROOT / "build" / "release",
                        help="a configured build tree of the instructors' source (default build/release)")
    parser.add_argument("--work-dir", type=Path, help="build the edition here instead of a temporary folder")
    parser.add_argument("--lesson", metavar="NN", action="append",
                        help="check the edition handing out only lesson NN instead (repeatable; see above)")
    parser.add_argument("--quick", action="store_true", help="with --lesson: run the lesson program with --quick")
    args = parser.parse_args()

    if args.lesson:
        try:
            lessons = [project.normalize_lesson(t) for text in args.lesson for t in text.split(",") if t.strip()]
        except ValueError as error:
            print(f"check_student_edition: --lesson: {error}", file=sys.stderr)
            return 2
        exercises = project.exercise_lessons(project.ROOT)
        unknown = [nn for nn in lessons if nn not in exercises]
        if unknown:  # checked before any folder is made or anything built
            print(f"check_student_edition: --lesson {', '.join(unknown)}: no such lesson with exercises "
                  f"(lessons with exercises: {', '.join(exercises)})", file=sys.stderr)
            return 2
        problems = []
        with tempfile.TemporaryDirectory(prefix="illum-student-lesson-") as temporary:
            work = (args.work_dir or Path(temporary)).resolve()
            work.mkdir(parents=True, exist_ok=True)
            for lesson in lessons:
                problems += check_one_lesson(lesson, work, args.quick)
        for problem in problems:
            print(f"PROBLEM {problem}")
        print(f"student edition of lesson(s) {', '.join(lessons)} alone: "
              + ("ok" if not problems else f"FAILED ({len(problems)} problem(s))"))
        return 0 if not problems else 1

    step = build.run_streaming(["cmake", "--build", str(args.build_dir), "--target", "student-edition"])
    if not step.ok:
        print("check_student_edition: could not build the student-edition target", file=sys.stderr)
        return 2
    edition = args.build_dir / "student-edition"
    problems = content_problems(edition)

    with tempfile.TemporaryDirectory(prefix="illum-student-edition-") as temporary:
        work = args.work_dir or Path(temporary)
        command = ["cmake", "-S", str(edition), "-B", str(work), "-DCMAKE_BUILD_TYPE=Release", "-DILLUM_WERROR=ON"]
        # What a student builds: the lesson programs, the illum command and every lesson's test
        # program (not the stub twins, fuzz replays or benchmarks, which only instructors' checks use).
        targets = ["programs"] + [f"tests_lesson{nn}" for nn in project.test_lessons(edition)]
        if not build.run_streaming(command).ok or not build.build(work, targets).ok:
            print("check_student_edition: the student edition does not build", file=sys.stderr)
            return 2
        programs = grading_programs(work / "bin")
        if not programs:
            problems.append("the student edition built no tests_lessonNN program")
        handed_out = project.exercise_lessons(edition)
        for lesson, program in programs.items():
            run = run_suite(program, f"lesson{lesson}")
            if lesson not in handed_out:  # shipped as reference code: its tests must pass
                failed = [t.name for t in run.results if not t.passed and not t.skipped]
                problems += [f"lesson{lesson} (not handed out): \"{name}\" fails on the reference code it ships"
                             for name in failed]
                print(f"lesson{lesson}: not handed out; {len(run.results) - len(failed)}/{len(run.results)} "
                      "grading test(s) pass on its reference code")
                continue
            if run.problem:
                problems.append(run.problem)
            if not run.results:
                print(f"warning: lesson{lesson} has no grading test yet")
            for test in run.results:
                if test.passed:
                    problems.append(f"lesson{lesson}: \"{test.name}\" passes on the stubs (free points)")
                elif not test.not_implemented_only:
                    problems.append(f"lesson{lesson}: \"{test.name}\" fails for a reason other than "
                                    f"NotImplemented:\n  {test.output().replace(chr(10), chr(10) + '  ')}")
            print(f"lesson{lesson}: {len(run.results)} grading test(s) fail with NotImplemented"
                  if run.results and not any(p.startswith(f"lesson{lesson}") for p in problems) else
                  f"lesson{lesson}: checked")
        listed = subprocess.run(["ctest", "-N", "-R", "^grading_integrity$"], cwd=work,
                                capture_output=True, text=True, check=False).stdout
        if "grading_integrity" in listed:
            problems.append("the grading_integrity test is registered in the student edition")

    for problem in problems:
        print(f"PROBLEM {problem}")
    print("student edition: " + ("ok" if not problems else f"FAILED ({len(problems)} problem(s))"))
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main())
