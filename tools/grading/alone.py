"""`tools/grade --check-alone`: each lesson stands alone. tests/e2e/alone.cmake links tests_lessonNN_alone
and lessonNN_alone with lesson NN's units (and those its exercises/NN_*/depends.txt declares) as the
reference and every other lesson's as stubs: what a student handed out only lesson NN builds. Suite
lessonNN must pass there, and `lessonNN_alone --quick` must finish."""
from __future__ import annotations

import os
import re
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from .project import ROOT, exercise_lessons
from .runner import run_suite

_TESTS = re.compile(r"tests_lesson(\d\d)_alone")
_PROGRAM = re.compile(r"lesson(\d\d)_alone")


@dataclass
class AloneReport:
    checked: list[str] = field(default_factory=list)
    offenders: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.offenders and bool(self.checked)


def declared_dependencies(lesson: str, root: Path = ROOT, program: bool = True) -> list[str]:
    """The lessons whose units lesson ``lesson`` needs, from ``exercises/<lesson>_*/depends.txt``.

    One line per lesson: ``MM`` (its grading tests and its program need lesson
    MM's units) or ``MM program`` (only its program does); ``#`` starts a
    comment. With ``program=False``, only what the grading tests need."""
    found: list[str] = []
    for file in sorted((root / "exercises").glob(f"{lesson}_*/depends.txt")):
        for line in file.read_text(encoding="utf-8").splitlines():
            text = line.split("#", 1)[0].strip()
            if not text:
                continue
            match = re.fullmatch(r"(\d\d)(?:\s+(program))?", text)
            if not match:
                raise ValueError(f"{file}: '{text}' is neither \"NN\" nor \"NN program\"")
            if program or not match.group(2):
                found.append(match.group(1))
    return found


def check_alone(build_dir: Path, root: Path = ROOT) -> AloneReport:
    report = AloneReport()
    bin_dir = build_dir / "bin"
    for lesson in exercise_lessons(root):
        tests = bin_dir / f"tests_lesson{lesson}_alone"
        program = bin_dir / f"lesson{lesson}_alone"
        depends = declared_dependencies(lesson, root, program=False)
        alone = "with only its own units" + (f" (and lesson {', '.join(depends)}'s, declared)" if depends else "")
        if any((root / "tests").glob(f"{lesson}_*/*.cpp")):
            if not tests.is_file():
                report.offenders.append(f"{tests} is missing; build the tree first")
            else:
                run = run_suite(tests, f"lesson{lesson}")
                if run.problem:
                    report.offenders.append(f"lesson{lesson}: {run.problem}")
                failed = [t for t in run.results if not t.passed and not t.skipped]
                for test in failed:
                    reason = next((f.describe() for f in test.failures), test.note or test.status)
                    report.offenders.append(
                        f"lesson{lesson}: \"{test.name}\" ({test.file}:{test.line}) fails {alone}: "
                        f"{reason.splitlines()[0]}")
                if run.results and not failed and not run.problem:
                    report.checked.append(f"lesson{lesson}: {len(run.results)} grading test(s) pass {alone}")
        depends = declared_dependencies(lesson, root, program=True)
        alone = "with only its own units" + (f" (and lesson {', '.join(depends)}'s, declared)" if depends else "")
        if any((root / "lessons").glob(f"{lesson}_*/*.cpp")):
            if not program.is_file():
                report.offenders.append(f"{program} is missing; build the tree first")
                continue
            with tempfile.TemporaryDirectory(prefix=f"illum-alone-{lesson}-") as out:
                completed = subprocess.run([str(program), "--quick", "--out", out], capture_output=True,
                                           text=True, errors="replace", check=False,
                                           env={**os.environ, "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "2")})
            if completed.returncode != 0:
                last = (completed.stderr.strip().splitlines() or ["(no message)"])[-1]
                report.offenders.append(f"lesson{lesson}: `lesson{lesson} --quick` stops {alone}: {last}")
            else:
                report.checked.append(f"lesson{lesson}: the program runs to completion {alone}")
    return report
