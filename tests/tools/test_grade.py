#!/usr/bin/env python3
"""Unit tests of the grading driver's pure parts: parsing reporter lines,
the score table, results.json, JUnit XML, exit codes, the student edition's
file selection and the submission installer. Nothing is built here; the
end-to-end behaviour is covered by the grading_integrity ctest and by
running tools/grade (docs/grading.md).

Run: python3 tests/tools/test_grade.py   (ctest: tools_grade_py)
"""
from __future__ import annotations

import csv
import io
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path
from unittest import mock

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
TOOLS = Path(__file__).resolve().parents[2] / "tools"

from grading import reports  # noqa: E402

from grading.autograder import install_submission, run_script, setup_script  # noqa: E402
from grading.build import failed_exercise_files  # noqa: E402
from grading.driver import main as grade_main  # noqa: E402
from grading.alone import declared_dependencies  # noqa: E402
from grading.edition import excluded_files  # noqa: E402
from grading.integrity import check_pair  # noqa: E402
from grading.project import normalize_lesson  # noqa: E402
from grading.reports import GradeRun  # noqa: E402
from grading.results import Failure, TestResult, merge, points_of  # noqa: E402
from grading.runner import _Records  # noqa: E402

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


def parse_lines(lines: list[str]) -> list[dict]:
    """The records among the reporter's lines, as the runner reads them from the records pipe."""
    records = _Records()
    records.feed("".join(line + "\n" for line in lines).encode())
    return records.records


def reports_failure(message: str):
    from grading.results import Failure

    return Failure(kind="assert", message=message, file="/src/tests/hidden/x.cpp", line=3)


def sample_run(hidden_extra: bool = False) -> GradeRun:
    results = merge(parse_lines(LISTING), parse_lines(RUN))
    if hidden_extra:
        results += merge(parse_lines([listed("hidden one", 3)]), parse_lines([ran("hidden one", 3, True)]),
                         hidden=True)
    return GradeRun(lessons=["01"], results=results)


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

    def test_nothing_of_a_hidden_test_reaches_what_students_read(self) -> None:
        secret = "SECRET_HIDDEN_EXPECTATION"
        run = sample_run(hidden_extra=True)
        hidden = run.results[-1]
        hidden.name, hidden.passed = f"hidden: {secret} name", False
        hidden.failures = [reports_failure(f"CHECK( {secret} == 42 ) is NOT correct")]
        run.problems = [f'tests_hidden: test "hidden: {secret} name": the test program was killed by SIGSEGV',
                        f'tests_lesson01: test "hidden: {secret} name" copied into another program']
        run.review = [f"tampering: tests_hidden -ts=lesson01: a second result for \"{secret}\""]
        run.hidden_build_failed, run.hidden_build_output = True, f"tests/hidden/x.cpp:3: error: {secret}"
        data = reports.gradescope_results(run, Path("/src"))
        shown = data["output"] + "".join(t["output"] + t["name"] for t in data["tests"] if t["visibility"] != "hidden")
        self.assertNotIn(secret, shown)
        self.assertIn(secret, json.dumps([t for t in data["tests"] if t["visibility"] == "hidden"]))

    def test_the_scans_findings_reach_the_instructor_only_and_cost_nothing(self) -> None:
        run = sample_run()
        run.review = ["exercises/01_ray_sphere/sphere.cpp:3: starts a process",
                      "exercises/01_ray_sphere/sphere.cpp: calls the C function malloc(), unusual"]
        data = reports.gradescope_results(run)
        review = [t for t in data["tests"] if t["name"].startswith("review")]
        self.assertEqual([t["visibility"] for t in review], ["hidden"])
        self.assertIn("starts a process", review[0]["output"])
        shown = data["output"] + "".join(t["output"] for t in data["tests"] if t["visibility"] != "hidden")
        self.assertNotIn("malloc", shown)
        self.assertNotIn("starts a process", shown)
        self.assertEqual(data["extra_data"]["illum"]["lessons"]["01"]["status"], "graded")
        self.assertEqual(data["score"], sample_run().results[0].score + sum(r.score for r in sample_run().results[1:]))
        run.fallbacks = {"exercises/01_ray_sphere/sphere.cpp": "multiple definition of `illum::f()'"}
        run.link_failures = {"exercises/01_ray_sphere/sphere.cpp"}
        data = reports.gradescope_results(run)
        self.assertIn("did not link", data["output"])
        self.assertTrue(any(t["name"].endswith("did not link (graded as the stub)") for t in data["tests"]))

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
# Stands in for a doctest program run through the illum-grade reporter: its records go to the pipe
# named by ILLUM_GRADE_RECORDS_FD, in the reporter's order. It has three tests, runs them from
# --first=N on, and test number K does what BEHAVIOUR[K] says (default: pass).
import json, os, signal, sys, time
BEHAVIOUR = __BEHAVIOUR__
out = os.fdopen(int(os.environ["ILLUM_GRADE_RECORDS_FD"]), "w")
names = ["one", "two", "three"]
def record(event, number, **extra):
    out.write(json.dumps(dict(event=event, suite="lesson01", name=names[number - 1], file="/t.cpp", line=number,
                              description="", **extra)) + "\\n")
    out.flush()
def finished(number, passed=True):
    record("test_case", number, passed=passed, skipped=False, failures=[])
if "--list-test-cases" in sys.argv:
    for number in (1, 2, 3):
        record("listed", number)
    sys.exit(0)
first = int(next((a.split("=", 1)[1] for a in sys.argv if a.startswith("--first=")), "1"))
if BEHAVIOUR.get(0) == "early-forgery":  # a forged record before any test starts, in every run
    finished(1)
    sys.exit(0)
for number in range(first, 4):
    what = BEHAVIOUR.get(number, "pass")
    record("started", number)
    if what == "hang":
        time.sleep(60)
    elif what == "crash":
        os.kill(os.getpid(), signal.SIGSEGV)
    elif what == "exit0":
        os._exit(0)
    elif what == "duplicate":
        finished(number)
    elif what == "forge":
        finished(3)  # a result for a test that is not running
    elif what == "print":
        sys.stdout.write("x" * (5 * 1024 * 1024) + "END-OF-OUTPUT")
        sys.stdout.flush()
    elif what == "daemon":
        if os.fork() == 0:
            os.setsid()
            if os.fork() == 0:
                time.sleep(60)
            os._exit(0)
    elif what == "fork-many":
        made = 0
        for _ in range(300):
            try:
                if os.fork() == 0:
                    time.sleep(60)
                    os._exit(0)
                made += 1
            except OSError:
                break
        sys.stdout.write(f"forked {made}\\n")
        sys.stdout.flush()
    elif what.startswith("check="):  # an observer's check records (checks.cpp): the left sides it saw
        for actual in what.split("=", 1)[1].split(","):
            out.write(json.dumps({"event": "check", "file": "/t.cpp", "line": 40, "kind": "CHECK",
                                  "lhs": float(actual)}) + "\\n")
        out.flush()
    elif what == "spin":  # processor time, without end
        while True:
            pass
    elif what == "skip-report":
        continue  # started, and never a result: the next test starts while it runs
    finished(number, passed=what != "fail")
