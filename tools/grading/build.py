"""Configuring and building a grading tree with CMake, and blaming a failed build on the student's files.
The reference is graded in build/grade-reference, a student's code in build/student (the preset's), the
autograder's in build/grade-student; only the test programs graded are built."""
from __future__ import annotations

import os
import re
import subprocess
import sys
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from .sandbox import kill_group

# A build's output is kept up to HEAD_BYTES from its start (the first error is what matters) and
# TAIL_BYTES from its end; a student's file can make a compiler print without end.
HEAD_BYTES = 256 * 1024
TAIL_BYTES = 64 * 1024
# A compiler or make error line that names an exercise unit, e.g.
#   /…/exercises/01_ray_sphere/sphere.cpp:12:5: error: expected ';'
#   make[2]: *** [… CMakeFiles/illum.dir/exercises/01_ray_sphere/sphere.cpp.o] Error 1
_EXERCISE_FILE = re.compile(r"(exercises/\d\d_[^/\s:]+/[^/\s:\]]+\.cpp)")
_ERROR_LINE = re.compile(r"\berror\b|\bError \d+|undefined reference", re.I)
# The linker names an archive member as libillum.a(sphere.cpp.o), an object by its path.
_MEMBER = re.compile(r"\(([^()\s]+\.cpp)\.o\)|/([^/\s:()]+\.cpp)\.o\b")
_UNDEFINED = re.compile(r"undefined reference to [`'‘]([^'’]+)['’]")


@dataclass
class StepResult:
    ok: bool
    output: str
    timed_out: bool = False


@dataclass
class Runner:
    """How build commands run: as the grader (default), or as the sandbox's user, with a time limit."""

    preexec: object = None
    env: dict | None = None
    timeout: float | None = None


def build_timeout_from_environment() -> float | None:
    value = os.environ.get("ILLUM_GRADE_BUILD_TIMEOUT", "").strip()
    return float(value) if value else None


def _head_and_tail(stream, echo: bool) -> tuple[bytearray, bytearray, int]:
    """The first HEAD_BYTES and the last TAIL_BYTES of a stream, and its length; the head echoed to stderr."""
    head, tail, total = bytearray(), bytearray(), 0
    while chunk := stream.read1(1 << 16):
        total += len(chunk)
        if len(head) < HEAD_BYTES:
            room = HEAD_BYTES - len(head)
            head += chunk[:room]
            if echo:
                print(chunk[:room].decode("utf-8", errors="replace"), end="", file=sys.stderr, flush=True)
            chunk = chunk[room:]
        tail += chunk
        del tail[:max(0, len(tail) - TAIL_BYTES)]
    return head, tail, total


def run_streaming(command: Sequence[str], echo: bool = True, cwd: Path | None = None,
                  runner: Runner | None = None) -> StepResult:
    """Runs a command, echoing its output to stderr as it comes (a build takes minutes; silence would look
    like a hang) and keeping its head and tail for the report."""
    runner = runner or Runner()
    if echo:
        print("$ " + " ".join(command), file=sys.stderr, flush=True)
    try:
        process = subprocess.Popen(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                   stdin=subprocess.DEVNULL, env=runner.env, preexec_fn=runner.preexec,
                                   start_new_session=runner.preexec is None)
    except OSError as error:
        return StepResult(False, f"could not run {command[0]}: {error}")
    timed_out = threading.Event()
    timer = threading.Timer(runner.timeout or 0, lambda: (timed_out.set(), kill_group(process.pid)))
    timer.daemon = True
    if runner.timeout:
        timer.start()
    head, tail, total = _head_and_tail(process.stdout, echo)
    status = process.wait()
    timer.cancel()
    kill_group(process.pid)  # whatever the build left behind
    text = head.decode("utf-8", errors="replace")
    if total - len(head) - len(tail) > 0:
        text += f"\n[... {total - len(head) - len(tail)} bytes of build output cut ...]\n"
        if echo:
            print(f"\n[... build output cut; {total} bytes in all ...]", file=sys.stderr, flush=True)
    text += tail.decode("utf-8", errors="replace")
    if timed_out.is_set():
        text += (f"\nthe build did not finish within {runner.timeout:g} s, the time limit of a build "
                 "(ILLUM_GRADE_BUILD_TIMEOUT), and was stopped\n")
    return StepResult(status == 0 and not timed_out.is_set(), text, timed_out.is_set())


