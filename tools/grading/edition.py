"""The student edition: the tracked tree without what students must not see.

The instructor chooses the lessons to hand out (default: every lesson with
exercises). Left out:
* the reference source of every exercise unit of a lesson handed out --
  ``lib/illum/**/<name>.cpp`` that has a twin ``exercises/NN_*/<name>.cpp``;
  CMake builds the stub when the reference is absent;
* ``exercises/NN_*/`` of every lesson *not* handed out: its units ship as
  working reference code, so that the lessons handed out can use its results
  (docs/grading.md, "Choosing the lessons to hand out");
* ``tests/hidden/`` (an instructor's hidden tests) and ``tests/attacks/``
  (hostile submissions the grader is tested with);
* ``build/`` and ``out/`` (generated).
A ``STUDENT_EDITION`` marker file tells CMake and the driver which tree
they are in (no integrity check, no autograder packing there).

The edition has a README of its own (``student_readme``: the lessons handed
out, the student commands, the ``illum`` command and its lab; nothing for
instructors), and every Markdown link to a file it leaves out is rewritten:
to the stub, for a reference unit handed out, else to plain text
(tools/check_student_edition.py checks that every link resolves).
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from .links import GENERATED, Link, resolve, rewrite_links
from .project import STUDENT_EDITION_MARKER

_GENERATED = ("build", "out")


def _git(source: Path, *arguments: str) -> subprocess.CompletedProcess | None:
    """``git -C source ...``, or None where there is no git program (the tree still packs: see
    ``tracked_files``)."""
    try:
        return subprocess.run(["git", "-C", str(source), *arguments], capture_output=True, check=False)
    except OSError:
        return None


def _git_toplevel(source: Path) -> Path | None:
    completed = _git(source, "rev-parse", "--show-toplevel")
    if completed is None or completed.returncode != 0:
        return None
    return Path(completed.stdout.decode("utf-8", errors="replace").strip()).resolve()


def _git_describe(source: Path) -> str:
    completed = _git(source, "describe", "--always", "--dirty")
    return completed.stdout.decode("utf-8", errors="replace").strip() if completed and completed.returncode == 0 else ""


def tracked_files(source: Path) -> list[str]:
    """POSIX paths relative to ``source``: ``git ls-files`` in a checkout (so
    untracked experiments never leak to students); else (no checkout, no git
    program, or git refusing a checkout of another user under sudo) the files
    of the tree less what its ``.gitignore`` files ignore, as ``git add -A``
    would take them."""
    source = source.resolve()
    if _git_toplevel(source) == source:
        completed = _git(source, "ls-files", "-z")
        if completed is not None and completed.returncode == 0:
            return sorted(p for p in completed.stdout.decode("utf-8").split("\0") if p)
    return _walk_files(source)


@dataclass
class _Ignore:
    """One pattern of a ``.gitignore`` (gitignore(5)): ``base`` is the folder of its file."""

    base: str
    pattern: re.Pattern
    negated: bool
    folders_only: bool
    anchored: bool  # a slash before its end: matched against the path from ``base``, else the name

    def matches(self, relative: str, is_folder: bool) -> bool:
        if self.folders_only and not is_folder:
            return False
        if self.base:
            if not relative.startswith(self.base + "/"):
                return False
            relative = relative[len(self.base) + 1:]
        return bool(self.pattern.fullmatch(relative if self.anchored else relative.rsplit("/", 1)[-1]))


def _glob_regex(glob: str) -> re.Pattern:
    """gitignore's glob: ``*`` and ``?`` stop at a slash, ``**`` crosses folders, ``[...]`` a class."""
    out, i = [], 0
    while i < len(glob):
        if glob.startswith("**/", i):
            out.append("(?:.*/)?")
            i += 3
        elif glob.startswith("/**", i) and i + 3 == len(glob):
            out.append("/.*")
            i += 3
        elif glob[i] == "*":
            out.append(".*" if glob.startswith("**", i) else "[^/]*")
            i += 2 if glob.startswith("**", i) else 1
        elif glob[i] == "?":
            out.append("[^/]")
            i += 1
        elif glob[i] == "[" and "]" in glob[i + 2:]:
            end = glob.index("]", i + 2)
            body = glob[i + 1:end]
            out.append("[" + ("^" + body[1:] if body[:1] == "!" else body) + "]")
            i = end + 1
        elif glob[i] == "\\" and i + 1 < len(glob):
            out.append(re.escape(glob[i + 1]))
            i += 2
        else:
            out.append(re.escape(glob[i]))
            i += 1
    return re.compile("".join(out))


