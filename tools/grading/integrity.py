"""The grading integrity check (docs/grading.md, "Integrity"): grading tests are tested, not assumed. Each
suite lessonNN of a built tree's tests_lessonNN (and of tests_hidden) has a test, passes on the reference,
fails on the `_stubs` build with NotImplemented only (a test failing there for another reason would also
fail a correct student, or pass a wrong one), and lives in its own lesson's program. Where the tree has the
observer builds, the same holds for the judge's verdicts (docs/grading-defences.md)."""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from .results import TestResult
from .runner import judge_suite, list_suites, run_suite, witness_checks

_PROGRAM = re.compile(r"tests_lesson(\d\d)")


@dataclass
class IntegrityReport:
    checked: list[str] = field(default_factory=list)    # one line per suite that is fine
    offenders: list[str] = field(default_factory=list)  # one line per problem

    @property
    def ok(self) -> bool:
        return not self.offenders and bool(self.checked)


def grading_programs(bin_dir: Path) -> dict[str, Path]:
    """lesson -> tests_lessonNN program found in a build's bin/."""
    return {match.group(1): path for path in (sorted(bin_dir.iterdir()) if bin_dir.is_dir() else [])
            if (match := _PROGRAM.fullmatch(path.name)) and path.is_file()}


def check_pair(label: str, reference: list[TestResult], stubs: list[TestResult]) -> list[str]:
    """The problems of one suite, given its results on the reference and on the stubs."""
    problems = []
    if not reference:
        problems.append(f"{label}: the suite has no test; every lesson needs at least one grading test")
    stub_by_key = {t.key: t for t in stubs}
    for test in reference:
        if not test.passed:
            reason = test.output().splitlines()[1:2] or [test.status]
            problems.append(f"{label}: \"{test.name}\" ({test.file}:{test.line}) does not pass on the reference: "
                            f"{reason[0].strip()}")
    for test in reference:
        stub = stub_by_key.get(test.key)
        if stub is None:
            problems.append(f"{label}: \"{test.name}\" did not report on the stubs")
        elif stub.passed:
            problems.append(f"{label}: \"{test.name}\" ({test.file}:{test.line}) PASSES on the stubs: "
                            "it must call into an exercise unit")
        elif not stub.not_implemented_only:
            detail = next((f.describe() for f in stub.failures if not f.not_implemented), stub.note or stub.status)
            problems.append(f"{label}: \"{test.name}\" ({test.file}:{test.line}) fails on the stubs for a reason "
                            f"other than NotImplemented: {detail.splitlines()[0]}")
    return problems


def judged_pair(witness_program: Path, suite: str, hidden: bool = False) -> tuple[str, list[str]]:
    """The same rules for the judge's verdicts: the reference's observer and the stubs' observer,
    each judged against the witness. ('' and no problem when the tree has no observer builds.)"""
    observer = witness_program.with_name(witness_program.name + "_observer")
    observer_stubs = witness_program.with_name(witness_program.name + "_observer_stubs")
    if not (observer.is_file() and observer_stubs.is_file()):
        return "", []
    witness = run_suite(witness_program, suite, hidden=hidden, role="witness")
    checks = witness_checks(witness)
    runs = [run_suite(program, suite, hidden=hidden, expected=witness.listed, role="observer")
            for program in (observer, observer_stubs)]
    problems = [f"{suite}: {r.problem}" for r in [witness, *runs] if r.problem]
    for run in runs:
        problems += [f"{suite}: {p}" for p in judge_suite(run, checks, hidden)]
    problems += check_pair(f"{observer.name} [{suite}], judged", runs[0].results, runs[1].results)
    return f"{suite}: {len(runs[0].results)} test(s) judged the same way outside the programs", problems


def _check_suite(report: IntegrityReport, program: Path, suite: str, hidden: bool = False,
                 misplaced: list[str] | None = None) -> None:
    """One suite of ``program`` on the reference and on its ``_stubs`` build, and judged (judged_pair)."""
    reference, stubs = run_suite(program, suite), run_suite(program.with_name(program.name + "_stubs"), suite)
    problems = [f"{suite}: {run.problem}" for run in (reference, stubs) if run.problem]
    problems += check_pair(f"{program.name} [{suite}]", reference.results, stubs.results) + (misplaced or [])
    judged, judged_problems = judged_pair(program, suite, hidden)
    report.offenders.extend(problems + judged_problems)
    if not problems and not (hidden and judged_problems):
        report.checked.append(f"{suite}{' (hidden)' if hidden else ''}: {len(reference.results)} "
                              f"{'test(s)' if hidden else 'grading test(s)'} pass on the reference and fail on the "
                              "stubs with NotImplemented")
    if judged and not judged_problems and not hidden:
        report.checked.append(judged)


def check_build(build_dir: Path) -> IntegrityReport:
    """Runs the integrity check on every grading program of a built tree."""
    report = IntegrityReport()
    bin_dir = build_dir / "bin"
    programs = grading_programs(bin_dir)
    if not programs:
        report.offenders.append(f"no tests_lessonNN program in {bin_dir}; build the tree first")
        return report
    for lesson, program in programs.items():
        misplaced = [f"{program.name}: \"{test.name}\" ({test.file}:{test.line}) is in suite {test.suite}, which "
                     f"this program never grades; move it to tests/{test.lesson}_*/"
                     for test in list_suites(program) if test.lesson and test.lesson != lesson]
        _check_suite(report, program, f"lesson{lesson}", misplaced=misplaced)
    hidden = bin_dir / "tests_hidden"
    if hidden.is_file() and not (bin_dir / "tests_hidden_stubs").is_file():
        report.offenders.append("tests_hidden exists but tests_hidden_stubs does not; build it")
    elif hidden.is_file():
        for lesson in sorted({t.lesson for t in list_suites(hidden) if t.lesson}):
            _check_suite(report, hidden, f"lesson{lesson}", hidden=True)
    return report
