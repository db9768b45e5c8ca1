"""Links and images of the Markdown texts resolve in the repository itself.

A student reads the texts in a fresh clone (or its repository browser), where
out/ does not exist yet: every relative link or image of a text must name a
file or folder of the source tree, outside out/, and a link to a heading
(`../10_hemicube/README.md#4-the-item-buffer`, `#erratum-4`) must name a
heading of that text. Headings are named as GitHub names them (`slug`),
which the gallery's rendered pages use too.

Decks (slides/NN_*.md) are left out: their links are relative to the built
deck in out/slides/ (slides/README.md).
"""
from __future__ import annotations

import re
import unicodedata
from pathlib import Path
from urllib.parse import unquote, urlsplit

# The texts whose links are checked, relative to the source tree.
TEXT_GLOBS = ("README.md", "CONTRIBUTING.md", "lessons/*/README.md", "exercises/*/README.md", "docs/*.md",
              "slides/README.md", "tests/*/README.md", "tools/*/README.md", "bench/*/README.md")
_INLINE_LINK = re.compile(r"(?P<image>!?)\[(?P<text>(?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?(?P<target>[^)\s>]+)>?"
                          r"(?:\s+\"[^\"]*\")?\s*\)")
_REFERENCE_DEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(?P<target>\S+?)>?(?:\s+.*)?$")
_HTML_REF = re.compile(r"<(?:img|a|source)\b[^>]*?\b(?:src|href)=\"(?P<target>[^\"]+)\"", re.I)
_HEADING = re.compile(r"^(?P<hashes>#{1,6})\s+(?P<text>.*?)\s*#*\s*$")
_CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")


def slug(heading: str) -> str:
    """GitHub's anchor for a heading: the text lower-cased, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"!\[[^\]]*\]\([^)]*\)", "", heading)            # images
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)            # links keep their text
    text = re.sub(r"<[^>]+>", "", text)                             # inline HTML
    text = text.replace("`", "").lower().strip()
    kept = []
    for c in text:
        category = unicodedata.category(c)
        if c in "-_ " or category[0] in "LN" or category == "Mn":
            kept.append("-" if c == " " else c)
    return "".join(kept)


def heading_ids(lines: list[str]) -> set[str]:
    """The anchors of a text's headings, duplicates numbered as GitHub does (-1, -2, …), and its HTML ids."""
    ids: set[str] = set()
    seen: dict[str, int] = {}
    fence = False
    for line in lines:
        if line.lstrip().startswith(("```", "~~~")):
            fence = not fence
            continue
        if fence:
            continue
        m = _HEADING.match(line)
        if m:
            base = slug(m.group("text"))
            n = seen.get(base, 0)
            ids.add(base if n == 0 else f"{base}-{n}")
            seen[base] = n + 1
        ids.update(re.findall(r"\b(?:id|name)=\"([^\"]+)\"", line))
    return ids


def link_targets(lines: list[str]) -> list[tuple[int, str, bool]]:
    """(0-based line, target, is an image) of every link of a text, outside code."""
    found = []
    fence = False
    for i, line in enumerate(lines):
        if line.lstrip().startswith(("```", "~~~")):
            fence = not fence
            continue
        if fence or line.startswith("    ") and not line.lstrip().startswith(("*", "-", "|", "[", "!")):
            continue
        bare = _CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line)
        bare = re.sub(r"<!--.*?-->", "", bare)
        for m in _INLINE_LINK.finditer(bare):
            found.append((i, m.group("target"), bool(m.group("image"))))
        m = _REFERENCE_DEF.match(bare)
        if m:
            found.append((i, m.group("target"), False))
        for m in _HTML_REF.finditer(bare):
            found.append((i, m.group("target"), m.group(0).lower().startswith("<img")))
    return found


def texts(source: Path) -> list[Path]:
    found: list[Path] = []
    for pattern in TEXT_GLOBS:
        found.extend(sorted(p for p in Path(source).glob(pattern) if p.is_file()))
    return found


def check_text_links(source: Path) -> tuple[list[str], int]:
    """Problems with the texts' links and images, and how many links were checked."""
    source = Path(source).resolve()
    out = source / "out"
    problems: list[str] = []
    anchors: dict[Path, set[str]] = {}
    checked = 0

    def ids_of(path: Path) -> set[str]:
        if path not in anchors:
            anchors[path] = heading_ids(path.read_text(encoding="utf-8").splitlines())
        return anchors[path]

    for text in texts(source):
        rel = text.relative_to(source)
        lines = text.read_text(encoding="utf-8").splitlines()
        for i, target, image in link_targets(lines):
            parts = urlsplit(target)
            if parts.scheme or target.startswith("//"):
                continue  # a web address: not checked offline
            checked += 1
            where = f"{rel}:{i + 1}"
            kind = "image" if image else "link"
            path = text if not parts.path else (text.parent / unquote(parts.path)).resolve()
            if path != source and source not in path.parents:
                problems.append(f"{where}: the {kind} '{target}' leaves the repository")
                continue
            if path == out or out in path.parents:
                problems.append(f"{where}: the {kind} '{target}' points into out/, which a fresh clone does not "
                                "have: link a kept copy (lessons/NN_topic/figures/, tools/figures.py "
                                "--update-images) or name the file in `code` instead")
                continue
            if not path.exists():
                problems.append(f"{where}: the {kind} '{target}' names {path.relative_to(source)}, which does "
                                "not exist")
                continue
            if parts.fragment and path.suffix == ".md" and path.is_file():
                fragment = unquote(parts.fragment)
                if fragment not in ids_of(path):
                    problems.append(f"{where}: the link '{target}' names no heading of "
                                    f"{path.relative_to(source)} (anchors are GitHub's: lower case, "
                                    f"punctuation dropped, spaces as hyphens)")
    return problems, checked