def _read_ignores(folder: Path, base: str) -> list[_Ignore]:
    try:
        lines = (folder / ".gitignore").read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return []
    ignores = []
    for line in lines:
        line = line.rstrip()
        if not line or line.startswith("#"):
            continue
        negated = line.startswith("!")
        line = line[1:] if negated or line.startswith("\\") else line
        folders_only = line.endswith("/")
        line = line.rstrip("/")
        anchored = "/" in line
        ignores.append(_Ignore(base, _glob_regex(line.lstrip("/")), negated, folders_only, anchored))
    return ignores


def _ignored(ignores: list[_Ignore], relative: str, is_folder: bool) -> bool:
    verdict = False
    for ignore in ignores:  # the last pattern that matches decides, as in git
        if ignore.matches(relative, is_folder):
            verdict = not ignore.negated
    return verdict


def _walk_files(source: Path) -> list[str]:
    """The files under ``source`` that ``.gitignore`` files (at any depth) do not ignore; ``.git`` and
    the generated folders at the top (build/, out/) are never taken, whatever .gitignore says."""
    files: list[str] = []
    ignores_of: dict[str, list[_Ignore]] = {}
    for folder, subfolders, names in os.walk(source):
        relative = Path(folder).relative_to(source).as_posix()
        relative = "" if relative == "." else relative
        parent = relative.rsplit("/", 1)[0] if "/" in relative else ""
        ignores = (ignores_of.get(parent, []) if relative else []) + _read_ignores(Path(folder), relative)
        ignores_of[relative] = ignores

        def path(name: str) -> str:
            return f"{relative}/{name}" if relative else name

        kept = []
        for name in sorted(subfolders):
            if name == ".git" or (not relative and name in _GENERATED):
                continue
            if os.path.islink(os.path.join(folder, name)):  # git keeps a link as a file
                if not _ignored(ignores, path(name), False):
                    files.append(path(name))
            elif not _ignored(ignores, path(name), True):
                kept.append(name)
        subfolders[:] = kept
        # A worktree's .git is a file naming the repository.
        files.extend(path(name) for name in names if name != ".git" and not _ignored(ignores, path(name), False))
    return sorted(files)


def _stub_lesson(path: str) -> str | None:
    """NN for ``exercises/NN_topic/<unit>.cpp``, else None."""
    parts = PurePosixPath(path).parts
    if len(parts) == 3 and parts[0] == "exercises" and parts[1][:2].isdigit() and path.endswith(".cpp"):
        return parts[1][:2]
    return None


def exercise_lessons_of(files: list[str]) -> list[str]:
    return sorted({nn for f in files if (nn := _stub_lesson(f))})


def excluded_files(files: list[str], handed_out: list[str] | None = None) -> dict[str, str]:
    """Path -> reason, for every path of ``files`` the student edition leaves out.

    ``handed_out``: the lessons whose exercises students get (None: all)."""
    lessons = exercise_lessons_of(files)
    handed = set(lessons if handed_out is None else handed_out)
    twins = {PurePosixPath(f).name for f in files if _stub_lesson(f) in handed}
    reasons = {}
    for f in files:
        parts = PurePosixPath(f).parts
        if parts[0] in _GENERATED:
            reasons[f] = "generated"
        elif parts[:2] == ("tests", "hidden"):
            reasons[f] = "hidden test"
        elif parts[:2] == ("tests", "attacks"):
            reasons[f] = "the grader's own attack tests"
        elif parts[:2] == ("lib", "illum") and f.endswith(".cpp") and parts[-1] in twins:
            reasons[f] = "reference solution of an exercise unit"
        elif parts[0] == "exercises" and len(parts) >= 3 and parts[1][:2].isdigit() and parts[1][:2] not in handed:
            reasons[f] = "exercise not handed out (its units ship as reference code)"
        elif f == STUDENT_EDITION_MARKER:
            reasons[f] = "marker, rewritten"
    return reasons


@dataclass
class Edition:
    out: Path
    copied: int = 0
    left_out: dict[str, str] = field(default_factory=dict)
    handed_out: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # dependencies among the lessons handed out


