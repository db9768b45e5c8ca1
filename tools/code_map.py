"""The lesson layout and its "Where the code is" blocks (docs/architecture.md, "Lesson programs"): the
generated block of every lesson text and exercise README, the same block as the last slide of every deck
(deck_slide), and layout_problems. tools/task_tables.py --update writes the blocks; --check checks them.
"""

import itertools
import os
import re
from pathlib import Path

from grading.project import exercise_stubs, lesson_folders

BEGIN = "<!-- code-map: begin (written by tools/task_tables.py --update) -->"
END = "<!-- code-map: end -->"
READ_IN_ORDER = "**Read in this order:**"

_LINK = re.compile(r"\[[^\]]*\]\(([^)\s#]+)(?:#[^)]*)?\)")
_STUDY = re.compile(r"s(\d\d)([a-z]?)_([a-z0-9_]+)\.cpp")
_SECTION_LABEL = re.compile(r'"§(\d+) ([^"]*)"')


def _rel(path: Path, start: Path) -> str:
    return Path(os.path.relpath(path, start)).as_posix()


def unit_header(root: Path, stem: str) -> Path | None:
    """lib/illum/<area>/STEM.hpp: the header of the unit STEM.cpp (the first by path if several), or None."""
    return min((root / "lib" / "illum").rglob(stem + ".hpp"), default=None)


def studies(lesson: Path) -> list[Path]:
    return sorted(s for s in (lesson / "studies").glob("s[0-9][0-9]*.cpp") if _STUDY.fullmatch(s.name))


def helpers(lesson: Path) -> list[Path]:
    """The headers beside main.cpp, a source beside it without a header, and studies/studies.hpp."""
    return (sorted(lesson.glob("*.hpp")) + [s for s in sorted(lesson.glob("*.cpp")) if s.name != "main.cpp"
                                            and not s.with_suffix(".hpp").is_file()]
            + [h for h in [lesson / "studies" / "studies.hpp"] if h.is_file()])


def sections(readme_text: str) -> dict[int, str]:
    """Section number -> the plain text of its "## N. Title" heading (links to their words, marks dropped)."""
    plain = lambda text: re.sub(r"[*`_]", "", re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)).strip()  # noqa: E731
    return {int(m.group(1)): plain(m.group(2)) for m in re.finditer(r"^## (\d+)\. (.+)$", readme_text, re.M)}


def _agrees(label: str, heading: str) -> bool:
    """One begins with the other, or the label with the heading's lead (before ':' or '—'), case aside."""
    label, heading = label.strip().rstrip(".").lower(), heading.strip().lower()
    lead = re.split(r"[:—]", heading, maxsplit=1)[0].strip()
    return label.startswith(heading) or heading.startswith(label) or (bool(lead) and label.startswith(lead))


def reading_list(readme_text: str) -> tuple[int, list[str]] | None:
    """(line index of READ_IN_ORDER, the link targets of the paragraph after it), or None when the text
    has none before its first section."""
    lines = readme_text.splitlines()
    for k, line in enumerate(lines):
        if line.startswith("## "):
            return None
        if line.strip() == READ_IN_ORDER:
            after = itertools.dropwhile(lambda text: not text.strip(), lines[k + 1:])
            paragraph = itertools.takewhile(lambda text: text.strip() and not text.startswith("#"), after)
            return k, [target for text in paragraph for target in _LINK.findall(text)]
    return None


def _folders(root: Path, lesson_nn: str) -> tuple[Path | None, Path | None]:
    """(lessons/NN_topic, exercises/NN_topic), either None when missing."""
    return lesson_folders(root, "lessons").get(lesson_nn), lesson_folders(root, "exercises").get(lesson_nn)


def library_pairs(root: Path, lesson_nn: str) -> list[Path]:
    """The lib/ headers of a lesson's code map: those its reading list links, then its exercise units'."""
    lesson, exercise = _folders(root, lesson_nn)
    found = reading_list((lesson / "README.md").read_text(encoding="utf-8")) \
        if lesson is not None and (lesson / "README.md").is_file() else None
    linked = [(lesson / t).resolve().with_suffix(".hpp") for t in (found[1] if found else [])
              if Path(t).suffix in (".hpp", ".cpp")]
    units = [unit_header(root, stub.stem) for stub in sorted(exercise.glob("*.cpp"))] if exercise else []
    return list(dict.fromkeys([h for h in linked if (root / "lib").resolve() in h.parents and h.is_file()]
                              + [h.resolve() for h in units if h is not None]))


