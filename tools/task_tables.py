#!/usr/bin/env python3
"""Which grading tests grade which task: tagged in the tests, tabled in the READMEs.

Every grading test (suite ``lessonNN``) names the tasks it needs in its
doctest description, beside its points if any:

    TEST_CASE("winding: …" * doctest::description("task=1,2"))
    TEST_CASE("…" * doctest::description("points=2 task=7"))

A task is a ``// Task N.`` comment of a stub in ``exercises/NN_topic/`` (``N``
may carry a letter: ``Task 6a``); a test needs the tasks whose functions it
reaches, directly or through other code. Each exercise README holds the table
written from those tags between the markers

    <!-- task-table: begin (written by tools/task_tables.py --update) -->
    <!-- task-table: end -->

Every lesson text and exercise README also holds a "Where the code is" block
(tools/code_map.py: the lesson's program and studies, library pairs, exercise
files, tests and deck, as links), and --check holds every lesson program to
the layout code_map.layout_problems states (studies numbered by the sections
that quote them, labels that agree with the headings, a reading list).

Commands:

    tools/task_tables.py --update          # rewrite every README's table and code map
    tools/task_tables.py --check           # CI: every grading test tagged, every tag a task of
                                           # its lesson, every task graded, every table current
    tools/task_tables.py --check --build-dir build/release
                                           # also: on the stubs, each test first stops in a
                                           # function of a task it names (tests_lessonNN_stubs)
    tools/task_tables.py --derive NN --build-dir build/release [--write]
                                           # find the tags: run each test on the reference with
                                           # the lesson's units compiled -finstrument-functions
                                           # and record which task functions it enters

A lesson without exercises or without tests is skipped (a lesson being
written has neither yet).
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

BEGIN = "<!-- task-table: begin (written by tools/task_tables.py --update) -->"
END = "<!-- task-table: end -->"
_TASK_COMMENT = re.compile(r"^// Task (\d+[a-z]?)\.", re.M)
_TAG = re.compile(r"\btask\s*=\s*([0-9a-z,]+)")
_LESSON_DIR = re.compile(r"(\d\d)_.+")


# --- the tasks of a lesson, from its stubs ---------------------------------------------------


def stub_tasks(exercise: Path) -> dict[str, list[str]]:
    """Task id -> the functions (NotImplemented labels) of its stub block, in the order of the stubs."""
    tasks: dict[str, list[str]] = {}
    for stub in sorted(exercise.glob("*.cpp")):
        text = stub.read_text(encoding="utf-8")
        marks = list(_TASK_COMMENT.finditer(text))
        for k, mark in enumerate(marks):
            block = text[mark.start(): marks[k + 1].start() if k + 1 < len(marks) else len(text)]
            labels = re.findall(r'NotImplemented\(\s*"([^"]+)"', block)
            tasks.setdefault(mark.group(1), []).extend(labels)
    return dict(sorted(tasks.items(), key=lambda item: _task_key(item[0])))


def _task_key(task: str) -> tuple[int, str]:
    match = re.fullmatch(r"(\d+)([a-z]?)", task)
    return (int(match.group(1)), match.group(2)) if match else (10**6, task)


# --- the grading tests, from the sources -----------------------------------------------------


@dataclass
class TestCase:
    name: str
    file: Path
    line: int
    suite: str
    description: str
    start: int  # offset of TEST_CASE( in the file
    end: int    # offset just past its closing parenthesis

    @property
    def tasks(self) -> list[str]:
        match = _TAG.search(self.description)
        return [t for t in match.group(1).split(",") if t] if match else []


def _skip_string(text: str, i: int) -> int:
    """Index just past the string or character literal starting at text[i]."""
    quote = text[i]
    if quote == '"' and text[max(0, i - 1)] == "R":  # raw string R"d(…)d"
        open_paren = text.index("(", i)
        delimiter = text[i + 1:open_paren]
        return text.index(")" + delimiter + '"', open_paren) + len(delimiter) + 2
    i += 1
    while text[i] != quote:
        i += 2 if text[i] == "\\" else 1
    return i + 1


def _literals(text: str) -> list[str]:
    """The contents of the string literals in ``text``, escapes undone for \\" and \\\\."""
    out = []
    for match in re.finditer(r'"((?:[^"\\]|\\.)*)"', text):
        out.append(re.sub(r"\\(.)", r"\1", match.group(1)))
    return out


