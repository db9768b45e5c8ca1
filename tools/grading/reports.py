"""What a grading run produces: the score table, Gradescope's results.json,
JUnit XML and the exit code. Pure functions of a ``GradeRun``, so that they
are tested without building anything (tests/tools/test_grade.py).
"""
from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .results import TestResult

EXIT_PASSED = 0
EXIT_FAILED = 1
EXIT_NOT_BUILT = 2

# Gradescope visibility of an instructor's hidden tests: never shown to students.
HIDDEN_VISIBILITY = "hidden"

# Gradescope shows outputs in a browser; a full compiler log can be huge.
MAX_OUTPUT_CHARS = 30_000


@dataclass
class GradeRun:
    """Everything one ``tools/grade`` invocation learned."""

    lessons: list[str]
    results: list[TestResult] = field(default_factory=list)
    build_failed: bool = False
    build_output: str = ""
    problems: list[str] = field(default_factory=list)  # crashes, timeouts, missing programs
    student: bool = False
    seconds: float = 0.0

    @property
    def score(self) -> float:
        return sum(r.score for r in self.results)

    @property
    def max_score(self) -> float:
        return sum(r.points for r in self.results)


def exit_code(run: GradeRun) -> int:
    """0: every test passed; 1: a test failed (or none were found); 2: no build.

    Finding no grading test at all is a failure, not a vacuous pass: a grader
    that graded nothing must not report success.
    """
    if run.build_failed:
        return EXIT_NOT_BUILT
    if not run.results:
        return EXIT_FAILED
    return EXIT_PASSED if all(r.passed for r in run.results) else EXIT_FAILED


def _fmt(x: float) -> str:
    return f"{x:g}"


def _rows(run: GradeRun) -> list[tuple[str, int, int, float, float]]:
    """(label, tests passed, tests, points, max points) per lesson, visible then hidden."""
    rows = []
    for lesson in run.lessons:
        for hidden in (False, True):
            group = [r for r in run.results if r.lesson == lesson and r.hidden == hidden]
            if hidden and not group:
                continue
            label = f"{lesson} (hidden)" if hidden else lesson
            rows.append((label, sum(r.passed for r in group), len(group),
                         sum(r.score for r in group), sum(r.points for r in group)))
    return rows


def score_table(run: GradeRun) -> str:
    """The table printed at the end of a run, one row per lesson."""
    if run.build_failed:
        return "The build failed: nothing was graded (score 0). The compiler's messages are above."
    header = ("lesson", "tests passed", "points")
    body = [(label, f"{passed}/{total}", f"{_fmt(points)}/{_fmt(max_points)}")
            for label, passed, total, points, max_points in _rows(run)]
    percent = 100.0 * run.score / run.max_score if run.max_score else 0.0
    total_passed = sum(r.passed for r in run.results)
    footer = ("total", f"{total_passed}/{len(run.results)}",
              f"{_fmt(run.score)}/{_fmt(run.max_score)}  ({percent:.0f}%)")
    widths = [max(len(row[i]) for row in [header, *body, footer]) for i in range(3)]

    def line(row: tuple[str, str, str]) -> str:
        return "  ".join(cell.ljust(width) for cell, width in zip(row, widths)).rstrip()

    rule = "  ".join("-" * w for w in widths)
    lines = [line(header), rule, *map(line, body), rule, line(footer)]
    if not run.results:
        lines.append("no grading tests were found for the lessons asked for")
    lines.extend(f"problem: {p}" for p in run.problems)
    return "\n".join(lines)


def failure_report(run: GradeRun, root: Path | None = None) -> str:
    """The explanation of every failed visible test, for the terminal."""
    parts = []
    for result in run.results:
        if result.passed or result.hidden:
            continue
        parts.append(f"[lesson{result.lesson}] {result.name}\n  " +
                     result.output(root).replace("\n", "\n  "))
    return "\n\n".join(parts)


def _truncate(text: str, limit: int = MAX_OUTPUT_CHARS) -> str:
    """Keeps the start of a long text, where the first compiler error is."""
    if len(text) <= limit:
        return text
    return text[:limit] + f"\n... ({len(text) - limit} more characters cut)"


def test_name(result: TestResult) -> str:
    return f"lesson{result.lesson}{' (hidden)' if result.hidden else ''}: {result.name}"


