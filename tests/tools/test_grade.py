#!/usr/bin/env python3
"""Unit tests of the grading driver's pure parts: parsing reporter lines,
the score table, results.json, JUnit XML, exit codes, the student edition's
file selection and the submission installer. Nothing is built here; the
end-to-end behaviour is covered by the grading_integrity ctest and by
running tools/grade (docs/grading.md).

Run: python3 tests/tools/test_grade.py   (ctest: tools_grade_py)
"""
from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))

from grading import reports  # noqa: E402
from grading.autograder import install_submission, run_script, setup_script  # noqa: E402
from grading.build import failed_exercise_files  # noqa: E402
from grading.driver import main as grade_main  # noqa: E402
from grading.alone import declared_dependencies  # noqa: E402
from grading.edition import excluded_files  # noqa: E402
from grading.integrity import check_pair  # noqa: E402
from grading.project import normalize_lesson  # noqa: E402
from grading.reports import GradeRun  # noqa: E402
from grading.results import merge, parse_lines, points_of  # noqa: E402

NI = "NotImplemented: intersect(Ray, Sphere) — take the nearest root"


def listed(name: str, line: int, description: str = "", suite: str = "lesson01") -> str:
    return json.dumps({"event": "listed", "suite": suite, "name": name, "file": "/src/tests/01_x/a.cpp",
                       "line": line, "description": description})


def ran(name: str, line: int, passed: bool, failures: list[dict] | None = None, suite: str = "lesson01") -> str:
    failures = failures or []
    return json.dumps({
        "event": "test_case", "suite": suite, "name": name, "file": "/src/tests/01_x/a.cpp", "line": line,
        "description": "", "passed": passed, "skipped": False, "seconds": 0.001, "asserts": 1,
        "asserts_failed": 0 if passed else 1, "failures": failures,
        "not_implemented_only": bool(failures) and all(f["not_implemented"] for f in failures)})


def assert_failure(message: str, not_implemented: bool = False, context: str = "") -> dict:
    return {"kind": "assert", "file": "/src/tests/01_x/a.cpp", "line": 12, "expression": "hit.s == 4",
            "expansion": "3 == 4", "exception": NI if not_implemented else "", "context": context,
            "subcases": [], "message": message, "not_implemented": not_implemented}


LISTING = [listed("head-on hit", 5), listed("refuses a negative radius", 9, "points=2"), listed("grazing", 14)]
RUN = [
    ran("head-on hit", 5, True),
    ran("refuses a negative radius", 9, False, [assert_failure("CHECK( r > 0 ) is NOT correct", context="r must be positive")]),
    ran("grazing", 14, False, [assert_failure("threw", not_implemented=True)]),
]


def sample_run(hidden_extra: bool = False) -> GradeRun:
    results = merge(parse_lines(LISTING), parse_lines(RUN))
    if hidden_extra:
        results += merge(parse_lines([listed("hidden one", 3)]), parse_lines([ran("hidden one", 3, True)]),
                         hidden=True)
    return GradeRun(lessons=["01"], results=results, student=True)


class ParsingTest(unittest.TestCase):
    def test_points_default_to_one_and_read_the_description(self) -> None:
        self.assertEqual(points_of(""), 1.0)
        self.assertEqual(points_of("points=3"), 3.0)
        self.assertEqual(points_of("the hard one, points = 2.5"), 2.5)

    def test_garbage_and_half_written_lines_are_skipped(self) -> None:
        records = parse_lines(["hello from student code", LISTING[0], '{"event": "test_ca', "", "[1,2]"])
        self.assertEqual(len(records), 1)

    def test_merge_keeps_listing_order_and_the_listed_points(self) -> None:
        results = merge(parse_lines(LISTING), parse_lines(RUN))
        self.assertEqual([r.name for r in results], ["head-on hit", "refuses a negative radius", "grazing"])
        self.assertEqual([r.points for r in results], [1.0, 2.0, 1.0])
        self.assertEqual([r.passed for r in results], [True, False, False])
        self.assertTrue(results[2].not_implemented_only)
        self.assertFalse(results[1].not_implemented_only)

    def test_a_crash_fails_the_tests_that_never_ran(self) -> None:
        results = merge(parse_lines(LISTING), parse_lines(RUN[:1]), why_missing="killed by SIGSEGV")
        self.assertEqual([r.status for r in results], ["passed", "not run", "not run"])
        self.assertIn("killed by SIGSEGV", results[1].output())

    def test_lesson_numbers_are_normalised(self) -> None:
        self.assertEqual(normalize_lesson("1"), "01")
        self.assertEqual(normalize_lesson("lesson10"), "10")
        with self.assertRaises(ValueError):
            normalize_lesson("one")


