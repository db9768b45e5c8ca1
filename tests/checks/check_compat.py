#!/usr/bin/env python3
"""Checks that the grading code still fits Ubuntu 22.04, Gradescope's default image (GCC 11, CMake 3.22,
Python 3.10, doctest 2.4.8, nlohmann-json 3.10.5; docs/grading-reference.md, "Supported images"):

1. the grading reporter and the check macros compile against tools/compat/doctest-2.4.8/, the interface
   they use as doctest 2.4.8 declares it;
2. no source uses a doctest, nlohmann-json or libstdc++ facility newer than those;
3. the grading driver parses as Python 3.10 and imports no newer module;
4. no CMakeLists.txt asks for a CMake newer than 3.22.

    tests/checks/check_compat.py [--compiler c++]       exit 0 when everything fits, 1 with one line per offence
"""
from __future__ import annotations

import argparse
import ast
import re
import shutil
import subprocess
import sys
from pathlib import Path

from repo import ROOT, code_lines, cxx_sources

DOCTEST_248 = ROOT / "tools" / "compat" / "doctest-2.4.8"
SOURCE_DIRS = ("lib", "lessons", "tests", "tools", "bench", "exercises")

# (pattern, what it is, the version that added it)
NEWER_APIS = [
    (r"\bdoctest::Contains\b|\bContains\s*\(\s*\"", "doctest::Contains", "doctest 2.4.9"),
    (r"\bIsNaN\b", "doctest::IsNaN", "doctest 2.4.9"),
    (r"\bStringContains\b", "doctest::StringContains", "doctest 2.4.9"),
    (r"\bDOCTEST_CONFIG_NO_MULTITHREADING\b", "DOCTEST_CONFIG_NO_MULTITHREADING", "doctest 2.4.9"),
    (r"\bDOCTEST_CONFIG_REQUIRE_STRINGIFICATION_FOR_ALL_USED_TYPES\b", "that doctest option", "doctest 2.4.9"),
    (r"\bNLOHMANN_JSON_NAMESPACE(_BEGIN|_END)?\b", "NLOHMANN_JSON_NAMESPACE", "nlohmann-json 3.11.0"),
    (r"\bNLOHMANN_DEFINE_\w*_WITH_DEFAULT\b", "NLOHMANN_DEFINE_..._WITH_DEFAULT", "nlohmann-json 3.11.0"),
    (r"\bNLOHMANN_DEFINE_DERIVED_TYPE\w*", "NLOHMANN_DEFINE_DERIVED_TYPE", "nlohmann-json 3.12.0"),
    (r"\bpatch_inplace\b", "json::patch_inplace", "nlohmann-json 3.11.0"),
    (r"\bdefault_object_comparator_t\b", "json::default_object_comparator_t", "nlohmann-json 3.11.0"),
    (r"\bignore_trailing_commas\b", "json::parse(..., ignore_trailing_commas)", "nlohmann-json 3.12.0"),
    (r"#\s*include\s*<format>|\bstd::format\b|\bstd::vformat\b", "std::format", "GCC 13"),
    (r"#\s*include\s*<print>|\bstd::println?\b", "std::print", "GCC 14"),
    (r"#\s*include\s*<expected>|\bstd::expected\b", "std::expected", "GCC 12"),
    (r"#\s*include\s*<stacktrace>", "<stacktrace>", "GCC 12"),
    (r"\bstd::ranges::to\b", "std::ranges::to", "GCC 14"),
    (r"\bstd::(ranges::|)views::(zip|enumerate|chunk|slide|stride|cartesian_product|adjacent)\b",
     "a C++23 range view", "GCC 13"),
    (r"\bstd::ranges::(fold_left|fold_right|contains|starts_with|ends_with)\b", "a C++23 range algorithm", "GCC 13"),
    (r"\bstd::unreachable\b", "std::unreachable", "GCC 12"),
    (r"\bstd::move_only_function\b", "std::move_only_function", "GCC 12"),
    (r"\bstd::(flat_map|flat_set|mdspan)\b", "a C++23 container", "GCC 15"),
]

PYTHON_FILES = ["tools/grade", "tools/grading", "tools/common", "tests/checks/check_compat.py",
                "tests/checks/repo.py"]
