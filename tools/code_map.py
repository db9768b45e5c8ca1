"""One hop from every idea to its code, test and slide: the lesson layout and its "Where the code is" blocks.

A lesson program is lessons/NN_topic/main.cpp (the demonstration) and
studies/sMM_<name>.cpp, one per study, MM the number of the README section
that quotes it; a letter after MM (s06a_, s06b_) orders several studies of
one section as the program runs them (docs/architecture.md, "Lesson programs"). Every lesson text
opens with a hand-written reading list,

    **Read in this order:**

    1. the library: [`trace/optics.hpp`](../../lib/illum/trace/optics.hpp), …
    2. the demonstration: [`main.cpp`](main.cpp)
    3. the studies, in the text's order: [`studies/s01_….cpp`](studies/s01_….cpp) (§1), …

and every lesson text and exercise README holds a generated block between

    <!-- code-map: begin (written by tools/task_tables.py --update) -->
    <!-- code-map: end -->

that links the lesson's text, program, studies and helpers, its library
pairs (those of the reading list and the exercise's units), its exercise
files, its test files and its slide deck. Each deck (slides/NN_topic.md)
ends with the same block as a slide, "Where the code is", in a few lines
(deck_slide): the text, the exercise's files and contracts, the program,
the tests. tools/task_tables.py --update writes the blocks; --check fails
when one is stale or missing and when the layout breaks a rule below
(layout_problems).
"""
from __future__ import annotations

import os
import re
from pathlib import Path

BEGIN = "<!-- code-map: begin (written by tools/task_tables.py --update) -->"
END = "<!-- code-map: end -->"
READ_IN_ORDER = "**Read in this order:**"

_LESSON_DIR = re.compile(r"(\d\d)_.+")
_LINK = re.compile(r"\[[^\]]*\]\(([^)\s#]+)(?:#[^)]*)?\)")
_STUDY = re.compile(r"s(\d\d)([a-z]?)_([a-z0-9_]+)\.cpp")
_SECTION_LABEL = re.compile(r'"§(\d+) ([^"]*)"')


def _folders(root: Path, kind: str) -> dict[str, Path]:
    found = {}
    base = root / kind
    if base.is_dir():
        for child in sorted(base.iterdir()):
            match = _LESSON_DIR.fullmatch(child.name)
            if match and child.is_dir():
                found[match.group(1)] = child
    return found


def lesson_programs(root: Path) -> dict[str, Path]:
    """NN -> lessons/NN_topic for every lesson with a main.cpp."""
    return {nn: folder for nn, folder in _folders(root, "lessons").items() if (folder / "main.cpp").is_file()}


def _rel(path: Path, start: Path) -> str:
    return Path(os.path.relpath(path, start)).as_posix()


def exercise_units(root: Path) -> set[str]:
    """The file names of every exercise unit (a lib/ source with a stub in exercises/)."""
    return {stub.name for folder in _folders(root, "exercises").values() for stub in folder.glob("*.cpp")}


def studies(lesson: Path) -> list[Path]:
    return sorted(s for s in (lesson / "studies").glob("s[0-9][0-9]*.cpp") if _STUDY.fullmatch(s.name))


def helpers(lesson: Path) -> list[Path]:
    """The lesson's own helpers: the headers beside main.cpp, a source beside it that has
    no header (its declarations are in studies/studies.hpp), and studies/studies.hpp."""
    found = sorted(lesson.glob("*.hpp"))
    found += [s for s in sorted(lesson.glob("*.cpp")) if s.name != "main.cpp" and not s.with_suffix(".hpp").is_file()]
    if (lesson / "studies" / "studies.hpp").is_file():
        found.append(lesson / "studies" / "studies.hpp")
    return found


# --- the README's sections and its reading list ---------------------------------------------


def _plain(text: str) -> str:
    """A heading as text: links reduced to their words, emphasis and code marks dropped."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    return re.sub(r"[*`_]", "", text).strip()


def sections(readme_text: str) -> dict[int, str]:
    """Section number -> the plain text of its "## N. Title" heading."""
    return {int(m.group(1)): _plain(m.group(2)) for m in re.finditer(r"^## (\d+)\. (.+)$", readme_text, re.M)}


def _agrees(label: str, heading: str) -> bool:
    """A label agrees with a heading when one begins with the other, or the label begins
    with the heading's lead (its words before the first ':' or '—'), case aside."""
    label, heading = label.strip().rstrip(".").lower(), heading.strip().lower()
    lead = re.split(r"[:—]", heading, maxsplit=1)[0].strip()
    return label.startswith(heading) or heading.startswith(label) or (bool(lead) and label.startswith(lead))


