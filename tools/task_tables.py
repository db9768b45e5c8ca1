#!/usr/bin/env python3
"""Writes and checks the READMEs' generated blocks: each exercise's task table (which grading test grades
which task) and student commands, every lesson text's and exercise's "Where the code is" map
(tools/code_map.py), and the top README's student commands (docs/grading-reference.md, "Task tables").

    tools/task_tables.py --update          rewrite every table, command block and code map
    tools/task_tables.py --check           CI: every grading test tagged with tasks of its lesson, every
                                           task graded, every block current, the lesson layout kept
    tools/task_tables.py --check --build-dir build/release
                                           also: on the stubs, each test first stops in a function of
                                           a task it names (tests_lessonNN_stubs)
    tools/task_tables.py --derive NN --build-dir build/release [--write]
                                           find the tags: run each test on the reference with the lesson's
                                           units compiled -finstrument-functions (tools/task_probe.c)

A test's tags: `* doctest::description("points=2 task=1,2")`; a task: a stub's `// Task N.` comment. A
lesson without exercises or tests is skipped.
"""

import argparse
import itertools
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

import code_map  # noqa: E402
from code_map import refresh, replace_between  # noqa: E402
from common.cpp_text import blank_comments  # noqa: E402
from grading.alone import declared_dependencies  # noqa: E402
from grading.project import exercise_lessons, lesson_folders  # noqa: E402
from grading.results import points_of  # noqa: E402
from grading.runner import list_suites, run_suite  # noqa: E402

BEGIN = "<!-- task-table: begin (written by tools/task_tables.py --update) -->"
END = "<!-- task-table: end -->"
COMMANDS_BEGIN = "<!-- student-commands: begin (written by tools/task_tables.py --update) -->"
COMMANDS_END = "<!-- student-commands: end -->"
# Every stub starts "// Lesson NN exercise: <what>." and then these two lines.
STUB_BANNER = ("// Replace each `throw NotImplemented(...)` with your code. The tasks, hints",
               "// and the tests that grade them are in README.md beside this file;")
_TASK_COMMENT = re.compile(r"^// Task (\d+[a-z]?)\.", re.M)
_TAG = re.compile(r"\btask\s*=\s*([0-9a-z,]+)")
_DESCRIPTION = re.compile(r'doctest::description\(\s*"([^"]*)"\s*\)')


def stub_tasks(exercise: Path) -> dict[str, list[str]]:
    """Task id -> the functions (NotImplemented labels) of its stub block, in the order of the stubs."""
    tasks: dict[str, list[str]] = {}
    for stub in sorted(exercise.glob("*.cpp")):
        parts = _TASK_COMMENT.split(stub.read_text(encoding="utf-8"))  # text, then each task and its block
        for task, block in zip(parts[1::2], parts[2::2]):
            tasks.setdefault(task, []).extend(re.findall(r'NotImplemented\(\s*"([^"]+)"', block))
    return dict(sorted(tasks.items(), key=lambda item: _task_key(item[0])))


def _task_key(task: str) -> tuple[int, str]:
    match = re.fullmatch(r"(\d+)([a-z]?)", task)
    return (int(match.group(1)), match.group(2)) if match else (10**6, task)


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

    @property
    def points(self) -> float:
        return points_of(self.description)


def _literals(text: str) -> str:
    """The string literals of `text` joined, escapes undone for \\" and \\\\."""
    return "".join(re.sub(r"\\(.)", r"\1", m.group(1)) for m in re.finditer(r'"((?:[^"\\]|\\.)*)"', text))