def parse_tests(source: Path) -> list[TestCase]:
    """Every TEST_CASE of a file with its suite (the enclosing TEST_SUITE block)."""
    text = source.read_text(encoding="utf-8")
    tests: list[TestCase] = []
    suites: list[tuple[str, int]] = []  # (name, brace depth inside its block)
    depth = 0
    i = 0
    pending_suite: str | None = None
    while i < len(text):
        c = text[i]
        if text.startswith("//", i):
            i = text.find("\n", i) if text.find("\n", i) != -1 else len(text)
            continue
        if text.startswith("/*", i):
            i = text.index("*/", i) + 2
            continue
        if c in "\"'":
            if c == "'" and i > 0 and (text[i - 1].isalnum()):  # digit separator 1'000
                i += 1
                continue
            i = _skip_string(text, i)
            continue
        if c == "{":
            depth += 1
            if pending_suite is not None:
                suites.append((pending_suite, depth))
                pending_suite = None
        elif c == "}":
            if suites and suites[-1][1] == depth:
                suites.pop()
            depth -= 1
        elif text.startswith("TEST_SUITE(", i) and not text[i - 1:i].isalnum():
            close = _matching_paren(text, i + len("TEST_SUITE"))
            names = _literals(text[i:close])
            pending_suite = names[0] if names else ""
            i = close + 1
            continue
        elif text.startswith("TEST_CASE(", i) and not text[i - 1:i].isalnum() and not text[i - 1:i] == "_":
            close = _matching_paren(text, i + len("TEST_CASE"))
            inside = text[i + len("TEST_CASE("):close]
            name_part = re.split(r"\*\s*doctest::", inside, maxsplit=1)[0]
            description = ""
            match = re.search(r'doctest::description\(\s*"([^"]*)"\s*\)', inside)
            if match:
                description = match.group(1)
            tests.append(TestCase(name="".join(_literals(name_part)), file=source,
                                  line=text.count("\n", 0, i) + 1, suite=suites[-1][0] if suites else "",
                                  description=description, start=i, end=close + 1))
            i = close + 1
            continue
        i += 1
    return tests


def _matching_paren(text: str, open_index: int) -> int:
    depth = 0
    i = open_index
    while True:
        c = text[i]
        if c in "\"'" and not (c == "'" and text[i - 1].isalnum()):
            i = _skip_string(text, i)
            continue
        if c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
            if depth == 0:
                return i
        i += 1


def lesson_folders(root: Path, kind: str) -> dict[str, Path]:
    found = {}
    folder = root / kind
    if folder.is_dir():
        for child in sorted(folder.iterdir()):
            match = _LESSON_DIR.fullmatch(child.name)
            if match and child.is_dir():
                found[match.group(1)] = child
    return found


def grading_tests(root: Path, lesson: str) -> list[TestCase]:
    folder = lesson_folders(root, "tests").get(lesson)
    if folder is None:
        return []
    return [t for source in sorted(folder.glob("*.cpp")) for t in parse_tests(source) if t.suite == f"lesson{lesson}"]


# --- the table -------------------------------------------------------------------------------


def _points(test: TestCase) -> float:
    match = re.search(r"\bpoints\s*=\s*([0-9.]+)", test.description)
    return float(match.group(1)) if match else 1.0


def _escape(text: str) -> str:
    """A test name as a table cell: pipes escaped, and each 'erratum N' linked to the
    project's errata list, as every text that names an erratum does (tools/figures.py --check)."""
    text = text.replace("|", "\\|")
    return re.sub(r"\berratum (\d+)\b", r"[erratum \1](../../docs/errata.md#erratum-\1)", text)


def table(lesson: str, tasks: dict[str, list[str]], tests: list[TestCase], root: Path) -> str:
    """The Markdown of the task table: one row per test, the tasks it needs, its points."""
    lines = [BEGIN,
             f"| test (suite `lesson{lesson}`) | tasks it needs | points |",
             "|---|---|---|"]
    ordered = sorted(tests, key=lambda t: (min((_task_key(x) for x in t.tasks), default=(10**6, "")),
                                           len(t.tasks), t.file.name, t.line))
    for test in ordered:
        points = _points(test)
        lines.append(f"| {_escape(test.name)} | {', '.join(test.tasks)} | {points:g} |")
    total = sum(_points(t) for t in tests)
    per_task = []
    for task in tasks:
        graded = [t for t in tests if task in t.tasks]
        per_task.append(f"Task {task}: {len(graded)}")
    lines.append("")
    lines.append(f"{len(tests)} tests, {total:g} points. A test passes only when every task it needs "
                 f"is written. Tests per task — {'; '.join(per_task)}.")
    lines.append(END)
    return "\n".join(lines)