def reading_list(readme_text: str) -> tuple[int, list[str]] | None:
    """(line index of the READ_IN_ORDER line, the link targets of the list after it), or None
    when the text has none before its first section. The list is the paragraph that follows
    the line: its lines up to the next blank one."""
    lines = readme_text.splitlines()
    for k, line in enumerate(lines):
        if line.startswith("## "):
            return None  # the list must open the text, before the first section
        if line.strip() == READ_IN_ORDER:
            j = k + 1
            while j < len(lines) and not lines[j].strip():
                j += 1
            targets = []
            while j < len(lines) and lines[j].strip() and not lines[j].startswith("#"):
                targets += _LINK.findall(lines[j])
                j += 1
            return k, targets
    return None


def library_pairs(root: Path, lesson_nn: str) -> list[Path]:
    """The headers of lib/ a lesson's code map lists: those its reading list links, in its
    order, then the headers of its exercise units not linked already."""
    lesson = _folders(root, "lessons").get(lesson_nn)
    pairs: list[Path] = []
    if lesson is not None and (lesson / "README.md").is_file():
        found = reading_list((lesson / "README.md").read_text(encoding="utf-8"))
        for target in found[1] if found else []:
            path = (lesson / target).resolve()
            if path.suffix in (".hpp", ".cpp") and (root / "lib").resolve() in path.parents:
                header = path.with_suffix(".hpp")
                if header.is_file() and header not in pairs:
                    pairs.append(header)
    exercise = _folders(root, "exercises").get(lesson_nn)
    for stub in sorted(exercise.glob("*.cpp")) if exercise else []:
        header = next(iter(sorted((root / "lib" / "illum").rglob(stub.stem + ".hpp"))), None)
        if header is not None and header.resolve() not in pairs:
            pairs.append(header.resolve())
    return pairs


def test_files(root: Path, lesson_nn: str, pairs: list[Path]) -> tuple[list[Path], list[Path]]:
    """(the lesson's own test files, tests elsewhere named after one of its library pairs)."""
    own_folder = _folders(root, "tests").get(lesson_nn)
    own = sorted(own_folder.glob("*.cpp")) if own_folder else []
    stems = {p.stem for p in pairs}
    others = []
    tests = root / "tests"
    if tests.is_dir():
        for folder in sorted(tests.iterdir()):
            if folder.is_dir() and not _LESSON_DIR.fullmatch(folder.name) and folder.name != "hidden":
                others += [f for f in sorted(folder.glob("*.cpp")) if f.stem in stems]
    return own, others


# --- the block -------------------------------------------------------------------------------


def code_map(root: Path, lesson_nn: str, readme: Path) -> str:
    """The Markdown of lesson NN's "Where the code is" block as seen from `readme`."""
    root = root.resolve()
    base = readme.resolve().parent
    units = exercise_units(root)
    link = lambda path, text=None: f"[`{text or path.name}`]({_rel(path, base)})"  # noqa: E731
    rows: list[tuple[str, str]] = []
    lesson = _folders(root, "lessons").get(lesson_nn)
    exercise = _folders(root, "exercises").get(lesson_nn)
    if lesson is not None:
        if (lesson / "README.md").is_file() and (lesson / "README.md").resolve() != readme.resolve():
            rows.append(("lesson text", link(lesson / "README.md", f"lessons/{lesson.name}/README.md")))
        if (lesson / "main.cpp").is_file():
            program = [link(lesson / "main.cpp", "main.cpp") + " (the demonstration)"]
            program += [link(s, "studies/" + s.name) + f" (§{int(_STUDY.fullmatch(s.name).group(1))})"
                        for s in studies(lesson)]
            program += [link(h, _rel(h, lesson)) + " (helpers)" for h in helpers(lesson)]
            rows.append((f"program `lesson{lesson_nn}`", " · ".join(program)))
    pairs = library_pairs(root, lesson_nn)
    if pairs:
        cells = []
        lib = root / "lib" / "illum"
        for header in pairs:
            name = _rel(header, lib)
            cell = link(header, name)
            source = header.with_suffix(".cpp")
            if source.name in units:
                cell += " (exercise unit)"
            elif source.is_file():
                cell += " · " + link(source, ".cpp")
            cells.append(cell)
        rows.append(("library", "<br>".join(cells)))
    if exercise is not None:
        files = [link(exercise / "README.md", f"exercises/{exercise.name}/README.md")] if (
            exercise / "README.md").resolve() != readme.resolve() else []
        files += [link(stub, stub.name) for stub in sorted(exercise.glob("*.cpp"))]
        rows.append(("exercise", " · ".join(files)))
    own, others = test_files(root, lesson_nn, pairs)
    if own or others:
        cell = " · ".join(link(t, f"tests/{t.parent.name}/{t.name}") for t in own)
        if own:
            cell += f" (suite `lesson{lesson_nn}` and its hard cases)"
        if others:
            cell += ("; " if own else "") + "also " + " · ".join(
                link(t, f"tests/{t.parent.name}/{t.name}") for t in others)
        rows.append(("tests", cell))
    decks = sorted((root / "slides").glob(f"{lesson_nn}_*.md")) if (root / "slides").is_dir() else []
    if decks:
        rows.append(("slides", " · ".join(link(d, f"slides/{d.name}") for d in decks)
                     + f" (built to `out/slides/{decks[0].stem}.html`)"))
    body = "\n".join(f"| {what} | {where} |" for what, where in rows)
    return f"{BEGIN}\n| what | where |\n|---|---|\n{body}\n{END}"


