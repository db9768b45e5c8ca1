"""Reading Markdown: pipe tables, links and GitHub's heading anchors (the one home of each rule)."""

import functools
import itertools
import posixpath
import re
import unicodedata
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from urllib.parse import unquote, urlsplit

_SEPARATOR_CELL = re.compile(r"^:?-+:?$")
_FENCE = re.compile(r"^\s*(```|~~~)")
_CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")
# [text](target) or ![alt](<target> "title"); the text may hold one level of brackets.
_INLINE = re.compile(r"(!?)\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+\"[^\"]*\")?\s*\)")
_REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
_HTML = re.compile(r"<(img|a|source)\b[^>]*?\b(?:src|href)=\"([^\"]+)\"", re.I)
_HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")
GENERATED = ("out", "build")  # written by the programs or the build: absent from a fresh clone
# A deck, slides/NN_topic.md, is built to out/slides/NN_topic.html and links from there.
DECKS, DECKS_BUILT = PurePosixPath("slides"), PurePosixPath("out/slides")


def split_table_row(line: str) -> list[str]:
    """The cells of a row '| a | b |' (a pipe escaped as \\| stays in its cell)."""
    body = line.strip()
    body = body[1:] if body.startswith("|") else body
    body = body[:-1] if body.endswith("|") and not body.endswith("\\|") else body
    return [cell.replace("\\|", "|").strip() for cell in re.split(r"(?<!\\)\|", body)]


def alignment(cell: str) -> str:
    """'left', 'right', 'center' or '' for one separator cell."""
    c = cell.replace(" ", "")
    return ("", "left", "right", "center")[c.startswith(":") + 2 * c.endswith(":")]


@dataclass
class Table:
    header: list[str]
    rows: list[list[str]]
    start: int = 0  # 0-based line of the header
    align: list[str] = field(default_factory=list)


def parse_tables(lines: list[str]) -> tuple[list[Table], list[str]]:
    """Every pipe table of `lines` and the problems of the malformed ones (1-based line numbers)."""
    tables, problems = [], []
    for is_table, run in itertools.groupby(enumerate(lines), key=lambda item: item[1].lstrip().startswith("|")):
        if is_table:
            block = list(run)
            table, found = _block_table([line for _, line in block], block[0][0])
            problems += found
            tables += [table] if table is not None else []
    return tables, problems


def _block_table(block: list[str], start: int) -> tuple[Table | None, list[str]]:
    if len(block) < 2:
        return None, [f"line {start + 1}: a table row with no separator line ('|---|---|') after it"]
    header, separator = split_table_row(block[0]), split_table_row(block[1])
    if not all(_SEPARATOR_CELL.match(c.replace(" ", "")) for c in separator):  # never empty: split gives one
        return None, [f"line {start + 2}: expected the separator line ('|---|---|'), found {block[1].strip()!r}"]
    if len(separator) != len(header):
        return None, [f"line {start + 2}: the separator has {len(separator)} columns, the header has {len(header)}"]
    problems, rows = [], [split_table_row(line) for line in block[2:]]
    for k, (line, cells) in enumerate(zip(block[2:], rows)):
        if not line.rstrip().endswith("|"):
            problems.append(f"line {start + 3 + k}: a table row must end with '|'")
        if len(cells) != len(header):
            problems.append(f"line {start + 3 + k}: {len(cells)} cells, the header has {len(header)}")
    if not rows:
        problems.append(f"line {start + 1}: a table with a header but no rows")
    if not block[0].rstrip().endswith("|"):
        problems.append(f"line {start + 1}: the header row must end with '|'")
    return Table(header, rows, start, [alignment(c) for c in separator]), problems


@dataclass
class Link:
    line: int      # 1-based
    start: int     # span of the whole link in its line
    end: int
    image: bool
    text: str
    target: str    # as written, angle brackets removed
    inline: bool = True  # False: a reference definition or an HTML src/href

    @property
    def external(self) -> bool:
        return bool(urlsplit(self.target).scheme) or self.target.startswith("//")

    def split(self) -> tuple[str, str]:
        """(path, anchor) of the target, the path unquoted; either may be empty."""
        parts = urlsplit(self.target)
        return unquote(parts.path), unquote(parts.fragment)


def outside_fences(lines: list[str]):
    """(0-based index, line) of every line outside fenced code (the fences' own lines left out)."""
    fenced = False
    for i, line in enumerate(lines):
        if _FENCE.match(line):
            fenced = not fenced
        elif not fenced:
            yield i, line