def replace_table(readme_text: str, new_table: str) -> str | None:
    """The README with its table replaced, or None when it has no markers."""
    start, end = readme_text.find(BEGIN), readme_text.find(END)
    if start == -1 or end == -1:
        return None
    return readme_text[:start] + new_table + readme_text[end + len(END):]


# --- the student commands -----------------------------------------------------------------------

COMMANDS_BEGIN = "<!-- student-commands: begin (written by tools/task_tables.py --update) -->"
COMMANDS_END = "<!-- student-commands: end -->"


def student_commands(lesson: str, has_program: bool = True) -> str:
    """The one set of build commands a student types, for lesson ``lesson`` ("NN" in the top README)."""
    targets = f"tests_lesson{lesson}" + (f" lesson{lesson}" if has_program else "")
    rows = [("cmake --preset student", "once: configure build/student with your exercises"),
            (f"cmake --build --preset student --target {targets}", "build your code, its tests"
             + (" and the lesson program" if has_program else "")),
            (f"build/student/bin/tests_lesson{lesson} -ts=lesson{lesson}", "the grading tests, with their explanations")]
    if has_program:
        rows.append((f"build/student/bin/lesson{lesson} --out out/lesson{lesson}", "the lesson's pictures, drawn by your code"))
    rows.append((f"tools/grade --student {lesson}", "your score, as the autograder computes it"))
    width = max(len(command) for command, _ in rows) + 2
    body = "\n".join(f"{command.ljust(width)}# {why}" for command, why in rows)
    return f"{COMMANDS_BEGIN}\n```sh\n{body}\n```\n{COMMANDS_END}"


def replace_between(text: str, begin: str, end: str, block: str) -> str | None:
    start, stop = text.find(begin), text.find(end)
    if start == -1 or stop == -1:
        return None
    return text[:start] + block + text[stop + len(end):]


def updated_readme(root: Path, lesson: str) -> tuple[Path, str, str | None]:
    """(README, its text, its text with the table and the commands rewritten, or None without markers)."""
    exercise = lesson_folders(root, "exercises")[lesson]
    readme = exercise / "README.md"
    text = readme.read_text(encoding="utf-8") if readme.is_file() else ""
    new = replace_table(text, table(lesson, stub_tasks(exercise), grading_tests(root, lesson), root))
    has_program = lesson in lesson_folders(root, "lessons")
    if new is not None:
        new = replace_between(new, COMMANDS_BEGIN, COMMANDS_END, student_commands(lesson, has_program))
    return readme, text, new


# --- checks ----------------------------------------------------------------------------------

# Every stub starts "// Lesson NN exercise: <what>." and then these two lines.
STUB_BANNER = ("// Replace each `throw NotImplemented(...)` with your code. The tasks, hints",
               "// and the tests that grade them are in README.md beside this file;")


def lessons_to_check(root: Path) -> list[str]:
    exercises, tests = lesson_folders(root, "exercises"), lesson_folders(root, "tests")
    return [nn for nn in exercises if nn in tests and any(exercises[nn].glob("*.cpp"))
            and grading_tests(root, nn)]