class ReportTest(unittest.TestCase):
    def test_score_table_counts_tests_and_points(self) -> None:
        table = reports.score_table(sample_run())
        self.assertRegex(table, r"\n01\s+1/3\s+1/4")
        self.assertRegex(table, r"total\s+1/3\s+1/4\s+\(25%\)")

    def test_hidden_tests_get_their_own_row(self) -> None:
        table = reports.score_table(sample_run(hidden_extra=True))
        self.assertRegex(table, r"01 \(hidden\)\s+1/1\s+1/1")
        self.assertRegex(table, r"total\s+2/4\s+2/5")

    def test_results_json_follows_gradescope(self) -> None:
        data = reports.gradescope_results(sample_run(hidden_extra=True), Path("/src"))
        self.assertEqual((data["score"], data["max_score"]), (2.0, 5.0))
        self.assertEqual(data["visibility"], "visible")
        # The compiler's output and the logs are on stdout too: students read them once, in results.json.
        self.assertEqual(data["stdout_visibility"], "hidden")
        self.assertEqual(data["output_format"], "md")
        self.assertIn("```text\nlesson", data["output"])  # the table in a code block keeps its columns
        # While hidden tests exist, students see neither their row nor the total (Gradescope hides it too).
        self.assertNotIn("hidden", data["output"].split("```text")[1].split("Hidden tests")[0])
        self.assertNotRegex(data["output"], r"(?m)^total")
        self.assertEqual(len(data["tests"]), 4)
        for test in data["tests"]:
            self.assertEqual(set(test) >= {"name", "score", "max_score", "status", "output", "visibility"}, True)
            self.assertIn(test["status"], ("passed", "failed"))
        negative = data["tests"][1]
        self.assertEqual((negative["score"], negative["max_score"], negative["status"]), (0.0, 2.0, "failed"))
        self.assertIn("tests/01_x/a.cpp:12", negative["output"])  # path relative to the tree
        self.assertIn("r must be positive", negative["output"])   # the test's explanation reaches the student
        self.assertIn("not implemented yet: " + NI, data["tests"][2]["output"])
        self.assertEqual(data["tests"][3]["visibility"], reports.HIDDEN_VISIBILITY)
        json.dumps(data)  # serialisable

    def test_build_failure_scores_zero_and_shows_the_compiler_once(self) -> None:
        run = GradeRun(lessons=["01"], build_failed=True,
                       build_output="exercises/01_ray_sphere/sphere.cpp:3: error: expected ';' in vector<T>")
        data = reports.gradescope_results(run)
        self.assertEqual(data["score"], 0)
        self.assertIn("did not compile", data["output"])
        self.assertNotIn("expected ';'", data["output"])  # once: in the build entry
        self.assertEqual(data["tests"][0]["status"], "failed")
        self.assertEqual(data["tests"][0]["output_format"], "text")  # keeps the <T>
        self.assertIn("expected ';' in vector<T>", data["tests"][0]["output"])
        self.assertIn("build failed", reports.score_table(run))

    def test_a_broken_tree_does_not_blame_the_student(self) -> None:
        run = GradeRun(lessons=["01"], build_failed=True, blame_student=False, build_output="lib/x.cpp: error")
        self.assertNotIn("Your code", reports.gradescope_results(run)["output"])
        self.assertIn("not your code", reports.gradescope_results(run)["output"])

    def test_hidden_tests_that_do_not_build_are_shown_to_instructors_only(self) -> None:
        run = sample_run()
        run.hidden_build_failed = True
        run.hidden_build_output = "tests/hidden/secret.cpp:9: error: SECRET_EXPECTATION undeclared"
        data = reports.gradescope_results(run, Path("/src"))
        self.assertIn("misconfigured", data["output"])
        self.assertNotIn("SECRET", data["output"])
        secret = [t for t in data["tests"] if "SECRET" in t["output"]]
        self.assertEqual([t["visibility"] for t in secret], ["hidden"])
        self.assertEqual(sum(t["max_score"] for t in data["tests"]), 4.0)  # the visible tests are graded
        self.assertEqual(reports.exit_code(run), 2)

    def test_a_file_that_fell_back_to_its_stub_is_named(self) -> None:
        run = sample_run()
        run.fallbacks = {"exercises/01_ray_sphere/sphere.cpp": "sphere.cpp:1: error: x"}
        data = reports.gradescope_results(run)
        self.assertIn("exercises/01_ray_sphere/sphere.cpp", data["output"])
        self.assertEqual(data["tests"][0]["name"],
                         "build: exercises/01_ray_sphere/sphere.cpp did not compile (graded as the stub)")

    def test_results_say_what_was_graded(self) -> None:
        run = sample_run()
        run.submission = {"installed": [{"file": "sphere (1).cpp", "target": "exercises/01_ray_sphere/sphere.cpp",
                                         "note": "taken as sphere.cpp"}],
                          "ignored": [{"file": "notes.txt", "reason": "not a C++ file"}],
                          "notes": [], "expected": ["sphere.cpp"]}
        output = reports.gradescope_results(run)["output"]
        self.assertIn("used `sphere (1).cpp` as `exercises/01_ray_sphere/sphere.cpp` (taken as sphere.cpp)", output)
        self.assertIn("ignored `notes.txt`: not a C++ file", output)
        run.submission["expected"] = ["sphere.cpp", "triangle.cpp"]
        self.assertIn("not in your upload, so graded as the unchanged stub: `triangle.cpp`",
                      reports.gradescope_results(run)["output"])
        run.submission = {"installed": [], "ignored": [], "notes": [], "expected": ["sphere.cpp"]}
        self.assertIn("Upload `sphere.cpp`", reports.gradescope_results(run)["output"])

    def test_long_outputs_are_cut(self) -> None:
        run = GradeRun(lessons=["01"], build_failed=True, build_output="x" * (reports.MAX_OUTPUT_CHARS + 10))
        self.assertLess(len(reports.gradescope_results(run)["output"]), reports.MAX_OUTPUT_CHARS + 200)

    def test_junit_has_a_suite_per_lesson_and_failures_typed(self) -> None:
        root = ET.fromstring(reports.junit_xml(sample_run(hidden_extra=True)))
        suites = {s.get("name"): s for s in root.iter("testsuite")}
        self.assertEqual(set(suites), {"lesson01", "lesson01.hidden"})
        self.assertEqual((suites["lesson01"].get("tests"), suites["lesson01"].get("failures")), ("3", "2"))
        types = [f.get("type") for f in root.iter("failure")]
        self.assertEqual(types, ["AssertionFailure", "NotImplemented"])
        self.assertEqual(root.get("tests"), "4")

    def test_junit_survives_control_characters(self) -> None:
        run = sample_run()
        run.results[1].failures[0].message = "bad \x01 byte"
        ET.fromstring(reports.junit_xml(run))

    def test_junit_reports_a_build_failure_as_an_error(self) -> None:
        run = GradeRun(lessons=["01"], build_failed=True, build_output="error: boom")
        root = ET.fromstring(reports.junit_xml(run))
        self.assertEqual(root.get("errors"), "1")
        self.assertIn("boom", next(root.iter("error")).text)


