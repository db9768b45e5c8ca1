"""Gradescope's autograder zip, its setup check, and grading one submission (docs/grading.md, "Gradescope").

The zip unpacks to ``$ROOT/source/`` (``/autograder`` on Gradescope; ``ILLUM_AUTOGRADER_ROOT`` moves it).
``python3 -m grading.autograder setup ROOT NN…`` (setup.sh) checks the toolchain, proves the grader on the
reference (full marks) and the stubs (0) and keeps the trusted data; any failure exits non-zero with a
message an instructor can act on, since a grader that cannot build the reference must never tell a student
that their code did not compile. ``… run ROOT NN…`` (run_autograder) installs the upload over the stubs
(``install_submission``), runs tools/grade with Gradescope's limits, and makes sure results.json exists.
"""
from __future__ import annotations

import contextlib
import json
import os
import pwd
import re
import shlex
import shutil
import stat
import subprocess
import sys
import tempfile
import zipfile
from collections import Counter
from dataclasses import asdict, dataclass, field
from pathlib import Path, PurePosixPath

from . import build
from .edition import make_student_edition
from .project import exercise_stubs
from .sandbox import Account, Sandbox, SandboxError, chown_tree, create_account, user_lock
from .suspicious import object_of, object_symbols

DEFAULT_ROOT = "/autograder"
DEFAULT_USER = "illum-student"  # the unprivileged user setup.sh creates (ILLUM_GRADE_USER changes it)

# Packages of tools/debian-packages.txt that grading does not need.
NOT_FOR_GRADING = {"chromium", "nodejs", "npm", "gnuplot-nox", "zip", "libbenchmark-dev", "libcpp-httplib-dev",
                   "pkgconf"}

# The oldest versions the grading build is checked against: Ubuntu 22.04's, Gradescope's default image.
MINIMUM_VERSIONS = {"g++": (11, 0), "cmake": (3, 22), "python3": (3, 10), "doctest": (2, 4, 8),
                    "nlohmann-json": (3, 10, 5)}

# Within Gradescope's default container (0.5 vCPU, 768 MB, 10 minutes a run; docs/grading.md, "Gradescope"):
# no test starts after 8 minutes, so that results.json is written in time.
RUN_LIMITS = {"CMAKE_BUILD_PARALLEL_LEVEL": "2", "ILLUM_GRADE_TEST_TIMEOUT": "30", "ILLUM_GRADE_TIMEOUT": "240",
              "ILLUM_GRADE_DEADLINE": "480", "ILLUM_GRADE_MEMORY_MB": "512", "ILLUM_GRADE_BUILD_TIMEOUT": "300"}


def debian_packages(root: Path) -> list[str]:
    """The package names of tools/debian-packages.txt, comments removed."""
    names: list[str] = []
    for line in (root / "tools" / "debian-packages.txt").read_text(encoding="utf-8").splitlines():
        names.extend(n for n in line.split("#", 1)[0].split() if n not in NOT_FOR_GRADING)
    return names


def _script(template: str, lessons: list[str], **values: str) -> str:
    """setup.sh or run_autograder from its template beside this file (@NAME@ replaced)."""
    text = Path(__file__).with_name(template).read_text(encoding="utf-8")
    for name, value in dict(values, DEFAULT_ROOT=DEFAULT_ROOT, LESSONS=" ".join(lessons)).items():
        text = text.replace(f"@{name}@", value)
    return text


def setup_script(packages: list[str], lessons: list[str]) -> str:
    """setup.sh: installs the build packages missing, then runs ``setup`` below (it fails loudly)."""
    return _script("setup.sh.in", lessons, PACKAGES=" ".join(shlex.quote(p) for p in packages))


def run_script(lessons: list[str]) -> str:
    """run_autograder: ``run`` below with Gradescope's limits (RUN_LIMITS) where none is set."""
    return _script("run_autograder.in", lessons,
                   LIMITS="\n".join(f'export {k}="${{{k}:-{v}}}"' for k, v in RUN_LIMITS.items()))


def _add_script(archive: zipfile.ZipFile, name: str, text: str) -> None:
    """An executable script, dated as every pack dates it."""
    info = zipfile.ZipInfo(name, date_time=(2024, 1, 1, 0, 0, 0))
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = (stat.S_IFREG | 0o755) << 16
    archive.writestr(info, text)


