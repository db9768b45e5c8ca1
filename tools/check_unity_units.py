#!/usr/bin/env python3
"""Private helpers that meet in a unity unit: fails, naming both files, where they could.

    tools/check_unity_units.py --build-dir DIR [--source DIR] [--require-units]   (CTest `unity_units`)

CMakeLists.txt (`illum_unity_build`) compiles a target's sources sixteen to a unit:
DIR/unity/<target>/unit_N.cpp includes them one after another, so a helper
private to one file (in an unnamed namespace, or `static`) is visible to every
file after it in the unit. Two private helpers of one name and signature stop
the build; of one name and different signatures they compile, and overload
resolution may then hand a later file's call to the earlier file's helper, a
change of behaviour no compiler reports. This check reads the units the build
wrote and reports each private function defined at file scope in one member
that a later member of the same unit calls by its bare name (not as `x.f(`,
`p->f(` or `ns::f(`). Rename one of the two, or give the helper one home in a
header (docs/architecture.md, "Units of compilation").

Exit 0 when nothing is found, 1 otherwise, 2 on a bad argument. A build that
compiles every file alone (-DILLUM_UNITY_BUILD=OFF) has no unity/ folder and
passes, unless --require-units (what CTest passes when the build makes units)
says that units must be there: then finding none is a failure, not a pass.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_one_home import blank_comments_and_strings  # noqa: E402

SOURCE = Path(__file__).resolve().parent.parent
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
        code[member] = blank_comments_and_strings(path.read_text(encoding="utf-8"))
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
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
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
    for problem in problems:
        print(problem)
    print(f"check_unity_units: {len(units)} unit(s), {len(problems)} problem(s)",
          file=sys.stderr if problems else sys.stdout)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