FAKE_PROGRAM = """#!/usr/bin/env python3
# Stands in for a doctest program: lists two tests, reports the first, then dies.
import os, signal, sys, time
out = next(a.split("=", 1)[1] for a in sys.argv if a.startswith("--out="))
with open(out, "w") as f:
    if "--list-test-cases" in sys.argv:
        f.write(LISTED)
        sys.exit(0)
    f.write(FIRST + "\\n")
    f.flush()
print("student debug output on stdout")
if MODE == "crash":
    os.kill(os.getpid(), signal.SIGSEGV)
time.sleep(30)
"""


RERUN_PROGRAM = """#!/usr/bin/env python3
# Stands in for a doctest program with three tests; the second never ends.
import json, sys, time
out = next(a.split("=", 1)[1] for a in sys.argv if a.startswith("--out="))
first = int(next((a.split("=", 1)[1] for a in sys.argv if a.startswith("--first=")), "1"))
names = ["one", "loops", "three"]
def record(event, number, **extra):
    return json.dumps(dict(event=event, suite="lesson01", name=names[number - 1], file="/t.cpp", line=number,
                           description="", **extra)) + "\\n"
with open(out, "w") as f:
    if "--list-test-cases" in sys.argv:
        f.write("".join(record("listed", n) for n in (1, 2, 3)))
        sys.exit(0)
    for number in range(first, 4):
        f.write(record("started", number)); f.flush()
        if number == 2:
            time.sleep(60)
        f.write(record("test_case", number, passed=True, skipped=False, failures=[])); f.flush()
"""


