"""Where lessons live in a source tree, found from folder names (tests/NN_topic/, exercises/NN_topic/),
never listed by hand, so that a lesson added by someone else is graded without touching the driver."""
from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]  # tools/grading/project.py -> the source tree
STUDENT_EDITION_MARKER = "STUDENT_EDITION"
_LESSON_DIR = re.compile(r"(\d\d)_.+")


def lesson_folders(root: Path, kind: str) -> dict[str, Path]:
    """NN -> root/kind/NN_topic for every lesson folder of `kind` (lessons, exercises, tests)."""
    return {m.group(1): child for child in (sorted((root / kind).iterdir()) if (root / kind).is_dir() else [])
            if (m := _LESSON_DIR.fullmatch(child.name)) and child.is_dir()}


def test_lessons(root: Path = ROOT) -> list[str]:
    """Lessons with a folder of tests (built as tests_lessonNN)."""
    return sorted(nn for nn, child in lesson_folders(root, "tests").items() if any(child.glob("*.cpp")))


def exercise_lessons(root: Path = ROOT) -> list[str]:
    """Lessons with exercise stubs: the ones a student can be graded on."""
    return sorted(nn for nn, child in lesson_folders(root, "exercises").items() if any(child.glob("*.cpp")))


def exercise_stubs(root: Path = ROOT, lessons: list[str] | None = None) -> dict[str, Path]:
    """File name -> stub path for every exercise unit (names are unique in lib/), of `lessons` only if given."""
    return {stub.name: stub for stub in sorted((root / "exercises").glob("[0-9][0-9]_*/*.cpp"))
            if lessons is None or stub.parent.name[:2] in lessons}


def hidden_sources(root: Path = ROOT, extra: Path | None = None) -> list[Path]:
    """The .cpp files that make up tests_hidden (tests/hidden/ and --hidden DIR)."""
    return sorted((root / "tests" / "hidden").glob("*.cpp")) + (sorted(extra.glob("*.cpp")) if extra else [])


def is_student_edition(root: Path = ROOT) -> bool:
    return (root / STUDENT_EDITION_MARKER).exists()


def normalize_lesson(text: str) -> str:
    """'1', '01' and 'lesson01' all mean lesson 01."""
    match = re.fullmatch(r"(?:lesson)?(\d{1,2})", text.strip())
    if not match:
        raise ValueError(f"'{text}' is not a lesson number (expected NN, e.g. 01)")
    return f"{int(match.group(1)):02d}"