def hidden_test_files(root: Path, extra: Path | None) -> list[Path]:
    """The instructor's hidden test files: tests/hidden/ and --hidden DIR (READMEs left out)."""
    folders = [root / "tests" / "hidden"] + ([extra] if extra else [])
    files = [p for folder in folders if folder.is_dir() for p in sorted(folder.iterdir())
             if p.is_file() and p.suffix != ".md"]
    clashes = sorted(name for name, count in Counter(p.name for p in files).items() if count > 1)
    if clashes:
        raise ValueError(f"hidden test files with the same name in tests/hidden/ and {extra}: {', '.join(clashes)}")
    return files


def reference_units(root: Path, lessons: list[str]) -> list[Path]:
    """lib/illum/**/<name>.cpp for every exercise stub of the graded lessons."""
    units = []
    for name, stub in sorted(exercise_stubs(root, lessons).items()):
        found = sorted((root / "lib" / "illum").rglob(name))
        if len(found) != 1:
            raise ValueError(f"exercise {stub.relative_to(root)} has {len(found)} reference units in lib/illum")
        units.append(found[0])
    return units


def pack_autograder(root: Path, zip_path: Path, lessons: list[str], extra_hidden: Path | None) -> list[str]:
    """Writes the autograder zip; returns its file names (for the summary)."""
    hidden_files = hidden_test_files(root, extra_hidden)
    references = reference_units(root, lessons)
    temporary = zip_path.with_name(zip_path.name + ".tmp-pack")
    try:
        with tempfile.TemporaryDirectory(prefix="illum-autograder-") as folder:
            # Only the graded lessons are exercises there: the others are reference code, so a
            # lesson that builds on an earlier one (docs/grading.md) is graded on its own units.
            edition = make_student_edition(root, Path(folder) / "illum", lessons)
            with zipfile.ZipFile(temporary, "w") as archive:
                _add_script(archive, "setup.sh", setup_script(debian_packages(root), lessons))
                _add_script(archive, "run_autograder", run_script(lessons))
                files = [(p, "illum/" + p.relative_to(edition.out).as_posix())
                         for p in sorted(edition.out.rglob("*")) if p.is_file()]
                files += [(p, "reference/" + p.name) for p in references]
                for path, name in files + [(p, "hidden-tests/" + p.name) for p in hidden_files]:
                    archive.write(path, name, zipfile.ZIP_DEFLATED)
                names = archive.namelist()
        temporary.replace(zip_path)
    finally:
        temporary.unlink(missing_ok=True)
    return names


# --- the upload ------------------------------------------------------------------------------

# What browsers and file managers do to a name: "sphere (1).cpp", "sphere(2).cpp", "sphere-1.cpp",
# "Copy of sphere.cpp", "sphere.CPP".
_RENAMED = re.compile(r"^(?:copy of |copia de )?(?P<stem>.+?)(?:\s*\(\d+\)|-\d+| copy| copia)?\.(?:cpp|cc|cxx|c\+\+)$",
                      re.I)
MAX_ZIP_BYTES = 20 * 1024 * 1024


@dataclass
class Submission:
    """What was made of an upload; written as JSON for tools/grade --submission-info."""

    installed: list[dict[str, str]] = field(default_factory=list)  # file, target, note
    ignored: list[dict[str, str]] = field(default_factory=list)    # file, reason
    notes: list[str] = field(default_factory=list)
    expected: list[str] = field(default_factory=list)


def _skipped_part(part: str) -> bool:
    return part.startswith(".") or part == "__MACOSX"


def _through_link(submission: Path, path: Path) -> bool:
    """Whether `path` or a folder on its way down from `submission` is a symbolic link: it could point at
    the grader's own files (a zip of the reference units, say), which no upload may reach."""
    relative = path.relative_to(submission).parts
    return any((submission.joinpath(*relative[:k])).is_symlink() for k in range(1, len(relative) + 1))