def _tests_cell(root: Path, lesson_nn: str, pairs: list[Path], link) -> str:
    """The lesson's own test files, then tests elsewhere named after one of its library pairs ('' if none)."""
    lessons = lesson_folders(root, "tests")
    own = sorted(lessons[lesson_nn].glob("*.cpp")) if lesson_nn in lessons else []
    others = [f for f in sorted((root / "tests").glob("*/*.cpp")) if f.stem in {p.stem for p in pairs}
              and f.parent not in lessons.values() and f.parent.name != "hidden"]
    name = lambda t: link(t, f"tests/{t.parent.name}/{t.name}")  # noqa: E731
    suites = dict.fromkeys(s for t in own for s in re.findall(r'TEST_SUITE\("([^"]+)"\)', t.read_text()))
    cell = " · ".join(name(t) for t in own)
    if suites:
        graded_first = sorted(suites, key=lambda s: not s.startswith(f"lesson{lesson_nn}"))
        cell += f" (suite{'s' if len(suites) > 1 else ''} " + ", ".join(f"`{s}`" for s in graded_first) + ")"
    if others:
        cell += ("; " if own else "") + "also " + " · ".join(name(t) for t in others)
    return cell


def code_map(root: Path, lesson_nn: str, readme: Path) -> str:
    """The Markdown of lesson NN's "Where the code is" block as seen from `readme`."""
    root, readme = root.resolve(), readme.resolve()
    link = lambda path, text=None: f"[`{text or path.name}`]({_rel(path, readme.parent)})"  # noqa: E731
    rows: list[tuple[str, str]] = []
    lesson, exercise = _folders(root, lesson_nn)
    if lesson is not None and (lesson / "README.md").is_file() and (lesson / "README.md").resolve() != readme:
        rows.append(("lesson text", link(lesson / "README.md", f"lessons/{lesson.name}/README.md")))
    if lesson is not None and (lesson / "main.cpp").is_file():
        rows.append((f"program `lesson{lesson_nn}`", " · ".join(
            [link(lesson / "main.cpp", "main.cpp") + " (the demonstration)"]
            + [link(s, "studies/" + s.name) + f" (§{int(_STUDY.fullmatch(s.name).group(1))})" for s in studies(lesson)]
            + [link(h, _rel(h, lesson)) + " (helpers)" for h in helpers(lesson)])))
    units, cells = exercise_stubs(root), []
    for header in (pairs := library_pairs(root, lesson_nn)):
        source = header.with_suffix(".cpp")
        cells.append(link(header, _rel(header, root / "lib" / "illum"))
                     + (" (exercise unit)" if source.name in units else
                        " · " + link(source, ".cpp") if source.is_file() else ""))
    if cells:
        rows.append(("library", "<br>".join(cells)))
    if exercise is not None:
        own_readme = (exercise / "README.md").resolve() == readme
        rows.append(("exercise", " · ".join(
            ([] if own_readme else [link(exercise / "README.md", f"exercises/{exercise.name}/README.md")])
            + [link(stub, stub.name) for stub in sorted(exercise.glob("*.cpp"))])))
    if tests := _tests_cell(root, lesson_nn, pairs, link):
        rows.append(("tests", tests))
    if decks := sorted((root / "slides").glob(f"{lesson_nn}_*.md")):
        rows.append(("slides", " · ".join(link(d, f"slides/{d.name}") for d in decks)
                     + f" (built to `out/slides/{decks[0].stem}.html`)"))
    body = "\n".join(f"| {what} | {where} |" for what, where in rows)
    return f"{BEGIN}\n| what | where |\n|---|---|\n{body}\n{END}"