def configure(source: Path, build_dir: Path, exercises: Sequence[str], hidden: Path | None,
              hidden_objects: Sequence[Path] = (), runner: Runner | None = None) -> StepResult:
    """Configures a Release tree; warnings never fail a student's build. The reference build leaves
    ILLUM_WERROR as the tree has it, so that grading an existing preset tree (CI grades build/release)
    reuses its objects instead of rebuilding everything for a changed flag."""
    command = ["cmake", "-S", str(source), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
               *(["-DILLUM_WERROR=OFF"] if exercises else []), "-DILLUM_BUILD_TESTS=ON",
               f"-DILLUM_EXERCISES={','.join(exercises)}",
               # Always set, so that a tree configured earlier with --hidden forgets it.
               f"-DILLUM_HIDDEN_TESTS={hidden.resolve() if hidden else ''}",
               f"-DILLUM_HIDDEN_OBJECTS={';'.join(str(p) for p in hidden_objects)}"]
    # Already configured from `source` with every -D value of `command` (its CMakeCache.txt says so): make re-runs
    # CMake itself if a CMakeLists.txt changed, so configuring again would only cost time (each submission of an
    # autograder run starts here).
    try:
        cache = (build_dir / "CMakeCache.txt").read_text(encoding="utf-8", errors="replace")
    except OSError:
        cache = ""
    values = dict(re.findall(r"^([A-Za-z_][A-Za-z0-9_]*):[A-Z]+=(.*)$", cache, re.M))
    wanted = [(name.partition(":")[0], value) for name, _, value in (a[2:].partition("=") for a in command
                                                                       if a.startswith("-D"))]
    if (build_dir / "Makefile").is_file() and values.get("CMAKE_HOME_DIRECTORY") == str(source.resolve()) and all(
            values.get(name) == value for name, value in wanted):
        return StepResult(True, "")
    return run_streaming(command, runner=runner)


def build(build_dir: Path, targets: Sequence[str], runner: Runner | None = None) -> StepResult:
    """Builds ``targets`` (all when empty) with CMAKE_BUILD_PARALLEL_LEVEL jobs if set, else one per core."""
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
    return run_streaming(["cmake", "--build", str(build_dir), "-j", jobs, *(["--target", *targets] if targets else [])],
                         runner=runner)


def failed_exercise_files(output: str) -> list[str]:
    """The exercise units (``exercises/NN_topic/name.cpp``) a failed build blames, read from the lines that
    report an error; a unit named only in an "In file included from" line counts too (its include broke).
    Empty when the failure names no exercise unit (then the tree itself is broken)."""
    return sorted({unit for line in output.splitlines()
                   if _ERROR_LINE.search(line) or line.lstrip().startswith("In file included from")
                   for unit in _EXERCISE_FILE.findall(line)})


def linker_blames(output: str, units: dict[str, str], symbol_units: dict[str, str] | None = None) -> list[str]:
    """The exercise units (``exercises/NN_topic/name.cpp``) a failed link blames. ``units``: file name ->
    exercise path of the units that hold the student's code. A "multiple definition" names the objects that
    define the symbol twice; an "undefined reference" is blamed on the object that makes it when that is a
    student's, else on the unit whose stub defines the symbol (``symbol_units``, demangled name -> path)."""
    blamed: set[str] = set()
    lines = output.splitlines()
    for before, line in zip(["", *lines], lines):
        # The line names the second definition or the reference; the line before ("in function") or the
        # same one the first definition or the object that makes the reference.
        context = line + " " + before
        members = [units[name] for m in _MEMBER.findall(context) if (name := m[0] or m[1]) in units]
        if "multiple definition of" in line:
            blamed.update(members)
        if undefined := _UNDEFINED.search(line):
            mine = members + [units[m] for m in re.findall(r"^([^\s:()]+\.cpp):\(", line) if m in units]
            if mine:
                blamed.update(mine)
            elif symbol_units:
                symbol = undefined.group(1)
                blamed.update(filter(None, [symbol_units.get(symbol) or symbol_units.get(symbol.split("(", 1)[0])]))
    return sorted(blamed)


def error_lines_outside(output: str, files: list[str]) -> bool:
    """True when an error is reported in a source file (.cpp) other than ``files``. An error in a header
    counts as the includer's (a student's call can fail inside a template of a header); an error in another
    .cpp means the tree itself does not build, and then no stub can help."""
    errors = (re.match(r"\s*(\S+\.(?:cpp|cc|cxx)):\d+(?::\d+)?: (?:fatal )?error\b", line)
              for line in output.splitlines())
    return any(match and not any(match.group(1).endswith(f) for f in files) for match in errors)