def deck_slide(root: Path, lesson_nn: str) -> str:
    """The Markdown of the last slide of lesson NN's deck, "Where the code is": the same sources as
    the texts' block (code_map), in a few lines that fit a slide. Links are relative to
    out/slides/, where the deck is built (slides/README.md)."""
    root = root.resolve()
    base = root / "out" / "slides"
    link = lambda path, text: f"[{text}]({_rel(path, base)})"  # noqa: E731
    lines = []
    lesson = _folders(root, "lessons").get(lesson_nn)
    exercise = _folders(root, "exercises").get(lesson_nn)
    if lesson is not None and (lesson / "README.md").is_file():
        lines.append(f"- **Text:** {link(lesson / 'README.md', f'`lessons/{lesson.name}/README.md`')}")
    if exercise is not None:
        stubs = sorted(exercise.glob("*.cpp"))
        units = [next(iter(sorted((root / "lib" / "illum").rglob(s.stem + ".hpp"))), None) for s in stubs]
        you_write = ", ".join(link(s, f"`{s.name}`") for s in stubs)
        contracts = ", ".join(link(h, f"`{_rel(h, root / 'lib' / 'illum')}`") for h in units if h is not None)
        lines.append(f"- **Exercise:** {link(exercise / 'README.md', f'`exercises/{exercise.name}/`')}: "
                     f"you write {you_write}; the contracts are in {contracts}")
    if lesson is not None and (lesson / "main.cpp").is_file():
        program = link(lesson / "main.cpp", f"`lessons/{lesson.name}/main.cpp`")
        studies_note = " and `studies/` (one file per study, numbered by its section)" if studies(lesson) else ""
        lines.append(f"- **Program** `lesson{lesson_nn}`: {program}{studies_note}")
    tests = _folders(root, "tests").get(lesson_nn)
    if tests is not None:
        lines.append(f"- **Tests:** {link(tests, f'`tests/{tests.name}/`')} (suite `lesson{lesson_nn}`): "
                     f"`tools/grade --student {lesson_nn}`")
    body = "\n".join(lines)
    return f"{BEGIN}\n## Where the code is\n\n{body}\n{END}"


def decks(root: Path) -> list[tuple[str, Path]]:
    """(NN, deck) of every lesson's slide deck."""
    slides = root / "slides"
    if not slides.is_dir():
        return []
    return [(d.name[:2], d) for d in sorted(slides.glob("[0-9][0-9]_*.md"))]


def replace_block(text: str, block: str) -> str | None:
    start, stop = text.find(BEGIN), text.find(END)
    if start == -1 or stop == -1:
        return None
    return text[:start] + block + text[stop + len(END):]


def readmes(root: Path) -> list[tuple[str, Path]]:
    """(NN, README) of every lesson text and exercise README that must hold a code map."""
    found = []
    for kind in ("lessons", "exercises"):
        for nn, folder in _folders(root, kind).items():
            if (folder / "README.md").is_file() and (kind == "exercises" or (folder / "main.cpp").is_file()):
                found.append((nn, folder / "README.md"))
    return found


def update(root: Path, write: bool) -> list[str]:
    """Rewrites (write=True) or checks every code map, in the texts and as each deck's last slide;
    returns the problems (stale or missing blocks)."""
    problems = []
    for nn, deck in decks(root):
        text = deck.read_text(encoding="utf-8")
        block = deck_slide(root, nn)
        new = replace_block(text, block)
        if new is None and write:  # the first time: the deck's last slide
            new = text.rstrip("\n") + "\n\n---\n\n" + block + "\n"
        relative = _rel(deck, root)
        if new is None:
            problems.append(f"{relative}: no \"Where the code is\" slide at its end ({BEGIN} … {END}); "
                            "run tools/task_tables.py --update")
        elif new != text:
            if write:
                deck.write_text(new, encoding="utf-8")
            else:
                problems.append(f"{relative}: the \"Where the code is\" slide is not current; "
                                "run tools/task_tables.py --update")
        elif not text.rstrip().endswith(END):
            problems.append(f"{relative}: the \"Where the code is\" slide must be the deck's last")
    for nn, readme in readmes(root):
        text = readme.read_text(encoding="utf-8")
        new = replace_block(text, code_map(root, nn, readme))
        relative = _rel(readme, root)
        if new is None:
            problems.append(f"{relative}: no \"Where the code is\" block ({BEGIN} … {END})")
        elif new != text:
            if write:
                readme.write_text(new, encoding="utf-8")
            else:
                problems.append(f"{relative}: the \"Where the code is\" block is not current; "
                                "run tools/task_tables.py --update")
    return problems


