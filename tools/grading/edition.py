"""The student edition (docs/grading.md, "Student edition"): the tracked tree without what students must not
see (excluded_files says what and why). It has a README of its own (student_readme.md.in) and every link to a
file it leaves out is rewritten: to the stub for a reference unit handed out, else to plain text."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from common.markdown import GENERATED, Link, link_problems, resolve, rewrite_links

from .alone import declared_dependencies
from .project import STUDENT_EDITION_MARKER

README_TEMPLATE = Path(__file__).with_name("student_readme.md.in")


def _git(source: Path, *arguments: str) -> str | None:
    """The output of `git -C source …`, or None where it fails or there is no git."""
    try:
        done = subprocess.run(["git", "-C", str(source), *arguments], capture_output=True, check=False)
    except OSError:
        return None
    return done.stdout.decode("utf-8", errors="replace") if done.returncode == 0 else None


def tracked_files(source: Path) -> list[str]:
    """POSIX paths relative to `source`: `git ls-files` in a checkout (untracked experiments never reach
    students); else (no checkout, no git, or git refusing another user's checkout under sudo) the files
    of the tree less what its .gitignore files ignore, as `git add -A` would take them."""
    source = source.resolve()
    top = _git(source, "rev-parse", "--show-toplevel")
    listed = _git(source, "ls-files", "-z") if top and Path(top.strip()).resolve() == source else None
    return sorted(p for p in listed.split("\0") if p) if listed is not None else _walk_files(source)


_GLOB_PART = re.compile(r"/\*\*\Z|\*\*/|\*\*|\*|\?|\[.[^]]*\]|\\.|.", re.S)
_GLOB_REGEX = {"/**": "/.*", "**/": "(?:.*/)?", "**": ".*", "*": "[^/]*", "?": "[^/]"}


def _glob_part(match: re.Match) -> str:
    """A piece of a gitignore(5) glob as a regex: `*` and `?` stop at a slash, `**` crosses folders, `[...]` a class."""
    part = match.group()
    if part[0] == "[" and len(part) > 1:  # a class, `[!...]` negated
        return "[" + ("^" + part[2:-1] if part[1] == "!" else part[1:-1]) + "]"
    return _GLOB_REGEX.get(part) or re.escape(part[-1])  # `\x`: x itself


def _read_ignores(folder: Path, base: str) -> list[tuple]:
    """(base, pattern, negated, folders only, anchored) of each line of the folder's .gitignore."""
    try:
        lines = (folder / ".gitignore").read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return []
    ignores = []
    for line in (raw.rstrip() for raw in lines):
        if line and not line.startswith("#"):
            negated = line.startswith("!")
            line = line[1:] if negated or line.startswith("\\") else line
            body = line.rstrip("/")
            pattern = re.compile(_GLOB_PART.sub(_glob_part, body.lstrip("/")))
            ignores.append((base, pattern, negated, line.endswith("/"), "/" in body))
    return ignores


def _ignored(ignores: list[tuple], relative: str, is_folder: bool) -> bool:
    verdict = False
    for base, pattern, negated, folders_only, anchored in ignores:  # the last match decides, as in git
        if (folders_only and not is_folder) or (base and not relative.startswith(base + "/")):
            continue
        path = relative[len(base) + 1:] if base else relative
        if pattern.fullmatch(path if anchored else path.rsplit("/", 1)[-1]):
            verdict = not negated
    return verdict


def _walk_files(source: Path) -> list[str]:
    """The files under `source` its .gitignore files (at any depth) do not ignore; .git and the generated
    folders at the top are never taken."""
    files: list[str] = []
    ignores_of: dict[str, list[tuple]] = {}
    for folder, subfolders, names in os.walk(source):
        relative = "" if Path(folder) == source else Path(folder).relative_to(source).as_posix()
        prefix = f"{relative}/" if relative else ""
        ignores = ignores_of[relative] = ignores_of.get(relative.rpartition("/")[0], []) + _read_ignores(
            Path(folder), relative)
        subfolders[:] = [name for name in sorted(subfolders) if name != ".git" and (relative or name not in GENERATED)]
        links = [name for name in subfolders if os.path.islink(os.path.join(folder, name))]  # git keeps them as files
        # A worktree's .git is a file naming the repository.
        files += [prefix + name for name in links + names
                  if name != ".git" and not _ignored(ignores, prefix + name, False)]
        subfolders[:] = [name for name in subfolders
                         if name not in links and not _ignored(ignores, prefix + name, True)]
    return sorted(files)


def _stub_lesson(path: str) -> str | None:
    """NN for `exercises/NN_topic/<unit>.cpp`, else None."""
    parts = PurePosixPath(path).parts
    return parts[1][:2] if len(parts) == 3 and parts[0] == "exercises" and parts[1][:2].isdigit() \
        and path.endswith(".cpp") else None


def exercise_lessons_of(files: list[str]) -> list[str]:
    return sorted({nn for f in files if (nn := _stub_lesson(f))})


def excluded_files(files: list[str], handed_out: list[str] | None = None) -> dict[str, str]:
    """Path -> reason for every path of `files` the edition leaves out (`handed_out`: None for all lessons)."""
    handed = set(exercise_lessons_of(files) if handed_out is None else handed_out)
    twins = {PurePosixPath(f).name for f in files if _stub_lesson(f) in handed}
    reasons = {}
    for f in files:
        parts = PurePosixPath(f).parts
        if parts[0] in GENERATED:
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
    """Writes the edition of `source` to `out` (replacing an earlier one), handing out the exercises of
    `handed_out` (None: every lesson with exercises). Refused (ValueError) before anything is removed: an `out`
    that is a link, lies in the source tree or is something else than an earlier edition."""
    if out.is_symlink():  # its target would be replaced, or written, through the link
        raise ValueError(f"{out} is a symbolic link; refusing to write through it (give the folder itself)")
    source, out = source.resolve(), out.resolve()
    if not (source / "lessons").is_dir():  # it would walk all of it (/tmp, or /)
        raise ValueError(f"{source} is not an illum source tree (it has no lessons/ folder)")
    # Inside the source tree only the generated folders are safe: elsewhere the edition would copy itself.
    in_generated = any(out == source / g or source / g in out.parents for g in GENERATED)
    if out == source or (source in out.parents and not in_generated):
        raise ValueError(f"{out} lies inside the source tree; write the edition under build/ or elsewhere")
    if out.exists() and not out.is_dir():
        raise ValueError(f"{out} exists and is not a folder; refusing to replace it")
    if out.exists() and any(out.iterdir()) and not (out / STUDENT_EDITION_MARKER).exists():
        raise ValueError(f"{out} exists and is not a student edition; refusing to replace it")
    files = tracked_files(source)
    lessons = exercise_lessons_of(files)
    if unknown := sorted(set(handed_out or []) - set(lessons)):
        raise ValueError(f"lesson(s) {', '.join(unknown)} have no exercises; lessons with exercises: "
                         f"{', '.join(lessons)}")
    chosen = lessons if handed_out is None else sorted(set(handed_out))
    if not chosen:
        raise ValueError("no lesson to hand out")
    # Written beside `out` and renamed into place at the end: an interrupted or failed run leaves the
    # earlier edition (or nothing) as it was, never half of a new one.
    out.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{out.name}.new.", dir=out.parent))
    umask = os.umask(0)
    os.umask(umask)
    staging.chmod(0o777 & ~umask)  # mkdtemp's 0700 would become the edition's own mode
    try:
        edition = _write_edition(source, staging, files, lessons, chosen)
        old = Path(tempfile.mkdtemp(prefix=f".{out.name}.old.", dir=out.parent))
        old.rmdir()
        if out.exists():  # an earlier edition (its marker says so)
            out.rename(old)
        staging.rename(out)
        shutil.rmtree(old, ignore_errors=True)
    finally:
        if staging.exists():
            shutil.rmtree(staging)
    edition.out = out
    return edition


def _write_edition(source: Path, out: Path, files: list[str], lessons: list[str], chosen: list[str]) -> Edition:
    """The edition's files in the empty folder `out`, its marker last."""
    edition = Edition(out, left_out=excluded_files(files, chosen), handed_out=chosen)
    for lesson in chosen:
        if needed := [d for d in declared_dependencies(lesson, source) if d in chosen]:
            edition.notes.append(f"lesson {lesson} builds on lesson {', '.join(needed)}, also handed out: its "
                                 f"program and tests need the students' lesson {', '.join(needed)} code first")
    kept = {f for f in files if f not in edition.left_out and (source / f).is_file()}
    # Where a link to an exercise unit goes: the stub of a lesson handed out, else the reference (working code).
    twins = {PurePosixPath(f).name: f for f in kept if f.startswith("lib/") and f.endswith(".cpp")}
    twins.update({PurePosixPath(f).name: f for f in kept if _stub_lesson(f) in chosen})
    for relative in sorted(kept):
        origin, target = source / relative, out / relative
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
    version = (_git(source, "describe", "--always", "--dirty") or "").strip()
    given = [nn for nn in lessons if nn not in chosen]
    (out / STUDENT_EDITION_MARKER).write_text(
        "This is the student edition of illum" + (f", made from {version}" if version else "")
        + f".\nExercises handed out: lessons {', '.join(chosen)}.\n"
        + (f"Lessons {', '.join(given)} are not exercises here: their units are working reference code.\n"
           if given else "")
        + "The reference solutions of the exercises handed out and the instructors' hidden tests are not part\n"
        "of it; the exercise stubs in exercises/ are built in their place. Grade your work with\n"
        "    tools/grade --student NN\n(see docs/grading.md).\n", encoding="utf-8")
    return edition


def _edition_links(text: str, out: Path, file: Path, kept: set[str], twins: dict[str, str]) -> str:
    """`text` with every link to what the edition leaves out rewritten: a unit's link to its twin (the stub
    where handed out, else the reference), anything else to its words."""

    def replace(link: Link) -> str | None:
        path = link.split()[0]
        target = resolve(out, file, path) if path and not link.external else None
        key = target.as_posix() if target is not None else ""
        if target is None or target.parts[:1] and target.parts[0] in GENERATED or key == "." or key in kept \
                or any(f.startswith(key + "/") for f in kept):
            return None
        twin = twins.get(target.name) if target.suffix == ".cpp" else None
        if twin is None:
            return link.text
        here = PurePosixPath(file.relative_to(out).as_posix()).parent.as_posix() or "."
        return f"{'!' if link.image else ''}[{link.text}]({os.path.relpath(twin, here).replace(os.sep, '/')})"

    return rewrite_links(text, replace)


def broken_links(tree: Path) -> list[str]:
    """Every link of the tree's Markdown files that does not resolve (out/ and build/ may be missing)."""
    tree = tree.resolve()
    files = [f for f in sorted(tree.rglob("*.md")) if f.relative_to(tree).parts[0] not in GENERATED + ("node_modules",)
             and "fixtures" not in f.relative_to(tree).parts]  # test data, broken on purpose
    return link_problems(tree, files, generated_ok=True)[0]


def _lesson_titles(source: Path, files: list[str], folder: str) -> dict[str, tuple[str, str]]:
    """NN -> (the folder's README, its title without "Lesson NN —") for lessons/ or exercises/."""
    titles = {}
    for f in files:
        parts = PurePosixPath(f).parts
        if len(parts) == 3 and parts[0] == folder and parts[2] == "README.md" and parts[1][:2].isdigit():
            first = (source / f).read_text(encoding="utf-8").splitlines()[:1]
            title = re.sub(r"^#\s*(Lesson|Exercise)\s+\d+\s*[—-]\s*", "", first[0]) if first else parts[1]
            titles[parts[1][:2]] = (f, title.strip())
    return titles


def student_readme(source: Path, files: list[str], handed_out: list[str]) -> str:
    """The edition's README (student_readme.md.in): what the students got, and how to build, test, see
    and grade their code, with the student commands of the top README (tools/task_tables.py writes them)."""
    match = re.search(r"<!-- student-commands: begin[^>]*-->\n(.*?)<!-- student-commands: end -->",
                      (source / "README.md").read_text(encoding="utf-8"), re.S)
    if not match:
        raise ValueError("README.md has no student-commands block (tools/task_tables.py --update writes it)")
    lessons, exercises = _lesson_titles(source, files, "lessons"), _lesson_titles(source, files, "exercises")
    slides = {PurePosixPath(f).name[:2]: f for f in files if PurePosixPath(f).parent.as_posix() == "slides"
              and f.endswith(".md") and PurePosixPath(f).name[:2].isdigit()}
    rows = [f"| {nn} | [{lessons[nn][1]}]({lessons[nn][0]}) | "
            + (f"[exercise {nn}]({exercises[nn][0]}) (yours to write)" if nn in handed_out and nn in exercises
               else "not handed out: its code is in `lib/` as working reference code")
            + f" | {f'[slides]({slides[nn]})' if nn in slides else ''} |" for nn in sorted(lessons)]
    given = [nn for nn in sorted(lessons) if nn not in handed_out]
    text = README_TEMPLATE.read_text(encoding="utf-8")
    # The paragraph on Windows and macOS only where the development container is part of the tree.
    keep = ".devcontainer/Dockerfile" in files
    text = re.sub(r"<!-- if devcontainer -->\n(.*?)<!-- end if -->\n", r"\1" if keep else "", text, flags=re.S)
    return text.format(handed_out=", ".join(handed_out), rows="\n".join(rows), commands=match.group(1).strip(),
                       first=handed_out[0] if handed_out else "NN",
                       given=f" (lessons {', '.join(given)} are working code you can read and use)" if given else "")
