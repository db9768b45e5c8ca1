"""The links of the Markdown files of a tree: where they point, and whether it exists.

Used by the student edition (tools/grading/edition.py rewrites the links to
what it leaves out; tools/check_student_edition.py checks that every link of
the edition resolves). A link is ``[text](target)`` or ``![alt](target)``
outside code spans and fenced code blocks. Targets on the web
(``http:``, ``https:``, ``mailto:``) are not checked; a target under
``out/`` or ``build/`` of the tree is written by a program (the lesson
programs, the build), so it is allowed to be missing. A slide deck's links
are read from where it is built, ``out/slides/``.
"""
from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

_FENCE = re.compile(r"^\s*(```|~~~)")
_CODE_SPAN = re.compile(r"(`+)(.+?)\1")
# [text](target) or ![alt](target "title"); text may hold one level of brackets.
_LINK = re.compile(r"(!?)\[((?:[^\[\]]|\[[^\[\]]*\])*)\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+\"[^\"]*\")?\s*\)")
_HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
GENERATED = ("out", "build")
# Markdown files read from somewhere else than where they lie: a slide deck is built to
# out/slides/NN_topic.html, and its links are written from there.
READ_FROM = {"slides": PurePosixPath("out/slides")}


@dataclass
class Link:
    line: int      # 1-based
    start: int     # offsets of the whole link in its line (after code spans were blanked)
    end: int
    image: bool
    text: str
    target: str    # as written (angle brackets removed)

    @property
    def external(self) -> bool:
        return bool(re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", self.target))

    def split(self) -> tuple[str, str]:
        """(path, anchor) of the target; either may be empty."""
        path, _, anchor = self.target.partition("#")
        return path, anchor


def _blank_code_spans(line: str) -> str:
    return _CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line)


def markdown_links(text: str) -> list[Link]:
    """Every inline link and image of a Markdown text, outside code."""
    links = []
    fenced = False
    for number, line in enumerate(text.splitlines(), start=1):
        if _FENCE.match(line):
            fenced = not fenced
            continue
        if fenced:
            continue
        for match in _LINK.finditer(_blank_code_spans(line)):
            # Found where code spans are blanked out, read from the line as written (a link's text
            # may itself be a code span: [`sphere.cpp`](…)).
            target = line[match.start(3):match.end(3)]
            if target.startswith("<") and target.endswith(">"):
                target = target[1:-1]
            links.append(Link(number, match.start(), match.end(), match.group(1) == "!",
                              line[match.start(2):match.end(2)], target))
    return links


def heading_anchors(text: str) -> set[str]:
    """The anchors GitHub gives the headings of a Markdown text (lower case, punctuation dropped,
    spaces to hyphens; a repeated heading gets -1, -2, ...)."""
    anchors: set[str] = set()
    seen: dict[str, int] = {}
    fenced = False
    for line in text.splitlines():
        if _FENCE.match(line):
            fenced = not fenced
            continue
        match = None if fenced else _HEADING.match(line)
        if not match:
            continue
        title = re.sub(r"`", "", match.group(2))
        title = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", title)  # a link in a heading keeps its text
        slug = "".join(c for c in title.lower()
                       if c in " -_" or unicodedata.category(c)[0] in ("L", "N", "M"))
        slug = slug.replace(" ", "-")
        count = seen.get(slug, 0)
        seen[slug] = count + 1
        anchors.add(slug if count == 0 else f"{slug}-{count}")
    return anchors


def resolve(tree: Path, file: Path, path: str) -> PurePosixPath | None:
    """The target's path relative to the tree root (None when it leaves the tree)."""
    base = PurePosixPath(file.relative_to(tree).as_posix()).parent
    base = READ_FROM.get(base.as_posix(), base)
    parts: list[str] = []
    for part in (base / path).parts:
        if part in ("", "."):
            continue
        if part == "..":
            if not parts:
                return None
            parts.pop()
        else:
            parts.append(part)
    return PurePosixPath(*parts) if parts else PurePosixPath(".")


def broken_links(tree: Path, files: list[Path] | None = None) -> list[str]:
    """``file:line: [text](target): why`` for every link of the tree's Markdown files (or of
    ``files``) that does not resolve: a missing file or folder, a missing heading anchor."""
    tree = tree.resolve()
    files = sorted(tree.rglob("*.md")) if files is None else files
    problems: list[str] = []
    anchors_of: dict[Path, set[str]] = {}

    def anchors(path: Path) -> set[str]:
        if path not in anchors_of:
            anchors_of[path] = heading_anchors(path.read_text(encoding="utf-8", errors="replace"))
        return anchors_of[path]

    for file in files:
        relative = file.relative_to(tree)
        if relative.parts and relative.parts[0] in GENERATED + ("node_modules",):
            continue
        if "fixtures" in relative.parts:  # test data, broken on purpose (tests/slides/fixtures)
            continue
        text = file.read_text(encoding="utf-8", errors="replace")
        for link in markdown_links(text):
            if link.external:
                continue
            path, anchor = link.split()
            where = f"{relative.as_posix()}:{link.line}: [{link.text}]({link.target})"
            if not path:  # an anchor of this file
                if anchor and anchor not in anchors(file):
                    problems.append(f"{where}: no heading of this file has the anchor #{anchor}")
                continue
            target = resolve(tree, file, path)
            if target is None:
                problems.append(f"{where}: points outside the tree")
                continue
            if target.parts and target.parts[0] in GENERATED:
                continue  # written by the programs or the build
            absolute = tree / target
            if not absolute.exists():
                problems.append(f"{where}: {target.as_posix()} does not exist")
            elif anchor and absolute.suffix == ".md" and anchor not in anchors(absolute):
                problems.append(f"{where}: {target.as_posix()} has no heading with the anchor #{anchor}")
    return problems


def rewrite_links(text: str, replace) -> str:
    """``text`` with each link passed to ``replace(link) -> str | None``: a string replaces the whole
    link (``[text](target)``), None keeps it."""
    lines = text.split("\n")
    by_line: dict[int, list[Link]] = {}
    for link in markdown_links(text):
        by_line.setdefault(link.line, []).append(link)
    for number, links in by_line.items():
        line = lines[number - 1]
        for link in sorted(links, key=lambda l: l.start, reverse=True):
            new = replace(link)
            if new is not None:
                line = line[:link.start] + new + line[link.end:]
        lines[number - 1] = line
    return "\n".join(lines)
