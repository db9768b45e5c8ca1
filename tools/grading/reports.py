"""What a grading run produces: the score table, Gradescope's results.json, JUnit XML and the exit code;
pure functions of a GradeRun, tested without building anything."""
from __future__ import annotations

import errno
import json
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from common.files import atomic_write_text

from .results import TestResult, _short_path

EXIT_PASSED = 0
EXIT_FAILED = 1
EXIT_NOT_BUILT = 2
HIDDEN_VISIBILITY = "hidden"  # Gradescope's visibility of an instructor's hidden tests: never shown to students
MAX_OUTPUT_CHARS = 30_000  # Gradescope shows outputs in a browser; a full compiler log can be huge
_XML_INVALID = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")  # XML 1.0 cannot hold these


@dataclass
class GradeRun:
    """Everything one ``tools/grade`` invocation learned."""

    lessons: list[str]
    results: list[TestResult] = field(default_factory=list)
    build_failed: bool = False
    build_output: str = ""
    problems: list[str] = field(default_factory=list)  # crashes, timeouts, missing programs
    seconds: float = 0.0
    # The student's files that alone failed to build, each graded as its stub (file -> compiler output).
    fallbacks: dict[str, str] = field(default_factory=dict)
    link_failures: set[str] = field(default_factory=set)  # the fallbacks that compiled but did not link
    hidden_build_failed: bool = False  # the instructor's hidden tests did not build: a misconfigured grader
    hidden_build_output: str = ""
    submission: dict[str, Any] | None = None  # what the autograder did with the upload (install_submission)
    blame_student: bool = True  # False when the build failure is not the student's (a broken tree)
    # For instructors only: what the suspicious-code checks noticed (they advise, never decide),
    # tampering the runner saw, processes killed, the grader's own problems.
    review: list[str] = field(default_factory=list)

    def lesson_status(self, lesson: str) -> str:
        """"graded", "not gradable" (a file of the lesson did not compile or link) or "grader error"."""
        if self.build_failed:
            return "not gradable" if self.blame_student else "grader error"
        lessons = {match.group(1) for f in self.fallbacks if (match := re.search(r"exercises/(\d\d)_", f))}
        return "not gradable" if lesson in lessons else "graded"

    @property
    def score(self) -> float:
        return sum(r.score for r in self.results)

    @property
    def max_score(self) -> float:
        return sum(r.points for r in self.results)


def exit_code(run: GradeRun) -> int:
    """0: every test passed; 1: a test failed, or none was found (a grader that graded nothing must not
    report success); 2: no build."""
    if run.build_failed or run.hidden_build_failed:
        return EXIT_NOT_BUILT
    return EXIT_PASSED if run.results and all(r.passed for r in run.results) else EXIT_FAILED


def _cells(group: list[TestResult]) -> tuple[str, str]:
    """A row's "tests passed" and "points": 3/4 and 3/5."""
    return (f"{sum(r.passed for r in group)}/{len(group)}",
            f"{sum(r.score for r in group):g}/{sum(r.points for r in group):g}")