def _unpack_zips(submission: Path, into: Path, report: Submission) -> list[tuple[Path, str]]:
    """(file, name shown to the student) of every file inside the zips of the upload."""
    found: list[tuple[Path, str]] = []
    for number, archive_path in enumerate(sorted(submission.rglob("*.zip"))):
        shown = archive_path.relative_to(submission).as_posix()
        # A link is not followed: install_submission reports it.
        if any(_skipped_part(p) for p in PurePosixPath(shown).parts) or _through_link(submission, archive_path):
            continue
        try:
            with zipfile.ZipFile(archive_path) as archive:
                members = [m for m in archive.infolist() if not m.is_dir()]
                if sum(m.file_size for m in members) > MAX_ZIP_BYTES:
                    report.ignored.append({"file": shown, "reason": "the zip is too large to unpack"})
                    continue
                target = into / str(number)
                for member in members:
                    parts = PurePosixPath(member.filename).parts
                    if member.filename.startswith("/") or ".." in parts or any(_skipped_part(p) for p in parts):
                        continue
                    out = target.joinpath(*parts)
                    out.parent.mkdir(parents=True, exist_ok=True)
                    out.write_bytes(archive.read(member))
                    found.append((out, f"{shown}/{member.filename}"))
                report.notes.append(f"unpacked `{shown}` (a zip in your upload) and looked inside it")
        except (zipfile.BadZipFile, OSError) as error:
            report.ignored.append({"file": shown, "reason": f"not a zip that can be opened ({error})"})
    return found


def install_submission(submission: Path, tree: Path, lessons: list[str]) -> Submission:
    """Copies the uploaded exercise files over the stubs of the graded lessons, matched by name wherever they
    are, in a zip too (the rules: docs/grading.md, "Gradescope"). A copy gets a fresh modification time, so
    that make recompiles it even if it is older than the warm build."""
    stubs = exercise_stubs(tree, lessons or None)
    report = Submission(expected=sorted(stubs))
    lowered = {name.lower(): name for name in stubs}
    with tempfile.TemporaryDirectory(prefix="illum-upload-") as folder:
        candidates: list[tuple[Path, str]] = []
        for path in sorted(submission.rglob("*")):
            relative = path.relative_to(submission)
            if any(_skipped_part(p) for p in relative.parts):
                continue
            if _through_link(submission, path):  # it could point at the grader's own files
                report.ignored.append({"file": relative.as_posix(), "reason": "a symbolic link, not a file"})
                continue
            if path.is_file() and path.suffix.lower() != ".zip":  # a zip's files are taken from inside it
                candidates.append((path, relative.as_posix()))
        candidates += _unpack_zips(submission, Path(folder), report)
        done: dict[str, str] = {}
        # An exact name first, then the file nearest the top of the upload.
        for path, shown in sorted(candidates, key=lambda item: (PurePosixPath(item[1]).name not in stubs,
                                                                 len(PurePosixPath(item[1]).parts), item[1])):
            name = PurePosixPath(shown).name
            match = _RENAMED.match(name)
            wanted = name if name in stubs else lowered.get(f"{match.group('stem')}.cpp".lower()) if match else None
            if wanted is None:
                reason = ("not an exercise file of lesson(s) " + ", ".join(lessons) if lessons else
                          "not an exercise file") if path.suffix.lower() in (".cpp", ".hpp", ".h") else "not a C++ file"
                report.ignored.append({"file": shown, "reason": reason})
                continue
            if wanted in done:
                report.ignored.append({"file": shown, "reason": f"a second {wanted}; `{done[wanted]}` was used"})
                continue
            target = stubs[wanted]
            shutil.copyfile(path, target)
            target.touch()
            done[wanted] = shown
            note = "" if name == wanted else f"taken as {wanted}; next time upload it under that name"
            report.installed.append({"file": shown, "target": target.relative_to(tree).as_posix(), "note": note})
    return report


# --- setup.sh and run_autograder -------------------------------------------------------------

class SetupError(Exception):
    """Something an instructor must fix before the autograder can grade."""


def _command_version(command: list[str]) -> tuple[tuple[int, ...], str]:
    """The version ``command`` prints on its first line (empty when none), and that line."""
    try:
        completed = subprocess.run(command, capture_output=True, text=True, check=False)
    except OSError as error:
        return (), str(error)
    text = (completed.stdout or completed.stderr).strip().splitlines()
    first = text[0] if text else ""
    match = re.search(r"(\d+)\.(\d+)(?:\.(\d+))?", first)
    return tuple(int(g) for g in match.groups() if g is not None) if match else (), first