def parse_tests(source: Path) -> list[TestCase]:
    """Every TEST_CASE of a file with its suite (the enclosing TEST_SUITE block), found in the code with
    its comments and strings blanked, read from the text as written."""
    text = source.read_text(encoding="utf-8")
    code = blank_comments(text)
    tests, suites, depth, pending, pos = [], [], 0, None, 0
    token = re.compile(r"[{}]|\b(TEST_SUITE|TEST_CASE)\(")
    while match := token.search(code, pos):
        pos = match.end()
        if match.group() == "{":
            depth += 1
            if pending is not None:
                suites.append((pending, depth))
                pending = None
        elif match.group() == "}":
            if suites and suites[-1][1] == depth:
                suites.pop()
            depth -= 1
        else:
            close, level = pos, 1
            while level:
                level += {"(": 1, ")": -1}.get(code[close], 0)
                close += 1
            inside = text[pos:close - 1]
            if match.group(1) == "TEST_SUITE":
                pending = _literals(inside)
            else:
                description = _DESCRIPTION.search(inside)
                tests.append(TestCase(_literals(re.split(r"\*\s*doctest::", inside, maxsplit=1)[0]), source,
                                      text.count("\n", 0, match.start()) + 1, suites[-1][0] if suites else "",
                                      description.group(1) if description else "", match.start(), close))
            pos = close
    return tests


def grading_tests(root: Path, lesson: str) -> list[TestCase]:
    folder = lesson_folders(root, "tests").get(lesson)
    return [t for source in sorted(folder.glob("*.cpp")) for t in parse_tests(source)
            if t.suite == f"lesson{lesson}"] if folder else []


def table(lesson: str, tasks: dict[str, list[str]], tests: list[TestCase]) -> str:
    """The Markdown of the task table: one row per test, the tasks it needs, its points (each "erratum N"
    of a test's name linked, as every text that names one)."""
    ordered = sorted(tests, key=lambda t: (min((_task_key(x) for x in t.tasks), default=(10**6, "")),
                                           len(t.tasks), t.file.name, t.line))
    name = lambda t: re.sub(r"\berratum (\d+)\b", r"[erratum \1](../../docs/errata.md#erratum-\1)",  # noqa: E731
                            t.name.replace("|", "\\|"))
    per_task = "; ".join(f"Task {task}: {sum(task in t.tasks for t in tests)}" for task in tasks)
    return "\n".join([BEGIN, f"| test (suite `lesson{lesson}`) | tasks it needs | points |", "|---|---|---|"]
                     + [f"| {name(t)} | {', '.join(t.tasks)} | {t.points:g} |" for t in ordered]
                     + ["", f"{len(tests)} tests, {sum(t.points for t in tests):g} points. A test passes only when "
                        f"every task it needs is written. Tests per task — {per_task}.", END])


def student_commands(lesson: str, has_program: bool = True) -> str:
    """The one set of build commands a student types, for lesson `lesson` ("NN" in the top README)."""
    program = f" lesson{lesson}" if has_program else ""
    rows = [("cmake --preset student", "once: configure build/student with your exercises"),
            (f"cmake --build --preset student --target tests_lesson{lesson}{program}",
             "build your code, its tests" + (" and the lesson program" if has_program else "")),
            (f"build/student/bin/tests_lesson{lesson} -ts=lesson{lesson}",
             "the grading tests, with their explanations"),
            (f"build/student/bin/lesson{lesson} --out out/lesson{lesson}", "the lesson's pictures, drawn by your code"),
            (f"tools/grade --student {lesson}", "your score, as the autograder computes it")]
    rows = [(command, why) for command, why in rows if has_program or " --out " not in command]
    width = max(len(command) for command, _ in rows) + 2
    body = "\n".join(f"{command.ljust(width)}# {why}" for command, why in rows)
    return f"{COMMANDS_BEGIN}\n```sh\n{body}\n```\n{COMMANDS_END}"


def updated_readme(root: Path, lesson: str) -> tuple[Path, str, str | None]:
    """(README, its text, its text with the table and the commands rewritten, or None without markers)."""
    exercise = lesson_folders(root, "exercises")[lesson]
    readme = exercise / "README.md"
    text = readme.read_text(encoding="utf-8") if readme.is_file() else ""
    new = replace_between(text, BEGIN, END, table(lesson, stub_tasks(exercise), grading_tests(root, lesson)))
    commands = student_commands(lesson, has_program=lesson in lesson_folders(root, "lessons"))
    return readme, text, new and replace_between(new, COMMANDS_BEGIN, COMMANDS_END, commands)