class RunnerTest(unittest.TestCase):
    def test_a_hanging_test_costs_only_itself(self) -> None:
        from grading.runner import run_suite

        with tempfile.TemporaryDirectory() as folder:
            program = Path(folder) / "tests_lesson01"
            program.write_text(RERUN_PROGRAM)
            program.chmod(0o755)
            run = run_suite(program, "lesson01", timeout=30, test_timeout=1.0)
        self.assertEqual([(r.name, r.status) for r in run.results],
                         [("one", "passed"), ("loops", "failed"), ("three", "passed")])
        self.assertIn("did not finish within 1 s", run.results[1].output())
        self.assertIn('test "loops"', run.problem)

    def test_no_test_starts_after_the_deadline(self) -> None:
        from grading import runner

        with tempfile.TemporaryDirectory() as folder:
            program = Path(folder) / "tests_lesson01"
            program.write_text(RERUN_PROGRAM)
            program.chmod(0o755)
            runner.set_deadline(0.0)
            try:
                run = runner.run_suite(program, "lesson01", timeout=30, test_timeout=1.0)
            finally:
                runner.set_deadline(None)
        self.assertEqual([r.status for r in run.results], ["not run"] * 3)
        self.assertIn("ILLUM_GRADE_DEADLINE", run.results[0].output())

    """A crashing or hanging program still gives a result for every listed test."""

    def run_fake(self, mode: str, timeout: float) -> "object":
        from grading.runner import run_suite

        with tempfile.TemporaryDirectory() as folder:
            program = Path(folder) / "tests_lesson01"
            shebang, body = FAKE_PROGRAM.split("\n", 1)
            constants = (f"LISTED = {(LISTING[0] + chr(10) + LISTING[2] + chr(10))!r}\n"
                         f"FIRST = {RUN[0]!r}\nMODE = {mode!r}\n")
            program.write_text(shebang + "\n" + constants + body)
            program.chmod(0o755)
            return run_suite(program, "lesson01", timeout=timeout)

    def test_crash(self) -> None:
        run = self.run_fake("crash", timeout=20)
        self.assertEqual([r.status for r in run.results], ["passed", "not run"])
        self.assertIn("SIGSEGV", run.problem)
        self.assertIn("SIGSEGV", run.results[1].output())

    def test_timeout(self) -> None:
        run = self.run_fake("hang", timeout=1.5)
        self.assertEqual([r.status for r in run.results], ["passed", "not run"])
        self.assertIn("did not finish", run.results[1].note)


class ExitCodeTest(unittest.TestCase):
    def test_exit_codes(self) -> None:
        self.assertEqual(reports.exit_code(sample_run()), 1)
        passing = sample_run()
        passing.results = [r for r in passing.results if r.passed]
        self.assertEqual(reports.exit_code(passing), 0)
        self.assertEqual(reports.exit_code(GradeRun(lessons=["01"], build_failed=True)), 2)
        # Nothing graded is not a pass.
        self.assertEqual(reports.exit_code(GradeRun(lessons=["01"])), 1)


class IntegrityTest(unittest.TestCase):
    def test_a_clean_pair_has_no_problem(self) -> None:
        reference = merge(parse_lines(LISTING[:1]), parse_lines(RUN[:1]))
        stubs = merge(parse_lines(LISTING[:1]), parse_lines([ran("head-on hit", 5, False,
                                                                 [assert_failure("t", not_implemented=True)])]))
        self.assertEqual(check_pair("x", reference, stubs), [])

    def test_offenders(self) -> None:
        reference = merge(parse_lines(LISTING), parse_lines(RUN))
        stubs = merge(parse_lines(LISTING), parse_lines([
            ran("head-on hit", 5, True),
            ran("refuses a negative radius", 9, False, [assert_failure("CHECK( r > 0 ) is NOT correct")]),
            ran("grazing", 14, False, [assert_failure("t", not_implemented=True)])]))
        problems = "\n".join(check_pair("x", reference, stubs))
        self.assertIn("does not pass on the reference", problems)
        self.assertIn("PASSES on the stubs", problems)
        self.assertIn("other than NotImplemented", problems)
        self.assertIn("no test", "\n".join(check_pair("x", [], [])))


