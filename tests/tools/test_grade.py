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
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))

from grading import reports  # noqa: E402
from grading.autograder import install_submission, run_script, setup_script  # noqa: E402
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
        self.assertEqual(data["stdout_visibility"], "visible")
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

    def test_build_failure_scores_zero_and_shows_the_compiler(self) -> None:
        run = GradeRun(lessons=["01"], build_failed=True, build_output="sphere.cpp:3: error: expected ';'")
        data = reports.gradescope_results(run)
        self.assertEqual(data["score"], 0)
        self.assertIn("expected ';'", data["output"])
        self.assertEqual(data["tests"][0]["status"], "failed")
        self.assertIn("expected ';'", data["tests"][0]["output"])
        self.assertIn("build failed", reports.score_table(run))

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


class RunnerTest(unittest.TestCase):
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


class AutograderTest(unittest.TestCase):
    def test_submission_files_replace_the_stubs_by_name(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            tree, submission = Path(folder) / "tree", Path(folder) / "submission"
            (tree / "exercises" / "01_ray_sphere").mkdir(parents=True)
            (tree / "exercises" / "02_polygons").mkdir(parents=True)
            (tree / "exercises" / "01_ray_sphere" / "sphere.cpp").write_text("stub")
            (tree / "exercises" / "02_polygons" / "polygon.cpp").write_text("stub")
            (submission / "deep" / "er").mkdir(parents=True)
            (submission / "deep" / "er" / "sphere.cpp").write_text("older copy")
            (submission / "sphere.cpp").write_text("mine")
            (submission / "polygon.cpp").write_text("not graded in this assignment")
            (submission / "notes.cpp").write_text("?")
            installed, ignored = install_submission(submission, tree, ["01"])
            self.assertEqual(installed, ["sphere.cpp -> exercises/01_ray_sphere/sphere.cpp"])
            self.assertEqual((tree / "exercises" / "01_ray_sphere" / "sphere.cpp").read_text(), "mine")
            self.assertEqual((tree / "exercises" / "02_polygons" / "polygon.cpp").read_text(), "stub")
            self.assertEqual(sorted(ignored), ["deep/er/sphere.cpp", "notes.cpp", "polygon.cpp"])

    def test_scripts_install_the_packages_and_grade_the_lessons(self) -> None:
        setup = setup_script(["cmake", "g++"], ["--student", "01"])
        self.assertIn("apt-get install -y --no-install-recommends cmake g++", setup)
        run = run_script(["01"], ["--student", "--hidden", "/autograder/source/hidden-tests", "01"])
        self.assertIn("tools/grade --student --hidden /autograder/source/hidden-tests 01", run)
        self.assertIn("/autograder/results/results.json", run)


if __name__ == "__main__":
    unittest.main(verbosity=2)