def _tag_problems(root: Path, lesson: str, exercise: Path) -> list[str]:
    """Every grading test tagged with tasks its lesson's stubs have, every task graded by a test."""
    tasks, tests = stub_tasks(exercise), grading_tests(root, lesson)
    problems = [] if tasks else [f"lesson {lesson}: no '// Task N.' comment in the stubs of "
                                 f"{exercise.relative_to(root)}"]
    for test in tests:
        where = f"{test.file.relative_to(root)}:{test.line}: \"{test.name}\""
        if not test.tasks:
            problems.append(f"{where} has no task tag; add * doctest::description(\"task=N\")")
        problems += [f"{where} names task {task}, which no stub of lesson {lesson} has (tasks: {', '.join(tasks)})"
                     for task in test.tasks if task not in tasks]
    return problems + [f"lesson {lesson}: Task {task} ({', '.join(labels)}) is graded by no test"
                       for task, labels in tasks.items() if not any(task in t.tasks for t in tests)]


def _stub_file_problems(root: Path, lesson: str, exercise: Path) -> list[str]:
    """Each stub opens with the banner; its header's second line names it an exercise unit."""
    problems = []
    banner = [f"// Lesson {lesson} exercise: ", *STUB_BANNER]
    for stub in sorted(exercise.glob("*.cpp")):
        lines = stub.read_text(encoding="utf-8").splitlines()[:3] + ["", "", ""]  # too short: fails below
        if not lines[0].startswith(banner[0]) or lines[1] != banner[1] or not lines[2].startswith(banner[2]):
            problems.append(f"{stub.relative_to(root)}: the banner must be \"{banner[0]}<what>.\" then "
                            f"\"{banner[1]}\" then \"{banner[2]}…\"")
        header = code_map.unit_header(root, stub.stem)
        mark = f"// Exercise unit of lesson {lesson}: students write {stub.name}."
        if header is not None and mark not in header.read_text(encoding="utf-8").splitlines()[:3]:
            problems.append(f"{header.relative_to(root)}: the second line must be \"{mark}\"")
    return problems


def _readme_problems(root: Path, lesson: str, readme: Path, text: str) -> list[str]:
    """The README's sections in order, its "Builds on" naming what depends.txt declares."""
    where = readme.relative_to(root)
    problems = []
    headings = re.findall(r"^## (.+)$", text, re.M)
    if headings[:4] != ["Build and test", "Tasks", "Hints", "Grading"]:
        problems.append(f"{where}: the sections must be Build and test · Tasks · Hints · Grading (found: "
                        f"{' · '.join(headings)})")
    builds_on = next((line for line in text.splitlines() if line.startswith("**Builds on:**")), None)
    if builds_on is None:
        return problems + [f"{where}: no \"**Builds on:**\" line naming the earlier exercises"]
    return problems + [f"{where}: \"Builds on\" does not name exercise {needed}, which depends.txt declares"
                       for needed in declared_dependencies(lesson, root) if not re.search(rf"\b{needed}\b", builds_on)]


def stub_problems(root: Path, lesson: str, build_dir: Path) -> list[str]:
    """On the stubs, a test first stops in the function of one of the tasks it names (or of an earlier
    lesson this one declares it needs, depends.txt)."""
    program = build_dir / "bin" / f"tests_lesson{lesson}_stubs"
    if not program.is_file():
        return [f"{program} is missing; build it (or run without --build-dir)"]
    task_of = {label: task for task, labels in stub_tasks(lesson_folders(root, "exercises")[lesson]).items()
               for label in labels}
    tagged = {t.name: t for t in grading_tests(root, lesson)}
    depends = declared_dependencies(lesson, root, program=False)
    lesson_of = {label: other for other, folder in lesson_folders(root, "exercises").items()
                 for labels in stub_tasks(folder).values() for label in labels}
    problems = []
    for result in run_suite(program, f"lesson{lesson}").results:
        test = tagged.get(result.name)
        message = next((f.describe() for f in result.failures if f.not_implemented), "")
        label = match.group(1) if (match := re.search(r"NotImplemented: (.+?) — ", message)) else None
        if test and label and lesson_of.get(label) not in depends and task_of.get(label) not in test.tasks:
            problems.append(f"{test.file.relative_to(root)}:{test.line}: \"{test.name}\" is tagged task="
                            f"{','.join(test.tasks)} but first calls {label} (Task {task_of.get(label, '?')})")
    return problems