def library_versions() -> dict[str, tuple[int, ...]]:
    """doctest and nlohmann-json as the compiler finds them (their version macros)."""
    probe = "#include <doctest/doctest.h>\n#include <nlohmann/json.hpp>\n"
    completed = subprocess.run(["c++", "-std=c++20", "-E", "-dM", "-x", "c++", "-"], input=probe,
                               capture_output=True, text=True, check=False)
    if completed.returncode != 0:
        raise SetupError("the compiler cannot include <doctest/doctest.h> and <nlohmann/json.hpp>: install "
                         "doctest-dev and nlohmann-json3-dev\n" + completed.stderr[-2000:])
    macros = dict(re.findall(r"^#define (\w+) (\d+)\s*$", completed.stdout, re.M))
    found = {library: [macros.get(prefix + part) for part in ("MAJOR", "MINOR", "PATCH")]
             for library, prefix in (("doctest", "DOCTEST_VERSION_"), ("nlohmann-json", "NLOHMANN_JSON_VERSION_"))}
    return {library: tuple(map(int, parts)) for library, parts in found.items() if all(parts)}


def check_toolchain() -> None:
    """Prints the versions found; raises SetupError if one is missing or too old."""
    found: dict[str, tuple[tuple[int, ...], str]] = {
        "g++": _command_version(["c++", "-dumpfullversion"]),
        "cmake": _command_version(["cmake", "--version"]),
        "python3": (sys.version_info[:3], sys.version.split()[0]),
    }
    found.update((name, (version, ".".join(map(str, version)))) for name, version in library_versions().items())
    lines, problems = [], []
    for name, minimum in MINIMUM_VERSIONS.items():
        version, text = found.get(name, ((), "not found"))
        ok = bool(version) and version >= minimum
        lines.append(f"  {name:<14} {'.'.join(map(str, version)) or text:<10} "
                     f"(needs {'.'.join(map(str, minimum))}){'' if ok else '  <-- TOO OLD or MISSING'}")
        if not ok:
            problems.append(f"{name} {text} is older than {'.'.join(map(str, minimum))} or missing")
    print("setup: toolchain and libraries found:\n" + "\n".join(lines), flush=True)
    if problems:
        raise SetupError("; ".join(problems) + ". Choose an Ubuntu 22.04 (or newer) or Debian 12 base image.")


def _grade(tree: Path, lessons: list[str], hidden: Path | None, results: Path,
           extra: list[str] | None = None, env: dict[str, str] | None = None) -> int:
    # The autograder's own tree, configured for the graded lessons alone (not the student preset's).
    command = [sys.executable, str(tree / "tools" / "grade"), "--student",
               "--build-dir", str(tree / "build" / "grade-student"), *(extra or [])]
    if hidden is not None:
        command += ["--hidden", str(hidden)]
    command += [*lessons, "--results", str(results)]
    print("$ " + " ".join(shlex.quote(c) for c in command), flush=True)
    return subprocess.run(command, check=False, env=env).returncode


def _paths(root: Path) -> tuple[Path, Path, Path | None, Path, Path]:
    """The unpacked autograder's source/, its tree, the hidden tests (None when there are none), the pristine
    stubs, and the grader's folder (what setup keeps for the runs, readable by root only)."""
    source = root / "source"
    tree, hidden = source / "illum", source / "hidden-tests"
    return (source, tree, hidden if any(hidden.glob("*.cpp")) else None, tree / "build" / "pristine-stubs",
            source / "grader")


def _restore_stubs(tree: Path, pristine: Path) -> None:
    for stub in sorted(pristine.rglob("*.cpp")):
        target = tree / "exercises" / stub.relative_to(pristine)
        if not target.exists() or target.read_bytes() != stub.read_bytes():
            shutil.copyfile(stub, target)
            target.touch()


def build_jobs() -> int:
    """Build jobs for this machine: one per core, but no more than memory allows (a C++ compile of
    this tree takes up to about 1.5 GB) and at most 4, so that setup.sh never swaps an image to death."""
    try:
        with open("/proc/meminfo", encoding="utf-8") as meminfo:
            fields = dict(line.split(":", 1) for line in meminfo)
        available_gb = int(fields["MemAvailable"].split()[0]) / (1024 * 1024)
    except (OSError, KeyError, ValueError):
        available_gb = 2.0
    return max(1, min(os.cpu_count() or 1, int(available_gb / 1.5), 4))


