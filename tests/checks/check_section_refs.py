#!/usr/bin/env python3
"""Every "lesson NN, §M" in the code, the stubs, the hints, the tests, the texts and the decks
names a section the lesson's text has.

A lesson text's sections are its headings: "## M. Title" is §M, "### M.K Title" is §M.K. A
reference is "§M" (or "§M.K", "§M–K", "§M and §K"): after "lesson NN" (also "[lesson NN](…)",
"lesson NN's", "(lesson NN, §M)") it means lesson NN's section; alone it means the section of the
lesson the file belongs to (lessons/NN_*/, exercises/NN_*/, tests/NN_*/, slides/NN_*.md), or,
in a file of no lesson (lib/, tests/<other>/), of the lesson the file last named before it.

Each reference must name a section the text has; a label quoted after it must be in that
section's title; and a source file the text names (`bvh.hpp`, `slab_test.cpp`) in some sections
(§1, which lists the whole library, aside) is the material of those sections: its references to
the lesson, and those of its header, its source and its stub, must name one of them (the slab
test cited as §4 "Octrees" when the text teaches it in §2 fails; production code, which points
to the course's sections, aside). A §
after a book's name in the same paragraph ("pbrt-v4 §6.8.6", "*Numerical Recipes*, §9.4"), or
under a text's "Further reading", is the book's and is not checked.

    tests/checks/check_section_refs.py            # exit 1 and one line per stale reference
    tests/checks/check_section_refs.py --list     # every reference and where it points

CTest `section_refs` (tests/e2e/tools.cmake) runs it.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from repo import ROOT, report
from grading.edition import tracked_files as edition_files  # tools/ is on the path (repo)

SCANNED = ("lib", "exercises", "tests", "lessons", "slides")
SUFFIXES = {".cpp", ".hpp", ".h", ".md", ".py", ".txt", ".cmake", ".mjs", ".cjs", ".json"}
# Fixtures of the tools' own tests (texts of made-up lessons), and the checks, which quote made-up references.
SKIPPED = ("tests/tools/", "tests/slides/fixtures/", "tests/texts/fixtures/", "tests/checks/")

_OWN = re.compile(r"^(?:lessons|exercises|tests|slides)/(\d\d)_")
_HEADING = re.compile(r"^#{2,4} (\d+(?:\.\d+)*)\.?\s", re.M)
_LESSON = re.compile(r"\[?\b[Ll]esson ?(\d\d)\b(?:\]\([^)\s]*\))?")
# What may stand between "lesson NN" and its first "§": a comma, a parenthesis, "'s", a colon.
_JOIN = re.compile(r"(?:['’]s)?[\s,(:]{0,4}(?=§)")
_SECTION = re.compile(r"§ ?(\d+(?:\.\d+)*)")
# A book's section, not a lesson's: "pbrt-v4 §6.8.6", "*Numerical Recipes*, §9.4", and every bare
# § under a text's "Further reading".
_BOOK = re.compile(r"pbrt|Pharr|Physically Based Rendering|Numerical Recipes|Press et al|Ericson|Akenine|"
                   r"\d(?:st|nd|rd|th) ed")
_READING = re.compile(r"^## Further reading\s*$", re.M)
# What continues a chain of sections: "–5", "-5", ", §5", " and §5", "/§5", " or §5".
_MORE = re.compile(r"(?:\s*[–-]\s*|\s*(?:,|and|or|/)\s*§\s?)(\d+(?:\.\d+)*)")


_TITLED = re.compile(r"^#{2,4} (\d+(?:\.\d+)*)\.?\s+(.*)$", re.M)
_FILE = re.compile(r"\b([a-z][a-z0-9_]*)\.(?:hpp|cpp)\b")
# A label quoted right after the section: lesson 08, §5 "comprobar (nodo, rayo)".
_LABEL = re.compile(r'\s*\\?"([^"\\]+)\\?"')


class Text:
    """One lesson text: its section numbers and titles, and the sections that name each source file."""

    def __init__(self, readme: Path):
        text = readme.read_text(encoding="utf-8")
        self.titles = {m.group(1): m.group(2) for m in _TITLED.finditer(text)}
        self.names: dict[str, set[str]] = {}
        starts = [(m.start(), m.group(1)) for m in re.finditer(r"^## (\d+)\.", text, re.M)]
        ends = [m.start() for m in re.finditer(r"^## ", text, re.M)] + [len(text)]
        for start, number in starts:
            if number == "1":  # §1 opens a text and often lists the whole library: it says where nothing is taught
                continue
            body = text[start:min(e for e in ends if e > start)]
            for name in _FILE.findall(body):
                self.names.setdefault(name, set()).add(number)


def lesson_texts(root: Path) -> dict[str, Text]:
    """NN -> lessons/NN_*/README.md, read."""
    return {readme.parent.name[:2]: Text(readme) for readme in sorted((root / "lessons").glob("[0-9][0-9]_*/README.md"))}


def tracked_files(root: Path) -> list[str]:
    """The files to scan: git's list in a checkout, else (the student edition) the tree less what it ignores."""
    return [n for n in edition_files(root) if n.split("/", 1)[0] in SCANNED and Path(n).suffix in SUFFIXES
            and not n.startswith(SKIPPED)]