def _compile(commands: dict[Path, dict], source: Path, obj: Path, flag: str) -> None:
    """SOURCE compiled as compile_commands.json compiles it, its object renamed and one more flag. A source the
    build compiles inside a unity unit (CMakeLists.txt, illum_unity_build) takes that unit's command."""
    source = source.resolve()
    entry = commands.get(source) or next(
        e for file, e in commands.items() if "unity" in file.parts
        and f'#include "{source.relative_to(ROOT).as_posix()}"' in file.read_text(encoding="utf-8"))
    args = [str(source) if a == entry["file"] else a for a in shlex.split(entry["command"])]
    args[args.index("-o") + 1] = str(obj)
    subprocess.run(args + [flag], cwd=entry["directory"], check=True)


def _nm(*arguments: str) -> str:
    return subprocess.run(["nm", "-C", "--defined-only", *arguments], capture_output=True, text=True,
                          check=True).stdout


def _task_symbols(exercise: Path, commands: dict[Path, dict], work: Path) -> dict[str, str]:
    """Demangled function name -> task, from the stubs compiled with -g (nm -l gives each line)."""
    result = {}
    for stub in sorted(exercise.glob("*.cpp")):
        obj = work / (stub.name + ".stub.o")
        _compile(commands, stub, obj, "-g")
        marks = [(k + 1, m.group(1)) for k, line in enumerate(stub.read_text(encoding="utf-8").splitlines())
                 if (m := _TASK_COMMENT.match(line))]
        for line in _nm("-l", str(obj)).splitlines():
            match = re.match(r"[0-9a-f]+ [TW] (.+)\t(.+):(\d+)$", line)
            if match and Path(match.group(2)).name == stub.name:
                task = next((t for start, t in reversed(marks) if start <= int(match.group(3))), None)
                if task is not None:
                    result[match.group(1)] = task
    return result


def _probed_program(root: Path, lesson: str, build_dir: Path, commands: dict[Path, dict], work: Path) -> Path:
    """The lesson's test program linked with its reference units compiled -finstrument-functions and the probe."""
    objects = []
    for stub in sorted(lesson_folders(root, "exercises")[lesson].glob("*.cpp")):
        obj = work / (stub.name + ".ref.o")
        _compile(commands, next((root / "lib" / "illum").rglob(stub.name)), obj, "-finstrument-functions")
        objects.append(str(obj))
    subprocess.run(["cc", "-O2", "-c", str(ROOT / "tools" / "task_probe.c"), "-o", str(work / "probe.o")], check=True)
    link_dir = build_dir / "tests"
    link = shlex.split((link_dir / "CMakeFiles" / f"tests_lesson{lesson}.dir" / "link.txt").read_text())
    program = work / "tests"
    link[link.index("-o") + 1] = str(program)
    link.insert(1, "-no-pie")  # addresses as nm prints them
    at = link.index(str(program)) + 1
    link[at:at] = objects + [str(work / "probe.o")]
    subprocess.run(link, cwd=link_dir, check=True)
    return program


PROBE_SECONDS = 600  # one probed test; the slowest grading test takes a few seconds