out.write(json.dumps({"event": "run_end"}) + "\\n")
out.flush()
"""


def fake_program(folder: str, behaviour: dict[int, str]) -> Path:
    program = Path(folder) / "tests_lesson01"
    program.write_text(FAKE_PROGRAM.replace("__BEHAVIOUR__", repr(behaviour)))
    program.chmod(0o755)
    Path(folder).chmod(0o755)
    return program


class RunnerTest(unittest.TestCase):
    """What run_suite makes of a test program that hangs, crashes, exits, lies or floods (runner.py)."""

    def run_fake(self, behaviour: dict[int, str], **options) -> "object":
        from grading.runner import run_suite

        with tempfile.TemporaryDirectory() as folder:
            return run_suite(fake_program(folder, behaviour), "lesson01", timeout=options.pop("timeout", 30),
                             test_timeout=options.pop("test_timeout", 5.0), **options)

    def statuses(self, run) -> list[tuple[str, str]]:
        return [(r.name, r.status) for r in run.results]

    def test_a_hanging_test_costs_only_itself(self) -> None:
        run = self.run_fake({2: "hang"}, test_timeout=0.3)
        self.assertEqual(self.statuses(run), [("one", "passed"), ("two", "failed"), ("three", "passed")])
        self.assertIn("did not finish within 3 s", run.results[1].output())
        self.assertIn('test "two"', run.problem)

    def test_a_crash_costs_only_the_test_that_crashed(self) -> None:
        run = self.run_fake({2: "crash"})
        self.assertEqual(self.statuses(run), [("one", "passed"), ("two", "failed"), ("three", "passed")])
        self.assertIn("SIGSEGV", run.results[1].output())

    def test_exit_inside_a_test_is_reported_as_such(self) -> None:
        run = self.run_fake({1: "exit0"})
        self.assertEqual(self.statuses(run), [("one", "failed"), ("two", "passed"), ("three", "passed")])
        self.assertIn("exit(0)", run.results[0].output())

    def test_a_second_record_for_a_test_fails_it_as_tampering(self) -> None:
        run = self.run_fake({2: "duplicate"})
        self.assertEqual(self.statuses(run), [("one", "passed"), ("two", "failed"), ("three", "passed")])
        self.assertIn("tampering", run.results[1].output())
        self.assertTrue(run.tampering)

    def test_a_record_for_a_test_that_is_not_running_is_tampering(self) -> None:
        run = self.run_fake({1: "forge"})
        self.assertEqual([r.passed for r in run.results], [False, True, True])
        self.assertIn("tampering", run.results[0].output())
        self.assertIn("was not running", run.results[0].output())

    def test_a_listed_test_without_a_result_fails(self) -> None:
        # The trusted list has a fourth test the program never reports.
        expected = [{"suite": "lesson01", "name": n, "file": "/t.cpp", "line": k, "description": ""}
                    for k, n in enumerate(["one", "two", "three", "four"], start=1)]
        run = self.run_fake({}, expected=expected)
        self.assertEqual(self.statuses(run)[-1], ("four", "not run"))
        self.assertIn("no result was received", run.results[-1].output())
        self.assertEqual([r.passed for r in run.results[:3]], [True, True, True])

    def test_observed_values_are_judged_by_the_judge(self) -> None:
        # The witness's run of test "two" checked 2.5 and then 7 at /t.cpp:40, relative 1e-9. The observer's
        # own verdict says passed every time; only the values it sends decide.
        from grading.runner import judge_suite
        from grading.results import TestResult

        def check(value):
            return {"event": "check", "file": "../../t.cpp", "line": 40, "kind": "CHECK", "expr": "v == w",
                    "op": "==", "rhs": {"approx": value, "epsilon": 1e-9, "scale": 1.0}, "passed": True}

        listed = [{"suite": "lesson01", "name": n, "file": "/t.cpp", "line": k, "description": ""}
                  for k, n in enumerate(["one", "two", "three"], 1)]
        witness = {TestResult.from_json(r).key: [check(1.0)] for r in listed}
        witness[TestResult.from_json(listed[1]).key] = [check(2.5), check(7.0)]
        for sent, passed, words in (("2.5,7.000000001", True, ""),
                                    ("2.5,7.1", False, "got:      7.0999999999999996"),
                                    ("2.5", False, "stopped before this check"),
                                    ("2.5,7,9", False, "more check(s) than the reference"),
                                    ("pass", False, "stopped before this check")):
            behaviour = {1: "check=1", 2: sent if sent == "pass" else f"check={sent}", 3: "check=1"}
            run = self.run_fake(behaviour, expected=listed, role="observer")
            self.assertEqual(judge_suite(run, witness, hidden=False), [])
            self.assertEqual(run.results[1].passed, passed, sent)
            self.assertIn(words, run.results[1].output(), sent)
            self.assertEqual([run.results[0].passed, run.results[2].passed], [True, True])

    def test_a_program_that_forges_before_every_test_is_not_run_again_and_again(self) -> None:
        import time

        start = time.monotonic()
        run = self.run_fake({0: "early-forgery"})
        self.assertLess(time.monotonic() - start, 20)
        self.assertEqual([r.passed for r in run.results], [False, False, False])

    def test_processor_time_not_wall_time_stops_a_spinning_test(self) -> None:
        run = self.run_fake({2: "spin"}, test_timeout=0.5)
        self.assertEqual(self.statuses(run), [("one", "passed"), ("two", "failed"), ("three", "passed")])
        self.assertIn("0.5 s of processor time", run.results[1].output())
        # A test that only waits is stopped by the wall-time cap, ten times longer.
        run = self.run_fake({2: "hang"}, test_timeout=0.5)
        self.assertIn("did not finish within 5 s", run.results[1].output())

    def test_output_is_capped_to_its_last_64_kb(self) -> None:
        run = self.run_fake({1: "print"})
        self.assertEqual([r.passed for r in run.results], [True, True, True])
        self.assertLess(len(run.output), 70 * 1024)
        self.assertIn("END-OF-OUTPUT", run.output)
        self.assertIn("earlier bytes of output cut", run.output)

    def test_no_test_starts_after_the_deadline(self) -> None:
        from grading import runner

        runner.set_deadline(0.0)
        try:
            run = self.run_fake({})
        finally:
            runner.set_deadline(None)
        self.assertEqual([r.status for r in run.results], ["not run"] * 3)
        self.assertIn("ILLUM_GRADE_DEADLINE", run.results[0].output())

    def test_the_records_order_is_checked(self) -> None:
        from grading.runner import check_records

        def rec(event: str, number: int, **extra) -> dict:
            return dict(event=event, suite="lesson01", name=f"t{number}", file="/t.cpp", line=number, **extra)

        order = {TestResult.from_json(rec("listed", k)).key: k for k in (1, 2, 3)}
        good = [rec("started", 1), rec("test_case", 1), rec("started", 2), rec("test_case", 2), {"event": "run_end"}]
        self.assertEqual(check_records(good, order, 1).violation, "")
        for records, words in (
                ([rec("test_case", 1)], "was not running"),
                ([rec("started", 1), rec("started", 2)], "while \"t1\" was still running"),
                ([rec("started", 2), rec("test_case", 2), rec("started", 1)], "out of order"),
                ([rec("started", 1), rec("test_case", 1), rec("test_case", 1)], "second result"),
                ([rec("started", 9)], "not one of the graded tests"),
                ([{"event": "run_end"}, rec("started", 1)], "after the end")):
            checked = check_records(records, order, 1)
            self.assertIn(words, checked.violation, records)
        self.assertIn("not records", check_records(good, order, 1, garbage=1).violation)


@unittest.skipUnless(os.geteuid() == 0, "a second user and its limits need root")
class SandboxTest(unittest.TestCase):
    """As the unprivileged user: nothing outlives the program, the process limit holds (sandbox.py)."""

    def setUp(self) -> None:
        from grading import runner
        from grading.sandbox import Limits, Sandbox, create_account

        self.account = create_account("illum-test-unit")  # its own: other tests grade side by side
        self.sandboxes = [Sandbox(self.account, Limits(processes=64), namespace=False),
                          Sandbox(self.account, Limits(processes=64))]
        self.runner = runner

    def tearDown(self) -> None:
        self.runner.set_sandbox(None)

    def run_as_student(self, sandbox, behaviour: dict[int, str]):
        from grading.sandbox import user_processes

        self.runner.set_sandbox(sandbox)
        with tempfile.TemporaryDirectory() as folder:
            run = self.runner.run_suite(fake_program(folder, behaviour), "lesson01", timeout=30, test_timeout=10)
        return run, user_processes(self.account.uid)

    def test_a_daemon_does_not_outlive_the_program(self) -> None:
        for sandbox in self.sandboxes:
            run, alive = self.run_as_student(sandbox, {1: "daemon"})
            self.assertEqual(alive, [], f"namespace={sandbox.namespace}")
            self.assertEqual([r.passed for r in run.results], [True, True, True])

    def test_the_process_limit_holds(self) -> None:
        run, alive = self.run_as_student(self.sandboxes[0], {1: "fork-many"})
        made = int(re.search(r"forked (\d+)", run.output).group(1))
        self.assertLess(made, 64)
        self.assertEqual(alive, [])

    def test_the_program_runs_as_the_student_with_a_private_home(self) -> None:
        from grading.sandbox import Sandbox

        sandbox = Sandbox(self.account)
        launched = sandbox.launch(["/usr/bin/id", "-u"], records=False)
        launched.process.wait()
        output = os.read(launched.output_fd, 4096).decode()
        home = launched.scratch / "home"
        mode = home.stat().st_mode & 0o777
        sandbox.finish(launched)
        self.assertEqual(output.strip(), str(self.account.uid))
        self.assertEqual(mode, 0o700)


@unittest.skipUnless(os.geteuid() == 0, "the grading lock is root's (without root there is no second user)")
class UserLockTest(unittest.TestCase):
    """sandbox.user_lock: a second run with the same user waits for the first, saying so; a lock folder
    that another user could enter or replace is refused by name."""

    def setUp(self) -> None:
        from grading import sandbox

        self.sandbox = sandbox
        self.tmp = Path(tempfile.mkdtemp())
        self.folder = self.tmp / "locks"
        patcher = mock.patch.object(sandbox, "LOCK_FOLDER", self.folder)
        patcher.start()
        self.addCleanup(patcher.stop)
        self.addCleanup(shutil.rmtree, self.tmp)

    def test_second_holder_waits_until_the_first_ends(self) -> None:
        import fcntl
        import threading

        with self.sandbox.user_lock("illum-a"):
            self.assertEqual(0o700, self.folder.stat().st_mode & 0o777)
            entered = threading.Event()

            def second() -> None:
                with self.sandbox.user_lock("illum-a"):
                    entered.set()

            with mock.patch("sys.stderr", new=io.StringIO()) as err:
                thread = threading.Thread(target=second)
                thread.start()
                self.assertFalse(entered.wait(0.5), "the second run went on while the first held the user")
                with self.sandbox.user_lock("illum-b"):  # another user's lock is free meanwhile
                    pass
                self.assertIn("another grading run uses the user illum-a; waiting", err.getvalue())
                # flock is per open file: the holder here is this block, released when it ends
                fd = os.open(self.folder / "illum-a.lock", os.O_RDWR)
                with self.assertRaises(BlockingIOError):
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                os.close(fd)
        thread.join(5)
        self.assertTrue(entered.is_set(), "the second run never got the user after the first ended")

    def test_a_folder_others_may_enter_or_a_link_is_refused(self) -> None:
        self.folder.mkdir(mode=0o755)
        self.folder.chmod(0o755)
        with self.assertRaisesRegex(self.sandbox.SandboxError, re.escape(str(self.folder)) + " must be a folder"):
            with self.sandbox.user_lock("illum-a"):
                pass
        self.folder.rmdir()
        (self.tmp / "elsewhere").mkdir(mode=0o700)
        self.folder.symlink_to(self.tmp / "elsewhere")
        with self.assertRaisesRegex(self.sandbox.SandboxError, "must be a folder that only root may enter"):
            with self.sandbox.user_lock("illum-a"):
                pass


class StudentTreeTest(unittest.TestCase):
    """tools/grade --student builds in the student's own tree, configured as the preset does."""

    def arguments(self, *argv: str):
        from grading.driver import parse_arguments

        return parse_arguments(list(argv))

    def test_the_student_tree_is_the_presets(self) -> None:
        from grading.driver import build_tree

        root = Path("/course")
        build_dir, exercises = build_tree(self.arguments("--student", "06"), root, ["06"])
        self.assertEqual(build_dir, root / "build" / "student")
        self.assertEqual(exercises, ["all"], "configured as `cmake --preset student`: ILLUM_EXERCISES=all")
        build_dir, exercises = build_tree(self.arguments("--student", "--build-dir", str(root / "build/grade-student"),
                                                         "06"), root, ["06"])
        self.assertEqual((build_dir, exercises), (root / "build" / "grade-student", ["06"]))
        build_dir, exercises = build_tree(self.arguments("06"), root, ["06"])
        self.assertEqual((build_dir, exercises), (root / "build" / "grade-reference", []))

    def test_the_autograder_keeps_its_own_tree(self) -> None:
        text = (TOOLS / "grading" / "autograder.py").read_text(encoding="utf-8")
        self.assertIn('"--build-dir", str(tree / "build" / "grade-student")', text)