def gradescope_results(run: GradeRun, root: Path | None = None) -> dict[str, Any]:
    """Gradescope's results.json: one entry per test, hidden tests marked hidden.

    On a failed build the score is 0 and the single entry carries the
    compiler's output, so the student sees why nothing was graded.
    """
    if run.build_failed:
        return {
            "score": 0,
            "output": "Your code did not compile, so no test could run. The compiler said:\n\n"
                      + _truncate(run.build_output),
            "visibility": "visible",
            "stdout_visibility": "visible",
            "execution_time": round(run.seconds, 1),
            "tests": [{
                "name": "build",
                "score": 0,
                "max_score": 0,
                "status": "failed",
                "output": _truncate(run.build_output),
                "visibility": "visible",
            }],
        }
    tests = []
    for number, result in enumerate(run.results, start=1):
        tests.append({
            "name": test_name(result),
            "number": str(number),
            "score": result.score,
            "max_score": result.points,
            "status": "passed" if result.passed else "failed",
            "output": _truncate(result.output(root)),
            "visibility": HIDDEN_VISIBILITY if result.hidden else "visible",
        })
    summary = score_table(run)
    return {
        "score": run.score,
        "max_score": run.max_score,
        "output": summary,
        "visibility": "visible",
        "stdout_visibility": "visible",
        "execution_time": round(run.seconds, 1),
        "tests": tests,
    }


# Characters XML 1.0 cannot hold; a student's output may contain them.
_XML_INVALID = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def _xml_text(text: str) -> str:
    return _XML_INVALID.sub("?", text)


def junit_xml(run: GradeRun, root: Path | None = None) -> str:
    """JUnit XML: one <testsuite> per lesson (hidden tests in their own suite)."""
    suites = ET.Element("testsuites", name="illum grading")
    if run.build_failed:
        suite = ET.SubElement(suites, "testsuite", name="build", tests="1", failures="0", errors="1", skipped="0")
        case = ET.SubElement(suite, "testcase", classname="build", name="build")
        error = ET.SubElement(case, "error", message="the code did not compile", type="BuildError")
        error.text = _xml_text(_truncate(run.build_output))
    groups: dict[str, list[TestResult]] = {}
    for result in run.results:
        groups.setdefault(f"lesson{result.lesson}{'.hidden' if result.hidden else ''}", []).append(result)
    total = failures = skipped = 0
    for name, group in groups.items():
        n_failed = sum(not r.passed and not r.skipped for r in group)
        n_skipped = sum(r.skipped for r in group)
        total, failures, skipped = total + len(group), failures + n_failed, skipped + n_skipped
        suite = ET.SubElement(suites, "testsuite", name=name, tests=str(len(group)), failures=str(n_failed),
                              errors="0", skipped=str(n_skipped), time=f"{sum(r.seconds for r in group):.6f}")
        for result in group:
            attributes = {"classname": name, "name": _xml_text(result.name), "time": f"{result.seconds:.6f}"}
            if result.file:
                attributes.update(file=_xml_text(result.file), line=str(result.line))
            case = ET.SubElement(suite, "testcase", attributes)
            if result.skipped:
                ET.SubElement(case, "skipped")
            elif not result.passed:
                kind = "NotImplemented" if result.not_implemented_only else "AssertionFailure"
                first = result.failures[0].describe(root).splitlines()[0] if result.failures else result.note
                failure = ET.SubElement(case, "failure", message=_xml_text(first), type=kind)
                failure.text = _xml_text(result.output(root))
    suites.set("tests", str(total + (1 if run.build_failed else 0)))
    suites.set("failures", str(failures))
    suites.set("errors", "1" if run.build_failed else "0")
    suites.set("skipped", str(skipped))
    suites.set("time", f"{run.seconds:.3f}")
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n"


def write_text(path: Path, text: str) -> None:
    """Writes through a temporary name and a rename: a reader never sees half a file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(path.name + ".tmp-grade")
    temporary.write_text(text, encoding="utf-8")
    temporary.replace(path)


def write_results_json(path: Path, run: GradeRun, root: Path | None = None) -> None:
    write_text(path, json.dumps(gradescope_results(run, root), indent=2, ensure_ascii=False) + "\n")


def write_junit(path: Path, run: GradeRun, root: Path | None = None) -> None:
    write_text(path, junit_xml(run, root))