class EditionTest(unittest.TestCase):
    def test_reference_units_hidden_tests_and_generated_files_are_left_out(self) -> None:
        files = ["CMakeLists.txt", "lib/illum/geometry/sphere.cpp", "lib/illum/geometry/sphere.hpp",
                 "lib/illum/core/ray.cpp", "exercises/01_ray_sphere/sphere.cpp", "exercises/01_ray_sphere/README.md",
                 "tests/hidden/lesson01_hidden.cpp", "tests/hidden/README.md", "tests/01_ray_sphere/grading.cpp",
                 "build/release/x", "out/index.html"]
        left_out = excluded_files(files)
        self.assertEqual(set(left_out), {"lib/illum/geometry/sphere.cpp", "tests/hidden/lesson01_hidden.cpp",
                                         "tests/hidden/README.md", "build/release/x", "out/index.html"})


class HandOutTest(unittest.TestCase):
    FILES = ["lib/illum/geometry/sphere.cpp", "lib/illum/geometry/parity.cpp", "lib/illum/core/ray.cpp",
             "exercises/01_ray_sphere/sphere.cpp", "exercises/01_ray_sphere/README.md",
             "exercises/02_polygon_parity/parity.cpp", "exercises/02_polygon_parity/README.md",
             "exercises/02_polygon_parity/depends.txt", "tests/02_polygon_parity/grading.cpp"]

    def test_lessons_not_handed_out_keep_their_reference_and_lose_their_exercise(self) -> None:
        left_out = excluded_files(self.FILES, ["02"])
        self.assertEqual(set(left_out), {"lib/illum/geometry/parity.cpp", "exercises/01_ray_sphere/sphere.cpp",
                                         "exercises/01_ray_sphere/README.md"})
        self.assertNotIn("lib/illum/geometry/sphere.cpp", left_out)  # lesson 01 ships as working code

    def test_every_lesson_is_handed_out_by_default(self) -> None:
        left_out = excluded_files(self.FILES)
        self.assertIn("lib/illum/geometry/sphere.cpp", left_out)
        self.assertIn("lib/illum/geometry/parity.cpp", left_out)
        self.assertFalse(any(f.startswith("exercises/") for f in left_out))

    def test_depends_txt_separates_grading_from_program_dependencies(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            root = Path(folder)
            (root / "exercises" / "06_ray_tree").mkdir(parents=True)
            (root / "exercises" / "06_ray_tree" / "depends.txt").write_text(
                "# comment\n01   # spheres\n03 program  # meshes\n\n")
            self.assertEqual(declared_dependencies("06", root), ["01", "03"])
            self.assertEqual(declared_dependencies("06", root, program=False), ["01"])
            self.assertEqual(declared_dependencies("07", root), [])
            (root / "exercises" / "06_ray_tree" / "depends.txt").write_text("lesson one\n")
            with self.assertRaises(ValueError):
                declared_dependencies("06", root)


class AutograderTest(unittest.TestCase):
    def make_tree(self, folder: str) -> tuple[Path, Path]:
        tree, submission = Path(folder) / "tree", Path(folder) / "submission"
        (tree / "exercises" / "01_ray_sphere").mkdir(parents=True)
        (tree / "exercises" / "02_polygons").mkdir(parents=True)
        (tree / "exercises" / "01_ray_sphere" / "sphere.cpp").write_text("stub")
        (tree / "exercises" / "02_polygons" / "polygon.cpp").write_text("stub")
        submission.mkdir()
        return tree, submission

    def test_submission_files_replace_the_stubs_by_name(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            tree, submission = self.make_tree(folder)
            (submission / "deep" / "er").mkdir(parents=True)
            (submission / "deep" / "er" / "sphere.cpp").write_text("older copy")
            (submission / "sphere.cpp").write_text("mine")
            (submission / "polygon.cpp").write_text("not graded in this assignment")
            (submission / "notes.cpp").write_text("?")
            (submission / "notes.txt").write_text("?")
            report = install_submission(submission, tree, ["01"])
            self.assertEqual(report.installed, [{"file": "sphere.cpp", "target": "exercises/01_ray_sphere/sphere.cpp",
                                                 "note": ""}])
            self.assertEqual((tree / "exercises" / "01_ray_sphere" / "sphere.cpp").read_text(), "mine")
            self.assertEqual((tree / "exercises" / "02_polygons" / "polygon.cpp").read_text(), "stub")
            reasons = {i["file"]: i["reason"] for i in report.ignored}
            self.assertEqual(sorted(reasons), ["deep/er/sphere.cpp", "notes.cpp", "notes.txt", "polygon.cpp"])
            self.assertIn("`sphere.cpp` was used", reasons["deep/er/sphere.cpp"])
            self.assertEqual(reasons["notes.txt"], "not a C++ file")
            self.assertEqual(report.expected, ["sphere.cpp"])

    def test_renamed_files_and_zips_are_recognised(self) -> None:
        import zipfile
        with tempfile.TemporaryDirectory() as folder:
            tree, submission = self.make_tree(folder)
            (submission / "Sphere (1).cpp").write_text("renamed by a browser")
            report = install_submission(submission, tree, ["01"])
            self.assertEqual(report.installed[0]["file"], "Sphere (1).cpp")
            self.assertIn("taken as sphere.cpp", report.installed[0]["note"])
            (submission / "Sphere (1).cpp").unlink()
            with zipfile.ZipFile(submission / "homework.zip", "w") as archive:
                archive.writestr("homework/exercises/01_ray_sphere/sphere.cpp", "zipped")
                archive.writestr("../evil.cpp", "outside")
                archive.writestr("__MACOSX/homework/._sphere.cpp", "junk")
            report = install_submission(submission, tree, ["01"])
            self.assertEqual((tree / "exercises" / "01_ray_sphere" / "sphere.cpp").read_text(), "zipped")
            self.assertEqual(report.installed[0]["file"], "homework.zip/homework/exercises/01_ray_sphere/sphere.cpp")
            self.assertTrue(any("unpacked `homework.zip`" in n for n in report.notes))
            self.assertFalse((Path(folder) / "evil.cpp").exists())

    def test_scripts_install_the_packages_and_grade_the_lessons(self) -> None:
        setup = setup_script(["cmake", "g++"], ["01"])
        self.assertIn("packages=(cmake g++)", setup)
        self.assertIn("apt-get install -y --no-install-recommends", setup)
        self.assertIn('ROOT="${ILLUM_AUTOGRADER_ROOT:-/autograder}"', setup)
        self.assertIn("grading.autograder setup \"$ROOT\" 01", setup)
        self.assertNotIn("> /dev/null", setup)  # the warm build is shown
        self.assertNotIn("|| true", setup)    # and its failure stops the image
        run = run_script(["01"])
        self.assertIn("grading.autograder run \"$ROOT\" 01", run)
        self.assertIn('CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-2}"', run)
        self.assertIn("ILLUM_GRADE_TEST_TIMEOUT", run)


class BuildFailureTest(unittest.TestCase):
    def test_the_broken_exercise_file_is_named(self) -> None:
        output = ("/a/exercises/01_ray_sphere/sphere.cpp:12:5: error: expected ';' before '}' token\n"
                  "make[2]: *** [CMakeFiles/illum.dir/build.make:90: CMakeFiles/illum.dir/exercises/"
                  "03_orientation_convex/triangle.cpp.o] Error 1\n"
                  "note: exercises/05_x/mentioned_only.cpp is fine\n")
        self.assertEqual(failed_exercise_files(output), ["exercises/01_ray_sphere/sphere.cpp",
                                                         "exercises/03_orientation_convex/triangle.cpp"])
        self.assertEqual(failed_exercise_files("lib/illum/core/ray.cpp:1:1: error: x"), [])


class FallbackTest(unittest.TestCase):
    """A student file that does not compile is swapped for its stub; the other lessons keep theirs."""

    def test_only_the_broken_file_falls_back(self) -> None:
        import argparse
        from unittest import mock

        from grading import build, driver

        with tempfile.TemporaryDirectory() as folder:
            tree, pristine = Path(folder) / "tree", Path(folder) / "pristine"
            for lesson, name in (("01_ray_sphere", "sphere.cpp"), ("10_hemicube", "hemicube_deltas.cpp")):
                (tree / "exercises" / lesson).mkdir(parents=True)
                (tree / "exercises" / lesson / name).write_text("student's " + name)
                (pristine / lesson).mkdir(parents=True)
                (pristine / lesson / name).write_text("stub")
            outputs = iter([
                build.StepResult(False, "/x/exercises/01_ray_sphere/sphere.cpp:3:1: error: expected ';'\n"),
                build.StepResult(True, "")])
            args = argparse.Namespace(student=True, fallback_stubs=pristine)
            run = GradeRun(lessons=["01", "10"], student=True)
            with mock.patch.object(build, "build", side_effect=lambda *a, **k: next(outputs)):
                step = driver._build_with_fallback(args, run, Path(folder) / "b", tree, ["illum"])
            self.assertTrue(step.ok)
            self.assertEqual(list(run.fallbacks), ["exercises/01_ray_sphere/sphere.cpp"])
            self.assertEqual((tree / "exercises/01_ray_sphere/sphere.cpp").read_text(), "stub")
            self.assertEqual((tree / "exercises/10_hemicube/hemicube_deltas.cpp").read_text(),
                             "student's hemicube_deltas.cpp")

    def test_an_error_outside_the_students_files_is_not_papered_over(self) -> None:
        import argparse
        from unittest import mock

        from grading import build, driver

        with tempfile.TemporaryDirectory() as folder:
            pristine = Path(folder) / "pristine" / "01_ray_sphere"
            pristine.mkdir(parents=True)
            (pristine / "sphere.cpp").write_text("stub")
            broken = build.StepResult(False, "/x/exercises/01_ray_sphere/sphere.cpp:3:1: error: a\n"
                                             "/x/lib/illum/core/ray.cpp:9:1: error: b\n")
            args = argparse.Namespace(student=True, fallback_stubs=pristine.parent)
            run = GradeRun(lessons=["01"], student=True)
            with mock.patch.object(build, "build", return_value=broken):
                step = driver._build_with_fallback(args, run, Path(folder), Path(folder), ["illum"])
            self.assertFalse(step.ok)
            self.assertEqual(run.fallbacks, {})


class CommandLineTest(unittest.TestCase):
    """Wrong commands stop before anything is built (exit 2), without a traceback or a file."""

    def run_main(self, argv: list[str]) -> tuple[int, str]:
        import contextlib
        import io
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            try:
                status = grade_main(argv)
            except SystemExit as exit_:  # argparse
                status = int(exit_.code)
        return status, err.getvalue()

    def test_a_lesson_that_does_not_exist(self) -> None:
        status, err = self.run_main(["99"])
        self.assertEqual(status, 2)
        self.assertIn("lesson 99 does not exist; the lessons are 01", err)
        self.assertNotIn("Traceback", err)

    def test_output_paths_that_cannot_be_written(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            for option in ("--results", "--junit", "--pack-autograder"):
                for path, words in ((folder, "is a folder"), (f"{folder}/none/x", "does not exist")):
                    status, err = self.run_main([option, path, "01"])
                    self.assertEqual(status, 2, (option, path))
                    self.assertIn(words, err)
                    self.assertNotIn("Traceback", err)
            self.assertEqual(list(Path(folder).iterdir()), [])  # nothing left behind



class CheckStudentEditionOptionsTest(unittest.TestCase):
    """tools/check_student_edition.py --lesson refuses what names no lesson with exercises, with exit 2 and
    one line naming the option and the value, before it makes a folder or builds anything."""

    def run_check(self, *args: str):
        script = Path(__file__).resolve().parents[2] / "tools" / "check_student_edition.py"
        return subprocess.run([sys.executable, str(script), *args], capture_output=True, text=True, timeout=60)

    def test_bad_lessons(self) -> None:
        for value, words in (("99", "--lesson 99: no such lesson with exercises"),
                             ("abc", "--lesson: 'abc' is not a lesson number")):
            with self.subTest(value=value), tempfile.TemporaryDirectory() as folder:
                work = Path(folder) / "work"
                done = self.run_check("--lesson", value, "--work-dir", str(work))
                self.assertEqual(done.returncode, 2, done.stderr)
                self.assertIn(words, done.stderr)
                self.assertNotIn("Traceback", done.stderr)
                self.assertFalse(work.exists(), "nothing may be made before the options are checked")


if __name__ == "__main__":
    unittest.main(verbosity=2)
