"""Gradescope's autograder zip, and putting a submission in place.

The zip unpacks to /autograder/source/ as:

    setup.sh          installs tools/debian-packages.txt and warms the build
    run_autograder    installs the submission, runs tools/grade --student
    illum/            the student edition of the tree (no reference units)
    hidden-tests/     tests/hidden/ plus the --hidden folder given when packing

Gradescope runs ``setup.sh`` once when it builds the image and
``run_autograder`` once per submission, with the student's files in
/autograder/submission/ and results expected in /autograder/results/.
"""
from __future__ import annotations

import shlex
import shutil
import stat
import sys
import tempfile
import zipfile
from pathlib import Path

from .edition import make_student_edition
from .project import exercise_stubs

SOURCE = "/autograder/source"
SUBMISSION = "/autograder/submission"
RESULTS = "/autograder/results"

# Packages of tools/debian-packages.txt that grading does not need.
NOT_FOR_GRADING = {"chromium", "nodejs", "npm", "gnuplot-nox", "zip", "libbenchmark-dev"}


def debian_packages(root: Path) -> list[str]:
    """The package names of tools/debian-packages.txt, comments removed."""
    names: list[str] = []
    for line in (root / "tools" / "debian-packages.txt").read_text(encoding="utf-8").splitlines():
        names.extend(n for n in line.split("#", 1)[0].split() if n not in NOT_FOR_GRADING)
    return names


def setup_script(packages: list[str], grade_arguments: list[str]) -> str:
    return f"""#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder image.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends {" ".join(shlex.quote(p) for p in packages)}

# Everything comes from the distribution's packages: CMakeLists.txt needs
# CMake 3.22 (Ubuntu 22.04's); only the presets, unused here, need 3.25.
# chromium, nodejs and npm serve the slides, not grading, and are skipped.

chmod +x {SOURCE}/run_autograder {SOURCE}/illum/tools/grade
# Build once with the stubs, so that grading a submission recompiles only the
# student's files. The score of this run means nothing.
cd {SOURCE}/illum
python3 tools/grade {" ".join(shlex.quote(a) for a in grade_arguments)} > /dev/null 2>&1 || true
"""


def run_script(lessons: list[str], grade_arguments: list[str]) -> str:
    return f"""#!/usr/bin/env bash
# Gradescope runs this for every submission. tools/grade writes results.json
# whatever happens (a compile error gives score 0 and the compiler's output).
set -uo pipefail
mkdir -p {RESULTS}
cd {SOURCE}/illum
PYTHONPATH=tools python3 -m grading.autograder {SUBMISSION} . {" ".join(lessons)}
python3 tools/grade {" ".join(shlex.quote(a) for a in grade_arguments)} \\
    --results {RESULTS}/results.json --junit {RESULTS}/junit.xml
exit 0
"""


def _add(archive: zipfile.ZipFile, path: Path, name: str) -> None:
    """Adds a file keeping its executable bit (zipfile.write does, explicitly here for the scripts)."""
    info = zipfile.ZipInfo.from_file(path, name)
    info.compress_type = zipfile.ZIP_DEFLATED
    with path.open("rb") as data:
        archive.writestr(info, data.read())


def _add_text(archive: zipfile.ZipFile, name: str, text: str, executable: bool) -> None:
    info = zipfile.ZipInfo(name, date_time=(2024, 1, 1, 0, 0, 0))
    info.compress_type = zipfile.ZIP_DEFLATED
    mode = 0o755 if executable else 0o644
    info.external_attr = (stat.S_IFREG | mode) << 16
    archive.writestr(info, text)


def hidden_test_files(root: Path, extra: Path | None) -> list[Path]:
    """The instructor's hidden test files: tests/hidden/ and --hidden DIR (READMEs left out)."""
    folders = [root / "tests" / "hidden"] + ([extra] if extra else [])
    files = []
    for folder in folders:
        if folder.is_dir():
            files.extend(p for p in sorted(folder.iterdir()) if p.is_file() and p.suffix != ".md")
    names = [p.name for p in files]
    clashes = sorted({n for n in names if names.count(n) > 1})
    if clashes:
        raise ValueError(f"hidden test files with the same name in tests/hidden/ and {extra}: {', '.join(clashes)}")
    return files


def pack_autograder(root: Path, zip_path: Path, lessons: list[str], extra_hidden: Path | None) -> list[str]:
    """Writes the autograder zip; returns its file names (for the summary)."""
    hidden_files = hidden_test_files(root, extra_hidden)
    grade_arguments = ["--student"]
    if hidden_files:
        grade_arguments += ["--hidden", f"{SOURCE}/hidden-tests"]
    grade_arguments += lessons
    with tempfile.TemporaryDirectory(prefix="illum-autograder-") as folder:
        edition = make_student_edition(root, Path(folder) / "illum")
        zip_path.parent.mkdir(parents=True, exist_ok=True)
        temporary = zip_path.with_name(zip_path.name + ".tmp-pack")
        with zipfile.ZipFile(temporary, "w") as archive:
            _add_text(archive, "setup.sh", setup_script(debian_packages(root), grade_arguments), True)
            _add_text(archive, "run_autograder", run_script(lessons, grade_arguments), True)
            for path in sorted(edition.out.rglob("*")):
                if path.is_file():
                    _add(archive, path, "illum/" + path.relative_to(edition.out).as_posix())
            for path in hidden_files:
                _add(archive, path, "hidden-tests/" + path.name)
            names = archive.namelist()
        temporary.replace(zip_path)
    return names


def install_submission(submission: Path, tree: Path, lessons: list[str]) -> tuple[list[str], list[str]]:
    """Copies the submitted .cpp files over the stubs of the graded lessons.

    Files are matched by name (exercise units have unique names), wherever
    the student put them in the submission. Returns (installed, ignored).
    The copy gets a fresh modification time so that make recompiles it even
    if the student's file is older than the build warmed up by setup.sh.
    """
    stubs = {name: path for name, path in exercise_stubs(tree).items()
             if not lessons or path.parent.name[:2] in lessons}
    installed: list[str] = []
    ignored: list[str] = []
    done: set[str] = set()
    # Shallowest first: a file at the top of the submission wins over a copy in a subfolder.
    candidates = sorted(submission.rglob("*.cpp"), key=lambda p: (len(p.parts), str(p)))
    for path in candidates:
        relative = path.relative_to(submission).as_posix()
        if any(part.startswith(".") or part == "__MACOSX" for part in path.relative_to(submission).parts):
            continue
        if path.name in stubs and path.name not in done:
            target = stubs[path.name]
            shutil.copyfile(path, target)
            target.touch()
            done.add(path.name)
            installed.append(f"{relative} -> {target.relative_to(tree).as_posix()}")
        else:
            ignored.append(relative)
    return installed, ignored


def main(argv: list[str]) -> int:
    """``python3 -m grading.autograder SUBMISSION TREE [NN ...]`` (used by run_autograder)."""
    if len(argv) < 2:
        print("usage: python3 -m grading.autograder SUBMISSION TREE [NN ...]", file=sys.stderr)
        return 2
    submission, tree, lessons = Path(argv[0]), Path(argv[1]), argv[2:]
    installed, ignored = install_submission(submission, tree, lessons)
    for line in installed:
        print(f"installed {line}")
    for line in ignored:
        print(f"ignored {line} (not an exercise file of the graded lessons)")
    if not installed:
        expected = sorted(name for name, path in exercise_stubs(tree).items()
                          if not lessons or path.parent.name[:2] in lessons)
        print("None of your files matched an exercise file; expected: " + ", ".join(expected))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