def score_table(run: GradeRun, for_students: bool = False) -> str:
    """The table printed at the end of a run, one row per lesson. `for_students` (results.json): while
    hidden tests exist, neither their row nor the total is shown, as Gradescope hides the total then."""
    if run.build_failed:
        return "The build failed: nothing was graded (score 0). The compiler's messages are above."
    # Any entry hidden from students (a hidden test, or the hidden tests' failed build) hides the total.
    hide = for_students and (run.hidden_build_failed or any(r.hidden for r in run.results))
    header = ("lesson", "tests passed", "points")
    # (label, tests passed, points) per lesson, visible then hidden
    body = [(f"{lesson} (hidden)" if hidden else lesson, *_cells(group)) for lesson in run.lessons
            for hidden in ((False,) if hide else (False, True))
            if (group := [r for r in run.results if r.lesson == lesson and r.hidden == hidden]) or not hidden]
    passed, points = _cells(run.results)  # (only shown when nothing is hidden)
    footer = ("total", passed, f"{points}  ({100.0 * run.score / run.max_score if run.max_score else 0.0:.0f}%)")
    widths = [max(len(row[i]) for row in [header, *body] + ([] if hide else [footer])) for i in range(3)]
    rule = tuple("-" * w for w in widths)
    lines = ["  ".join(cell.ljust(width) for cell, width in zip(row, widths)).rstrip()
             for row in [header, rule, *body] + ([] if hide else [rule, footer])]
    if hide:
        lines.append("Hidden tests are graded too; your total appears when your instructor publishes the scores.")
    if not run.results:
        lines.append("no grading tests were found for the lessons asked for")
    lines.extend(f"problem: {p}" for p in (run.problems if not for_students else _visible_problems(run)))
    return "\n".join(lines)


def _visible_problems(run: GradeRun) -> list[str]:
    """Problems a student may read: none about the hidden tests' program, and the ones of a single test
    only counted (each test's entry says why)."""
    hidden_names = [r.name for r in run.results if r.hidden and r.name]
    problems = [p for p in run.problems if "tests_hidden" not in p and not any(n in p for n in hidden_names)]
    per_test = sum(part.count(': test "') for part in problems)
    general = [part for p in problems for part in p.split("; ") if ': test "' not in part]
    lines = [f"{per_test} test(s) crashed or did not finish; their entries say which and why"] if per_test else []
    return lines + general


def failure_report(run: GradeRun, root: Path | None = None) -> str:
    """The explanation of every failed visible test, for the terminal."""
    return "\n\n".join(f"[lesson{r.lesson}] {r.name}\n  " + r.output(root).replace("\n", "\n  ")
                       for r in run.results if not r.passed and not r.hidden)


def failure_summary(run: GradeRun, root: Path | None = None) -> str:
    """After the score table: each failed visible test with its first failing check, one entry each,
    so that the reason stays beside the score (the full explanations are above the table)."""
    lines = []
    for result in run.results:
        if result.passed or result.hidden or result.skipped:
            continue
        why = result.note or "failed"
        if result.failures:
            first = result.failures[0]
            why = (f"{_short_path(first.file, root)}:{first.line}: " if first.file else "") + first.headline()
        lines.append(f"  lesson{result.lesson}: {result.name}\n      {why.splitlines()[0] if why else ''}")
    return f"{len(lines)} test(s) failed; the first failing check of each (details above):\n" + "\n".join(lines) \
        if lines else ""


def _truncate(text: str, limit: int = MAX_OUTPUT_CHARS) -> str:
    """Keeps the start of a long text, where the first compiler error is."""
    return text if len(text) <= limit else text[:limit] + f"\n... ({len(text) - limit} more characters cut)"


def test_name(result: TestResult) -> str:
    return f"lesson{result.lesson}{' (hidden)' if result.hidden else ''}: {result.name}"


def submission_summary(run: GradeRun) -> str:
    """Markdown: which uploaded files were graded, which were ignored, what was expected."""
    info = run.submission
    if not info:
        return ""
    lines = ["**What was graded**", "",
             *(f"- used `{u['file']}` as `{u['target']}`" + (f" ({u['note']})" if u.get("note") else "")
               for u in info.get("installed", [])),
             *(f"- ignored `{i['file']}`: {i['reason']}" for i in info.get("ignored", [])),
             *(f"- {note}" for note in info.get("notes", []))]
    used = {Path(item["target"]).name for item in info.get("installed", [])}
    missing = [name for name in info.get("expected", []) if name not in used]
    if info.get("installed") and missing:
        lines.append("- not in your upload, so graded as the unchanged stub: " + ", ".join(f"`{m}`" for m in missing))
    if not info.get("installed"):
        expected = ", ".join(f"`{name}`" for name in info.get("expected", []))
        lines.append(f"- **none of your files is an exercise file of lesson(s) {', '.join(run.lessons)}**, so the "
                     f"unchanged stubs were graded. Upload {expected} (the files of `exercises/NN_topic/`, "
                     "under those names).")
    return "\n".join(lines)