class FailureMessageTest(unittest.TestCase):
    def test_a_failed_comparison_says_what_it_got_and_what_it_expected(self) -> None:
        failure = Failure.from_json({
            "kind": "assert", "file": "tests/12_vertex_colours/vertex_colours.cpp", "line": 50,
            "expression": "got.g == doctest::Approx(want.g).epsilon(1e-12)",
            "expansion": "0.5 == Approx( 0.25 )",
            "message": "CHECK( got.g == doctest::Approx(want.g).epsilon(1e-12) ) is NOT correct; values: "
                       "CHECK( 0.5 == Approx( 0.25 ) )",
            "context": "barycentric (1 − u − v, u, v)"})
        text = failure.describe()
        self.assertIn("CHECK( got.g == doctest::Approx(want.g).epsilon(1e-12) ) failed", text)
        self.assertIn("got:      0.5", text)
        self.assertIn("expected: Approx( 0.25 )", text)
        self.assertIn("barycentric (1 − u − v, u, v)", text)
        other = Failure.from_json({"kind": "assert", "expression": "split.size() < 4", "expansion": "5 < 4",
                                   "message": "CHECK( split.size() < 4 ) is NOT correct; values: CHECK( 5 < 4 )"})
        self.assertIn("values: CHECK( 5 < 4 )", other.describe())

    def test_the_summary_after_the_table_names_each_failed_check(self) -> None:
        run = GradeRun(lessons=["12"], results=[
            TestResult(suite="lesson12", name="gouraud: by hand", passed=False, failures=[Failure.from_json({
                "kind": "assert", "file": "tests/x.cpp", "line": 9, "expression": "a == b",
                "expansion": "1 == 2", "message": "CHECK( a == b ) is NOT correct; values: CHECK( 1 == 2 )"})]),
            TestResult(suite="lesson12", name="fine", passed=True)])
        summary = reports.failure_summary(run)
        self.assertIn("1 test(s) failed", summary)
        self.assertIn("lesson12: gouraud: by hand", summary)
        self.assertIn("tests/x.cpp:9: CHECK( a == b ) failed: got 1, expected 2", summary)
        self.assertEqual(reports.failure_summary(GradeRun(lessons=["12"])), "")


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


    def tiny_tree(self, root: Path) -> list[str]:
        """A tree, its .gitignore files, and the files git would take (worked out by hand)."""
        files = {
            ".gitignore": "/build/\n/out/\n/node_modules\n*.tmp-*\n/compile_commands.json\n__pycache__/\n*.tmp\n"
                          "!keep.tmp\n# a comment\n\ndocs/*.log\n**/cache/\n",
            "sub/.gitignore": "local.txt\n/only_here.txt\n",
            "README.md": "", "a.tmp": "", "keep.tmp": "", "x.tmp-grade": "", "build/o.o": "", "out/i.html": "",
            "node_modules/m.js": "", "lib/__pycache__/c.pyc": "", "lib/m.py": "", "compile_commands.json": "",
            "lib/compile_commands.json": "", "sub/local.txt": "", "sub/deep/local.txt": "", "sub/only_here.txt": "",
            "sub/deep/only_here.txt": "", "docs/a.log": "", "docs/deep/b.log": "", "x/cache/y": "", "cache": "",
        }
        for name, text in files.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text(text)
        (root / "link").symlink_to("README.md")
        return [".gitignore", "README.md", "cache", "docs/deep/b.log", "keep.tmp", "lib/compile_commands.json",
                "lib/m.py", "link", "sub/.gitignore", "sub/deep/only_here.txt"]

    def test_without_git_the_files_are_what_git_would_take(self) -> None:
        from grading.edition import tracked_files

        with tempfile.TemporaryDirectory() as folder:
            root = Path(folder)
            expected = self.tiny_tree(root)
            with mock.patch.dict(os.environ, {"PATH": str(root / "no-programs")}):
                self.assertEqual(tracked_files(root), expected)  # no git program
            if shutil.which("git") is None:
                self.skipTest("git is not installed: the walk was checked against the list worked out by hand only")
            git = ["git", "-C", folder, "-c", "user.name=t", "-c", "user.email=t@x"]
            subprocess.run([*git, "init", "-q"], check=True)
            subprocess.run([*git, "add", "-A"], check=True)
            listed = subprocess.run([*git, "ls-files"], check=True, capture_output=True, text=True).stdout.split()
            self.assertEqual(sorted(listed), expected)  # git agrees with the hand-made list
            self.assertEqual(tracked_files(root), expected)
            (root / "untracked.txt").write_text("")  # a checkout with git: git's list, not the walk
            self.assertEqual(tracked_files(root), expected)
            with mock.patch.dict(os.environ, {"PATH": str(root / "no-programs")}):
                self.assertEqual(tracked_files(root), sorted(expected + ["untracked.txt"]))

    def test_the_autograder_packs_without_git(self) -> None:
        from grading.autograder import pack_autograder

        with tempfile.TemporaryDirectory() as folder:
            source = Path(folder) / "src"
            LinksTest.write_tiny_source(source)
            (source / "tools").mkdir()
            (source / "tools" / "debian-packages.txt").write_text("g++ cmake  # the build\n")
            (source / "tests" / "hidden").mkdir(parents=True)
            (source / "tests" / "hidden" / "lesson01_more.cpp").write_text("// hidden\n")
            (source / "notes.tmp").write_text("")  # ignored, as git would
            (source / ".gitignore").write_text("*.tmp\n")
            with mock.patch.dict(os.environ, {"PATH": str(Path(folder) / "no-programs")}):
                names = pack_autograder(source, Path(folder) / "a.zip", ["01"], None)
            self.assertIn("illum/exercises/01_ray_sphere/sphere.cpp", names)
            self.assertIn("reference/sphere.cpp", names)
            self.assertIn("hidden-tests/lesson01_more.cpp", names)
            self.assertNotIn("illum/lib/illum/geometry/sphere.cpp", names)
            self.assertNotIn("illum/notes.tmp", names)
            with zipfile.ZipFile(Path(folder) / "a.zip") as archive:
                self.assertIn("This is the student edition of illum.\n", archive.read("illum/STUDENT_EDITION").decode())


