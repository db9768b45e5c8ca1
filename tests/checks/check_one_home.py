#!/usr/bin/env python3
"""One home per helper: fails, with file:line, where C++ code rebuilds one by hand (CTest `one_home`).

    tests/checks/check_one_home.py [--root DIR]

Reads the C++ sources of lib/, lessons/, tests/, bench/ and tools/ (comments and strings blanked, so
prose may name what code must not do) and reports a hand-written best-of-N timing loop, π typed in,
OpenMP called outside core/threads.hpp, a second definition of a helper of HOMES, and, in the code every
student's machine compiles, a compiler extension or an operating system's call outside PLATFORM_HOMES
(CONTRIBUTING.md, "Library code"). Exit 0 when nothing is found, 1 otherwise.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from repo import ROOT, code_lines, cxx_sources, report

FOLDERS = ("lib", "lessons", "tests", "bench", "tools")

THREADS_HOME = "lib/illum/core/threads.hpp"
STOPWATCH_HOME = "lib/illum/core/stopwatch.hpp"

BEST_OF_LOOP = re.compile(r"\bfor\s*\(\s*(?:int|std::size_t|auto)\s+(?:repeat|repeats|run|rep|attempt)\s*=")
# What makes such a loop a timing loop: a stopwatch or a clock read within its first lines.
TIMING = re.compile(r"\bStopwatch\b|\.seconds\s*\(|\bsteady_clock\b|\bhigh_resolution_clock\b|\bclock_gettime\b")

# (pattern, problem, files allowed to match); patterns run on code with comments and strings blanked.
RULES: list[tuple[re.Pattern[str], str, tuple[str, ...]]] = [
    (BEST_OF_LOOP,
     "a hand-written best-of-N loop: time it with best_seconds or best_nanoseconds_per_call "
     "(core/stopwatch.hpp)", (STOPWATCH_HOME,)),
    (re.compile(r"std::min\s*\([^;]*\.seconds\s*\(\s*\)"),
     "the minimum of stopwatch readings taken by hand: use best_seconds or best_nanoseconds_per_call "
     "(core/stopwatch.hpp)", (STOPWATCH_HOME,)),
    (re.compile(r"\b3\.14159|\bM_PI\b|\bacos\s*\(\s*-\s*1(?:\.0*)?\s*\)"),
     "π typed in: write `using std::numbers::pi;`", ()),
    (re.compile(r"\bpi\s*=\s*(?:[\w:]*::pi\b|[-+]?\d|(?:std::)?acos\b)"),
     "a copy of π: write `using std::numbers::pi;`", ()),
    (re.compile(r"\bomp_\w+\s*\("),
     "a call of the OpenMP runtime: use the functions of core/threads.hpp "
     "(available_threads, thread_index, team_size, processor_count, ScopedThreadCount)", (THREADS_HOME,)),
    (re.compile(r"#\s*include\s*<omp\.h>"),
     "OpenMP's header included: include illum/core/threads.hpp, its one home", (THREADS_HOME,)),
]

# What differs between compilers and systems, and the files allowed to hold it (each guards it
# with a fallback, or is POSIX by design: docs/architecture.md, "Platforms").
PLATFORM_FOLDERS = ("lib/", "lessons/", "tools/")
COMPILER_HOMES = ("lib/illum/system/platform.hpp", "lib/illum/core/stopwatch.hpp",
                  "lib/illum/accel/production/compact_bvh.cpp", "lib/illum/radiosity/form_factor_quadrature.cpp")
SYSTEM_HOMES = ("lib/illum/system/platform.cpp", "lib/illum/system/atomic_file.cpp",
                "lib/illum/system/child_process.cpp", "lib/illum/system/input_file.cpp",
                "lib/illum/system/memory_budget.cpp", "lib/illum/system/huge_pages.cpp",
                # the lab's reference child: a second lab kept running beside the first (fork, a pipe for
                # its port, PR_SET_PDEATHSIG), which child_process's run-to-the-end call does not do
                "tools/lab/lab_reference.cpp", "tools/lab/lab_reference.hpp")
PLATFORM_RULES: list[tuple[re.Pattern[str], str, tuple[str, ...]]] = [
    (re.compile(r"\b__builtin_\w+|\b__attribute__\b|\basm\s+volatile\b|\b__asm__\b|\b__int128\b|\b__float128\b"
                r"|\b__extension__\b|\b__declspec\b"),
     "a compiler extension: use standard C++ (<bit>: std::countr_zero, std::popcount) or a macro of "
     "system/platform.hpp (ILLUM_FLATTEN)", COMPILER_HOMES),
    (re.compile(r"#\s*include\s*<(?:unistd|fcntl|dirent|spawn|poll|windows|io|signal)\.h>|#\s*include\s*<sys/"
                r"|\b(?:clock_gettime|isatty|_isatty|sysconf|aligned_alloc|getrandom|getentropy|syscall)\s*\("),
     "a call or header of one operating system: use system/platform.hpp (thread_cpu_seconds, "
     "stderr_is_terminal, physical_memory_bytes, random_bytes), aligned operator new or std::filesystem",
     SYSTEM_HOMES),
]

# Helpers with a home: a definition anywhere else is a second copy.
HOMES: list[tuple[re.Pattern[str], str]] = [
    (re.compile(r"\bdouble\s+log_log_slope\s*\("), "lib/illum/core/log_log_fit"),
    (re.compile(r"\bstd::string\s+fixed\s*\(\s*double"), "lessons/support/lesson_support"),
    (re.compile(r"\bImage\s+side_by_side\s*\("), "lessons/support/lesson_support"),
    (re.compile(r"\b(?:double|ImageDifference)\s+(?:rms_difference|image_error|image_difference)\s*\("),
     "lessons/support/lesson_support"),
    (re.compile(r"\bstruct\s+(?:TangentFrame|Frame)\b"), "lib/illum/core/frame"),
    (re.compile(r"\bclass\s+ScopedThreadCount\b"), "lib/illum/core/threads"),
]


def problems_in(path: Path, root: Path) -> list[str]:
    relative = path.relative_to(root).as_posix()
    lines = code_lines(path)
    rules = RULES + (PLATFORM_RULES if relative.startswith(PLATFORM_FOLDERS) else [])
    rules += [(pattern, f"a second definition of a helper whose home is {home}.hpp", ())
              for pattern, home in HOMES if not relative.startswith(home + ".")]
    found = []
    for number, line in enumerate(lines, start=1):
        for pattern, problem, allowed in rules:
            # A loop counter named `attempt` or `run` makes a best-of loop only when the loop times something.
            if relative not in allowed and pattern.search(line) and not (
                    pattern is BEST_OF_LOOP and not TIMING.search("\n".join(lines[number - 1:number + 12]))):
                found.append(f"{relative}:{number}: {problem}")
    return found


def problems_found(root: Path) -> list[str]:
    root = root.resolve()
    return [p for path in cxx_sources(root, FOLDERS) for p in problems_in(path, root)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", type=Path, default=ROOT, help="the source tree (default: this checkout)")
    args = parser.parse_args(argv)
    return report(problems_found(args.root), "one home", "every helper in its home")


if __name__ == "__main__":
    sys.exit(main())
