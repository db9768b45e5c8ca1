#!/usr/bin/env python3
"""Writes the student edition of illum (CMake target `student-edition`, lessons from ILLUM_HAND_OUT; the
rules are in tools/grading/edition.py).

    tools/student_edition.py                                  every exercise, into build/student-edition
    tools/student_edition.py --lessons 03 11                  lessons 03 and 11 only
    tools/student_edition.py --source . --out /tmp/edition    another source tree or folder
"""

import argparse
import os
import re
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common.files import lock_folder  # noqa: E402
from common.path_options import folder_problem, path_argument  # noqa: E402
from grading.edition import make_student_edition  # noqa: E402
from grading.project import normalize_lesson  # noqa: E402


def hold_and_clean(out: Path) -> tuple[int | None, list[str]]:
    """Locks the folder OUT is written in (lock_folder: a second run beside it is refused) and removes what a
    run killed there left: its half-written edition (.OUT.new.XXXXXXXX), or the earlier edition it had moved
    aside (.OUT.old.XXXXXXXX), which goes back to OUT if OUT is missing. Returns the descriptor (None when the
    folder does not exist yet, or OUT is a link, which make_student_edition refuses) and one note per thing done."""
    if out.is_symlink() or not (parent := out.resolve().parent).is_dir():
        return None, []
    if (fd := lock_folder(parent)) is None:
        raise ValueError(f"--out {out}: another student_edition.py run is writing in {parent}; wait for it "
                         "to end")
    notes = []
    left = re.compile(rf"\.{re.escape(out.name)}\.(new|old)\.[a-z0-9_]{{8}}")
    for path in sorted(parent.iterdir(), key=lambda p: ".old." not in p.name):  # .old first
        match = left.fullmatch(path.name)
        if not match or path.is_symlink() or not path.is_dir() or path.stat().st_uid != os.geteuid():
            continue
        if match.group(1) == "old" and not os.path.lexists(out):
            path.rename(out)
            notes.append(f"restored {out} from {path}, where a run killed while replacing it had moved it")
        else:
            shutil.rmtree(path)
            notes.append(f"removed {path}, left by a run that was killed before it finished")
    return fd, notes


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--source", type=path_argument, default=Path(__file__).resolve().parent.parent,
                        help="the instructors' tree (default: the one this tool is in)")
    parser.add_argument("--out", type=path_argument,
                        help="where to write the student edition (default: SOURCE/build/student-edition)")
    parser.add_argument("--lessons", nargs="*", metavar="NN",
                        help="the lessons whose exercises to hand out (default: every lesson with exercises)")
    args = parser.parse_args()
    args.out = args.out or args.source / "build" / "student-edition"
    # Before anything is written: an --out under a file (afile/edition) would end in a traceback.
    for option, path in (("--out", args.out), ("--source", args.source)):
        if problem := folder_problem(path):
            parser.error(f"{option} {path}: {problem}")
    try:
        lessons = [normalize_lesson(t) for text in args.lessons for t in text.split(",") if t.strip()] \
            if args.lessons else None  # "03 11", "03,11", "3"
        _, notes = hold_and_clean(args.out)
        for note in notes:
            print(f"student_edition.py: note: {note}", file=sys.stderr)
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
