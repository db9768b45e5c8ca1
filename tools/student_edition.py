#!/usr/bin/env python3
"""Writes the student edition of illum: the tracked tree without the reference
sources of exercise units and without hidden tests (CMake target
``student-edition``; the rules are in tools/grading/edition.py)."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from grading.edition import make_student_edition  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--source", type=Path, required=True, help="the instructors' tree")
    parser.add_argument("--out", type=Path, required=True, help="where to write the student edition")
    args = parser.parse_args()
    try:
        edition = make_student_edition(args.source, args.out)
    except ValueError as error:
        print(f"student_edition.py: {error}", file=sys.stderr)
        return 2
    for path, reason in sorted(edition.left_out.items()):
        print(f"left out {path} ({reason})")
    print(f"student edition: {edition.copied} files in {edition.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