def _student_user(name: str) -> str | None:
    """Creates the unprivileged user; None (and a loud warning) where that is impossible."""
    if os.geteuid() != 0:
        print(f"setup: WARNING: not running as root, so there is no separate user for students' code: it will "
              f"run as {pwd.getpwuid(os.geteuid()).pw_name}, without privilege separation "
              "(docs/grading-defences.md, \"What is left\")", flush=True)
        return None
    try:
        account = create_account(name)
    except SandboxError as error:
        print(f"setup: WARNING: {error}; students' code will run as root, without privilege separation "
              "(docs/grading-defences.md, \"What is left\")", flush=True)
        return None
    print(f"setup: students' code is compiled and run as the user {account.name} (uid {account.uid})", flush=True)
    return account.name


def _read_results(path: Path) -> dict:
    try:
        return json.loads(path.read_text(encoding="utf-8")) if path.exists() else {}
    except ValueError:
        return {}


def reference_environment() -> dict[str, str]:
    """ccache off for the builds of the reference: no cache may keep an object of it after setup.
    ILLUM_GRADE_REFERENCE_CCACHE=1 keeps it on, for the grader's own tests (a scratch machine)."""
    keep = os.environ.get("ILLUM_GRADE_REFERENCE_CCACHE") == "1"
    return dict(os.environ, **({} if keep else {"CCACHE_DISABLE": "1"}))


def _build_witness(tree: Path, grader: Path, lessons: list[str], hidden: Path | None) -> None:
    """The witness: the tests built with the reference units (in place of the stubs) in a tree only
    root reads; its programs are kept in ``grader/witness``, and the hidden tests' observer objects
    (their expected sides cut away) in ``grader/hidden-objects``, for every run to link with the
    student's code. Nothing of it stays in the tree the student's user builds in."""
    work = grader / "witness-build"
    programs = [f"tests_lesson{nn}" for nn in lessons if any((tree / "tests").glob(f"{nn}_*"))]
    targets = programs + (["tests_hidden", "tests_hidden_observer"] if hidden else [])
    runner = build.Runner(env=reference_environment())
    step = build.configure(tree, work, lessons, hidden, runner=runner)
    if step.ok:
        step = build.build(work, targets, runner=runner)
    if not step.ok:
        raise SetupError("the reference solutions and the tests did not build (see above)")
    kept = grader / "witness"
    kept.mkdir()
    for name in programs + (["tests_hidden"] if hidden else []):
        if (work / "bin" / name).is_file():
            shutil.copy2(work / "bin" / name, kept / name)
    if hidden:
        objects = sorted((work / "tests" / "CMakeFiles" / "tests_hidden_observer_objects.dir").rglob("*.o"))
        if not objects:
            raise SetupError(f"the hidden tests' observer objects were not found in {work}")
        (grader / "hidden-objects").mkdir()
        for number, obj in enumerate(objects):
            shutil.copyfile(obj, grader / "hidden-objects" / f"{number:02d}_{obj.name}")
    shutil.rmtree(work)  # the reference's objects: no run may read them


def _stub_symbols(tree: Path, build_dir: Path, lessons: list[str]) -> dict[str, str]:
    """Demangled function name (with and without its parameters) -> the exercise unit whose stub
    defines it, so that an undefined reference at link time is blamed on the right file."""
    owners: dict[str, str] = {}
    for _name, stub in sorted(exercise_stubs(tree, lessons).items()):
        relative = stub.relative_to(tree).as_posix()
        obj = object_of(build_dir, relative)
        if obj is None:
            continue
        defined, _ = object_symbols(obj)
        for kind, _mangled, shown in defined:
            if kind in "TW" and shown.startswith("illum::"):
                owners.setdefault(shown, relative)
                owners.setdefault(shown.split("(", 1)[0], relative)
    return owners


