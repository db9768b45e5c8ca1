"""Configuring and building a grading tree with CMake.

The driver keeps its own build trees (build/grade-reference,
build/grade-student) so that grading never disturbs a developer's
build/release, and it builds only the test programs it runs: the lesson
programs and the stub twins are not needed to grade.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence


@dataclass
class StepResult:
    ok: bool
    output: str


def run_streaming(command: Sequence[str], echo: bool = True, cwd: Path | None = None) -> StepResult:
    """Runs a command, echoing its output to stderr as it comes (a build takes
    minutes; silence would look like a hang) and keeping it for the report."""
    if echo:
        print("$ " + " ".join(command), file=sys.stderr, flush=True)
    try:
        process = subprocess.Popen(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                   text=True, errors="replace")
    except OSError as error:
        return StepResult(False, f"could not run {command[0]}: {error}")
    captured: list[str] = []
    assert process.stdout is not None
    for line in process.stdout:
        captured.append(line)
        if echo:
            sys.stderr.write(line)
            sys.stderr.flush()
    return StepResult(process.wait() == 0, "".join(captured))


def configure(source: Path, build_dir: Path, exercises: Sequence[str], hidden: Path | None,
              echo: bool = True) -> StepResult:
    """Configures a Release tree; warnings never fail a student's build.

    The reference build leaves ILLUM_WERROR as the tree has it, so that
    grading an existing preset tree (CI grades build/release) reuses its
    objects instead of rebuilding everything for a changed flag.
    """
    command = [
        "cmake", "-S", str(source), "-B", str(build_dir),
        "-DCMAKE_BUILD_TYPE=Release",
        *(["-DILLUM_WERROR=OFF"] if exercises else []),
        "-DILLUM_BUILD_TESTS=ON",
        f"-DILLUM_EXERCISES={','.join(exercises)}",
        # Always set, so that a tree configured earlier with --hidden forgets it.
        f"-DILLUM_HIDDEN_TESTS={hidden.resolve() if hidden else ''}",
    ]
    return run_streaming(command, echo)


def jobs() -> str:
    """Parallel jobs: CMAKE_BUILD_PARALLEL_LEVEL if set, else every core."""
    return os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)


def build(build_dir: Path, targets: Sequence[str], echo: bool = True) -> StepResult:
    command = ["cmake", "--build", str(build_dir), "-j", jobs()]
    if targets:
        command += ["--target", *targets]
    return run_streaming(command, echo)


# A compiler or make error line that names an exercise unit, e.g.
#   /…/exercises/01_ray_sphere/sphere.cpp:12:5: error: expected ';'
#   make[2]: *** [… CMakeFiles/illum.dir/exercises/01_ray_sphere/sphere.cpp.o] Error 1
_EXERCISE_FILE = re.compile(r"(exercises/\d\d_[^/\s:]+/[^/\s:\]]+\.cpp)")
_ERROR_LINE = re.compile(r"\berror\b|\bError \d+|undefined reference", re.I)


def failed_exercise_files(output: str) -> list[str]:
    """The exercise units (``exercises/NN_topic/name.cpp``) a failed build blames.

    Read from the lines that report an error; a unit named only in an
    "In file included from" line counts too (its include broke). Empty when
    the failure names no exercise unit (then the tree itself is broken).
    """
    blamed: set[str] = set()
    for line in output.splitlines():
        if _ERROR_LINE.search(line) or line.lstrip().startswith("In file included from"):
            blamed.update(_EXERCISE_FILE.findall(line))
    return sorted(blamed)


def error_lines_outside(output: str, files: list[str]) -> bool:
    """True when an error is reported in a source file (.cpp) other than ``files``.

    An error in a header counts as the includer's (a student's call can fail
    inside a template of a header); an error in another .cpp means the tree
    itself does not build, and then no stub can help.
    """
    for line in output.splitlines():
        match = re.match(r"\s*(\S+\.(?:cpp|cc|cxx)):\d+(?::\d+)?: (?:fatal )?error\b", line)
        if match and not any(match.group(1).endswith(f) for f in files):
            return True
    return False