def derive(root: Path, lesson: str, build_dir: Path, write: bool) -> int:
    commands = {Path(e["file"]).resolve(): e for e in json.loads((build_dir / "compile_commands.json").read_text())}
    found: dict[str, list[str]] = {}
    with tempfile.TemporaryDirectory(prefix=f"illum-tasks-{lesson}-") as folder:
        work = Path(folder)
        task_of_symbol = _task_symbols(lesson_folders(root, "exercises")[lesson], commands, work)
        program = _probed_program(root, lesson, build_dir, commands, work)
        symbols = {int(parts[0], 16): parts[2] for line in _nm(str(program)).splitlines()
                   if len(parts := line.split(" ", 2)) == 3 and parts[1] in "TtWw"}
        out = work / "probe.txt"
        for k, test in enumerate((t for t in list_suites(program) if t.suite == f"lesson{lesson}"), start=1):
            out.unlink(missing_ok=True)
            try:  # one process (the probe records in it), at most PROBE_SECONDS a test; nothing written yet
                subprocess.run([str(program), f"-ts=lesson{lesson}", f"--first={k}", f"--last={k}"],
                               env={**os.environ, "ILLUM_TASK_PROBE": str(out), "OMP_NUM_THREADS": "1",
                                    "ILLUM_TEST_ONE_PROCESS": "1"},
                               capture_output=True, check=False, timeout=PROBE_SECONDS)
            except subprocess.TimeoutExpired:
                sys.exit(f"task_tables.py --derive: test '{test.name}' ran over {PROBE_SECONDS} s; no tag written")
            entered = {symbols.get(int(a, 16), "") for a in out.read_text().split()} if out.exists() else set()
            found[test.name] = sorted({task_of_symbol[s] for s in entered if s in task_of_symbol}, key=_task_key)
            print(f"{','.join(found[test.name]) or '-':10} {test.name}")
    if write:
        _write_tags(root, lesson, found)
    return 0


def _write_tags(root: Path, lesson: str, found: dict[str, list[str]]) -> None:
    for source, tests in itertools.groupby(grading_tests(root, lesson), key=lambda t: t.file):
        text = source.read_text(encoding="utf-8")
        for test in reversed(list(tests)):  # from the end, so that the earlier offsets hold
            if not (tasks := found.get(test.name)):
                continue
            head, tag = text[test.start:test.end], "task=" + ",".join(tasks)
            if old := _DESCRIPTION.search(head):
                kept = _TAG.sub("", old.group(1)).strip()
                head = head[:old.start(1)] + (kept + " " + tag).strip() + head[old.end(1):]
            else:
                head = head[:-1] + f' * doctest::description("{tag}"))'
            text = text[:test.start] + head + text[test.end:]
        source.write_text(text, encoding="utf-8")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--update", action="store_true", help="rewrite the tables, command blocks and code maps")
    parser.add_argument("--check", action="store_true", help="fail when a tag or a block is missing or stale")
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
    for lesson in (nn for nn in exercise_lessons(root) if grading_tests(root, nn)):
        readme, text, updated = updated_readme(root, lesson)
        problems += refresh(readme, root, text, updated, args.update, "task table and student commands",
                            f"({BEGIN} … {END}, {COMMANDS_BEGIN} … {COMMANDS_END})")
        if args.check:
            problems += [*_tag_problems(root, lesson, readme.parent), *_stub_file_problems(root, lesson, readme.parent),
                         *_readme_problems(root, lesson, readme, text)]
            problems += stub_problems(root, lesson, args.build_dir) if args.build_dir else []
    problems += code_map.update(root, write=args.update and not args.check)
    problems += code_map.layout_problems(root) if args.check else []
    if (top := root / "README.md").is_file():  # its commands say NN for the lesson
        text = top.read_text(encoding="utf-8")
        new = replace_between(text, COMMANDS_BEGIN, COMMANDS_END, student_commands("NN"))
        problems += refresh(top, root, text, new, args.update, "student commands",
                            f"({COMMANDS_BEGIN} … {COMMANDS_END})")
    for problem in problems:
        print(f"PROBLEM {problem}")
    if args.check:
        print("task tables: " + ("current" if not problems else f"FAILED ({len(problems)} problem(s))"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