def setup(root: Path, lessons: list[str]) -> None:
    """setup.sh's work (docs/grading.md, "Gradescope"): versions checked, the witness built, the reference
    graded (full marks) and the stubs (0), the sources nothing may read deleted, the trusted data kept."""
    source, tree, hidden, pristine, grader = _paths(root)
    check_toolchain()
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(build_jobs())
    os.environ["CMAKE_BUILD_PARALLEL_LEVEL"] = jobs
    print(f"setup: {jobs} build job(s) (CMAKE_BUILD_PARALLEL_LEVEL; from the cores and the memory available)",
          flush=True)
    user = _student_user(os.environ.get("ILLUM_GRADE_USER", DEFAULT_USER))
    if grader.exists():
        shutil.rmtree(grader)
    grader.mkdir(parents=True)
    grader.chmod(0o700)
    build_dir = tree / "build" / "grade-student"
    _check_reach(user, (tree, build_dir.parent))
    references, stubs = _keep_stubs(source, tree, pristine)
    # Builds run as root here (the sources are the instructor's); the tests run as the student's user,
    # through the same sandbox as every submission's.
    common = ["--build-as-grader"] + (["--as-user", user] if user else [])
    with tempfile.TemporaryDirectory(prefix="illum-setup-") as folder:
        print("\nsetup: building the witness (the tests with the reference solutions) where only root reads",
              flush=True)
        for unit in references:
            shutil.copyfile(unit, stubs[unit.name])
            stubs[unit.name].touch()
        _build_witness(tree, grader, lessons, hidden)
        if hidden is not None:
            shutil.rmtree(hidden)  # compiled; no run may read them
            print("setup: the hidden tests' sources are deleted", flush=True)
        try:
            with user_lock(user) if user else contextlib.nullcontext():
                tests = _prove_reference(root, lessons, common, Path(folder) / "reference.json")
                _prove_stubs(tree, lessons, common + ["--grader-data", str(grader)],
                             Path(folder) / "stubs.json", tests)
        except SandboxError as error:
            raise SetupError(str(error)) from error
    symbols = _stub_symbols(tree, build_dir, lessons)
    (grader / "stub-symbols.json").write_text(json.dumps(symbols, indent=1) + "\n", encoding="utf-8")
    (grader / "config.json").write_text(json.dumps({"user": user, "lessons": lessons}) + "\n", encoding="utf-8")
    # Nothing in source/ is writable but by root (runs make the build tree the student's while it compiles).
    chown_tree(source, 0, 0, strip_write=True)
    grader.chmod(0o700)
    print(f"setup: the prepared tree is ready: {source}", flush=True)


def _check_reach(user: str | None, paths: tuple[Path, ...]) -> None:
    """The student's user must be able to reach the build tree (every folder above it searchable)."""
    if user is None:
        return
    sandbox = Sandbox(Account.lookup(user))
    for path in paths:
        path.mkdir(parents=True, exist_ok=True)
        if not sandbox.can_reach(path):
            raise SetupError(f"the user {user} cannot reach {path}: every folder above it must be "
                             "searchable by others (chmod o+x), as /autograder is on Gradescope")


def _keep_stubs(source: Path, tree: Path, pristine: Path) -> tuple[list[Path], dict[str, Path]]:
    """Keeps the stubs as they came (for run_autograder and the fallback of a broken file); returns the
    reference units and the stubs they replace, each reference checked to have its stub."""
    if pristine.exists():
        shutil.rmtree(pristine)
    for stub in sorted((tree / "exercises").glob("[0-9][0-9]_*/*.cpp")):
        target = pristine / stub.relative_to(tree / "exercises")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(stub, target)
    references = sorted((source / "reference").glob("*.cpp"))
    if not references:
        raise SetupError(f"{source / 'reference'} holds no reference unit: repack the autograder with "
                         "tools/grade --pack-autograder")
    stubs = exercise_stubs(tree)
    for unit in references:
        if unit.name not in stubs:
            raise SetupError(f"reference/{unit.name} has no stub in exercises/: repack the autograder")
    return references, stubs


def _prove_reference(root: Path, lessons: list[str], common: list[str], results: Path) -> int:
    """Grades the reference solutions as a submission (they must score full marks), keeps their checks as
    the witness's tests.json, restores the stubs and deletes the references; returns the test count."""
    source, tree, _, pristine, grader = _paths(root)
    print("\nsetup: grading the reference solutions as a submission (they must score full marks)", flush=True)
    status = _grade(tree, lessons, None, results,
                    common + ["--grader-data", str(grader), "--save-tests", str(grader / "tests.json")],
                    env=reference_environment())
    data = _read_results(results)
    _restore_stubs(tree, pristine)
    shutil.rmtree(source / "reference")  # proved; no run may read them
    if status != 0 or not data.get("tests") or data.get("score") != data.get("max_score"):
        failed = [t["name"] for t in data.get("tests", []) if t.get("status") != "passed"]
        raise SetupError(
            f"the reference solutions did not pass (tools/grade exited {status}; score "
            f"{data.get('score')}/{data.get('max_score')}; failing: {', '.join(failed[:10]) or 'the build'}). "
            "The grader would blame students for its own fault: fix the tree, the hidden tests or the "
            "image, and repack.")
    print(f"setup: the reference scored {data['score']}/{data['max_score']} over {len(data['tests'])} tests; "
          "its units are deleted", flush=True)
    return len(data["tests"])


