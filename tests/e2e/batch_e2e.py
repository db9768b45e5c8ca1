#!/usr/bin/env python3
"""End-to-end test of ``tools/grade --batch`` on a folder of submissions (docs/grading.md, "Batch grading").

Writes a class of seven submissions for lesson 01, as folders and zips, and a
roster (with one student who submitted nothing and one e-mail spelt in capitals),
runs ``tools/grade --batch DIR --jobs 2 --roster roster.csv --format canvas 01``
and checks grades.csv row by row against what each submission deserves,
worked out here, not read from the grader:

  ana      folder  the reference unit                      every test: full marks
  ben      zip     the untouched stub                      0
  carla    folder  one bug (a zero radius accepted)        all but the radius test
  dario    folder  a crash in the notes' form              all but the 4 notes' form tests
  elena    zip     an endless loop in the notes' form      all but the 4 notes' form tests
  fede     folder  an attacker: a stub that forks a daemon to rewrite results.json
                                                          0, a note for review, nothing alive afterwards
  gala     folder  a file that does not compile            "not gradable", no total (not 0)
  hugo     -       in the roster only                      "missing"

It also checks the Canvas file (the Points Possible row, an empty grade for
the not gradable and the missing), that each student's results.json exists
and was written only by the grader, and the progress lines on stderr.

The batch runs without the git program on PATH (an instructor's machine, or
a tree, without git): the autograder is packed from the tree's files less
what .gitignore ignores.

    python3 tests/e2e/batch_e2e.py --work-dir DIR
"""
from __future__ import annotations

import argparse
import csv
import io
import json
import os
import re
import shutil
import subprocess
import sys
import time
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
STUB = ROOT / "exercises" / "01_ray_sphere" / "sphere.cpp"
REFERENCE = ROOT / "lib" / "illum" / "geometry" / "sphere.cpp"
ATTACK = ROOT / "tests" / "attacks" / "fork_rewrites_results.cpp"
NOTES = "notes' form"
RADIUS_TEST = "Sphere refuses a zero, negative or non-finite radius"

failures: list[str] = []


def check(condition: bool, message: str) -> bool:
    if not condition:
        failures.append(message)
        print(f"  FAILED: {message}", flush=True)
    return condition


def mutate(text: str, pattern: str, replacement: str) -> str:
    changed, count = re.subn(pattern, replacement, text, count=1)
    if count != 1:
        sys.exit(f"batch e2e: {pattern!r} is not in the file it should change")
    return changed


def with_hook(text: str, payload: str, hook: str) -> str:
    at = text.index("namespace illum {")
    text = text[:at] + payload + "\n" + text[at:]
    return mutate(text, hook, r"\1\n  attack_hook();")


def class_of_submissions(folder: Path) -> None:
    reference = REFERENCE.read_text(encoding="utf-8")
    notes = r"(SphereRoots<T> sphere_roots_notes\([^{]*\{)"
    crash = "namespace {\nvoid attack_hook() {\n  volatile int* nowhere = nullptr;\n  *nowhere = 1;\n}\n}  // namespace\n"
    loop = "namespace {\nvoid attack_hook() {\n  for (volatile bool forever = true; forever;) {\n  }\n}\n}  // namespace\n"
    files = {
        "ana/sphere.cpp": reference,
        "carla/work/sphere.cpp": mutate(reference, r"radius > 0\.0", "radius >= 0.0"),
        "dario/sphere.cpp": with_hook(reference, crash, notes),
        "fede/sphere.cpp": with_hook(STUB.read_text(encoding="utf-8"), ATTACK.read_text(encoding="utf-8"),
                                     r"(Sphere::Sphere\([^{]*\{)"),
        "gala/sphere.cpp": reference + "\nthis line is not C++\n",
    }
    for relative, text in files.items():
        (folder / relative).parent.mkdir(parents=True, exist_ok=True)
        (folder / relative).write_text(text, encoding="utf-8")
    for name, text in (("ben", STUB.read_text(encoding="utf-8")), ("elena", with_hook(reference, loop, notes))):
        with zipfile.ZipFile(folder / f"{name}.zip", "w") as archive:
            archive.writestr("homework/sphere.cpp", text)
    (folder / "notes.txt").write_text("not a submission\n", encoding="utf-8")