def links(text: str) -> list[Link]:
    """Every link and image of a text outside code: inline ones, reference definitions, HTML src/href."""
    found = []
    for i, line in outside_fences(text.splitlines()):
        number, bare = i + 1, re.sub(r"<!--.*?-->", lambda m: " " * len(m.group(0)),
                      _CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line))
        for m in _INLINE.finditer(bare):  # found where code is blanked, read as written ([`x.cpp`](…))
            found.append(Link(number, m.start(), m.end(), m.group(1) == "!", line[m.start(2):m.end(2)],
                              line[m.start(3):m.end(3)].removeprefix("<").removesuffix(">")))
        if m := _REFERENCE.match(bare):
            found.append(Link(number, m.start(1), m.end(1), False, "", m.group(1), inline=False))
        for m in _HTML.finditer(bare):
            found.append(Link(number, m.start(2), m.end(2), m.group(1).lower() == "img", "", m.group(2), False))
    return found


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"!\[[^\]]*\]\([^)]*\)", "", heading)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"<[^>]+>", "", text).replace("`", "").lower().strip()
    return "".join("-" if c == " " else c for c in text
                   if c in "-_ " or unicodedata.category(c)[0] in "LN" or unicodedata.category(c) == "Mn")


def anchors(text: str) -> set[str]:
    """The anchors of a text's headings (a repeated one gets -1, -2, … as on GitHub) and its HTML ids."""
    ids: set[str] = set()
    seen: dict[str, int] = {}
    for _, line in outside_fences(text.splitlines()):
        if m := _HEADING.match(line):
            base = slug(m.group(1))
            ids.add(f"{base}-{seen[base]}" if seen.get(base) else base)
            seen[base] = seen.get(base, 0) + 1
        ids.update(re.findall(r"\b(?:id|name)=\"([^\"]+)\"", line))
    return ids


def resolve(tree: Path, file: Path, path: str) -> PurePosixPath | None:
    """A link's path relative to the tree's root (None when it leaves the tree)."""
    base = PurePosixPath(file.relative_to(tree).as_posix()).parent
    base = DECKS_BUILT if base == DECKS and file.name[:2].isdigit() else base
    joined = posixpath.normpath((base / path).as_posix())
    return None if joined == ".." or joined.startswith("../") else PurePosixPath(joined)


def link_problems(tree: Path, files: list[Path], generated_ok: bool) -> tuple[list[str], int]:
    """`file:line: …` for every link of `files` that does not resolve in `tree` (a missing file or
    heading, a target outside the tree, or in out/ unless `generated_ok`), and how many were checked."""
    tree = tree.resolve()
    problems, checked = [], 0

    @functools.cache
    def ids(path: Path) -> set[str]:
        return anchors(path.read_text(encoding="utf-8", errors="replace"))

    for file in files:
        for link in links(file.read_text(encoding="utf-8", errors="replace")):
            if link.external:
                continue
            checked += 1
            where = f"{file.relative_to(tree).as_posix()}:{link.line}: the {'image' if link.image else 'link'} " \
                    f"'{link.target}'"
            path, anchor = link.split()
            target = resolve(tree, file, path) if path else PurePosixPath(file.relative_to(tree).as_posix())
            if target is None:
                problems.append(f"{where} leaves the repository")
            elif target.parts[:1] and target.parts[0] in GENERATED:
                if not generated_ok:
                    problems.append(f"{where} points into {target.parts[0]}/, which a fresh clone does not have: "
                                    "link a kept copy (lessons/NN_topic/figures/, tools/figures.py "
                                    "--update-images) or name the file in `code` instead")
            elif not (tree / target).exists():
                problems.append(f"{where} names {target.as_posix()}, which does not exist")
            elif anchor and target.suffix == ".md" and (tree / target).is_file() and anchor not in ids(tree / target):
                problems.append(f"{where} names no heading of {target.as_posix()} (anchors are GitHub's: lower "
                                "case, punctuation dropped, spaces as hyphens)")
    return problems, checked


def rewrite_links(text: str, replace) -> str:
    """`text` with each inline link passed to `replace(link) -> str | None`: a string replaces the
    whole link, None keeps it."""
    lines = text.split("\n")
    for link in sorted((k for k in links(text) if k.inline), key=lambda k: (k.line, -k.start)):
        new = replace(link)
        if new is not None:
            line = lines[link.line - 1]
            lines[link.line - 1] = line[:link.start] + new + line[link.end:]
    return "\n".join(lines)