class LinksTest(unittest.TestCase):
    def test_links_outside_code_with_their_text_as_written(self) -> None:
        from common.markdown import links as markdown_links

        text = ("See [`sphere.cpp`](../../lib/illum/geometry/sphere.cpp) and ![plot](../../out/x.png).\n"
                "`[not a link](a.md)` stays code\n```\n[nor this](b.md)\n```\n[anchor](#tasks)")
        links = markdown_links(text)
        self.assertEqual([(l.text, l.target, l.image) for l in links],
                         [("`sphere.cpp`", "../../lib/illum/geometry/sphere.cpp", False),
                          ("plot", "../../out/x.png", True), ("anchor", "#tasks", False)])

    def test_broken_links_files_anchors_and_generated_outputs(self) -> None:
        from common.markdown import anchors as heading_anchors
        from grading.edition import broken_links

        self.assertIn("choosing-the-lessons-to-hand-out", heading_anchors("### Choosing the lessons to hand out"))
        self.assertEqual(heading_anchors("## 6. The study: uniform against adaptive\n## Tasks\n## Tasks"),
                         {"6-the-study-uniform-against-adaptive", "tasks", "tasks-1"})
        with tempfile.TemporaryDirectory() as folder:
            root = Path(folder)
            (root / "docs").mkdir()
            (root / "docs" / "a.md").write_text("# A\n## The lab\n")
            (root / "slides").mkdir()
            (root / "slides" / "01.md").write_text("![w:3](../lesson01/x.png) [e](../../docs/a.md#the-lab)\n")
            (root / "README.md").write_text(
                "[ok](docs/a.md#the-lab) [gone](docs/b.md) [bad anchor](docs/a.md#nope) [run it](out/lesson01/x.png)"
                " [web](https://example.org/x) [out of the tree](../x.md)\n")
            problems = broken_links(root)
            self.assertEqual(len(problems), 3, problems)
            self.assertTrue(any("docs/b.md, which does not exist" in p for p in problems))
            self.assertTrue(any("#nope" in p for p in problems))
            self.assertTrue(any("leaves the repository" in p for p in problems))

    @staticmethod
    def write_tiny_source(source: Path) -> None:
        """Two lessons, each with one exercise unit and its reference, and the documents the edition's
        README links to."""
        files = {
            "README.md": "# illum\n## For instructors\n`tools/grade --batch`\n<!-- student-commands: begin -->\n"
                         "```sh\ncmake --preset student\n```\n<!-- student-commands: end -->\n",
            "lessons/01_ray_sphere/README.md": "# Lesson 01 — The ray and the sphere\n"
                                               "[`sphere.cpp`](../../lib/illum/geometry/sphere.cpp) "
                                               "[exercise](../../exercises/01_ray_sphere/README.md)\n",
            "lessons/02_polygon_parity/README.md": "# Lesson 02 — Parity\n"
                                                   "[exercise](../../exercises/02_polygon_parity/README.md) "
                                                   "[`parity.cpp`](../../exercises/02_polygon_parity/parity.cpp)\n",
            "lib/illum/geometry/sphere.cpp": "", "lib/illum/geometry/parity.cpp": "",
            "exercises/01_ray_sphere/sphere.cpp": "", "exercises/01_ray_sphere/README.md": "# Exercise 01 — x\n",
            "exercises/02_polygon_parity/parity.cpp": "", "exercises/02_polygon_parity/README.md": "# Exercise 02\n",
            "docs/errata.md": "# Errata\n", "docs/lab.md": "# Lab\n", "docs/grading.md": "# Grading\n## Students\n",
            "docs/scene-format.md": "# Scenes\n",
        }
        for name, text in files.items():
            (source / name).parent.mkdir(parents=True, exist_ok=True)
            (source / name).write_text(text, encoding="utf-8")

    def test_the_edition_refuses_before_it_removes_or_writes_anything(self) -> None:
        from grading.edition import make_student_edition
        from grading.project import STUDENT_EDITION_MARKER

        with tempfile.TemporaryDirectory() as folder:
            source, out = Path(folder) / "src", Path(folder) / "edition"
            self.write_tiny_source(source)
            make_student_edition(source, out, ["01"])
            marker = (out / STUDENT_EDITION_MARKER).read_text(encoding="utf-8")
            # A lesson without exercises: refused, and the earlier edition is left whole.
            with self.assertRaisesRegex(ValueError, "lesson.s. 99 have no exercises"):
                make_student_edition(source, out, ["99"])
            self.assertEqual((out / STUDENT_EDITION_MARKER).read_text(encoding="utf-8"), marker)
            self.assertTrue((out / "README.md").is_file())
            # A folder that is no source tree is refused before it is read (it could be / itself).
            with self.assertRaisesRegex(ValueError, "is not an illum source tree"):
                make_student_edition(Path(folder) / "src" / "docs", Path(folder) / "other", None)
            self.assertFalse((Path(folder) / "other").exists())
            # A file where the edition goes: refused, left as it was.
            a_file = Path(folder) / "a_file"
            a_file.write_text("keep\n")
            with self.assertRaisesRegex(ValueError, "exists and is not a folder"):
                make_student_edition(source, a_file, ["01"])
            self.assertEqual(a_file.read_text(), "keep\n")
            # A link to an earlier edition: refused; the edition it points to is not replaced through it.
            link = Path(folder) / "link"
            link.symlink_to(out)
            with self.assertRaisesRegex(ValueError, "is a symbolic link"):
                make_student_edition(source, link, ["02"])
            self.assertEqual((out / STUDENT_EDITION_MARKER).read_text(encoding="utf-8"), marker)

    def test_a_failed_edition_leaves_the_earlier_one_whole(self) -> None:
        from unittest import mock
        from grading import edition
        from grading.project import STUDENT_EDITION_MARKER

        with tempfile.TemporaryDirectory() as folder:
            source, out = Path(folder) / "src", Path(folder) / "edition"
            self.write_tiny_source(source)
            edition.make_student_edition(source, out, ["01"])
            before = sorted(p.relative_to(out).as_posix() for p in out.rglob("*"))
            marker = (out / STUDENT_EDITION_MARKER).read_text(encoding="utf-8")

            def interrupted(*_args, **_kwargs):  # the README is written part way through the copy
                raise KeyboardInterrupt

            with mock.patch.object(edition, "student_readme", interrupted), self.assertRaises(KeyboardInterrupt):
                edition.make_student_edition(source, out, ["02"])
            self.assertEqual(sorted(p.relative_to(out).as_posix() for p in out.rglob("*")), before)
            self.assertEqual((out / STUDENT_EDITION_MARKER).read_text(encoding="utf-8"), marker)
            self.assertEqual(sorted(p.name for p in Path(folder).iterdir()), ["edition", "src"])  # no half copy
            # And a run that succeeds replaces it whole, with the folder's usual mode, not mkdtemp's 0700.
            edition.make_student_edition(source, out, ["02"])
            self.assertIn("lessons 02", (out / STUDENT_EDITION_MARKER).read_text(encoding="utf-8"))
            self.assertEqual(sorted(p.name for p in Path(folder).iterdir()), ["edition", "src"])
            self.assertEqual(out.stat().st_mode & 0o777, source.stat().st_mode & 0o777)

    def test_the_edition_rewrites_links_to_what_it_leaves_out_and_has_its_own_readme(self) -> None:
        from grading.edition import make_student_edition

        with tempfile.TemporaryDirectory() as folder:
            source, out = Path(folder) / "src", Path(folder) / "edition"
            self.write_tiny_source(source)
            make_student_edition(source, out, ["01"])
            readme = (out / "README.md").read_text(encoding="utf-8")
            self.assertTrue(readme.startswith("# illum — student edition"))
            self.assertNotIn("For instructors", readme)
            self.assertNotIn("--batch", readme)
            self.assertIn("cmake --preset student", readme)
            self.assertIn("illum lab", readme)
            one = (out / "lessons/01_ray_sphere/README.md").read_text(encoding="utf-8")
            self.assertIn("[`sphere.cpp`](../../exercises/01_ray_sphere/sphere.cpp)", one, "the stub, handed out")
            two = (out / "lessons/02_polygon_parity/README.md").read_text(encoding="utf-8")
            self.assertIn("exercise [`parity.cpp`](../../lib/illum/geometry/parity.cpp)", two,
                          "lesson 02 is not handed out: its exercise is text, its unit the reference")
            from grading.edition import broken_links

            self.assertEqual(broken_links(out), [])


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

    def test_a_symbolic_link_in_the_upload_is_not_followed(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            tree, submission = self.make_tree(folder)
            secret = Path(folder) / "reference.cpp"
            secret.write_text("the reference")
            (submission / "sphere.cpp").symlink_to(secret)
            report = install_submission(submission, tree, ["01"])
            self.assertEqual(report.installed, [])
            self.assertEqual((tree / "exercises" / "01_ray_sphere" / "sphere.cpp").read_text(), "stub")
            self.assertIn("symbolic link", report.ignored[0]["reason"])

    def test_a_zip_behind_a_symbolic_link_is_not_opened(self) -> None:
        """A link named like a zip, to a zip outside the upload that holds an exercise file (the grader's own
        files, say): not unpacked, nothing installed, the link reported."""
        import zipfile
        with tempfile.TemporaryDirectory() as folder:
            tree, submission = self.make_tree(folder)
            outside = Path(folder) / "grader.zip"
            with zipfile.ZipFile(outside, "w") as archive:
                archive.writestr("exercises/01_ray_sphere/sphere.cpp", "the reference")
            (submission / "homework.zip").symlink_to(outside)
            (submission / "folder").symlink_to(Path(folder), target_is_directory=True)
            report = install_submission(submission, tree, ["01"])
            self.assertEqual(report.installed, [])
            self.assertEqual((tree / "exercises" / "01_ray_sphere" / "sphere.cpp").read_text(), "stub")
            self.assertFalse(any("unpacked" in n for n in report.notes), report.notes)
            reasons = {i["file"]: i["reason"] for i in report.ignored}
            self.assertIn("symbolic link", reasons["homework.zip"])

    def test_setup_caps_its_build_jobs(self) -> None:
        from unittest import mock

        from grading import autograder

        for cores, available_kb, jobs in ((64, 6 * 1024 * 1024, 4), (2, 2 * 1024 * 1024, 1), (8, 40 << 20, 4),
                                          (1, 40 << 20, 1), (3, 5 * 1024 * 1024, 3)):
            meminfo = f"MemTotal: 999 kB\nMemAvailable: {available_kb} kB\n"
            with mock.patch("builtins.open", mock.mock_open(read_data=meminfo)), \
                    mock.patch.object(autograder.os, "cpu_count", return_value=cores):
                self.assertEqual(autograder.build_jobs(), jobs, (cores, available_kb))

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
            run = GradeRun(lessons=["01", "10"])
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
            run = GradeRun(lessons=["01"])
            with mock.patch.object(build, "build", return_value=broken):
                step = driver._build_with_fallback(args, run, Path(folder), Path(folder), ["illum"])
            self.assertFalse(step.ok)
            self.assertEqual(run.fallbacks, {})


class SuspiciousCodeTest(unittest.TestCase):
    """The checks that flag an exercise file reaching outside the computation (suspicious.py)."""

    def findings(self, text: str) -> list[str]:
        from grading.suspicious import scan_source

        return [f.what for f in scan_source(text, "exercises/01_ray_sphere/sphere.cpp")]

    def test_every_stub_and_reference_unit_passes(self) -> None:
        from grading.suspicious import scan_source

        root = Path(__file__).resolve().parents[2]
        for stub in sorted(root.glob("exercises/[0-9][0-9]_*/*.cpp")):
            for path in [stub, *root.glob(f"lib/illum/**/{stub.name}")]:
                self.assertEqual(scan_source(path.read_text(encoding="utf-8"), str(path)), [], path)

    def test_each_rule(self) -> None:
        base = '#include "illum/geometry/sphere.hpp"\n#include <cmath>\n#include <glm/glm.hpp>\nnamespace illum {\n'
        self.assertEqual(self.findings(base + "double f(double x) { return std::sqrt(x); }\n}\n"), [])
        for line, words in (
                ("#include <unistd.h>", "outside illum/"),
                ('#include "../../../reference/sphere.cpp"', "leaves the include folders"),
                ('#include "illum/geometry/sphere.cpp"', "a source file"),
                ("#include <fstream>", "may not touch files"),
                ("#include SOMETHING", "computes the name"),
                ("void f() { DOCTEST_CHECK(1); }", "doctest"),
                ("void f() { if (fork() == 0) return; }", "starts a process"),
                ("void f() { std::system(\"ls\"); }", "starts a process"),
                ("void f() { std::exit(0); }", "ends the program"),
                ("void f() { _exit(0); }", "ends the program"),
                ("void f() { asm(\"nop\"); }", "inline assembly"),
                ("long f() { return syscall(1); }", "system call"),
                ('const char* p = "/proc/self/fd/3";', "/proc"),
                ('extern "C" long write(int, const void*, unsigned long);', "extern \"C\""),
                ("__attribute__((constructor)) void f() {}", "starts or ends"),
                ("#define NAME(a, b) a##b", "token pasting"),
                ("void f() { auto p = getenv(\"HOME\"); }", "environment")):
            self.assertTrue(any(words in w for w in self.findings(base + line + "\n}\n")), (line, words))

    def test_comments_and_names_that_only_look_alike_pass(self) -> None:
        text = ('#include "illum/core/error.hpp"\n// exit(0) in a comment, fork() too, doctest is the framework\n'
                "/* asm */\nnamespace illum {\ndouble coordinate_system(double x) { return x; }\n"
                "double exit_angle(double x) { return coordinate_system(x); }\n}\n")
        self.assertEqual(self.findings(text), [])

    def test_a_rule_found_on_many_lines_is_one_finding(self) -> None:
        text = "\n".join(["void f() { std::exit(1); }"] * 5)
        found = self.findings(text)
        self.assertEqual(len(found), 1)
        self.assertIn("also lines 2, 3, 4, 5", found[0])

    @unittest.skipUnless(shutil.which("c++") and shutil.which("nm"), "needs a compiler and nm")
    def test_the_object_file_is_checked_too(self) -> None:
        from grading.suspicious import scan_object

        with tempfile.TemporaryDirectory() as folder:
            source, obj = Path(folder) / "x.cpp", Path(folder) / "x.o"
            # Names a text scan cannot see (built by the preprocessor from pieces) are still symbols.
            source.write_text('#define JOIN(a, b) a##b\nextern "C" long JOIN(wri, te)(int, const void*, unsigned long n)'
                              " { return (long)n; }\nextern \"C\" int JOIN(fo, rk)();\n"
                              "namespace illum { int twice(int x) { return JOIN(fo, rk)() + 2 * x; } }\n")
            subprocess.run(["c++", "-c", "-O2", str(source), "-o", str(obj)], check=True)
            found = [f for f in scan_object(obj, "exercises/01_ray_sphere/sphere.cpp") if f.serious]
            text = "\n".join(f.what for f in found)
            self.assertIn("defines `write`", text)
            self.assertIn("calls fork()", text)
            self.assertNotIn("twice", text)
            found = scan_object(obj, "x.cpp", library={"_ZN5illum5twiceEi": "ray.cpp.o"})
            self.assertTrue(any("which the library already has" in f.what for f in found))


class LinkAttributionTest(unittest.TestCase):
    """A link error is blamed on the student's files that cause it (build.linker_blames)."""

    UNITS = {"parity.cpp": "exercises/02_polygon_parity/parity.cpp",
             "plane.cpp": "exercises/02_polygon_parity/plane.cpp",
             "sphere.cpp": "exercises/01_ray_sphere/sphere.cpp"}

    def test_a_helper_defined_twice(self) -> None:
        from grading.build import linker_blames

        output = ("/usr/bin/ld: ../libillum.a(plane.cpp.o): in function `illum::twice(double)':\n"
                  "plane.cpp:(.text+0x0): multiple definition of `illum::twice(double)'; "
                  "../libillum.a(parity.cpp.o):parity.cpp:(.text+0x0): first defined here\n"
                  "collect2: error: ld returned 1 exit status\n")
        self.assertEqual(linker_blames(output, self.UNITS), ["exercises/02_polygon_parity/parity.cpp",
                                                             "exercises/02_polygon_parity/plane.cpp"])

    def test_an_undefined_reference(self) -> None:
        from grading.build import linker_blames

        mine = ("/usr/bin/ld: ../libillum.a(sphere.cpp.o): in function `illum::intersect(illum::Ray const&, "
                "illum::Sphere const&)':\nsphere.cpp:(.text+0x4): undefined reference to `illum::my_helper(double)'\n")
        self.assertEqual(linker_blames(mine, self.UNITS), ["exercises/01_ray_sphere/sphere.cpp"])
        tests = ("/usr/bin/ld: CMakeFiles/x.dir/01_ray_sphere/grading.cpp.o: in function `DOCTEST_ANON_FUNC_2()':\n"
                 "grading.cpp:(.text+0x9): undefined reference to `illum::Sphere::Sphere(glm::vec<3, double, "
                 "(glm::qualifier)0> const&, double)'\n")
        owners = {"illum::Sphere::Sphere": "exercises/01_ray_sphere/sphere.cpp"}
        self.assertEqual(linker_blames(tests, self.UNITS, owners), ["exercises/01_ray_sphere/sphere.cpp"])
        self.assertEqual(linker_blames(tests, self.UNITS), [])
        self.assertEqual(linker_blames("/usr/bin/ld: cannot find -lfoo\n", self.UNITS), [])


class BatchTest(unittest.TestCase):
    """tools/grade --batch's pure parts: grades.csv, the results.json it reads, its time limits."""

    def outcome(self, ident: str, status: str, scores: dict[str, tuple[float, float, str]]):
        from grading.gradebook import Outcome

        lessons = {nn: {"score": got, "max_score": top, "status": st} for nn, (got, top, st) in scores.items()}
        gradable = [v for v in lessons.values() if v["status"] != "not gradable"]
        total = sum(v["score"] for v in gradable) if gradable else None
        tests = {f"lesson{nn}: t": got for nn, (got, top, st) in scores.items()}
        return Outcome(ident, status=status, total=total, max_score=sum(v["max_score"] for v in lessons.values()),
                       lessons=lessons, tests=tests, visible={nn: (got, top) for nn, (got, top, _) in scores.items()})

    def test_grades_csv_columns_and_not_gradable(self) -> None:
        from grading.gradebook import Outcome, csv_text, grades_rows

        rows = [self.outcome("ana", "graded", {"01": (3, 4, "graded"), "02": (1, 2, "graded")}),
                self.outcome("ben", "partly gradable", {"01": (0, 4, "not gradable"), "02": (2, 2, "graded")}),
                self.outcome("cris", "not gradable", {"01": (0, 4, "not gradable"), "02": (0, 2, "not gradable")}),
                Outcome("dan", status="missing")]
        table = list(csv.reader(io.StringIO(csv_text(grades_rows(rows, ["01", "02"], None))[1:], newline="")))
        self.assertEqual(table[0], ["id", "status", "total", "max", "lesson01", "lesson02", "lesson01: t",
                                    "lesson02: t", "notes"])
        self.assertEqual(table[1][:8], ["ana", "graded", "4", "6", "3", "1", "3", "1"])
        self.assertEqual(table[2][:8], ["ben", "partly gradable", "2", "6", "not gradable", "2", "", "2"])
        self.assertEqual(table[3][:6], ["cris", "not gradable", "", "6", "not gradable", "not gradable"])
        self.assertEqual(table[4][:4], ["dan", "missing", "", ""])

    def test_what_results_json_says_becomes_the_row(self) -> None:
        from grading.batch import outcome_of

        run = sample_run()
        run.fallbacks = {"exercises/01_ray_sphere/sphere.cpp": "error"}
        data = reports.gradescope_results(run)
        outcome = outcome_of("ana", data)
        self.assertEqual(outcome.status, "not gradable")
        self.assertIsNone(outcome.total)
        self.assertIn("exercises/01_ray_sphere/sphere.cpp did not compile", outcome.notes)
        self.assertEqual(outcome_of("ben", None).status, "grader error")

    def test_the_students_feedback_never_counts_hidden_tests(self) -> None:
        from grading.batch import outcome_of
        from grading.gradebook import canvas_rows, feedback, grades_rows, moodle_rows

        # sample_run: visible tests of 1 + 2 + 1 points, 1 passed; the hidden test (1 point) passed.
        run = sample_run(hidden_extra=True)
        run.review = ["a note for the instructor"]
        outcome = outcome_of("ana", reports.gradescope_results(run))
        self.assertEqual((outcome.total, outcome.max_score), (2.0, 5.0))  # the grade counts the hidden test
        words = feedback(outcome)
        self.assertIn("lesson 01: 1/4", words)
        self.assertIn("visible tests 1/4", words)
        self.assertNotIn("2/5", words)
        self.assertNotIn("/5", words)
        self.assertNotIn("hidden one", words)
        self.assertNotIn("review", words)  # the instructor's notes stay in grades.csv
        moodle, _ = moodle_rows([outcome], None, "Lab 1")
        self.assertEqual(moodle[1][2:], ["2", words])
        canvas, _ = canvas_rows([outcome], None, "Lab 1")
        self.assertEqual(canvas[1][5], "5")  # Points Possible: the grade's maximum
        self.assertEqual(canvas[2][5], "2")
        grades = grades_rows([outcome], ["01"], None)
        self.assertIn("lesson01 (hidden): hidden one", grades[0])  # the instructor's file has everything
        self.assertIn("1 note(s) for review in results.json", grades[1][-1])
        # Without hidden tests the total is the student's to see.
        plain = outcome_of("ben", reports.gradescope_results(sample_run()))
        self.assertEqual(feedback(plain), "1/4 (lesson 01: 1/4)")

    def test_setup_has_a_build_limit_of_its_own(self) -> None:
        from grading.batch import Slots, run_environment, setup_environment

        instructor = {"PATH": os.environ["PATH"], "ILLUM_GRADE_TEST_TIMEOUT": "3"}
        run = run_environment(instructor)
        self.assertEqual(run["ILLUM_GRADE_BUILD_TIMEOUT"], "300")  # a student's rebuild: Gradescope's limit
        self.assertEqual(run["ILLUM_GRADE_TEST_TIMEOUT"], "3")
        self.assertNotIn("ILLUM_GRADE_BUILD_TIMEOUT", setup_environment(run))  # setup: none
        self.assertNotIn("ILLUM_GRADE_DEADLINE", setup_environment(instructor))
        self.assertEqual(setup_environment(instructor)["ILLUM_GRADE_TEST_TIMEOUT"], "3")  # set by the instructor
        self.assertEqual(setup_environment(dict(run, ILLUM_GRADE_SETUP_BUILD_TIMEOUT="900"))
                         ["ILLUM_GRADE_BUILD_TIMEOUT"], "900")
        # Through a worker's preparation, as --batch runs it: setup.sh sees setup's limit.
        with tempfile.TemporaryDirectory() as folder:
            zip_path = Path(folder) / "autograder.zip"
            with zipfile.ZipFile(zip_path, "w") as archive:
                archive.writestr("setup.sh", 'echo "limit=${ILLUM_GRADE_BUILD_TIMEOUT-none}"; exit 3\n')
                archive.writestr("run_autograder", "exit 0\n")
                archive.writestr("illum/tools/grade", "")
            slots = Slots(Path(folder) / "work", 1, zip_path, run)
            self.assertEqual(slots.prepare(0), (3, "limit=none\n"))
            slots = Slots(Path(folder) / "work", 1, zip_path, dict(run, ILLUM_GRADE_SETUP_BUILD_TIMEOUT="900"))
            self.assertEqual(slots.prepare(0), (3, "limit=900\n"))

    def test_a_limit_that_is_hit_is_named_with_its_variable(self) -> None:
        import time
        from grading.batch import explain_setup_failure, run_limited
        from grading.build import Runner, run_streaming

        step = run_streaming(["sleep", "20"], echo=False, runner=Runner(timeout=0.3))
        self.assertTrue(step.timed_out)
        self.assertIn("did not finish within 0.3 s, the time limit of a build (ILLUM_GRADE_BUILD_TIMEOUT)",
                      step.output)
        self.assertIn("its time limit, 600 s (ILLUM_GRADE_SETUP_BUILD_TIMEOUT)",
                      explain_setup_failure("setup:\n" + step.output, {"ILLUM_GRADE_SETUP_BUILD_TIMEOUT": "600"}))
        self.assertEqual(explain_setup_failure("setup: FAILED: apt-get update failed", {}), "")
        # One submission's limit: everything it started is stopped (a background child would keep the
        # output open, and the batch waiting, for 30 s).
        start = time.monotonic()
        output, stopped = run_limited(["bash", "-c", "echo started; sleep 30 & sleep 30"], dict(os.environ), 0.5)
        self.assertLess(time.monotonic() - start, 10)
        self.assertEqual(output, "started\n")
        self.assertIn("did not finish within 0.5 s, the time limit of one submission (ILLUM_GRADE_BATCH_TIMEOUT)",
                      stopped)
        self.assertEqual(run_limited(["true"], dict(os.environ), 5), ("", ""))


class RosterTest(unittest.TestCase):
    """The roster as spreadsheets and LMSs write it: read with the csv module, checked before grading."""

    def roster(self, text: str, encoding: str = "utf-8"):
        from grading.gradebook import read_roster

        folder = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, folder)
        path = Path(folder) / "roster.csv"
        path.write_bytes(text.encode(encoding))
        return read_roster(path)

    def submissions(self, *names: str) -> list:
        from grading.batch import Submission

        return [Submission(n, Path(n)) for n in names]

    def test_join_by_id_or_email(self) -> None:
        roster = self.roster("\ufeffNombre;Correo;Login\r\nAna;ANA@uni.example;a1\r\nBen;ben@uni.example;b2\r\n"
                             "Cris;cris@uni.example;c3\r\n")
        self.assertEqual(roster.keys, ["Correo", "Login"])
        matched, unmatched = roster.match(self.submissions("ana", "b2", "zoe"))
        self.assertEqual({i: s.ident for i, s in matched.items()}, {0: "ana", 1: "b2"})
        self.assertEqual([s.ident for s in unmatched], ["zoe"])

    def test_quotes_separators_bom_and_line_ends(self) -> None:
        # RFC 4180: a quote inside a quoted field is doubled; a quoted field may hold the separator and a line
        # break. The same roster with commas, semicolons and tabs, LF and CRLF, with and without a BOM.
        # (csv.Sniffer guesses doublequote=False for the first name, and read it as 'García, Ana "Pepa"""'.)
        rows = [["Student", "ID", "SIS User ID", "SIS Login ID", "Section"],
                ['García, Ana "Pepa"', "11", "s1", "ana", "T1; T2"],
                ["O'Neil, Ben", "12", "s2", "ben", "T1\nlate"]]
        for delimiter in (",", ";", "\t"):
            for end in ("\n", "\r\n"):
                for bom in ("", "\ufeff"):
                    lines = [delimiter.join('"' + c.replace('"', '""') + '"' if any(x in c for x in ',;\t"\n') else c
                                            for c in row) for row in rows]
                    roster = self.roster(bom + end.join(lines) + end)
                    label = (delimiter, end, bom)
                    self.assertEqual(roster.headers, rows[0], label)
                    self.assertEqual(roster.rows[0]["Student"], 'García, Ana "Pepa"', label)
                    self.assertEqual(roster.rows[1]["Section"], "T1\nlate", label)
                    self.assertEqual(roster.lines, [2, 3], label)
                    self.assertEqual(roster.names(roster.rows[1]), ("Ben O'Neil", "O'Neil, Ben"), label)

    def test_a_malformed_roster_is_refused_naming_the_line(self) -> None:
        from grading.gradebook import RosterError

        with self.assertRaisesRegex(RosterError, "line 3: unexpected end of data"):
            self.roster('id,name\n1,Ana\n2,"Ben\n3,Cris\n')  # an opened quote would swallow the rest
        with self.assertRaisesRegex(RosterError, "line 3 has 3 fields, the header .line 1. 2"):
            self.roster("id,name\n1,Ana\n2,García, Ana\n")  # an unquoted comma shifts the columns
        with self.assertRaisesRegex(RosterError, "line 2 is not UTF-8 text: save the file as \"CSV UTF-8\""):
            self.roster("id,name\n1,García\n", encoding="latin-1")
        with self.assertRaisesRegex(RosterError, "the file is empty"):
            self.roster("\ufeff\r\n")

    def test_duplicates_are_refused_naming_both_lines(self) -> None:
        from grading.gradebook import RosterError

        # The second student's record spans lines 3-4, so the duplicate is on line 5, not 4.
        with self.assertRaisesRegex(RosterError, "lines 2 and 5 have the same ID '7'"):
            self.roster('ID,Name\n7,Ana\n8,"Ben\nBenito"\n7,Cris\n')
        with self.assertRaisesRegex(RosterError, "lines 3 and 4 have the same Email address 'BEN@x.example'"):
            self.roster("ID number,Email address\n1,ana@x.example\n2,ben@x.example\n3,BEN@x.example\n")
        roster = self.roster("Username,Email\nana,ana@a.example\nann,ana@b.example\n")  # same name before the @
        with self.assertRaisesRegex(RosterError, "the submission ana matches the rows on lines 2 and 3"):
            roster.match(self.submissions("ana"))
        with self.assertRaisesRegex(RosterError, "the row on line 3 matches two submissions: ann and ana@b.example"):
            roster.match(self.submissions("ann", "ana@b.example"))
        # Two students with one name are two students.
        self.assertEqual(len(self.roster("Student,ID\n\"Ruiz, Ana\",1\n\"Ruiz, Ana\",2\n").rows), 2)