def source_problems(root: Path, lesson: str) -> list[str]:
    exercise = lesson_folders(root, "exercises")[lesson]
    tasks = stub_tasks(exercise)
    tests = grading_tests(root, lesson)
    problems = []
    if not tasks:
        problems.append(f"lesson {lesson}: no '// Task N.' comment in the stubs of {exercise.relative_to(root)}")
    for test in tests:
        where = f"{test.file.relative_to(root)}:{test.line}"
        if not test.tasks:
            problems.append(f"{where}: \"{test.name}\" has no task tag; add * doctest::description(\"task=N\")")
        for task in test.tasks:
            if task not in tasks:
                problems.append(f"{where}: \"{test.name}\" names task {task}, which no stub of lesson {lesson} "
                                f"has (tasks: {', '.join(tasks)})")
    for task in tasks:
        if not any(task in t.tasks for t in tests):
            problems.append(f"lesson {lesson}: Task {task} ({', '.join(tasks[task])}) is graded by no test")
    for stub in sorted(exercise.glob("*.cpp")):
        lines = stub.read_text(encoding="utf-8").splitlines()[:3]
        banner = [f"// Lesson {lesson} exercise: ", STUB_BANNER[0], STUB_BANNER[1]]
        if len(lines) < 3 or not lines[0].startswith(banner[0]) or lines[1] != banner[1] \
                or not lines[2].startswith(banner[2]):
            problems.append(f"{stub.relative_to(root)}: the banner must be \"{banner[0]}<what>.\" then "
                            f"\"{banner[1]}\" then \"{banner[2]}…\"")
        headers = sorted((root / "lib" / "illum").glob(f"*/{stub.stem}.hpp"))
        mark = f"// Exercise unit of lesson {lesson}: students write {stub.name}."
        if headers and mark not in headers[0].read_text(encoding="utf-8").splitlines()[:3]:
            problems.append(f"{headers[0].relative_to(root)}: the second line must be \"{mark}\"")
    readme, text, updated = updated_readme(root, lesson)
    if updated is None:
        problems.append(f"{readme.relative_to(root)}: no task table or student command markers "
                        f"({BEGIN} … {END}, {COMMANDS_BEGIN} … {COMMANDS_END})")
    elif updated != text:
        problems.append(f"{readme.relative_to(root)}: the task table or the build commands are not current; "
                        "run tools/task_tables.py --update")
    headings = re.findall(r"^## (.+)$", text, re.M)
    if headings[:4] != ["Build and test", "Tasks", "Hints", "Grading"]:
        problems.append(f"{readme.relative_to(root)}: the sections must be Build and test · Tasks · Hints · "
                        f"Grading (found: {' · '.join(headings)})")
    from grading.alone import declared_dependencies

    builds_on = next((line for line in text.splitlines() if line.startswith("**Builds on:**")), None)
    if builds_on is None:
        problems.append(f"{readme.relative_to(root)}: no \"**Builds on:**\" line naming the earlier exercises")
    else:
        for needed in declared_dependencies(lesson, root):
            if f"exercise {needed}" not in builds_on.lower() and f"exercises {needed}" not in builds_on.lower() \
                    and not re.search(rf"\b{needed}\b", builds_on):
                problems.append(f"{readme.relative_to(root)}: \"Builds on\" does not name exercise {needed}, "
                                "which depends.txt declares")
    return problems


def stub_problems(root: Path, lesson: str, build_dir: Path) -> list[str]:
    """On the stubs, a test first stops in the function of one of the tasks it names."""
    from grading.runner import run_suite

    program = build_dir / "bin" / f"tests_lesson{lesson}_stubs"
    if not program.is_file():
        return [f"{program} is missing; build it (or run without --build-dir)"]
    tasks = stub_tasks(lesson_folders(root, "exercises")[lesson])
    task_of = {label: task for task, labels in tasks.items() for label in labels}
    tagged = {t.name: t for t in grading_tests(root, lesson)}
    from grading.alone import declared_dependencies

    depends = declared_dependencies(lesson, root, program=False)
    lesson_of = {label: other for other, folder in lesson_folders(root, "exercises").items()
                 for labels in stub_tasks(folder).values() for label in labels}
    problems = []
    run = run_suite(program, f"lesson{lesson}")
    for result in run.results:
        test = tagged.get(result.name)
        if test is None:
            continue
        message = next((f.describe() for f in result.failures if f.not_implemented), "")
        match = re.search(r"NotImplemented: (.+?) — ", message)
        if match and match.group(1) in lesson_of and lesson_of[match.group(1)] in depends:
            continue  # a function of an earlier lesson this one declares it needs (depends.txt)
        if match and task_of.get(match.group(1)) not in test.tasks:
            problems.append(f"{test.file.relative_to(root)}:{test.line}: \"{test.name}\" is tagged task="
                            f"{','.join(test.tasks)} but first calls {match.group(1)} "
                            f"(Task {task_of.get(match.group(1), '?')})")
    return problems


# --- deriving the tags -----------------------------------------------------------------------