ROSTER = """Student,ID,SIS User ID,SIS Login ID,Section,Email
Ana A,101,s101,ana,T1,ana@uni.example
Ben B,102,s102,ben,T1,ben@uni.example
Carla C,103,s103,carla,T1,CARLA@uni.example
Dario D,104,s104,dario,T2,dario@uni.example
Elena E,105,s105,elena,T2,elena@uni.example
Fede F,106,s106,fede,T2,fede@uni.example
Gala G,107,s107,gala,T2,gala@uni.example
Hugo H,108,s108,hugo,T2,hugo@uni.example
"""


def path_without_git(work: Path) -> str:
    """PATH with every folder that holds a git program replaced by a copy of its links less git."""
    folders = []
    for number, folder in enumerate(os.environ.get("PATH", "").split(os.pathsep)):
        if not folder or not (Path(folder) / "git").exists():
            folders.append(folder)
            continue
        mirror = work / "path-without-git" / str(number)
        mirror.mkdir(parents=True)
        for program in Path(folder).iterdir():
            if program.name != "git":
                (mirror / program.name).symlink_to(program)
        folders.append(str(mirror))
    return os.pathsep.join(folders)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--work-dir", type=Path, required=True)
    args = parser.parse_args(argv)
    work = args.work_dir.resolve()
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    work.chmod(0o755)
    submissions, out = work / "submissions", work / "grades"
    submissions.mkdir()
    class_of_submissions(submissions)
    (work / "roster.csv").write_text(ROSTER, encoding="utf-8")
    # Users of its own: CTest runs the end-to-end tests side by side, and every process of a grading
    # user is killed at the end of each run.
    env = dict(os.environ, ILLUM_GRADE_TEST_TIMEOUT="3", PYTHONDONTWRITEBYTECODE="1", ILLUM_GRADE_USER="illum-test-b",
               PATH=path_without_git(work), ILLUM_GRADE_REFERENCE_CCACHE="1")
    if shutil.which("git", path=env["PATH"]):
        sys.exit("batch e2e: git is still on the PATH meant to be without it")
    command = [sys.executable, str(ROOT / "tools" / "grade"), "--batch", str(submissions), "--out", str(out),
               "--jobs", "2", "--roster", str(work / "roster.csv"), "--format", "canvas", "--assignment",
               "Lesson 01", "--work-dir", str(work / "batch-work"), "01"]
    start = time.monotonic()
    done = subprocess.run(command, env=env, capture_output=True, text=True, errors="replace", check=False)
    seconds = time.monotonic() - start
    print(done.stderr[-6000:])
    print(f"tools/grade --batch: exit {done.returncode} in {seconds:.1f} s", flush=True)
    check(done.returncode == 0, f"tools/grade --batch exited {done.returncode}")
    check(bool(re.search(r"\[\d/7\] ana: ", done.stderr)), "no progress line for ana on stderr")
    check("skipped notes.txt" in done.stderr, "the stray notes.txt is not reported as skipped")
    check("Traceback" not in done.stderr, "a traceback on stderr")
    check("its builds: no time limit" in done.stderr, "setup's builds are not said to be without a time limit")
    if not check((out / "grades.csv").is_file(), "no grades.csv"):
        return 1
    raw = (out / "grades.csv").read_bytes()
    check(raw.startswith("\ufeffid,".encode()) and b"\r\n" in raw and b"\n" not in raw.replace(b"\r\n", b""),
          "grades.csv is not UTF-8 with a BOM and CRLF line ends")
    rows = list(csv.DictReader(io.StringIO(raw.decode("utf-8-sig"), newline="")))
    by_id = {row["id"]: row for row in rows}
    check([row["id"] for row in rows] == ["ana", "ben", "carla", "dario", "elena", "fede", "gala", "hugo"],
          f"the rows are not the roster's, in its order: {[row['id'] for row in rows]}")
    header = list(rows[0]) if rows else []
    tests = [h for h in header if h.startswith("lesson01: ") or h.startswith("lesson01 (hidden): ")]
    check("lesson01" in header and "total" in header and "status" in header, "a column is missing")
    check(len(tests) >= 10, f"only {len(tests)} per-test columns")
    notes_tests = [h for h in tests if NOTES in h]
    check(len(notes_tests) == 4, f"expected the 4 notes' form tests (3 in grading.cpp, 1 in grading_power.cpp) among the columns, found {len(notes_tests)}")
    ana = by_id.get("ana", {})
    full = float(ana["total"]) if ana.get("total") else 0.0
    check(full > 0 and ana.get("max") == ana.get("total"), f"ana (the reference) scored {ana.get('total')!r} of "
                                                           f"{ana.get('max')!r}")
    points = {h: float(ana[h]) if ana.get(h) else 0.0 for h in tests}
    check(all(v > 0 for v in points.values()), "ana (the reference) failed a test")

    def expect(ident: str, status: str, total: float | None, failing: set[str] | None = None) -> None:
        row = by_id.get(ident)
        if not check(row is not None, f"{ident}: no row"):
            return
        check(row["status"] == status, f"{ident}: status {row['status']!r}, expected {status!r}")
        shown = None if row["total"] == "" else float(row["total"])
        check(shown == total, f"{ident}: total {row['total']!r}, expected {total}")
        if failing is not None:
            zero = {h for h in tests if row[h] == "0"}
            check(zero == failing, f"{ident}: the failing tests are {sorted(zero)}, expected {sorted(failing)}")
            check(row["lesson01"] == f"{total:g}", f"{ident}: lesson01 {row['lesson01']!r}, expected {total:g}")

    def without(failing: set[str]) -> float:
        return full - sum(points[h] for h in failing)

    radius = {h for h in tests if h == f"lesson01: {RADIUS_TEST}"}
    check(len(radius) == 1, "the radius test is not a column")
    expect("ana", "graded", full, set())
    expect("ben", "graded", 0.0, set(tests))
    expect("carla", "graded", without(radius), radius)
    expect("dario", "graded", without(set(notes_tests)), set(notes_tests))
    expect("elena", "graded", without(set(notes_tests)), set(notes_tests))
    expect("fede", "graded", 0.0, set(tests))
    check("review" in by_id.get("fede", {}).get("notes", ""), "fede: the notes do not point to the review notes")
    expect("gala", "not gradable", None)
    check(by_id.get("gala", {}).get("lesson01") == "not gradable", "gala: lesson01 is not 'not gradable'")
    check(all(by_id.get("gala", {}).get(h, "") == "" for h in tests), "gala: test cells are not empty")
    expect("hugo", "missing", None)
    check(by_id.get("carla", {}).get("roster: Email") == "CARLA@uni.example", "carla: the roster's columns are lost")

    for ident in ("ana", "ben", "carla", "dario", "elena", "fede", "gala"):
        results = out / ident / "results.json"
        if check(results.is_file(), f"{ident}: no results.json"):
            data = json.loads(results.read_text(encoding="utf-8"))
            check(isinstance(data.get("score"), (int, float)) and data.get("tests"), f"{ident}: results.json")
    fede = json.loads((out / "fede" / "results.json").read_text(encoding="utf-8"))
    check(fede.get("score") == 0, "fede: results.json was rewritten by the attack")

    canvas = list(csv.reader(io.StringIO((out / "grades-canvas.csv").read_bytes().decode("utf-8-sig"), newline="")))
    check(canvas[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Lesson 01"],
          f"canvas header {canvas[0]}")
    check(canvas[1][0] == "Points Possible" and canvas[1][5] == f"{full:g}", f"canvas points row {canvas[1]}")
    grades = {row[3]: row[5] for row in canvas[2:]}
    check(grades.get("ana") == f"{full:g}" and grades.get("ben") == "0", f"canvas grades {grades}")
    check(grades.get("gala") == "" and grades.get("hugo") == "", "canvas: not gradable and missing must be empty")
    check(canvas[2][:5] == ["Ana A", "101", "s101", "ana", "T1"], f"canvas: ana's row {canvas[2]}")
    if failures:
        print(f"batch e2e: {len(failures)} check(s) failed")
        return 1
    print(f"batch e2e: every check passed ({seconds:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
