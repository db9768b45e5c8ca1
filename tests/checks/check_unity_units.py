#!/usr/bin/env python3
"""Private helpers that meet in a unity unit: fails, naming both files, where they could.

    tests/checks/check_unity_units.py --build-dir DIR [--source DIR] [--require-units]   (CTest `unity_units`)

The build compiles a target's sources sixteen to a unit (DIR/unity/<target>/unit_N.cpp), so a helper
private to one file (an unnamed namespace, `static`) is visible to the files after it, where overload
resolution may quietly pick it (docs/architecture.md, "Units of compilation"). Reports each private
function of a member that a later member of its unit calls by its bare name. Exit 0 when nothing is
found, 1 otherwise (or when --require-units finds no unit), 2 on a bad argument.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from repo import ROOT as SOURCE, blank_comments, report

MEMBER = re.compile(r'^#include "([^"]+)"', re.M)
# A function's head at column 0: a return type, then the name and its opening parenthesis.
HEAD = re.compile(r"^(?!(?:return|if|for|while|switch|using|namespace|struct|class|enum|union|template|typedef)\b)"
                  r"[A-Za-z_][\w:<>,*&\s]*?[\s*&>](\w+)\s*\(")
KEYWORDS = {"return", "co_return", "else", "case", "throw", "do", "co_await", "co_yield", "new", "delete"}


def private_functions(code: str) -> set[str]:
    """Names of the functions a file defines at file scope with internal linkage: at column 0 inside
    `namespace {` … `}  // namespace`, or starting with `static`; a definition's head reaches `{`
    before `;`."""
    names: set[str] = set()
    unnamed = 0
    lines = code.split("\n")
    for i, line in enumerate(lines):
        if re.match(r"^namespace\s*\{", line):
            unnamed += 1
            continue
        if unnamed and re.match(r"^\}\s*(?://.*)?$", line):
            unnamed -= 1
            continue
        if not (unnamed or line.startswith("static ")):
            continue
        head = HEAD.match(line)
        if not head:
            continue
        rest = "\n".join(lines[i:i + 12])[head.end():]
        brace, semicolon = rest.find("{"), rest.find(";")
        if brace != -1 and (semicolon == -1 or brace < semicolon):
            names.add(head.group(1))
    return names


def bare_calls(code: str, name: str) -> list[int]:
    """Line numbers where `name(` is called unqualified: not a member, not qualified, not declared
    (a type name before it, as in `Point3 mean(0.0);`)."""
    found = []
    for m in re.finditer(r"(?<![\w.:>])" + re.escape(name) + r"\s*\(", code):
        before = code[:m.start()].rstrip()
        if before.endswith("->"):
            continue
        word = re.search(r"(\w+)$", before)
        if word and word.group(1) not in KEYWORDS and not before.endswith((")", "]")):
            continue  # a declaration: `Type name(`
        found.append(code.count("\n", 0, m.start()) + 1)
    return found


def problems_in_unit(unit: Path, source: Path) -> list[str]:
    members = MEMBER.findall(unit.read_text(encoding="utf-8"))
    code = {}
    for member in members:
        path = source / member
        if not path.is_file():
            return [f"{unit}: includes {member}, which is not a file under {source}"]
        code[member] = blank_comments(path.read_text(encoding="utf-8"))
    problems = []
    for i, earlier in enumerate(members):
        for name in sorted(private_functions(code[earlier])):
            for later in members[i + 1:]:
                for line in bare_calls(code[later], name):
                    problems.append(f"{later}:{line}: calls {name}(…), and {earlier}, before it in "
                                    f"{unit.parent.name}/{unit.name}, defines a private {name}: rename one "
                                    "or give it one home in a header")
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", type=Path, required=True, help="a configured build folder")
    parser.add_argument("--source", type=Path, default=SOURCE, help="the source tree (default: this checkout)")
    parser.add_argument("--require-units", action="store_true",
                        help="fail when DIR/unity/ holds no unit (the build was configured to make them)")
    args = parser.parse_args(argv)
    if not args.build_dir.is_dir():
        print(f"check_unity_units: --build-dir {args.build_dir}: not a folder", file=sys.stderr)
        return 2
    units = sorted((args.build_dir / "unity").glob("*/unit_*.cpp"))
    if args.require_units and not units:
        print(f"check_unity_units: no unit in {args.build_dir / 'unity'}, though the build makes them "
              "(ILLUM_UNITY_BUILD=ON): configure it first, or check illum_unity_build in CMakeLists.txt",
              file=sys.stderr)
        return 1
    problems = [p for unit in units for p in problems_in_unit(unit, args.source.resolve())]
    return report(problems, f"check_unity_units: {len(units)} unit(s)", "no private helper meets a bare call")


if __name__ == "__main__":
    sys.exit(main())