_PROBE = r"""
#include <stdio.h>
#include <stdlib.h>
#define SLOTS 4096
static void* seen[SLOTS];
static int count;
__attribute__((no_instrument_function)) static void dump(void) {
  const char* path = getenv("ILLUM_TASK_PROBE");
  if (!path) return;
  FILE* f = fopen(path, "w");
  if (!f) return;
  for (int i = 0; i < count; ++i) fprintf(f, "%p\n", seen[i]);
  fclose(f);
}
__attribute__((no_instrument_function)) void __cyg_profile_func_enter(void* fn, void* site) {
  (void)site;
  for (int i = 0; i < count; ++i)
    if (seen[i] == fn) return;
  if (count == 0) atexit(dump);
  if (count < SLOTS) seen[count++] = fn;
}
__attribute__((no_instrument_function)) void __cyg_profile_func_exit(void* fn, void* site) {
  (void)fn;
  (void)site;
}
"""


def _symbols(binary: Path) -> dict[int, str]:
    out = subprocess.run(["nm", "-C", "--defined-only", str(binary)], capture_output=True, text=True,
                         check=True).stdout
    table = {}
    for line in out.splitlines():
        parts = line.split(" ", 2)
        if len(parts) == 3 and parts[1] in "TtWw":
            table[int(parts[0], 16)] = parts[2]
    return table


def _task_symbols(root: Path, lesson: str, build_dir: Path, work: Path) -> dict[str, str]:
    """Demangled function name -> task, from the stubs compiled with -g (nm -l gives each line)."""
    exercise = lesson_folders(root, "exercises")[lesson]
    commands = {Path(e["file"]).resolve(): e for e in json.loads((build_dir / "compile_commands.json").read_text())}
    result = {}
    for stub in sorted(exercise.glob("*.cpp")):
        entry = commands[stub.resolve()]
        obj = work / (stub.name + ".stub.o")
        args = shlex.split(entry["command"])
        args[args.index("-o") + 1] = str(obj)
        subprocess.run(args + ["-g"], cwd=entry["directory"], check=True)
        text = stub.read_text(encoding="utf-8").splitlines()
        marks = [(k + 1, m.group(1)) for k, line in enumerate(text) if (m := _TASK_COMMENT.match(line))]
        listing = subprocess.run(["nm", "-C", "-l", "--defined-only", str(obj)], capture_output=True, text=True,
                                 check=True).stdout
        for line in listing.splitlines():
            match = re.match(r"[0-9a-f]+ [TW] (.+)\t(.+):(\d+)$", line)
            if not match or Path(match.group(2)).name != stub.name:
                continue
            number = int(match.group(3))
            task = next((t for start, t in reversed(marks) if start <= number), None)
            if task is not None:
                result[match.group(1)] = task
    return result


def derive(root: Path, lesson: str, build_dir: Path, write: bool) -> int:
    from grading.runner import list_suites

    exercise = lesson_folders(root, "exercises")[lesson]
    commands = {Path(e["file"]).resolve(): e for e in json.loads((build_dir / "compile_commands.json").read_text())}
    with tempfile.TemporaryDirectory(prefix=f"illum-tasks-{lesson}-") as folder:
        work = Path(folder)
        task_of_symbol = _task_symbols(root, lesson, build_dir, work)
        objects = []
        for stub in sorted(exercise.glob("*.cpp")):
            reference = next((root / "lib" / "illum").rglob(stub.name))
            entry = commands[reference.resolve()]
            obj = work / (stub.name + ".ref.o")
            args = shlex.split(entry["command"])
            args[args.index("-o") + 1] = str(obj)
            subprocess.run(args + ["-finstrument-functions"], cwd=entry["directory"], check=True)
            objects.append(str(obj))
        probe = work / "probe.c"
        probe.write_text(_PROBE)
        subprocess.run(["cc", "-O2", "-c", str(probe), "-o", str(work / "probe.o")], check=True)
        link_dir = build_dir / "tests"
        link = shlex.split((link_dir / "CMakeFiles" / f"tests_lesson{lesson}.dir" / "link.txt").read_text())
        program = work / "tests"
        link[link.index("-o") + 1] = str(program)
        link.insert(1, "-no-pie")  # addresses as nm prints them
        link[link.index(str(program)) + 1:link.index(str(program)) + 1] = objects + [str(work / "probe.o")]
        subprocess.run(link, cwd=link_dir, check=True)
        symbols = _symbols(program)
        listed = [t for t in list_suites(program) if t.suite == f"lesson{lesson}"]
        found: dict[str, list[str]] = {}
        for k, test in enumerate(listed, start=1):
            out = work / "probe.txt"
            out.unlink(missing_ok=True)
            subprocess.run([str(program), f"-ts=lesson{lesson}", f"--first={k}", f"--last={k}"],
                           env={**os.environ, "ILLUM_TASK_PROBE": str(out), "OMP_NUM_THREADS": "1"},
                           capture_output=True, check=False)
            entered = {symbols.get(int(a, 16), "") for a in out.read_text().split()} if out.exists() else set()
            tasks = sorted({task_of_symbol[s] for s in entered if s in task_of_symbol}, key=_task_key)
            found[test.name] = tasks
            print(f"{','.join(tasks) or '-':10} {test.name}")
    if write:
        _write_tags(root, lesson, found)
    return 0


