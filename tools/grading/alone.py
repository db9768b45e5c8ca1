"""`tools/grade --check-alone`: each lesson stands alone. tests/e2e/alone.cmake links tests_lessonNN_alone
and lessonNN_alone with lesson NN's units (and those its exercises/NN_*/depends.txt declares) as the
reference and every other lesson's as stubs: what a student handed out only lesson NN builds. Suite
lessonNN must pass there, and `lessonNN_alone --quick` must finish."""
from __future__ import annotations

import os
import re
import subprocess
import tempfile
from pathlib import Path

from .integrity import IntegrityReport as AloneReport  # the same report: lines checked, lines that offend
from .project import ROOT, exercise_lessons
from .runner import run_suite


def declared_dependencies(lesson: str, root: Path = ROOT, program: bool = True) -> list[str]:
    """The lessons whose units lesson `lesson` needs, from exercises/<lesson>_*/depends.txt: one line per
    lesson, `MM` (its grading tests and program need lesson MM's units) or `MM program` (only its program
    does); # starts a comment. With program=False, only what the grading tests need."""
    found: list[str] = []
    for file in sorted((root / "exercises").glob(f"{lesson}_*/depends.txt")):
        for text in (line.split("#", 1)[0].strip() for line in file.read_text(encoding="utf-8").splitlines()):
            match = re.fullmatch(r"(\d\d)(?:\s+(program))?", text)
            if text and not match:
                raise ValueError(f"{file}: '{text}' is neither \"NN\" nor \"NN program\"")
            if text and (program or not match.group(2)):
                found.append(match.group(1))
    return found


def _tests_alone(report: AloneReport, lesson: str, tests: Path, alone: str) -> None:
    run = run_suite(tests, f"lesson{lesson}")
    if run.problem:
        report.offenders.append(f"lesson{lesson}: {run.problem}")
    failed = [t for t in run.results if not t.passed and not t.skipped]
    for test in failed:
        reason = next((f.describe() for f in test.failures), test.note or test.status)
        report.offenders.append(f"lesson{lesson}: \"{test.name}\" ({test.file}:{test.line}) fails {alone}: "
                                f"{reason.splitlines()[0]}")
    if run.results and not failed and not run.problem:
        report.checked.append(f"lesson{lesson}: {len(run.results)} grading test(s) pass {alone}")


def _program_alone(report: AloneReport, lesson: str, program: Path, alone: str) -> None:
    with tempfile.TemporaryDirectory(prefix=f"illum-alone-{lesson}-") as out:
        completed = subprocess.run([str(program), "--quick", "--out", out], capture_output=True, text=True,
                                   errors="replace", check=False,
                                   env={**os.environ, "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "2")})
    if completed.returncode != 0:
        last = (completed.stderr.strip().splitlines() or ["(no message)"])[-1]
        report.offenders.append(f"lesson{lesson}: `lesson{lesson} --quick` stops {alone}: {last}")
    else:
        report.checked.append(f"lesson{lesson}: the program runs to completion {alone}")


def check_alone(build_dir: Path, root: Path = ROOT) -> AloneReport:
    report = AloneReport()
    for lesson in exercise_lessons(root):
        for folder, check, program in (("tests", _tests_alone, False), ("lessons", _program_alone, True)):
            if not any((root / folder).glob(f"{lesson}_*/*.cpp")):
                continue
            path = build_dir / "bin" / f"{'' if program else 'tests_'}lesson{lesson}_alone"
            depends = declared_dependencies(lesson, root, program)
            alone = "with only its own units" + (f" (and lesson {', '.join(depends)}'s, declared)" if depends else "")
            if path.is_file():
                check(report, lesson, path, alone)
            else:
                report.offenders.append(f"{path} is missing; build the tree first")
    return report