def make_student_edition(source: Path, out: Path, handed_out: list[str] | None = None) -> Edition:
    """Writes the student edition of ``source`` to ``out`` (replacing an earlier one),
    handing out the exercises of ``handed_out`` (None: every lesson with exercises)."""
    if out.is_symlink():  # its target would be replaced, or written, through the link
        raise ValueError(f"{out} is a symbolic link; refusing to write through it (give the folder itself)")
    source, out = source.resolve(), out.resolve()
    # Everything is checked before an earlier edition is removed or a file written. A folder
    # without lessons/ is no source tree: reading it would walk all of it (/tmp, or /).
    if not (source / "lessons").is_dir():
        raise ValueError(f"{source} is not an illum source tree (it has no lessons/ folder)")
    # Inside the source tree, only the generated folders are safe: anywhere
    # else the edition would be copied into itself next time.
    in_generated = any(out == source / g or source / g in out.parents for g in _GENERATED)
    if out == source or (source in out.parents and not in_generated):
        raise ValueError(f"{out} lies inside the source tree; write the edition under build/ or elsewhere")
    if out.exists():
        if not out.is_dir():
            raise ValueError(f"{out} exists and is not a folder; refusing to replace it")
        if any(out.iterdir()) and not (out / STUDENT_EDITION_MARKER).exists():
            raise ValueError(f"{out} exists and is not a student edition; refusing to replace it")
    files = tracked_files(source)
    lessons = exercise_lessons_of(files)
    unknown = sorted(set(handed_out or []) - set(lessons))
    if unknown:
        raise ValueError(f"lesson(s) {', '.join(unknown)} have no exercises; lessons with exercises: "
                         f"{', '.join(lessons)}")
    chosen = lessons if handed_out is None else sorted(set(handed_out))
    if not chosen:
        raise ValueError("no lesson to hand out")
    # Written into a new folder beside `out` and renamed into place at the end: an interrupted or
    # failed run leaves the earlier edition (or nothing) as it was, never half of a new one.
    out.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{out.name}.new.", dir=out.parent))
    umask = os.umask(0)
    os.umask(umask)
    staging.chmod(0o777 & ~umask)  # mkdtemp's 0700 would become the edition's own mode
    try:
        edition = _write_edition(source, staging, files, lessons, chosen)
        if out.exists():  # an earlier edition (its marker says so), now that nothing is left to refuse
            old = Path(tempfile.mkdtemp(prefix=f".{out.name}.old.", dir=out.parent))
            old.rmdir()
            out.rename(old)
            staging.rename(out)
            shutil.rmtree(old)
        else:
            staging.rename(out)
    finally:
        if staging.exists():
            shutil.rmtree(staging)
    edition.out = out
    return edition


def _write_edition(source: Path, out: Path, files: list[str], lessons: list[str], chosen: list[str]) -> Edition:
    """The edition's files in the empty folder ``out``, its marker last."""
    from .alone import declared_dependencies

    left_out = excluded_files(files, chosen)
    edition = Edition(out, left_out=left_out, handed_out=chosen)
    for lesson in chosen:
        needed = [d for d in declared_dependencies(lesson, source) if d in chosen]
        if needed:
            edition.notes.append(f"lesson {lesson} builds on lesson {', '.join(needed)}, also handed out: its "
                                 f"program and tests need the students' lesson {', '.join(needed)} code first")
    kept = {f for f in files if f not in left_out and (source / f).is_file()}
    # Where a link to an exercise unit goes in the edition: the stub of a lesson handed out, the
    # reference (kept as working code) of a lesson that is not.
    twins = {PurePosixPath(f).name: f for f in kept if f.startswith("lib/") and f.endswith(".cpp")}
    twins.update({PurePosixPath(f).name: f for f in kept if _stub_lesson(f) in chosen})
    for relative in files:
        if relative in left_out:
            continue
        origin = source / relative
        if not origin.is_file():  # deleted in the working tree but still tracked
            continue
        target = out / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        if relative == "README.md":
            target.write_text(student_readme(source, files, chosen), encoding="utf-8")
        elif relative.endswith(".md"):
            text = origin.read_text(encoding="utf-8")
            target.write_text(_edition_links(text, out, target, kept, twins), encoding="utf-8")
            shutil.copymode(origin, target)
        else:
            shutil.copy2(origin, target)
        edition.copied += 1
    version = _git_describe(source)
    given = [nn for nn in lessons if nn not in chosen]
    (out / STUDENT_EDITION_MARKER).write_text(
        "This is the student edition of illum"
        + (f", made from {version}" if version else "")
        + f".\nExercises handed out: lessons {', '.join(chosen)}.\n"
        + (f"Lessons {', '.join(given)} are not exercises here: their units are working reference code.\n"
           if given else "")
        + "The reference solutions of the exercises handed out and the instructors' hidden tests are not part\n"
        "of it; the exercise stubs in exercises/ are built in their place. Grade your work with\n"
        "    tools/grade --student NN\n"
        "(see docs/grading.md).\n", encoding="utf-8")
    return edition