def machine_summary(run: GradeRun) -> dict[str, Any]:
    """results.json's ``extra_data``: what tools/grade --batch reads back (per lesson, flags, build problems)."""
    groups = {lesson: [r for r in run.results if r.lesson == lesson] for lesson in run.lessons}
    return {"illum": {
        "lessons": {lesson: {"status": run.lesson_status(lesson), "score": sum(r.score for r in group),
                             "max_score": sum(r.points for r in group)} for lesson, group in groups.items()},
        "tests": [{"name": test_name(r), "lesson": r.lesson, "hidden": r.hidden, "score": r.score,
                   "max_score": r.points} for r in run.results],
        "not_gradable": ([f"{f} did not {'link' if f in run.link_failures else 'compile'}" for f in run.fallbacks]
                         if not run.build_failed else ["the build failed"] if run.blame_student else []),
        "review": list(run.review),
        "grader_error": bool(run.build_failed and not run.blame_student),
    }}


def _build_entry(name: str, output: str, visibility: str = "visible") -> dict[str, Any]:
    """A failed build's entry: its log without make's progress lines, which say nothing about the error."""
    output = "\n".join(line for line in output.splitlines()
                       if not re.match(r"\[\s*\d+%\]|gmake\[\d+\]: (Entering|Leaving)", line))
    return _entry(name, output, "failed", visibility)


def _entry(name: str, output: str, status: str, visibility: str, score: float = 0, max_score: float = 0) -> dict:
    return {"name": name, "score": score, "max_score": max_score, "status": status, "output": _truncate(output),
            "output_format": "text", "visibility": visibility}


def _fallback_summary(run: GradeRun) -> str:
    """The results' paragraph on the student's files that did not compile or link (graded as stubs)."""
    linked = run.link_failures & set(run.fallbacks)
    kind = 0 if not linked else 1 if linked == set(run.fallbacks) else 2
    what = ("did not compile", "did not link", "did not compile or link")[kind]
    words = ("the compiler's", "the linker's", "the compiler's and the linker's")[kind]
    return (f"**Some of your files {what}.** Each was replaced by its stub, so only its lesson lost points; {words} "
            "messages are in the `build:` entries below:\n"
            + "\n".join(f"- `{name}`" + (" (a link error: a name defined twice, or declared and never defined)"
                                          if name in run.link_failures else "") for name in run.fallbacks))


def _test_entries(run: GradeRun, root: Path | None) -> list[dict[str, Any]]:
    """A build entry per file graded as its stub, one for the hidden tests' failed build, one per test."""
    tests = [_build_entry(f"build: {file} {'did not link' if file in run.link_failures else 'did not compile'} "
                          "(graded as the stub)", output) for file, output in run.fallbacks.items()]
    if run.hidden_build_failed:  # not the student's fault, and the hidden tests' source must not reach students
        tests.append(_build_entry("hidden tests: build (instructors only)", "The instructor's hidden tests did not "
                                  "build; they were not graded.\n\n" + run.hidden_build_output, HIDDEN_VISIBILITY))
    return tests + [{"name": test_name(r), "number": str(number)}
                    | _entry(test_name(r), r.output(root), "passed" if r.passed else "failed",
                             HIDDEN_VISIBILITY if r.hidden else "visible", r.score, r.points)
                    for number, r in enumerate(run.results, start=1)] + _review_entries(run)


