"""What the repository checks of tests/checks/ share: the source tree, tools/ on the import path (its
common/, gallery/ and grading/ packages), the C++ sources of some folders read as code, and the closing
report. CTest runs each check (tests/e2e/*.cmake); so does .ci/run."""
from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from common.cpp_text import blank_comments  # noqa: E402

CXX_SUFFIXES = {".cpp", ".hpp", ".h", ".cc"}


def cxx_sources(root: Path, folders: tuple[str, ...], skip: Path | None = None) -> list[Path]:
    """The C++ sources under root/FOLDER for each folder, sorted (node_modules/ and the folder `skip` aside)."""
    return sorted(path for folder in folders if (root / folder).is_dir() for path in (root / folder).rglob("*")
                  if path.suffix in CXX_SUFFIXES and path.is_file() and "node_modules" not in path.parts
                  and (skip is None or skip not in path.parents))


def code_lines(path: Path) -> list[str]:
    """A C++ file's lines with comments and strings blanked, so that prose may name what code must not do."""
    return blank_comments(path.read_text(encoding="utf-8", errors="replace")).splitlines()


def report(problems: list[str], name: str, ok: str, prefix: str = "") -> int:
    """Prints each problem, then `NAME: OK-TEXT` or `NAME: FAILED (N problem(s))`; returns the exit status, 0 or 1."""
    for problem in problems:
        print(prefix + problem)
    print(f"{name}: " + (ok if not problems else f"FAILED ({len(problems)} problem(s))"))
    return 1 if problems else 0