# --- the edition's own texts ---------------------------------------------------------------------

def _edition_links(text: str, out: Path, file: Path, kept: set[str], stubs: dict[str, str]) -> str:
    """``text`` with every link to a file or folder the edition leaves out rewritten: a reference
    unit handed out points to its stub (what the student edits); anything else keeps its words,
    unlinked. ``kept``: the files (and so the folders) the edition holds."""

    def replace(link: Link) -> str | None:
        if link.external:
            return None
        path, _anchor = link.split()
        target = resolve(out, file, path) if path else None
        if target is None:
            return None
        key = target.as_posix()
        if target.parts and target.parts[0] in GENERATED:
            return None  # written by the programs or the build
        if key == "." or key in kept or any(f.startswith(key + "/") for f in kept):
            return None
        # A unit's file: the stub where the lesson is handed out, the reference where it is not.
        twin = stubs.get(target.name) if target.suffix == ".cpp" else None
        if twin is not None:
            here = PurePosixPath(file.relative_to(out).as_posix()).parent
            return f"{'!' if link.image else ''}[{link.text}]({_relative(twin, here)})"
        return link.text

    return rewrite_links(text, replace)


def _relative(path: str, start: PurePosixPath) -> str:
    """``path`` (from the tree's root) relative to the folder ``start``."""
    return os.path.relpath(path, start.as_posix() or ".").replace(os.sep, "/")


def _lesson_titles(source: Path, files: list[str], folder: str) -> dict[str, tuple[str, str]]:
    """NN -> (path of the folder's README, its title without "Lesson NN —") for lessons/ or exercises/."""
    titles = {}
    for f in files:
        parts = PurePosixPath(f).parts
        if len(parts) == 3 and parts[0] == folder and parts[2] == "README.md" and parts[1][:2].isdigit():
            first = (source / f).read_text(encoding="utf-8").splitlines()[:1]
            title = re.sub(r"^#\s*(Lesson|Exercise)\s+\d+\s*[—-]\s*", "", first[0]) if first else parts[1]
            titles[parts[1][:2]] = (f, title.strip())
    return titles


def _student_commands(source: Path) -> str:
    """The student build commands, as the top-level README holds them (tools/task_tables.py writes
    the block), so that the edition's README shows the same set."""
    text = (source / "README.md").read_text(encoding="utf-8")
    match = re.search(r"<!-- student-commands: begin[^>]*-->\n(.*?)<!-- student-commands: end -->", text, re.S)
    if not match:
        raise ValueError("README.md has no student-commands block (tools/task_tables.py --update writes it)")
    return match.group(1).strip()


