"""Test results as tests/support/grade_reporter.cpp writes them: one JSON object a line, `"event": "test_case"`
for a test that ran and `"listed"` for each test of --list-test-cases. The listing (or the trusted list the
autograder's setup kept) says which tests should have run, so a crash or a hang still yields every result."""
from __future__ import annotations

import itertools
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

# TEST_CASE("..." * doctest::description("points=3")) gives a test more weight.
_POINTS = re.compile(r"\bpoints\s*=\s*([0-9]+(?:\.[0-9]+)?)")


def points_of(description: str) -> float:
    """The weight of a test: 1 unless its description says ``points=N``."""
    match = _POINTS.search(description or "")
    return float(match.group(1)) if match else 1.0


@dataclass
class Failure:
    """One reason a test failed: a failed assertion, an exception, a crash..."""

    kind: str
    message: str
    file: str = ""
    line: int = 0
    context: str = ""
    exception: str = ""
    subcases: list[str] = field(default_factory=list)
    not_implemented: bool = False
    expression: str = ""  # the check as written: "got.g == doctest::Approx(want.g).epsilon(1e-12)"
    expansion: str = ""   # its values: "0.5 == Approx( 0.25 )"

    @staticmethod
    def from_json(data: dict[str, Any]) -> "Failure":
        return Failure(**{k: str(data.get(k, "")) for k in ("kind", "message", "file", "context", "exception")},
                       **{k: str(data.get(k, "") or "") for k in ("expression", "expansion")},
                       line=int(data.get("line", 0) or 0), subcases=[str(s) for s in data.get("subcases", []) or []],
                       not_implemented=bool(data.get("not_implemented", False)))

    def got_expected(self) -> tuple[str, str] | None:
        """(got, expected) of a failed ``CHECK(actual == expected)``: the tests write the value computed
        on the left and the expected one on the right. None for any other kind of check."""
        if self.kind != "assert" or self.exception or " == " not in self.expression or \
                self.expansion.count(" == ") != 1:
            return None
        got, expected = self.expansion.split(" == ")
        return got.strip(), expected.strip()

    def headline(self, lines: bool = False) -> str:
        """One line (with ``lines``, the values on lines of their own): which check, and the values it saw."""
        if self.not_implemented:
            return f"not implemented yet: {self.exception}"
        if pair := self.got_expected():
            check = self.message.split(" is NOT correct")[0]
            return (f"{check} failed\n  got:      {pair[0]}\n  expected: {pair[1]}" if lines else
                    f"{check} failed: got {pair[0]}, expected {pair[1]}")
        return self.message

    def describe(self, root: Path | None = None) -> str:
        """A few lines a student can act on: where, what, and the test's explanation."""
        text = (f"{_short_path(self.file, root)}:{self.line}: " if self.file else "") + self.headline(lines=True)
        if self.subcases:
            text += "\n  in subcase: " + " / ".join(self.subcases)
        if self.context:
            text += "\n  " + self.context.replace("\n", "\n  ")
        return text


@dataclass
class TestResult:
    suite: str
    name: str
    file: str = ""
    line: int = 0
    passed: bool = False
    skipped: bool = False
    ran: bool = True  # False when the program died before reaching the test
    hidden: bool = False
    points: float = 1.0
    seconds: float = 0.0
    failures: list[Failure] = field(default_factory=list)
    not_implemented_only: bool = False
    note: str = ""  # why the test has no result of its own (crash, timeout)

    @property
    def lesson(self) -> str:
        """The two digits of the suite name ``lessonNN`` (empty for other suites)."""
        match = re.fullmatch(r"lesson(\d\d)", self.suite)
        return match.group(1) if match else ""

    @property
    def key(self) -> tuple[str, str, str, int]:
        """Identifies a test across the listing and the run (names alone may repeat)."""
        return (self.suite, self.name, normal_file(self.file), self.line)

    @property
    def score(self) -> float:
        return self.points if self.passed else 0.0

    @property
    def status(self) -> str:
        return "passed" if self.passed else "skipped" if self.skipped else "not run" if not self.ran else "failed"

    def output(self, root: Path | None = None) -> str:
        """What the student reads about this test: empty when it passed."""
        if self.passed:
            return ""
        head = [f"{_short_path(self.file, root)}:{self.line}: test case \"{self.name}\"" if self.file else "",
                "skipped by a doctest::skip() decorator" if self.skipped else "", self.note]
        return "\n".join([*filter(None, head), *(f.describe(root) for f in self.failures)])

    @staticmethod
    def from_json(data: dict[str, Any], hidden: bool = False) -> "TestResult":
        return TestResult(**{k: str(data.get(k, "")) for k in ("suite", "name", "file")},
                          **{k: bool(data.get(k, False)) for k in ("passed", "skipped", "not_implemented_only")},
                          line=int(data.get("line", 0) or 0), ran=data.get("event") == "test_case", hidden=hidden,
                          points=points_of(str(data.get("description", ""))),
                          seconds=float(data.get("seconds", 0.0) or 0.0),
                          failures=[Failure.from_json(f) for f in data.get("failures", []) or []])


def merge(listed: list[dict[str, Any]], ran: list[dict[str, Any]], hidden: bool = False,
          why_missing: str = "") -> list[TestResult]:
    """One result per listed test, in listing order. A listed test without a run record did not run (the
    program crashed, hung or was killed first): it fails with ``why_missing`` as its explanation. Run
    records that were not listed (should not happen) are kept too."""
    by_key: dict[tuple[str, str, str, int], TestResult] = {}
    for result in (TestResult.from_json(r, hidden) for r in ran if r.get("event") == "test_case"):
        by_key.setdefault(result.key, result)
    results: dict[tuple[str, str, str, int], TestResult] = {}
    for expected in (TestResult.from_json(r, hidden) for r in listed if r.get("event") == "listed"):
        if expected.key in results:
            continue
        if expected.key in by_key:
            results[expected.key] = by_key[expected.key]
            results[expected.key].points = expected.points
        else:
            expected.passed = expected.ran = False
            expected.note = f"did not run: {why_missing}" if why_missing else "did not run"
            results[expected.key] = expected
    return list(results.values()) + [r for k, r in by_key.items() if k not in results]


def normal_file(file: str) -> str:
    """A test's source path as the same key whether the compiler saw it absolute or relative to the build
    folder (ccache's base_dir makes it ``../../../tests/x.cpp``): from its ``tests/`` folder on."""
    text = file.replace("\\", "/")
    if "/tests/" in text:
        return "tests/" + text.rsplit("/tests/", 1)[1]
    if text.startswith("tests/"):
        return text
    # Elsewhere (an instructor's --hidden folder): its folder and name, however the path began.
    parts = [part for part in text.split("/") if part not in ("", ".", "..")]
    return "/".join(parts[-2:])


def _short_path(file: str, root: Path | None) -> str:
    """A source path relative to the tree's root, as a student sees the tree."""
    if root is None or not file:
        return file
    if not Path(file).is_absolute():  # relative to the build folder: ../../../tests/x.cpp
        parts = list(itertools.dropwhile(lambda part: part == "..", Path(file).parts))
        return str(Path(*parts)) if parts else file
    try:
        return str(Path(file).resolve().relative_to(root.resolve()))
    except ValueError:
        return file