# --- the layout's rules ----------------------------------------------------------------------


def layout_problems(root: Path) -> list[str]:
    """Every rule of the lesson layout a lesson breaks, one line each (file:line where there is one):

    * studies/sMM[x]_<name>.cpp: README.md has a section "## M."; the file opens with
      "// §M <title>" agreeing with that heading; it defines sMM_<name>(…);
    * every "§M <title>" label in main.cpp and the studies (run_section's banners and
      timing labels) names a section of README.md and agrees with its heading;
    * README.md opens (before its first section) with the reading list, which links
      main.cpp, every study in file-name order, and the header of every exercise unit;
      every local link of the list resolves.
    """
    problems = []
    units_by_lesson = {nn: [s.stem for s in sorted(f.glob("*.cpp"))] for nn, f in _folders(root, "exercises").items()}
    for nn, lesson in lesson_programs(root).items():
        readme = lesson / "README.md"
        if not readme.is_file():
            problems.append(f"{_rel(lesson, root)}: no README.md")
            continue
        text = readme.read_text(encoding="utf-8")
        heads = sections(text)
        for study in studies(lesson):
            where = _rel(study, root)
            match = _STUDY.fullmatch(study.name)
            number = int(match.group(1))
            if number not in heads:
                problems.append(f"{where}: README.md has no section \"## {number}.\" for this study")
                continue
            source = study.read_text(encoding="utf-8")
            first = source.splitlines()[0] if source else ""
            banner = re.match(r"^// §(\d+) (.+)$", first)
            if not banner or int(banner.group(1)) != number or not _agrees(banner.group(2), heads[number]):
                problems.append(f"{where}:1: the first line must be \"// §{number} <title>\" agreeing with "
                                f"README.md's \"## {number}. {heads[number]}\"")
            if not re.search(rf"\b{re.escape(study.stem)}\s*\(", source):
                problems.append(f"{where}: defines no function {study.stem}(…), the study's entry point")
        for source in [lesson / "main.cpp", *studies(lesson)]:
            for number_line, line in enumerate(source.read_text(encoding="utf-8").splitlines(), start=1):
                for match in _SECTION_LABEL.finditer(line):
                    number = int(match.group(1))
                    if number not in heads:
                        problems.append(f"{_rel(source, root)}:{number_line}: label \"§{number} {match.group(2)}\" "
                                        f"names no section of README.md")
                    elif not _agrees(match.group(2), heads[number]):
                        problems.append(f"{_rel(source, root)}:{number_line}: label \"§{number} {match.group(2)}\" "
                                        f"does not agree with README.md's \"## {number}. {heads[number]}\"")
        found = reading_list(text)
        where = _rel(readme, root)
        if found is None:
            problems.append(f"{where}: the text must open (before its first section) with \"{READ_IN_ORDER}\" "
                            "and a list: the library pairs, main.cpp, the studies")
            continue
        line, targets = found
        resolved = [(lesson / t).resolve() for t in targets if not re.match(r"^[a-z]+:", t)]
        for target, path in zip(targets, resolved):
            if not path.exists():
                problems.append(f"{where}:{line + 1}: the reading list links {target}, which does not exist")
        if (lesson / "main.cpp").resolve() not in resolved:
            problems.append(f"{where}:{line + 1}: the reading list does not link main.cpp")
        listed = [p for p in resolved if p.parent == (lesson / "studies").resolve()]
        wanted = [s.resolve() for s in studies(lesson)]
        if listed != wanted:
            problems.append(f"{where}:{line + 1}: the reading list must link the studies in file-name order: "
                            + ", ".join(_rel(s, lesson) for s in wanted))
        for unit in units_by_lesson.get(nn, []):
            headers = sorted((root / "lib" / "illum").rglob(unit + ".hpp"))
            if headers and headers[0].resolve() not in resolved:
                problems.append(f"{where}:{line + 1}: the reading list does not link {_rel(headers[0], root)}, "
                                "the header of an exercise unit of this lesson")
        units = exercise_units(root)
        for target, path in zip(targets, resolved):
            if path.suffix == ".cpp" and path.name in units and (root / "lib").resolve() in path.parents:
                problems.append(f"{where}:{line + 1}: the reading list links {target}, a reference unit that "
                                "the student edition leaves out; link its header")
    return problems
