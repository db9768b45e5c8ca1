"""Where lessons live in a source tree.

Everything is discovered from folder names (``tests/NN_topic/``,
``exercises/NN_topic/``), never listed by hand, so that a lesson added by
someone else is graded without touching the driver.
"""
from __future__ import annotations

import re
from pathlib import Path

# tools/grading/project.py -> the source tree's root
ROOT = Path(__file__).resolve().parents[2]

STUDENT_EDITION_MARKER = "STUDENT_EDITION"

_LESSON_DIR = re.compile(r"(\d\d)_.+")


def lessons_with_sources(folder: Path, pattern: str = "*.cpp") -> list[str]:
    """The NN of every ``folder/NN_topic/`` that holds at least one matching file."""
    found = set()
    if folder.is_dir():
        for child in folder.iterdir():
            match = _LESSON_DIR.fullmatch(child.name)
            if match and child.is_dir() and any(child.glob(pattern)):
                found.add(match.group(1))
    return sorted(found)


def test_lessons(root: Path = ROOT) -> list[str]:
    """Lessons with a folder of tests (built as ``tests_lessonNN``)."""
    return lessons_with_sources(root / "tests")


def exercise_lessons(root: Path = ROOT) -> list[str]:
    """Lessons with exercise stubs, i.e. the ones a student can be graded on."""
    return lessons_with_sources(root / "exercises")


def exercise_stubs(root: Path = ROOT) -> dict[str, Path]:
    """File name -> stub path for every exercise unit (names are unique in lib/)."""
    stubs: dict[str, Path] = {}
    folder = root / "exercises"
    if folder.is_dir():
        for stub in sorted(folder.glob("[0-9][0-9]_*/*.cpp")):
            stubs[stub.name] = stub
    return stubs


def hidden_sources(root: Path = ROOT, extra: Path | None = None) -> list[Path]:
    """The .cpp files that make up ``tests_hidden`` (tests/hidden/ and --hidden DIR)."""
    sources = sorted((root / "tests" / "hidden").glob("*.cpp"))
    if extra is not None:
        sources += sorted(extra.glob("*.cpp"))
    return sources


def is_student_edition(root: Path = ROOT) -> bool:
    return (root / STUDENT_EDITION_MARKER).exists()


def normalize_lesson(text: str) -> str:
    """'1', '01' and 'lesson01' all mean lesson 01."""
    match = re.fullmatch(r"(?:lesson)?(\d{1,2})", text.strip())
    if not match:
        raise ValueError(f"'{text}' is not a lesson number (expected NN, e.g. 01)")
    return f"{int(match.group(1)):02d}"
