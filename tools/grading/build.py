"""Configuring and building a grading tree with CMake.

The driver keeps its own build trees (build/grade-reference,
build/grade-student) so that grading never disturbs a developer's
build/release, and it builds only the test programs it runs: the lesson
programs and the stub twins are not needed to grade.
"""
from __future__ import annotations

import os
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
