#!/usr/bin/env python3
"""One home per helper: fails, with file:line, where C++ code rebuilds one by hand.

    tools/check_one_home.py [--root DIR]      (CTest `one_home`)

CONTRIBUTING.md ("Library code") names the one home of each shared piece;
this check keeps the code to its word. It reads the C++ sources of lib/,
lessons/, tests/, bench/ and tools/ (comments and string literals blanked
first, so prose may name what code must not do) and reports:

* a hand-written best-of-N timing loop (a loop counter named repeat, run,
  rep or attempt around a timing, or the minimum of a stopwatch
  reading) outside core/stopwatch.hpp: use best_seconds or
  best_nanoseconds_per_call;
* π typed in (3.14159…, M_PI, acos(-1)) or a variable `pi` defined as a copy
  of it: write `using std::numbers::pi;`;
* any call of the OpenMP runtime (omp_…) or `#include <omp.h>` outside
  core/threads.hpp: use available_threads(), thread_index(),
  ScopedThreadCount, … (the one header through which OpenMP can be made
  optional);
* a second definition of a helper that has a home (HOMES below);
* in lib/, lessons/ and tools/ (the code every student's machine compiles):
  a compiler extension (__builtin_…, __attribute__, GNU asm, __int128) or an
  operating system's header or call (<unistd.h>, <sys/…>, clock_gettime,
  isatty, sysconf, std::aligned_alloc, …) outside core/platform, the POSIX
  files and the production code that guards its own (PLATFORM_HOMES below):
  use core/platform.hpp, whose functions have a fallback everywhere.

Exit 0 when nothing is found, 1 otherwise.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FOLDERS = ("lib", "lessons", "tests", "bench", "tools")
SUFFIXES = {".cpp", ".hpp", ".h", ".cc"}

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
COMPILER_HOMES = ("lib/illum/core/platform.hpp", "lib/illum/core/stopwatch.hpp",
                  "lib/illum/accel/production/compact_bvh.cpp", "lib/illum/radiosity/form_factor_quadrature.cpp")
SYSTEM_HOMES = ("lib/illum/core/platform.cpp", "lib/illum/core/atomic_file.cpp", "lib/illum/core/child_process.cpp",
                "lib/illum/core/input_file.cpp", "lib/illum/core/memory_budget.cpp", "lib/illum/core/huge_pages.cpp")
PLATFORM_RULES: list[tuple[re.Pattern[str], str, tuple[str, ...]]] = [
    (re.compile(r"\b__builtin_\w+|\b__attribute__\b|\basm\s+volatile\b|\b__asm__\b|\b__int128\b|\b__float128\b"
                r"|\b__extension__\b|\b__declspec\b"),
     "a compiler extension: use standard C++ (<bit>: std::countr_zero, std::popcount) or a macro of "
     "core/platform.hpp (ILLUM_FLATTEN)", COMPILER_HOMES),
    (re.compile(r"#\s*include\s*<(?:unistd|fcntl|dirent|spawn|poll|windows|io|signal)\.h>|#\s*include\s*<sys/"
                r"|\b(?:clock_gettime|isatty|_isatty|sysconf|aligned_alloc|getrandom|getentropy|syscall)\s*\("),
     "a call or header of one operating system: use core/platform.hpp (thread_cpu_seconds, "
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


def blank_comments_and_strings(text: str) -> str:
    """The text with every comment and string or character literal replaced by spaces
    (newlines kept, so line numbers hold); `#include <…>` is code and stays."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j == -1 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j == -1 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"' and i > 0 and text[i - 1] == "R" and re.match(r'"([^(\s]{0,16})\(', text[i:]):
            delimiter = re.match(r'"([^(\s]{0,16})\(', text[i:]).group(1)
            j = text.find(")" + delimiter + '"', i)
            j = n if j == -1 else j + len(delimiter) + 2
            out.append('"' + re.sub(r"[^\n]", " ", text[i + 1:j - 1]) + '"')
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator: 1'000
                out.append(c)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * max(0, j - i - 2) + (c if j - i >= 2 else ""))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def sources(root: Path) -> list[Path]:
    found = []
    for folder in FOLDERS:
        base = root / folder
        if base.is_dir():
            found += [p for p in base.rglob("*") if p.suffix in SUFFIXES and p.is_file()
                      and "node_modules" not in p.parts]
    return sorted(found)


def problems_in(path: Path, root: Path) -> list[str]:
    relative = path.relative_to(root).as_posix()
    text = path.read_text(encoding="utf-8", errors="replace")
    code = blank_comments_and_strings(text)
    found = []
    lines = code.splitlines()
    for number, line in enumerate(lines, start=1):
        for pattern, problem, allowed in RULES:
            if relative in allowed:
                continue
            # The include is checked on the raw line (the blanking keeps <omp.h>, but be sure).
            if pattern.search(line):
                # A loop counter named `attempt` or `run` is a best-of loop only when it times
                # something: a retry loop (a temporary name, a lock) is not one.
                if pattern is BEST_OF_LOOP and not TIMING.search("\n".join(lines[number - 1:number + 12])):
                    continue
                found.append(f"{relative}:{number}: {problem}")
        if relative.startswith(PLATFORM_FOLDERS):
            for pattern, problem, allowed in PLATFORM_RULES:
                if relative not in allowed and pattern.search(line):
                    found.append(f"{relative}:{number}: {problem}")
        for pattern, home in HOMES:
            if relative.startswith(home + ".") or not pattern.search(line):
                continue
            # A declaration or definition at the start of a statement, not a call.
            found.append(f"{relative}:{number}: a second definition of a helper whose home is {home}.hpp")
    return found


def problems_found(root: Path) -> list[str]:
    root = root.resolve()
    return [p for path in sources(root) for p in problems_in(path, root)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", type=Path, default=ROOT, help="the source tree (default: this checkout)")
    args = parser.parse_args(argv)
    problems = problems_found(args.root)
    for problem in problems:
        print(problem)
    print("one home: " + ("every helper in its home" if not problems else f"FAILED ({len(problems)} problem(s))"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
