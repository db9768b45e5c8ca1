#!/usr/bin/env python3
"""CI check of the student edition: what students get builds, holds no answers, and fails every grading
test of a lesson handed out with NotImplemented (a student starts at 0; each failure names the function
to write), while the lessons shipped as reference code pass.

    tests/checks/check_student_edition.py [--build-dir build/release] [--work-dir DIR]
    tests/checks/check_student_edition.py --lesson 07 [--quick] [--work-dir /tmp/ed07]

With --lesson NN (an instructor's re-verification, too slow for CI) it follows instead the student's
path for lesson NN handed out alone, by the commands of the edition's own README: on the stubs the tests
fail naming NotImplemented and tools/grade --student scores 0; with the reference units copied over the
stubs the build, the tests and the lesson program succeed and the score is 100%.
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

from repo import report
from gallery.kept_images import FIGURES_FOLDER, image_links, lesson_texts  # noqa: E402
from grading import build, project  # noqa: E402
from grading.edition import broken_links, make_student_edition  # noqa: E402
from grading.integrity import grading_programs  # noqa: E402
from grading.runner import run_suite  # noqa: E402

INSTRUCTORS_ONLY = ("## For instructors", "--pack-autograder", "--batch", "--check-integrity")


def content_problems(edition: Path) -> list[str]:
    """What must not be in the edition (reference units, hidden tests, instructors' material) and what must
    (its marker, the errata the texts cite, the lesson texts' kept images, a live target for every link)."""
    problems = []
    if not (edition / project.STUDENT_EDITION_MARKER).is_file():
        problems.append(f"{edition} has no {project.STUDENT_EDITION_MARKER} marker")
    if (edition / "tests" / "hidden").exists():
        problems.append("tests/hidden/ is in the student edition")
    if not (edition / "docs" / "errata.md").is_file():
        problems.append("docs/errata.md (the errata the lessons cite) is missing from the student edition")
    for text in lesson_texts(edition):
        links, _ = image_links(text.relative_to(edition), text.read_text(encoding="utf-8").splitlines())
        problems += [f"{text.relative_to(edition)}:{link.line + 1} shows {FIGURES_FOLDER}/{link.name}, which the "
                     "student edition lacks" for link in links
                     if link.kept and not (text.parent / FIGURES_FOLDER / link.name).is_file()]
    problems += [f"dead link: {problem}" for problem in broken_links(edition)]
    readme = (edition / "README.md").read_text(encoding="utf-8") if (edition / "README.md").is_file() else ""
    if not readme or "student edition" not in readme.splitlines()[0]:
        problems.append("README.md is not the student edition's own README")
    problems += [f"README.md holds instructors' material ({words!r})" for words in INSTRUCTORS_ONLY if words in readme]
    stubs = project.exercise_stubs(edition)
    return problems + [f"{reference.relative_to(edition)} is the reference of the exercise "
                       f"{stubs[reference.name].relative_to(edition)}"
                       for reference in sorted((edition / "lib").rglob("*.cpp")) if reference.name in stubs]


def readme_commands(edition: Path, lesson: str) -> tuple[dict[str, list[str]], list[str]]:
    """The student commands of the edition's own README ("Build, test and grade your code"), NN replaced
    by the lesson, by what each does; and the problems found (a block or a command missing)."""
    readme = edition / "README.md"
    section = (readme.read_text(encoding="utf-8") if readme.is_file() else "").split(
        "## Build, test and grade your code", 1)
    block = re.search(r"```sh\n(.*?)```", section[1], re.S) if len(section) == 2 else None
    if block is None:
        return {}, ["the edition's README.md has no ```sh block under \"Build, test and grade your code\""]
    commands: dict[str, list[str]] = {}
    for line in block.group(1).splitlines():
        if words := shlex.split(line.split("#", 1)[0].replace("NN", lesson)):
            kind = ("configure" if words[:2] == ["cmake", "--preset"] else
                    "build" if words[:2] == ["cmake", "--build"] else
                    "test" if words[0].endswith(f"/tests_lesson{lesson}") else
                    "program" if words[0].endswith(f"/lesson{lesson}") else
                    "grade" if words[0] == "tools/grade" else "other")
            commands.setdefault(kind, words)
    missing = [k for k in ("configure", "build", "test", "program", "grade") if k not in commands]
    return commands, [f"the edition's README.md has no {k} command in its student block" for k in missing]


class OneLesson:
    """The student's path for one lesson handed out alone, by the commands of the edition's README."""

    def __init__(self, lesson: str, work: Path, quick: bool):
        self.lesson, self.work, self.quick = lesson, work, quick
        self.edition = work / f"student-edition-{lesson}"
        self.results = work / f"grade-{lesson}.json"
        self.problems: list[str] = []

    def say(self, text: str) -> None:
        print(f"lesson {self.lesson}: {text}")

    def run(self, kind: str, echo: bool = True) -> build.StepResult:
        return build.run_streaming(self.commands[kind], echo=echo, cwd=self.edition)

    def grade(self) -> tuple[int, float | None, int]:
        """The README's grade command with a results file: (exit status, score %, grading tests)."""
        self.results.unlink(missing_ok=True)
        command = self.commands["grade"]
        step = build.run_streaming([sys.executable, str(self.edition / command[0]), *command[1:], "--results",
                                    str(self.results)], cwd=self.edition)
        if not self.results.is_file():
            return 2, None, 0
        report = json.loads(self.results.read_text(encoding="utf-8"))
        score = 100.0 * report["score"] / report["max_score"] if report.get("max_score") else None
        return 0 if step.ok else 1, score, len(report.get("tests", []))

    def check(self) -> list[str]:
        made = make_student_edition(project.ROOT, self.edition, [self.lesson])
        self.problems += content_problems(self.edition)
        stubs = sorted((self.edition / "exercises").glob(f"{self.lesson}_*/*.cpp"))
        self.say(f"edition in {self.edition} ({made.copied} files); exercise units: "
                 f"{', '.join(s.name for s in stubs)}")
        self.commands, missing = readme_commands(self.edition, self.lesson)
        if missing:
            return self.problems + [f"lesson {self.lesson}: {problem}" for problem in missing]
        self.say("the edition's README says: " + "; ".join(" ".join(c) for c in self.commands.values()))
        if failed := next((k for k in ("configure", "build") if not self.run(k).ok), None):
            return self.problems + [f"lesson {self.lesson}: `{' '.join(self.commands[failed])}` (the README's) fails "
                                    "in the edition on the stubs"]
        self.on_the_stubs()
        for stub in stubs:
            references = sorted((project.ROOT / "lib").rglob(stub.name))
            if len(references) != 1:
                self.problems.append(f"lesson {self.lesson}: {stub.name} has {len(references)} reference(s) under lib/")
                continue
            shutil.copyfile(references[0], stub)
            self.say(f"{references[0].relative_to(project.ROOT)} copied over {stub.relative_to(self.edition)}")
        if not self.run("build").ok:
            return self.problems + [f"lesson {self.lesson}: the edition does not build with the reference units as "
                                    "the student's files"]
        self.with_the_references()
        return self.problems

    def on_the_stubs(self) -> None:
        """The test command fails naming NotImplemented; the grade is 0."""
        test = " ".join(self.commands["test"])
        tested = self.run("test")
        self.say(f"on the untouched stubs, `{test}` " + ("passes" if tested.ok else "fails")
                 + (", naming NotImplemented" if "NotImplemented" in tested.output else ""))
        if tested.ok or "NotImplemented" not in tested.output:
            self.problems.append(f"lesson {self.lesson}: on the stubs `{test}` should fail with NotImplemented")
        status, score, tests = self.grade()
        self.say(f"on the untouched stubs, {' '.join(self.commands['grade'])} exits {status}, score {score}% over "
                 f"{tests} grading test(s)")
        if status != 1 or score != 0 or not tests:
            self.problems.append(f"lesson {self.lesson}: the stubs score {score}% (exit {status}, {tests} tests); "
                                 "expected 0%")

    def with_the_references(self) -> None:
        """The reference units as the student's: the tests pass, the program runs through, the grade is 100%."""
        test, last = " ".join(self.commands["test"]), lambda run: (run.output.strip().splitlines() or
                                                                   ["(no output)"])[-1]
        tested = self.run("test")
        self.say(f"with the reference units, `{test}` " + ("passes" if tested.ok else "FAILS"))
        if not tested.ok:
            self.problems.append(f"lesson {self.lesson}: with the reference units as the student's files `{test}` "
                                 f"fails: {last(tested)}")
        out = self.work / f"out-{self.lesson}"
        shutil.rmtree(out, ignore_errors=True)
        program = [str(self.edition / self.commands["program"][0]), *(["--quick"] if self.quick else []), "--out",
                   str(out / f"lesson{self.lesson}")]
        ran = build.run_streaming(program, echo=True, cwd=self.edition)
        self.say(f"`lesson{self.lesson}{' --quick' if self.quick else ''}` "
                 + ("runs to completion" if ran.ok else "FAILS"))
        if not ran.ok:
            self.problems.append(f"lesson {self.lesson}: the lesson program stops on the reference units placed as "
                                 f"the student's: {last(ran)}")
        status, score, tests = self.grade()
        self.say(f"with the reference units as the student's files, {' '.join(self.commands['grade'])} exits "
                 f"{status}, score {score}% over {tests} grading test(s)")
        if status != 0 or score != 100.0:
            self.problems.append(f"lesson {self.lesson}: the reference units score {score}% (exit {status}); "
                                 "expected 100%")


def check_lessons(texts: list[str], work_dir: Path | None, quick: bool) -> int:
    try:
        lessons = [project.normalize_lesson(t) for text in texts for t in text.split(",") if t.strip()]
    except ValueError as error:
        print(f"check_student_edition: --lesson: {error}", file=sys.stderr)
        return 2
    exercises = project.exercise_lessons(project.ROOT)
    if unknown := [nn for nn in lessons if nn not in exercises]:  # before any folder is made or anything built
        print(f"check_student_edition: --lesson {', '.join(unknown)}: no such lesson with exercises "
              f"(lessons with exercises: {', '.join(exercises)})", file=sys.stderr)
        return 2
    problems = []
    with tempfile.TemporaryDirectory(prefix="illum-student-lesson-") as temporary:
        work = (work_dir or Path(temporary)).resolve()
        work.mkdir(parents=True, exist_ok=True)
        for lesson in lessons:
            problems += OneLesson(lesson, work, quick).check()
    return report(problems, f"student edition of lesson(s) {', '.join(lessons)} alone", "ok", prefix="PROBLEM ")


def suite_problems(lesson: str, program: Path, handed_out: bool) -> list[str]:
    """A lesson handed out fails every grading test with NotImplemented; one shipped as reference code passes."""
    run = run_suite(program, f"lesson{lesson}")
    if not handed_out:
        failed = [t.name for t in run.results if not t.passed and not t.skipped]
        print(f"lesson{lesson}: not handed out; {len(run.results) - len(failed)}/{len(run.results)} grading test(s) "
              "pass on its reference code")
        return [f"lesson{lesson} (not handed out): \"{name}\" fails on the reference code it ships" for name in failed]
    problems = [run.problem] if run.problem else []
    if not run.results:
        print(f"warning: lesson{lesson} has no grading test yet")
    for test in run.results:
        if test.passed:
            problems.append(f"lesson{lesson}: \"{test.name}\" passes on the stubs (free points)")
        elif not test.not_implemented_only:
            problems.append(f"lesson{lesson}: \"{test.name}\" fails for a reason other than NotImplemented:\n  "
                            + test.output().replace("\n", "\n  "))
    print(f"lesson{lesson}: {len(run.results)} grading test(s) fail with NotImplemented" if run.results
          and not any(p.startswith(f"lesson{lesson}") for p in problems) else f"lesson{lesson}: checked")
    return problems


def check_edition(build_dir: Path, work_dir: Path | None) -> int:
    if not build.run_streaming(["cmake", "--build", str(build_dir), "--target", "student-edition"]).ok:
        print("check_student_edition: could not build the student-edition target", file=sys.stderr)
        return 2
    edition = build_dir / "student-edition"
    problems = content_problems(edition)
    with tempfile.TemporaryDirectory(prefix="illum-student-edition-") as temporary:
        work = work_dir or Path(temporary)
        # What a student builds: the lesson programs, the illum command and every lesson's test program.
        targets = ["programs"] + [f"tests_lesson{nn}" for nn in project.test_lessons(edition)]
        if not build.run_streaming(["cmake", "-S", str(edition), "-B", str(work), "-DCMAKE_BUILD_TYPE=Release",
                                    "-DILLUM_WERROR=ON"]).ok or not build.build(work, targets).ok:
            print("check_student_edition: the student edition does not build", file=sys.stderr)
            return 2
        programs = grading_programs(work / "bin")
        if not programs:
            problems.append("the student edition built no tests_lessonNN program")
        handed_out = project.exercise_lessons(edition)
        for lesson, program in programs.items():
            problems += suite_problems(lesson, program, lesson in handed_out)
        if "grading_integrity" in subprocess.run(["ctest", "-N", "-R", "^grading_integrity$"], cwd=work,
                                                 capture_output=True, text=True, check=False).stdout:
            problems.append("the grading_integrity test is registered in the student edition")
    return report(problems, "student edition", "ok", prefix="PROBLEM ")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", type=Path, default=project.ROOT / "build" / "release",
                        help="a configured build tree of the instructors' source (default build/release)")
    parser.add_argument("--work-dir", type=Path, help="build the edition here instead of a temporary folder")
    parser.add_argument("--lesson", metavar="NN", action="append",
                        help="check the edition handing out only lesson NN instead (repeatable; see above)")
    parser.add_argument("--quick", action="store_true", help="with --lesson: run the lesson program with --quick")
    args = parser.parse_args()
    return check_lessons(args.lesson, args.work_dir, args.quick) if args.lesson else \
        check_edition(args.build_dir, args.work_dir)


if __name__ == "__main__":
    sys.exit(main())
