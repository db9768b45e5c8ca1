#!/usr/bin/env python3
"""CI check of the student edition: what students get must build, must not
contain the answers, and must make every grading test fail with
NotImplemented (so a student starts at 0 and every failure names the
function still to write).

Steps: build the ``student-edition`` target of a configured tree; check the
edition holds no reference unit and no hidden test; configure and build it
in a temporary folder; run each ``tests_lessonNN`` on suite ``lessonNN``
through the illum-grade reporter (every test of a lesson handed out must fail
with NotImplemented, every test of a lesson shipped as reference code must
pass); check that the grading_integrity test is
not registered there.
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from grading import build, project  # noqa: E402
from grading.integrity import grading_programs  # noqa: E402
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
    stubs = project.exercise_stubs(edition)
    for reference in sorted((edition / "lib").rglob("*.cpp")):
        if reference.name in stubs:
            problems.append(f"{reference.relative_to(edition)} is the reference of the exercise "
                            f"{stubs[reference.name].relative_to(edition)}")
    return problems


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", type=Path, default=project.ROOT / "build" / "release",
                        help="a configured build tree of the instructors' source (default build/release)")
    parser.add_argument("--work-dir", type=Path, help="build the edition here instead of a temporary folder")
    args = parser.parse_args()

    step = build.run_streaming(["cmake", "--build", str(args.build_dir), "--target", "student-edition"])
    if not step.ok:
        print("check_student_edition: could not build the student-edition target", file=sys.stderr)
        return 2
    edition = args.build_dir / "student-edition"
    problems = content_problems(edition)

    with tempfile.TemporaryDirectory(prefix="illum-student-edition-") as temporary:
        work = args.work_dir or Path(temporary)
        command = ["cmake", "-S", str(edition), "-B", str(work), "-DCMAKE_BUILD_TYPE=Release", "-DILLUM_WERROR=ON"]
        if not build.run_streaming(command).ok or not build.build(work, []).ok:
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