NEWER_PYTHON_MODULES = {"tomllib": "3.11", "wsgiref.types": "3.11"}
NEWER_PYTHON_NAMES = [
    (r"\bdatetime\.UTC\b", "datetime.UTC", "3.11"),
    (r"\btyping\.Self\b|\bfrom typing import .*\bSelf\b", "typing.Self", "3.11"),
    (r"\bExceptionGroup\b|\bexcept\s*\*", "exception groups", "3.11"),
    (r"\bStrEnum\b", "enum.StrEnum", "3.11"),
    (r"\bhashlib\.file_digest\b", "hashlib.file_digest", "3.11"),
    (r"\bTaskGroup\b", "asyncio.TaskGroup", "3.11"),
]


def check_newer_apis() -> list[str]:
    offences = []
    for path in cxx_sources(ROOT, SOURCE_DIRS, skip=DOCTEST_248):
        for number, line in enumerate(code_lines(path), start=1):
            for pattern, what, since in NEWER_APIS:
                if re.search(pattern, line):
                    offences.append(f"{path.relative_to(ROOT)}:{number}: {what} needs {since}; "
                                    "Ubuntu 22.04 has doctest 2.4.8, nlohmann-json 3.10.5, GCC 11")
    return offences


def check_reporter(compiler: str) -> list[str]:
    if shutil.which(compiler) is None:
        return [f"{compiler}: no C++ compiler to check the reporter with"]
    offences = []
    for name in ("grade_reporter.cpp", "checks.cpp"):
        command = [compiler, "-std=c++20", "-fsyntax-only", "-Wall", "-Wextra", "-Werror",
                   f"-I{DOCTEST_248}", f"-I{ROOT / 'tests'}",  # support/*.hpp, as the build finds them
                   str(ROOT / "tests" / "support" / name)]
        completed = subprocess.run(command, capture_output=True, text=True, check=False)
        if completed.returncode != 0:
            offences.append(f"tests/support/{name} does not compile against doctest 2.4.8's interface "
                            "(tools/compat/doctest-2.4.8/):\n" + completed.stderr.strip())
    return offences


def python_files() -> list[Path]:
    files = []
    for name in PYTHON_FILES:
        path = ROOT / name
        files.extend(sorted(path.rglob("*.py")) if path.is_dir() else [path])
    return files


def check_python() -> list[str]:
    offences = []
    for path in python_files():
        text = path.read_text(encoding="utf-8")
        relative = path.relative_to(ROOT)
        try:
            tree = ast.parse(text, filename=str(relative), feature_version=(3, 10))
        except SyntaxError as error:
            offences.append(f"{relative}:{error.lineno}: not Python 3.10 syntax: {error.msg}")
            continue
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            for name in names:
                if name in NEWER_PYTHON_MODULES:
                    offences.append(f"{relative}:{node.lineno}: module {name} needs Python "
                                    f"{NEWER_PYTHON_MODULES[name]}; Ubuntu 22.04 has 3.10")
        if path == Path(__file__).resolve():
            continue  # this file names them to find them
        for number, line in enumerate(text.splitlines(), start=1):
            for pattern, what, since in NEWER_PYTHON_NAMES:
                if re.search(pattern, line.split("#", 1)[0]):
                    offences.append(f"{relative}:{number}: {what} needs Python {since}; Ubuntu 22.04 has 3.10")
    return offences


def check_cmake() -> list[str]:
    offences = []
    for path in [ROOT / "CMakeLists.txt", *sorted((ROOT / "cmake").glob("*.cmake")),
                 *sorted((ROOT / "tests").rglob("CMakeLists.txt")), *sorted((ROOT / "tools").rglob("CMakeLists.txt"))]:
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
            match = re.search(r"cmake_minimum_required\s*\(\s*VERSION\s+(\d+)\.(\d+)", line, re.I)
            if match and (int(match.group(1)), int(match.group(2))) > (3, 22):
                offences.append(f"{path.relative_to(ROOT)}:{number}: asks for CMake "
                                f"{match.group(1)}.{match.group(2)}; Ubuntu 22.04 has 3.22")
    return offences


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description="Check that grading fits Ubuntu 22.04 (Gradescope's image).")
    parser.add_argument("--compiler", default="c++", help="C++ compiler for the reporter check (default c++)")
    args = parser.parse_args(argv)
    checks = [("reporter against doctest 2.4.8", check_reporter(args.compiler)),
              ("APIs newer than Ubuntu 22.04's", check_newer_apis()),
              ("Python 3.10", check_python()),
              ("CMake 3.22", check_cmake())]
    failed = 0
    for name, offences in checks:
        print(f"{'ok      ' if not offences else 'FAILED  '} {name}")
        for offence in offences:
            print(f"  {offence}")
        failed += bool(offences)
    print(f"ubuntu 22.04 compatibility: {len(checks) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