def deck_slide(root: Path, lesson_nn: str) -> str:
    """The last slide of lesson NN's deck, "Where the code is": the sources of the texts' block in a few
    lines that fit a slide, linked from out/slides/, where the deck is built (slides/README.md)."""
    root = root.resolve()
    link = lambda path, text: f"[{text}]({_rel(path, root / 'out' / 'slides')})"  # noqa: E731
    lines = []
    lesson, exercise = _folders(root, lesson_nn)
    if lesson is not None and (lesson / "README.md").is_file():
        lines.append(f"- **Text:** {link(lesson / 'README.md', f'`lessons/{lesson.name}/README.md`')}")
    if exercise is not None:
        stubs = sorted(exercise.glob("*.cpp"))
        you_write = ", ".join(link(s, f"`{s.name}`") for s in stubs)
        contracts = ", ".join(link(h, f"`{_rel(h, root / 'lib' / 'illum')}`")
                              for h in (unit_header(root, s.stem) for s in stubs) if h is not None)
        lines.append(f"- **Exercise:** {link(exercise / 'README.md', f'`exercises/{exercise.name}/`')}: "
                     f"you write {you_write}; the contracts are in {contracts}")
    if lesson is not None and (lesson / "main.cpp").is_file():
        studies_note = " and `studies/` (one file per study, numbered by its section)" if studies(lesson) else ""
        main = link(lesson / "main.cpp", f"`lessons/{lesson.name}/main.cpp`")
        lines.append(f"- **Program** `lesson{lesson_nn}`: {main}{studies_note}")
    if (tests := lesson_folders(root, "tests").get(lesson_nn)) is not None:
        lines.append(f"- **Tests:** {link(tests, f'`tests/{tests.name}/`')} (graded: suite `lesson{lesson_nn}`): "
                     f"`tools/grade --student {lesson_nn}`")
    return f"{BEGIN}\n## Where the code is\n\n" + "\n".join(lines) + f"\n{END}"


def replace_between(text: str, begin: str, end: str, block: str) -> str | None:
    """`text` with what lies between `begin` and `end` (both included) replaced by `block`; None without them."""
    start, stop = text.find(begin), text.find(end)
    return None if start == -1 or stop == -1 else text[:start] + block + text[stop + len(end):]


def refresh(path: Path, root: Path, text: str, new: str | None, write: bool, block: str, markers: str) -> list[str]:
    """Writes `new`, the file's `text` with its generated `block` rewritten, when `write` is True and it differs;
    otherwise the problem: the block's `markers` missing (`new` is None) or the block not current."""
    where = _rel(path, root)
    if new is None:
        return [f"{where}: no {block} {markers}; run tools/task_tables.py --update"]
    if new != text and write:
        path.write_text(new, encoding="utf-8")
        print(f"updated {where}")
    elif new != text:
        return [f"{where}: the {block} is not current; run tools/task_tables.py --update"]
    return []


def update(root: Path, write: bool) -> list[str]:
    """Rewrites (write=True) or checks the code map of every lesson text and exercise README, and the
    slide that ends every deck; returns the problems (stale or missing blocks)."""
    problems = []
    for deck in sorted((root / "slides").glob("[0-9][0-9]_*.md")):
        text, block = deck.read_text(encoding="utf-8"), deck_slide(root, deck.name[:2])
        new = replace_between(text, BEGIN, END, block)
        if new is None and write:  # the first time: the deck's last slide
            new = text.rstrip("\n") + "\n\n---\n\n" + block + "\n"
        problems += refresh(deck, root, text, new, write, "\"Where the code is\" slide",
                            f"at its end ({BEGIN} … {END})")
        if new == text and not text.rstrip().endswith(END):
            problems.append(f"{_rel(deck, root)}: the \"Where the code is\" slide must be the deck's last")
    for kind in ("lessons", "exercises"):
        for nn, folder in lesson_folders(root, kind).items():
            readme = folder / "README.md"
            if not readme.is_file() or (kind == "lessons" and not (folder / "main.cpp").is_file()):
                continue
            text = readme.read_text(encoding="utf-8")
            new = replace_between(text, BEGIN, END, code_map(root, nn, readme))
            problems += refresh(readme, root, text, new, write, "\"Where the code is\" block", f"({BEGIN} … {END})")
    return problems