def references(path: str, text: str) -> list[tuple[int, str, str, str]]:
    """(line, lesson NN or "", section, the words as written, with a quoted label if one follows) of
    every § in `text`."""
    own = _OWN.match(path)
    found = []
    bound: set[int] = set()  # positions of the "§" already read as part of an explicit chain
    line_of = lambda pos: text.count("\n", 0, pos) + 1  # noqa: E731
    for mention in _LESSON.finditer(text):
        join = _JOIN.match(text, mention.end())
        if not join:
            continue
        first = _SECTION.match(text, join.end())
        if not first:
            continue
        bound.add(first.start())
        label = _LABEL.match(text, first.end())
        found.append((line_of(first.start()), mention.group(1), first.group(1),
                      text[mention.start():label.end() if label else first.end()]))
        end = first.end()
        while more := _MORE.match(text, end):
            section_start = text.rfind("§", end, more.end())
            if section_start >= 0:
                bound.add(section_start)
            found.append((line_of(more.start()), mention.group(1), more.group(1), text[mention.start():more.end()]))
            end = more.end()
    reading = _READING.search(text)
    for section in _SECTION.finditer(text):
        if section.start() in bound or (reading and section.start() > reading.start()):
            continue
        paragraph = text[max(text.rfind("\n\n", 0, section.start()), section.start() - 300, 0):section.start()]
        books = list(_BOOK.finditer(paragraph))
        lessons = list(_LESSON.finditer(paragraph))
        if books and (not lessons or books[-1].start() > lessons[-1].start()):
            continue
        if own:
            lesson = own.group(1)
        else:
            before = list(_LESSON.finditer(text, 0, section.start()))
            lesson = before[-1].group(1) if before else ""
        found.append((line_of(section.start()), lesson, section.group(1), section.group(0)))
    return sorted(found)


def problems(root: Path, listing: bool = False) -> list[str]:
    """One line per reference that points to no section, to a section whose title its label does not
    match, or, from a file the text names in some sections, to none of those."""
    texts = lesson_texts(root)
    out = []
    for path in tracked_files(root):
        try:
            text = (root / path).read_text(encoding="utf-8")
        except (UnicodeDecodeError, FileNotFoundError):
            continue
        stem = Path(path).stem
        for line, lesson, section, words in references(path, text):
            where = f"{path}:{line}"
            words = " ".join(words.split())
            if listing:
                print(f"{where}: lesson {lesson or '??'} §{section}  ({words})")
            if not lesson:
                out.append(f"{where}: \"{words}\" names no lesson, and the file names none before it")
                continue
            if lesson not in texts:
                out.append(f"{where}: \"{words}\": lesson {lesson} has no text (lessons/{lesson}_*/README.md)")
                continue
            lesson_text = texts[lesson]
            if section not in lesson_text.titles:
                heads = sorted(lesson_text.titles, key=lambda s: [int(k) for k in s.split(".")])
                out.append(f"{where}: \"{words}\": lesson {lesson}'s text has no §{section} "
                           f"(its sections: {', '.join(heads)})")
                continue
            title = lesson_text.titles[section]
            label = _LABEL.search(words)
            if label and label.group(1).lower() not in title.lower():
                out.append(f"{where}: \"{words}\": lesson {lesson}'s §{section} is \"{title}\"")
            named_in = lesson_text.names.get(stem)
            # Production code (lib/illum/<area>/production/) points to the course's sections, not its own.
            if (named_in and not path.startswith(("lessons/", "slides/")) and "/production/" not in path
                    and section.split(".")[0] not in named_in):
                out.append(f"{where}: \"{words}\": lesson {lesson}'s text names {stem} in "
                           + ", ".join(f"§{n} ({lesson_text.titles[n]})" for n in sorted(named_in, key=int))
                           + f", not in §{section} ({title})")
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=Path, default=ROOT)
    parser.add_argument("--list", action="store_true", help="print every reference and where it points")
    args = parser.parse_args()
    return report(problems(args.root.resolve(), args.list), "section references", "every one names a section")


if __name__ == "__main__":
    sys.exit(main())
