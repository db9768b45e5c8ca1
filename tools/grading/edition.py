"""The student edition: the tracked tree without what students must not see.

The instructor chooses the lessons to hand out (default: every lesson with
exercises). Left out:
* the reference source of every exercise unit of a lesson handed out --
  ``lib/illum/**/<name>.cpp`` that has a twin ``exercises/NN_*/<name>.cpp``;
  CMake builds the stub when the reference is absent;
* ``exercises/NN_*/`` of every lesson *not* handed out: its units ship as
  working reference code, so that the lessons handed out can use its results
  (docs/grading.md, "Choosing the lessons to hand out");
* ``tests/hidden/`` (an instructor's hidden tests) and ``tests/attacks/``
  (hostile submissions the grader is tested with);
* ``build/`` and ``out/`` (generated).
A ``STUDENT_EDITION`` marker file tells CMake and the driver which tree
they are in (no integrity check, no autograder packing there).
"""
from __future__ import annotations

import os
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from .project import STUDENT_EDITION_MARKER

_GENERATED = ("build", "out")


def _git_toplevel(source: Path) -> Path | None:
    try:
        completed = subprocess.run(["git", "-C", str(source), "rev-parse", "--show-toplevel"],
                                   capture_output=True, text=True, check=False)
    except OSError:
        return None
    if completed.returncode != 0:
        return None
    return Path(completed.stdout.strip()).resolve()


def _git_describe(source: Path) -> str:
    completed = subprocess.run(["git", "-C", str(source), "describe", "--always", "--dirty"],
                               capture_output=True, text=True, check=False)
    return completed.stdout.strip() if completed.returncode == 0 else ""


def tracked_files(source: Path) -> list[str]:
    """POSIX paths relative to ``source``: ``git ls-files`` in a checkout (so
    untracked experiments never leak to students), else every file."""
    source = source.resolve()
    if _git_toplevel(source) == source:
        completed = subprocess.run(["git", "-C", str(source), "ls-files", "-z"],
                                   capture_output=True, check=True)
        return sorted(p for p in completed.stdout.decode("utf-8").split("\0") if p)
    files = []
    for folder, subfolders, names in os.walk(source):
        relative = Path(folder).relative_to(source)
        subfolders[:] = [d for d in subfolders if not (relative == Path(".") and d in (".git", *_GENERATED))]
        files.extend((relative / name).as_posix() for name in names)
    return sorted(files)


def _stub_lesson(path: str) -> str | None:
    """NN for ``exercises/NN_topic/<unit>.cpp``, else None."""
    parts = PurePosixPath(path).parts
    if len(parts) == 3 and parts[0] == "exercises" and parts[1][:2].isdigit() and path.endswith(".cpp"):
        return parts[1][:2]
    return None


def exercise_lessons_of(files: list[str]) -> list[str]:
    return sorted({nn for f in files if (nn := _stub_lesson(f))})


def excluded_files(files: list[str], handed_out: list[str] | None = None) -> dict[str, str]:
    """Path -> reason, for every path of ``files`` the student edition leaves out.

    ``handed_out``: the lessons whose exercises students get (None: all)."""
    lessons = exercise_lessons_of(files)
    handed = set(lessons if handed_out is None else handed_out)
    twins = {PurePosixPath(f).name for f in files if _stub_lesson(f) in handed}
    reasons = {}
    for f in files:
        parts = PurePosixPath(f).parts
        if parts[0] in _GENERATED:
            reasons[f] = "generated"
        elif parts[:2] == ("tests", "hidden"):
            reasons[f] = "hidden test"
        elif parts[:2] == ("tests", "attacks"):
            reasons[f] = "the grader's own attack tests"
        elif parts[:2] == ("lib", "illum") and f.endswith(".cpp") and parts[-1] in twins:
            reasons[f] = "reference solution of an exercise unit"
        elif parts[0] == "exercises" and len(parts) >= 3 and parts[1][:2].isdigit() and parts[1][:2] not in handed:
            reasons[f] = "exercise not handed out (its units ship as reference code)"
        elif f == STUDENT_EDITION_MARKER:
            reasons[f] = "marker, rewritten"
    return reasons


@dataclass
class Edition:
    out: Path
    copied: int = 0
    left_out: dict[str, str] = field(default_factory=dict)
    handed_out: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # dependencies among the lessons handed out


def make_student_edition(source: Path, out: Path, handed_out: list[str] | None = None) -> Edition:
    """Writes the student edition of ``source`` to ``out`` (replacing an earlier one),
    handing out the exercises of ``handed_out`` (None: every lesson with exercises)."""
    from .alone import declared_dependencies

    source, out = source.resolve(), out.resolve()
    # Inside the source tree, only the generated folders are safe: anywhere
    # else the edition would be copied into itself next time.
    in_generated = any(out == source / g or source / g in out.parents for g in _GENERATED)
    if out == source or (source in out.parents and not in_generated):
        raise ValueError(f"{out} lies inside the source tree; write the edition under build/ or elsewhere")
    if out.exists():
        if any(out.iterdir()) and not (out / STUDENT_EDITION_MARKER).exists():
            raise ValueError(f"{out} exists and is not a student edition; refusing to replace it")
        shutil.rmtree(out)
    files = tracked_files(source)
    lessons = exercise_lessons_of(files)
    unknown = sorted(set(handed_out or []) - set(lessons))
    if unknown:
        raise ValueError(f"lesson(s) {', '.join(unknown)} have no exercises; lessons with exercises: "
                         f"{', '.join(lessons)}")
    chosen = lessons if handed_out is None else sorted(set(handed_out))
    if not chosen:
        raise ValueError("no lesson to hand out")
    left_out = excluded_files(files, chosen)
    edition = Edition(out, left_out=left_out, handed_out=chosen)
    for lesson in chosen:
        needed = [d for d in declared_dependencies(lesson, source) if d in chosen]
        if needed:
            edition.notes.append(f"lesson {lesson} builds on lesson {', '.join(needed)}, also handed out: its "
                                 f"program and tests need the students' lesson {', '.join(needed)} code first")
    for relative in files:
        if relative in left_out:
            continue
        origin = source / relative
        if not origin.is_file():  # deleted in the working tree but still tracked
            continue
        target = out / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(origin, target)
        edition.copied += 1
    version = _git_describe(source)
    given = [nn for nn in lessons if nn not in chosen]
    (out / STUDENT_EDITION_MARKER).write_text(
        "This is the student edition of illum"
        + (f", made from {version}" if version else "")
        + f".\nExercises handed out: lessons {', '.join(chosen)}.\n"
        + (f"Lessons {', '.join(given)} are not exercises here: their units are working reference code.\n"
           if given else "")
        + "The reference solutions of the exercises handed out and the instructors' hidden tests are not part\n"
        "of it; the exercise stubs in exercises/ are built in their place. Grade your work with\n"
        "    tools/grade --student NN\n"
        "(see docs/grading.md).\n", encoding="utf-8")
    return edition