def _study_problems(root: Path, lesson: Path, heads: dict[int, str]) -> list[str]:
    """Each study: a section "## M." of README.md, a first line "// §M <title>" agreeing with it, and a
    function sMM_<name>(…)."""
    problems = []
    for study in studies(lesson):
        where, number = _rel(study, root), int(_STUDY.fullmatch(study.name).group(1))
        if number not in heads:
            problems.append(f"{where}: README.md has no section \"## {number}.\" for this study")
            continue
        source = study.read_text(encoding="utf-8")
        banner = re.match(r"^// §(\d+) (.+)$", source.splitlines()[0] if source else "")
        if not banner or int(banner.group(1)) != number or not _agrees(banner.group(2), heads[number]):
            problems.append(f"{where}:1: the first line must be \"// §{number} <title>\" agreeing with "
                            f"README.md's \"## {number}. {heads[number]}\"")
        if not re.search(rf"\b{re.escape(study.stem)}\s*\(", source):
            problems.append(f"{where}: defines no function {study.stem}(…), the study's entry point")
    for source in [lesson / "main.cpp", *studies(lesson)]:  # run_section's banners and timing labels
        for number_line, line in enumerate(source.read_text(encoding="utf-8").splitlines(), start=1):
            for match in _SECTION_LABEL.finditer(line):
                number = int(match[1])
                where = f"{_rel(source, root)}:{number_line}: label \"§{match[1]} {match[2]}\""
                if number not in heads:
                    problems.append(f"{where} names no section of README.md")
                elif not _agrees(match.group(2), heads[number]):
                    problems.append(f"{where} does not agree with README.md's \"## {number}. {heads[number]}\"")
    return problems


def _reading_list_problems(root: Path, lesson: Path, text: str, units: list[str]) -> list[str]:
    """The reading list opens the text and links main.cpp, every study in file-name order and every
    exercise unit's header (never the reference unit itself), each link resolving."""
    where = _rel(lesson / "README.md", root)
    if (found := reading_list(text)) is None:
        return [f"{where}: the text must open (before its first section) with \"{READ_IN_ORDER}\" and a list: "
                "the library pairs, main.cpp, the studies"]
    where, targets = f"{where}:{found[0] + 1}", found[1]
    resolved = [(lesson / t).resolve() for t in targets if not re.match(r"^[a-z]+:", t)]
    problems = [f"{where}: the reading list links {t}, which does not exist" for t, p in zip(targets, resolved)
                if not p.exists()]
    if (lesson / "main.cpp").resolve() not in resolved:
        problems.append(f"{where}: the reading list does not link main.cpp")
    wanted = [s.resolve() for s in studies(lesson)]
    if [p for p in resolved if p.parent == (lesson / "studies").resolve()] != wanted:
        problems.append(f"{where}: the reading list must link the studies in file-name order: "
                        + ", ".join(_rel(s, lesson) for s in wanted))
    problems += [f"{where}: the reading list does not link {_rel(header, root)}, the header of an exercise unit of "
                 "this lesson" for header in (unit_header(root, unit) for unit in units)
                 if header is not None and header.resolve() not in resolved]
    every_unit = exercise_stubs(root)
    return problems + [f"{where}: the reading list links {t}, a reference unit that the student edition leaves "
                       "out; link its header" for t, p in zip(targets, resolved)
                       if p.suffix == ".cpp" and p.name in every_unit and (root / "lib").resolve() in p.parents]


def layout_problems(root: Path) -> list[str]:
    """Every rule of the lesson layout a lesson breaks, one line each (file:line where there is one)."""
    problems = []
    units = {nn: [s.stem for s in sorted(f.glob("*.cpp"))] for nn, f in lesson_folders(root, "exercises").items()}
    for nn, lesson in lesson_folders(root, "lessons").items():
        if not (lesson / "main.cpp").is_file():
            continue
        if not (lesson / "README.md").is_file():
            problems.append(f"{_rel(lesson, root)}: no README.md")
            continue
        text = (lesson / "README.md").read_text(encoding="utf-8")
        problems += _study_problems(root, lesson, sections(text))
        problems += _reading_list_problems(root, lesson, text, units.get(nn, []))
    return problems