class GradebookTest(unittest.TestCase):
    """The Moodle and Canvas files from either roster style, as those importers read them (gradebook.py's
    docstring says what each importer does with a row)."""

    MOODLE_ROSTER = ("First name,Last name,ID number,Institution,Department,Email address\n"
                     "Ana,García López,1001,U,CS,ana@uni.example\n"
                     "Ben,O'Neil,1002,U,CS,ben@uni.example\n"
                     "Cris,Ruiz,,U,CS,cris@uni.example\n")
    CANVAS_ROSTER = ("Student,ID,SIS User ID,SIS Login ID,Section\n"
                     "    Points Possible,,,,\n"
                     '"García López, Ana",88801,1001,ana,T1\n'
                     '"O\'Neil, Ben",88802,1002,ben,T2\n'
                     '"Ruiz, Cris",88803,1003,cris,T2\n')

    def rows(self, roster_text: str, submissions: dict[str, float | None]):
        """Outcomes as --batch makes them: roster order, a missing student, then the unmatched."""
        from grading.batch import Submission, _roster_rows
        from grading.gradebook import Outcome, read_roster

        folder = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, folder)
        (Path(folder) / "roster.csv").write_text(roster_text, encoding="utf-8")
        roster = read_roster(Path(folder) / "roster.csv")
        subs = [Submission(n, Path(n)) for n in submissions]
        outcomes = [Outcome(n, status="graded", total=t, max_score=10.0, lessons={"01": {"score": t, "max_score": 10}},
                            visible={"01": (t, 10.0)}) for n, t in submissions.items()]
        matched, unmatched = roster.match(subs)
        return roster, _roster_rows(roster, outcomes, matched, unmatched)

    def test_moodle_from_a_moodle_roster(self) -> None:
        from grading.gradebook import moodle_rows

        roster, rows = self.rows(self.MOODLE_ROSTER, {"ana": 7.5, "ben@uni.example": 10.0, "zoe": 3.0})
        table, left_out = moodle_rows(rows, roster, "Lab 1")
        self.assertEqual(table, [["Email address", "Full name", "Lab 1", "Lab 1 (feedback)"],
                                 ["ana@uni.example", "Ana García López", "7.5", "7.5/10 (lesson 01: 7.5/10)"],
                                 ["ben@uni.example", "Ben O'Neil", "10", "10/10 (lesson 01: 10/10)"],
                                 ["cris@uni.example", "Cris Ruiz", "", "no submission"]])
        self.assertEqual(left_out, ["zoe: no row of the roster matches this submission"])  # not in any column

    def test_moodle_from_a_canvas_roster(self) -> None:
        from grading.gradebook import moodle_rows

        roster, rows = self.rows(self.CANVAS_ROSTER, {"ana": 7.5, "1002": 10.0})
        table, left_out = moodle_rows(rows, roster, "Lab 1")
        # SIS User ID is the institution's ID number; Canvas's own ID (888..) is nothing to Moodle.
        self.assertEqual([r[:3] for r in table], [["ID number", "Full name", "Lab 1"], ["1001", "Ana García López", "7.5"],
                                                  ["1002", "Ben O'Neil", "10"], ["1003", "Cris Ruiz", ""]])
        self.assertEqual(left_out, [])

    def test_moodle_leaves_out_a_row_without_the_user_column(self) -> None:
        from grading.gradebook import moodle_rows

        # E-mails on two rows, ID numbers on two: the tie goes to e-mail, and Ana's row, without one, is left
        # out (Moodle would give the grade of a row with an empty user column to the student of the row before).
        roster, rows = self.rows(self.MOODLE_ROSTER.replace("ana@uni.example", ""), {"1001": 7.5, "cris": 5.0})
        table, left_out = moodle_rows(rows, roster, "Lab 1")
        self.assertEqual(table[0][0], "Email address")
        self.assertEqual([r[0] for r in table[1:]], ["ben@uni.example", "cris@uni.example"])
        self.assertEqual(left_out, ["1001: the roster's line 2 has no email address"])
        # A student row without any id is kept (missing in grades.csv, said when left out), never dropped.
        roster, rows = self.rows(self.MOODLE_ROSTER + "Dan,Soto,,U,CS,\n", {"ana": 7.5})
        self.assertEqual([(o.ident, o.status) for o in rows][-1], ("line 5", "missing"))
        self.assertEqual(moodle_rows(rows, roster, "Lab 1")[1], ["line 5: the roster's line 5 has no email address"])
        roster, rows = self.rows(self.MOODLE_ROSTER.replace("cris@uni.example", ""), {"ana": 7.5})
        self.assertEqual(moodle_rows(rows, roster, "Lab 1")[0][0][0], "Email address")  # 2 against 2 again

    def test_canvas_from_either_roster(self) -> None:
        from grading.gradebook import canvas_rows

        roster, rows = self.rows(self.MOODLE_ROSTER.replace("Department", "Group"), {"ana": 7.5, "zoe": 1.0})
        table, left_out = canvas_rows(rows, roster, "Lab 1")
        self.assertEqual(table[:3], [["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Lab 1"],
                                     ["Points Possible", "", "", "", "", "10"],
                                     ["García López, Ana", "", "1001", "ana@uni.example", "CS", "7.5"]])
        self.assertEqual(table[3], ["O'Neil, Ben", "", "1002", "ben@uni.example", "CS", ""])
        self.assertEqual(left_out, ["zoe: no row of the roster matches this submission"])
        self.assertFalse(any("zoe" in cell for row in table for cell in row))
        roster, rows = self.rows(self.CANVAS_ROSTER, {"ana": 7.5, "88802": 10.0})
        table, _ = canvas_rows(rows, roster, "Lab 1")
        self.assertEqual(table[2:], [["García López, Ana", "88801", "1001", "ana", "T1", "7.5"],
                                     ["O'Neil, Ben", "88802", "1002", "ben", "T2", "10"],
                                     ["Ruiz, Cris", "88803", "1003", "cris", "T2", ""]])
        # A plain roster's "id" is a student number, not Canvas's: it goes to SIS User ID.
        roster, rows = self.rows("id,name,email\n42,Ana Ruiz,ana@x.example\n", {"42": 3.0})
        table, _ = canvas_rows(rows, roster, "Lab 1")
        self.assertEqual(table[2], ["Ana Ruiz", "", "42", "ana@x.example", "", "3"])

    def test_names_from_the_columns_a_roster_has(self) -> None:
        for header, row, full in (("Nombre;Apellidos;Correo", "Ana;García López;a@x", "Ana García López"),
                                  ("Full name,Email", "Ana García López,a@x", "Ana García López"),
                                  ("First name,Surname,Email", "Ana,García López,a@x", "Ana García López"),
                                  ("Name,Email", '"García López, Ana",a@x', "Ana García López"),
                                  ("Nombre,Correo", "Ana García López,a@x", "Ana García López")):
            roster, rows = GradebookTest.rows(self, f"{header}\n{row}\n", {"a": 1.0})
            self.assertEqual(roster.names(rows[0].roster)[0], full, header)

    def test_written_files_are_rfc4180_with_a_bom_and_crlf(self) -> None:
        from grading.gradebook import csv_text

        text = csv_text([["Student", "Lab, 1"], ['Chevy "The Man" Chase', "3"], ["two\nlines", ""]])
        self.assertEqual(text, '\ufeffStudent,"Lab, 1"\r\n"Chevy ""The Man"" Chase",3\r\n"two\nlines",\r\n')


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

    def assert_refused(self, argv: list[str], words: str) -> None:
        status, err = self.run_main(argv)
        self.assertEqual(status, 2, argv)
        self.assertIn(words, err, argv)
        self.assertNotIn("Traceback", err, argv)

    def test_a_grader_data_that_is_not_a_folder(self) -> None:
        # Refused before the build, which would take minutes and write build/student: the build
        # step is replaced by one that fails the test if it is reached.
        from unittest import mock
        from grading import driver

        def no_build(*_args, **_kwargs):
            raise AssertionError("the build started before --grader-data was checked")

        with tempfile.TemporaryDirectory() as folder, mock.patch.object(driver, "build_tree", no_build):
            self.assert_refused(["--student", "--grader-data", f"{folder}/none", "01"],
                                f"--grader-data {folder}/none: no such folder")
            self.assert_refused(["--student", "--grader-data", "/dev/null", "01"],
                                "--grader-data /dev/null: not a folder")

    def test_a_submission_info_that_is_not_json(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            info = Path(folder) / "info.json"
            info.write_text("this is not JSON")
            self.assert_refused(["--student", "--submission-info", str(info), "01"],
                                f"--submission-info {info}: not a submission description")
            info.write_bytes(b"\xff\xfe not utf-8")
            self.assert_refused(["--student", "--submission-info", str(info), "01"], "--submission-info")
            self.assert_refused(["--student", "--submission-info", f"{folder}/none.json", "01"], "--submission-info")

    def test_a_results_file_under_a_file(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            (Path(folder) / "afile").write_text("x")
            for option in ("--results", "--junit"):
                self.assert_refused([option, f"{folder}/afile/x.json", "01"], f"{folder}/afile is a file, not a folder")

    def test_a_build_dir_that_is_a_file_or_missing(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            afile = Path(folder) / "afile"
            afile.write_text("x")
            self.assert_refused(["--build-dir", str(afile), "01"], f"--build-dir {afile}: is a file, not a folder")
            for check in ("--check-integrity", "--check-alone"):
                self.assert_refused([check, "--build-dir", f"{folder}/none"], f"--build-dir {folder}/none: no such folder")
                self.assert_refused([check, "--build-dir", str(afile)], "is a file, not a folder")

    def test_mutants_of_a_lesson_that_does_not_exist(self) -> None:
        done = subprocess.run([sys.executable, str(Path(__file__).resolve().parents[2] / "tools" / "grade"),
                               "--mutants", "99"], capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 2)
        self.assertIn("lesson(s) 99 have no exercise units", done.stderr)

    def test_an_output_that_cannot_be_written_says_why_and_leaves_nothing(self) -> None:
        import errno
        from unittest import mock

        from grading import driver

        with tempfile.TemporaryDirectory() as folder:
            target = Path(folder) / "results.json"
            for number, words in ((errno.EROFS, "Read-only file system"), (errno.ENOSPC, "disk is full"),
                                  (errno.EACCES, "Permission denied")):
                real_open = open

                def failing_open(path, *args, **kwargs):
                    if ".tmp-" in str(path):
                        real_open(path, "w").close()  # the temporary exists when the write fails
                        raise OSError(number, os.strerror(number), str(path))
                    return real_open(path, *args, **kwargs)

                with mock.patch("builtins.open", failing_open):
                    with self.assertRaises(reports.OutputError) as raised:
                        reports.write_text(target, "{}")
                self.assertIn(words, str(raised.exception))
                self.assertIn(str(target), str(raised.exception))
                self.assertEqual(list(Path(folder).iterdir()), [], "the temporary or a half file was left")
            with mock.patch.object(driver, "grade", side_effect=reports.OutputError("cannot write x: No space")):
                self.assert_refused(["01"], "cannot write x: No space")

    @unittest.skipUnless(os.geteuid() == 0 and shutil.which("unshare"), "mounting a file system needs root")
    def test_a_read_only_and_a_full_file_system(self) -> None:
        # Real file systems, mounted in a private mount namespace: a read-only tmpfs is refused before
        # anything is built; a full one fails the write, says so, and leaves no temporary behind.
        grade = Path(__file__).resolve().parents[2] / "tools" / "grade"
        with tempfile.TemporaryDirectory() as folder:
            script = (f"mount -t tmpfs -o ro,size=1m none {folder} && "
                      f"{sys.executable} {grade} --results {folder}/r.json 01; echo status=$?; "
                      f"mount -t tmpfs -o size=8k none {folder} && head -c 8192 /dev/zero > {folder}/fill; "
                      f"{sys.executable} -c 'import sys; sys.path.insert(0, \"{grade.parent}\"); "
                      "from pathlib import Path; from grading import reports; "
                      f"reports.write_text(Path(\"{folder}/r.json\"), \"x\" * 100000)'; echo status=$?; "
                      f"ls -A {folder}")
            done = subprocess.run(["unshare", "--mount", "sh", "-c", script], capture_output=True, text=True,
                                  timeout=120)
            # Where no private mount namespace can be made (a chroot, whose root is no mount point, or
            # a container without CAP_SYS_ADMIN, such as the development container), unshare or mount
            # stops before the script's first status line: nothing here is then the grader's doing.
            if "status=" not in done.stdout and ("mount:" in done.stderr or "unshare:" in done.stderr):
                self.skipTest(f"cannot mount here: {done.stderr.strip()}")
        self.assertIn(f"--results {folder}/r.json: the folder {folder} cannot be written", done.stderr)
        self.assertIn("cannot write", done.stderr)
        self.assertIn("No space left on device (the disk is full)", done.stderr)
        self.assertEqual(done.stdout.split(), ["status=2", "status=1", "fill"])  # no r.json.tmp-grade

    def test_batch_options(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            subs = Path(folder) / "subs"
            subs.mkdir()
            self.assert_refused(["--batch", f"{folder}/none"], "no such folder")
            self.assert_refused(["--batch", "/dev/null"], "--batch /dev/null: not a folder")
            self.assert_refused(["--hidden", f"{folder}/none", "01"], f"--hidden {folder}/none: no such folder")
            self.assert_refused(["--hidden", "/dev/null", "01"], "--hidden /dev/null: not a folder")
            self.assert_refused(["--hidden", str(subs), "01"], f"--hidden {subs}: no .cpp test files there")
            with tempfile.NamedTemporaryFile(suffix=".zip") as one_zip:  # a submission, not their folder
                self.assert_refused(["--batch", one_zip.name], "not a folder (--batch takes the folder")
            self.assert_refused(["--batch", str(subs), "--jobs", "0"], "--jobs 0")
            self.assert_refused(["--batch", str(subs), "--roster", f"{folder}/none.csv"], "--roster")
            self.assert_refused(["--batch", str(subs), "--roster", "/dev/null"], "not a regular file")
            self.assert_refused(["--batch", str(subs), "--roster", str(subs)], "not a regular file")
            self.assert_refused(["--batch", str(subs), "--student"], "does not take --student")
            self.assert_refused(["--format", "canvas", "01"], "--format belongs with --batch")
            self.assert_refused(["--assignment", "hw3", "01"], "--assignment belongs with --batch")
            self.assert_refused(["--batch", str(subs), "--out", str(subs / "out")], "inside the submissions folder")
            self.assert_refused(["--batch", str(subs)], "no submission")
            roster = Path(folder) / "roster.csv"
            roster.write_text("name,grade\nAna,1\n")
            (subs / "ana").mkdir()
            self.assert_refused(["--batch", str(subs), "--roster", str(roster)], "no id or e-mail column")
            # A roster that would lose a grade is refused before anything is packed or built.
            roster.write_text("Email,Name\nana@x.example,Ana\nben@x.example,Ben\nANA@x.example,Ana Bis\n")
            self.assert_refused(["--batch", str(subs), "--roster", str(roster)],
                                "lines 2 and 4 have the same Email 'ANA@x.example'")
            roster.write_text("Email,Login\nana@x.example,a1\nana@y.example,a2\n")
            self.assert_refused(["--batch", str(subs), "--roster", str(roster)],
                                "the submission ana matches the rows on lines 2 and 3")
            for value in ("abc", "0", "-5", "inf"):
                with mock.patch.dict(os.environ, {"ILLUM_GRADE_BATCH_TIMEOUT": value}):
                    self.assert_refused(["--batch", str(subs)], f"ILLUM_GRADE_BATCH_TIMEOUT={value}: not a number")
            with mock.patch.dict(os.environ, {"ILLUM_GRADE_SETUP_BUILD_TIMEOUT": "soon"}):
                self.assert_refused(["--batch", str(subs)], "ILLUM_GRADE_SETUP_BUILD_TIMEOUT=soon: not a number")
            self.assertEqual(sorted(p.name for p in Path(folder).iterdir()), ["roster.csv", "subs"])

    def test_batch_without_git_ends_in_words(self) -> None:
        # No git program (only bash on PATH): the autograder is packed from the tree's files, and setup.sh,
        # finding no package tools either, fails saying so: exit 2, no traceback.
        with tempfile.TemporaryDirectory() as folder:
            bin_dir, subs, out = Path(folder) / "bin", Path(folder) / "subs", Path(folder) / "grades"
            bin_dir.mkdir()
            (bin_dir / "bash").symlink_to(shutil.which("bash"))
            (subs / "ana").mkdir(parents=True)
            with mock.patch.dict(os.environ, {"PATH": str(bin_dir)}):
                status, err = self.run_main(["--batch", str(subs), "--out", str(out), "--jobs", "1", "01"])
            self.assertEqual(status, 2, err)
            self.assertNotIn("Traceback", err)
            self.assertIn("preparing the grader for lessons 01", err)  # packed
            self.assertIn("its builds: no time limit; ILLUM_GRADE_SETUP_BUILD_TIMEOUT sets one", err)
            self.assertIn("setup.sh failed in worker 1", err)
            self.assertIn("setup.sh: FAILED", (out / "setup.log").read_text(encoding="utf-8"))



class CheckStudentEditionOptionsTest(unittest.TestCase):
    """tests/checks/check_student_edition.py --lesson refuses what names no lesson with exercises, with exit 2 and
    one line naming the option and the value, before it makes a folder or builds anything."""

    def run_check(self, *args: str):
        script = Path(__file__).resolve().parents[2] / "tests" / "checks" / "check_student_edition.py"
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


class CheckStudentEditionCommandsTest(unittest.TestCase):
    """check_student_edition.py --lesson runs the commands of the edition's own README: they are read
    from its "Build, test and grade your code" block, NN replaced, each by what it does; a README that
    lacks one is a problem named, not a command guessed."""

    def load(self):
        checks = Path(__file__).resolve().parents[2] / "tests" / "checks"
        sys.path.insert(0, str(checks))
        spec = importlib.util.spec_from_file_location("check_student_edition", checks / "check_student_edition.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        from grading.edition import student_readme
        return module, student_readme

    def test_the_editions_readme_holds_every_student_command(self) -> None:
        module, student_readme = self.load()
        root = Path(__file__).resolve().parents[2]
        with tempfile.TemporaryDirectory() as folder:
            edition = Path(folder)
            text = student_readme(root, ["lessons/13_two_pass/README.md", "exercises/13_two_pass/README.md"], ["13"])
            (edition / "README.md").write_text(text, encoding="utf-8")
            commands, problems = module.readme_commands(edition, "13")
            self.assertEqual(problems, [])
            self.assertEqual(commands["configure"], ["cmake", "--preset", "student"])
            self.assertEqual(commands["build"][:4], ["cmake", "--build", "--preset", "student"])
            self.assertIn("tests_lesson13", commands["build"])
            self.assertEqual(commands["test"], ["build/student/bin/tests_lesson13", "-ts=lesson13"])
            self.assertEqual(commands["program"][0], "build/student/bin/lesson13")
            self.assertEqual(commands["grade"], ["tools/grade", "--student", "13"])
            # Without the test command the check names the gap.
            (edition / "README.md").write_text(
                "\n".join(line for line in text.splitlines() if "tests_lessonNN -ts" not in line), encoding="utf-8")
            _, problems = module.readme_commands(edition, "13")
            self.assertEqual(problems, ["the edition's README.md has no test command in its student block"])
            (edition / "README.md").write_text("# illum — student edition\n", encoding="utf-8")
            _, problems = module.readme_commands(edition, "13")
            self.assertEqual(len(problems), 1)
            self.assertIn("no ```sh block", problems[0])

    def test_the_editions_readme_tells_windows_and_macos_students_of_the_container(self) -> None:
        # A student on Windows or macOS has only the edition: its README must say how to get a Debian 12
        # (the container, WSL 2), in prose, so that the student block stays the section's first ```sh block.
        module, student_readme = self.load()
        root = Path(__file__).resolve().parents[2]
        files = ["lessons/13_two_pass/README.md", "exercises/13_two_pass/README.md"]
        with tempfile.TemporaryDirectory() as folder:
            edition = Path(folder)
            text = student_readme(root, files + [".devcontainer/Dockerfile"], ["13"])
            section = text.split("## Build, test and grade your code", 1)[1]
            self.assertLess(section.index("Reopen in Container"), section.index("```sh"))
            self.assertIn("docker build -f .devcontainer/Dockerfile -t illum-dev .", text)
            self.assertIn("wsl --install -d Debian", text)
            (edition / "README.md").write_text(text, encoding="utf-8")
            commands, problems = module.readme_commands(edition, "13")
            self.assertEqual(problems, [])
            self.assertEqual(commands["configure"], ["cmake", "--preset", "student"])
        # An edition without the container's files does not send the student looking for them.
        self.assertNotIn(".devcontainer", student_readme(root, files, ["13"]))


if __name__ == "__main__":
    unittest.main(verbosity=2)