def student_readme(source: Path, files: list[str], handed_out: list[str]) -> str:
    """The README of the student edition: what the students got, and how to build, test, see and
    grade their code. Every link points into the edition (tools/check_student_edition.py checks)."""
    lessons = _lesson_titles(source, files, "lessons")
    exercises = _lesson_titles(source, files, "exercises")
    slides = {PurePosixPath(f).name[:2]: f for f in files
              if PurePosixPath(f).parent.as_posix() == "slides" and f.endswith(".md") and PurePosixPath(f).name[:2].isdigit()}
    rows = []
    for nn in sorted(lessons):
        text, title = lessons[nn]
        exercise = (f"[exercise {nn}]({exercises[nn][0]}) (yours to write)" if nn in handed_out and nn in exercises
                    else "not handed out: its code is in `lib/` as working reference code")
        deck = f"[slides]({slides[nn]})" if nn in slides else ""
        rows.append(f"| {nn} | [{title}]({text}) | {exercise} | {deck} |")
    given = [nn for nn in sorted(lessons) if nn not in handed_out]
    commands = _student_commands(source)
    first = handed_out[0] if handed_out else "NN"
    # Prose only: the first ```sh block of the section is the student block check_student_edition reads.
    other_systems = "" if ".devcontainer/Dockerfile" not in files else """On Windows or macOS, work inside the development container
(`.devcontainer/`: Debian 12 with every package the build needs already
installed): with Docker Desktop and VS Code's Dev Containers
extension, open this folder and choose *Reopen in Container*; without VS
Code, run `docker build -f .devcontainer/Dockerfile -t illum-dev .` and then
`docker run --rm -it --shm-size=1g -v "$PWD":/workspaces/illum -w
/workspaces/illum illum-dev` in this folder (podman takes the same
arguments), and type the commands below in the shell it opens. On Windows,
WSL 2 with Debian works as well (`wsl --install -d Debian`): keep this folder
in Linux's file system (e.g. `~/illum`, not under `/mnt/c`).

"""
    return f"""# illum — student edition

illum is a course toolkit that teaches global illumination the way the
course notes *Tema 4. Modelos de Iluminación Global* do: backward ray
tracing, the ray tree and the structures that make it cheap, then
radiosity, form factors, the hemicube, the solvers and vertex colours.
Each lesson has a text, a program that draws its figures, an exercise and
the tests that grade it. This copy is yours: the exercises of lessons
{", ".join(handed_out)} are handed out{"" if not given else " (lessons " + ", ".join(given) + " are working code you can read and use)"};
their reference solutions are not here.

## Your lessons

| # | lesson text | exercise | slides |
|---|---|---|---|
{chr(10).join(rows)}

Read a lesson's text first, then its exercise's README (Build and test ·
Tasks · Hints · Grading), and write the functions of
`exercises/NN_topic/*.cpp`. Each stub throws `NotImplemented` with a hint
until you write it. The errata of the course notes that the texts cite are
in [docs/errata.md](docs/errata.md).

## Build, test and grade your code

{other_systems}On Debian 12 (or Ubuntu 22.04), install what the build needs once with
`tools/install-deps` (it asks for `sudo`). Then, with NN the lesson's number
(e.g. {first}):

{commands}

* **The first build** compiles the whole library with your files: about a
  minute for one lesson's tests and program on two cores, twice that on a
  slow machine (less when `ccache` is installed and has seen these
  sources). After that, a change to one of your files recompiles that file
  and relinks: a few seconds.
* **The tests** say, for each failed check, what they computed and what
  they expected, and the mathematics behind it. `tests_lessonNN` holds the
  graded tests of lesson NN and nothing else: its last lines count them
  (`test cases: 36 | 30 passed | 6 failed | 0 skipped`), the tests
  `tools/grade` scores. A test that runs longer
  than the grader allows one (60 s; `ILLUM_GRADE_TEST_TIMEOUT` changes it)
  is stopped with a message naming it: a loop in your code that never ends.
* **`tools/grade --student NN`** builds in the same `build/student` tree and
  prints your score as the autograder computes it, then each failed test's
  first failing check. It also checks your files as the autograder does
  (an exercise only computes: no files, no processes, no `exit()`) and says
  what it finds ([docs/grading.md](docs/grading.md#students)).
* Each exercise's README ends with what to upload to the autograder.

## See your code at work: the `illum` command and the lab

Your build has a command line, `illum`, that runs your code on the shipped
scenes (`build/student/bin/illum --help` lists its commands):

```sh
cmake --build --preset student --target illum_cli                        # once, and after each change
build/student/bin/illum scenes                                           # the scenes you can name
build/student/bin/illum render whitted --out out/whitted                 # a picture, drawn by your evaluate
build/student/bin/illum trace whitted --pixel 300 160 --out out/tree     # one pixel's ray tree: JSON, drawing
build/student/bin/illum lab whitted                                      # the lab: open http://127.0.0.1:8642/
```

The lab ([docs/lab.md](docs/lab.md)) is a local web page (on 127.0.0.1
only; Ctrl-C stops it): click a pixel and see the ray tree your `evaluate`
casts (lesson 06), each leaf saying why it stops; step radiosity one shot
at a time with your solvers (lesson 11); place the hemicube on any patch
with your delta form factors (lesson 10); and hold the pictures your lesson
programs drew in `out/lessonNN/` against the reference images of the
texts. A function you have not written yet is named in the page.

## Where things are

| path | what lives there |
|---|---|
| `exercises/NN_topic/` | your exercises: the tasks (README) and the files you write |
| `lessons/NN_topic/` | the lesson texts and the programs that draw their figures |
| `lib/illum/` | the shared library your files are part of; each header states the contract of every function you write |
| `tests/NN_topic/` | the grading tests (suite `lessonNN`, built as `build/student/bin/tests_lessonNN`) and, in files of their own, hard cases of the library that are not graded (`tests_lessonNN_ungraded`, not part of your commands) |
| `slides/` | one slide deck per lesson |
| `scenes/` | the scenes the programs and `illum` load ([docs/scene-format.md](docs/scene-format.md)) |
| `docs/` | how the toolkit is built, the scene format, grading, the lab |
"""