def _write_tags(root: Path, lesson: str, found: dict[str, list[str]]) -> None:
    by_file: dict[Path, list[TestCase]] = {}
    for test in grading_tests(root, lesson):
        by_file.setdefault(test.file, []).append(test)
    for source, tests in by_file.items():
        text = source.read_text(encoding="utf-8")
        for test in sorted(tests, key=lambda t: t.start, reverse=True):
            tasks = found.get(test.name)
            if not tasks:
                continue
            head = text[test.start:test.end]
            tag = "task=" + ",".join(tasks)
            if "doctest::description(" in head:
                old = re.search(r'doctest::description\(\s*"([^"]*)"\s*\)', head)
                kept = _TAG.sub("", old.group(1)).strip()
                new_head = head[:old.start(1)] + (kept + " " + tag).strip() + head[old.end(1):]
            else:
                new_head = head[:-1] + f' * doctest::description("{tag}"))'
            text = text[:test.start] + new_head + text[test.end:]
        source.write_text(text, encoding="utf-8")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--update", action="store_true", help="rewrite the README tables from the tags")
    parser.add_argument("--check", action="store_true", help="fail when a tag or a table is missing or stale")
    parser.add_argument("--derive", metavar="NN", help="find lesson NN's tags by running its tests (needs --build-dir)")
    parser.add_argument("--write", action="store_true", help="with --derive: write the tags into the test sources")
    parser.add_argument("--build-dir", type=Path, help="a built reference tree (build/release)")
    parser.add_argument("--root", type=Path, default=ROOT, help=argparse.SUPPRESS)
    args = parser.parse_args()
    root = args.root.resolve()
    if args.derive:
        if not args.build_dir:
            parser.error("--derive needs --build-dir")
        return derive(root, args.derive, args.build_dir.resolve(), args.write)
    if not (args.update or args.check):
        parser.error("say --update, --check or --derive NN")
    problems = []
    for lesson in lessons_to_check(root):
        exercise = lesson_folders(root, "exercises")[lesson]
        if args.update:
            readme, text, updated = updated_readme(root, lesson)
            if updated is not None and updated != text:
                readme.write_text(updated, encoding="utf-8")
                print(f"updated {readme.relative_to(root)}")
        if args.check:
            problems += source_problems(root, lesson)
            if args.build_dir:
                problems += stub_problems(root, lesson, args.build_dir)
    import code_map

    # Every lesson text and exercise README: its "Where the code is" block; every lesson: its layout.
    problems += code_map.update(root, write=args.update and not args.check)
    if args.check:
        problems += code_map.layout_problems(root)
    top = root / "README.md"
    if top.is_file():
        text = top.read_text(encoding="utf-8")
        updated = replace_between(text, COMMANDS_BEGIN, COMMANDS_END, student_commands("NN"))
        if updated is None:
            problems.append(f"README.md: no student command markers ({COMMANDS_BEGIN} … {COMMANDS_END})")
        elif updated != text:
            if args.update:
                top.write_text(updated, encoding="utf-8")
                print("updated README.md")
            elif args.check:
                problems.append("README.md: the student commands are not current; run tools/task_tables.py --update")
    for problem in problems:
        print(f"PROBLEM {problem}")
    if args.check:
        print("task tables: " + ("current" if not problems else f"FAILED ({len(problems)} problem(s))"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
