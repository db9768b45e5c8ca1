#!/usr/bin/env python3
"""Writes the student edition of illum (CMake target `student-edition`, lessons from ILLUM_HAND_OUT; the
rules are in tools/grading/edition.py).

    tools/student_edition.py                                  every exercise, into build/student-edition
    tools/student_edition.py --lessons 03 11                  lessons 03 and 11 only
    tools/student_edition.py --source . --out /tmp/edition    another source tree or folder
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from grading.edition import make_student_edition  # noqa: E402
from grading.project import normalize_lesson  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    root = Path(__file__).resolve().parent.parent
    parser.add_argument("--source", type=Path, default=root,
                        help="the instructors' tree (default: the one this tool is in)")
    parser.add_argument("--out", type=Path,
                        help="where to write the student edition (default: SOURCE/build/student-edition)")
    parser.add_argument("--lessons", nargs="*", metavar="NN",
                        help="the lessons whose exercises to hand out (default: every lesson with exercises)")
    args = parser.parse_args()
    if args.out is None:
        args.out = args.source / "build" / "student-edition"
    try:
        lessons = None
        if args.lessons:  # "03 11", "03,11", "3"
            lessons = [normalize_lesson(t) for text in args.lessons for t in text.split(",") if t.strip()]
        edition = make_student_edition(args.source, args.out, lessons)
    except ValueError as error:
        print(f"student_edition.py: {error}", file=sys.stderr)
        return 2
    for path, reason in sorted(edition.left_out.items()):
        print(f"left out {path} ({reason})")
    for note in edition.notes:
        print(f"note: {note}")
    print(f"student edition: {edition.copied} files in {edition.out}; exercises handed out: "
          f"lessons {', '.join(edition.handed_out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