def _prove_stubs(tree: Path, lessons: list[str], options: list[str], results: Path, tests: int) -> None:
    """The stubs, as every submission will find them: they must score 0 over the reference's tests."""
    print("\nsetup: the stubs, as every submission will find them (they must score 0)", flush=True)
    _grade(tree, lessons, None, results, options)
    again = _read_results(results)
    if again.get("score") != 0 or len(again.get("tests", [])) != tests:
        raise SetupError(f"the stubs scored {again.get('score')} over {len(again.get('tests', []))} entries "
                         f"(expected 0 over {tests}): the grading tests do not detect unwritten code")


def _fallback_results(results: Path, message: str) -> None:
    data = {"score": 0, "output": message, "output_format": "text", "visibility": "visible",
            "stdout_visibility": "hidden",
            "tests": [{"name": "grader", "score": 0, "max_score": 0, "status": "failed", "output": message,
                       "visibility": "visible"}]}
    results.write_text(json.dumps(data, indent=2) + "\n", encoding="utf-8")


def run(root: Path, lessons: list[str]) -> int:
    """run_autograder: stubs back, the upload installed, tools/grade with Gradescope's limits, as the
    student's user; results.json only once nothing of theirs is alive."""
    source, tree, hidden, pristine, grader = _paths(root)
    results_dir = root / "results"
    results_dir.mkdir(parents=True, exist_ok=True)
    results = results_dir / "results.json"
    results.unlink(missing_ok=True)
    if not pristine.is_dir() or not (grader / "config.json").is_file():
        _fallback_results(results, "The autograder was not set up (setup.sh did not finish). This is not your "
                                   "code's fault: tell your instructor.")
        return 2
    config = json.loads((grader / "config.json").read_text(encoding="utf-8"))
    user = config.get("user")  # None: setup could not separate privileges (it said so, loudly)
    if user and os.environ.get("ILLUM_GRADE_USER"):
        user = os.environ["ILLUM_GRADE_USER"]
    _restore_stubs(tree, pristine)
    report = install_submission(root / "submission", tree, lessons)
    info = tree / "build" / "submission.json"
    info.write_text(json.dumps(asdict(report), indent=2) + "\n", encoding="utf-8")
    for item in report.installed:
        print(f"installed {item['file']} -> {item['target']} {item['note']}".rstrip())
    for item in report.ignored:
        print(f"ignored {item['file']}: {item['reason']}")
    extra = ["--submission-info", str(info), "--fallback-stubs", str(pristine),
             "--junit", str(results_dir / "junit.xml"), "--grader-data", str(grader)]
    if user:
        if user != config.get("user") and os.geteuid() == 0:
            # Several submissions graded at once (tools/grade --batch --jobs) each get a user of their own.
            create_account(user)
        extra += ["--as-user", user]
    try:
        with user_lock(user) if user else contextlib.nullcontext():
            status = _grade(tree, lessons, hidden, results, extra)
            account = Account.lookup(user) if user else None
            if account is not None:  # tools/grade did this before writing; again, whatever happened to it
                Sandbox(account).reap()
    except SandboxError as error:
        print(f"run_autograder: {error}", file=sys.stderr)
        status = 2
    if not results.exists():
        _fallback_results(results, f"The grader failed (tools/grade exited {status}) before writing results. "
                                   "This is not your code's fault: tell your instructor.")
    return 0


def main(argv: list[str]) -> int:
    """``python3 -m grading.autograder setup|run ROOT [NN ...]``."""
    if len(argv) < 2 or argv[0] not in ("setup", "run"):
        print("usage: python3 -m grading.autograder setup|run ROOT [NN ...]", file=sys.stderr)
        return 2
    command, root, lessons = argv[0], Path(argv[1]), argv[2:]
    if command == "run":
        return run(root, lessons)
    try:
        setup(root, lessons)
    except SetupError as error:
        print(f"\nsetup: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