def gradescope_results(run: GradeRun, root: Path | None = None) -> dict[str, Any]:
    """Gradescope's results.json, which students read: what was graded, one entry per test (hidden ones marked
    hidden, and with the total out of the summary while they exist), each compiler output once (in its build
    entry); a failed build scores 0, its single entry carrying the compiler's output."""
    summary = submission_summary(run)
    common = {"output_format": "md", "test_output_format": "text", "visibility": "visible",
              "stdout_visibility": "hidden", "execution_time": round(run.seconds, 1),
              "extra_data": machine_summary(run)}
    if run.build_failed:
        headline = ("Your code did not compile, so no test could run. The compiler's messages are in the build "
                    "entry below." if run.blame_student else "The grader could not build (this is not your code's "
                    "fault: tell your instructor). Nothing was graded.")
        return {"score": 0, "output": "\n\n".join(part for part in (summary, headline) if part), **common,
                "tests": [_build_entry("build", run.build_output)] + _review_entries(run)}
    table = score_table(run, for_students=True)  # in a code block, which keeps its columns and a compiler's <T>
    fence = "`" * max(3, 1 + max(map(len, re.findall("`+", table)), default=0))
    parts = [summary, _fallback_summary(run) if run.fallbacks else "",
             "The grader is misconfigured: some of the instructor's tests could not be built. This is not your code's "
             "fault; your visible tests were graded, and your instructor has been shown why." if run.hidden_build_failed
             else "", f"{fence}text\n{table.rstrip()}\n{fence}"]
    return {"score": run.score, "max_score": run.max_score, "output": "\n\n".join(part for part in parts if part),
            **common, "tests": _test_entries(run, root)}


def _review_entries(run: GradeRun) -> list[dict[str, Any]]:
    """One entry hidden from students: what an instructor may want to look at (nothing fails for it)."""
    review = "\n".join(run.review)
    return [_entry("review (instructors only)", review, "passed", HIDDEN_VISIBILITY)] if run.review else []


def _xml_text(text: str) -> str:
    return _XML_INVALID.sub("?", text)


def _failed(group: list[TestResult]) -> int:
    return sum(not r.passed and not r.skipped for r in group)


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
    for name, group in groups.items():
        suite = ET.SubElement(suites, "testsuite", name=name, tests=str(len(group)), failures=str(_failed(group)),
                              errors="0", skipped=str(sum(r.skipped for r in group)),
                              time=f"{sum(r.seconds for r in group):.6f}")
        for result in group:
            case = ET.SubElement(suite, "testcase", classname=name, name=_xml_text(result.name),
                                 time=f"{result.seconds:.6f}",
                                 **({"file": _xml_text(result.file), "line": str(result.line)} if result.file else {}))
            if result.skipped:
                ET.SubElement(case, "skipped")
            elif not result.passed:
                first = result.failures[0].describe(root).splitlines()[0] if result.failures else result.note
                failure = ET.SubElement(case, "failure", message=_xml_text(first),
                                        type="NotImplemented" if result.not_implemented_only else "AssertionFailure")
                failure.text = _xml_text(result.output(root))
    suites.attrib.update(tests=str(len(run.results) + run.build_failed), failures=str(_failed(run.results)),
                         errors=str(int(run.build_failed)), skipped=str(sum(r.skipped for r in run.results)),
                         time=f"{run.seconds:.3f}")
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n"


class OutputError(Exception):
    """An output file could not be written (its message names the file and why)."""


def write_text(path: Path, text: str, mode: int = 0o644) -> None:
    """Writes atomically (never half a file, nor a temporary left behind); OutputError says why not."""
    try:
        atomic_write_text(path, text, mode)
    except OSError as error:
        reason = "No space left on device (the disk is full)" if error.errno == errno.ENOSPC else \
            error.strerror or str(error)
        raise OutputError(f"cannot write {path}: {reason}") from None


def write_results_json(path: Path, run: GradeRun, root: Path | None = None) -> None:
    write_text(path, json.dumps(gradescope_results(run, root), indent=2, ensure_ascii=False) + "\n")


def write_junit(path: Path, run: GradeRun, root: Path | None = None) -> None:
    write_text(path, junit_xml(run, root))
