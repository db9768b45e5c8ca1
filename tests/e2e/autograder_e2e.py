#!/usr/bin/env python3
"""End-to-end test of the Gradescope autograder, as an instructor would run it.

Packs the autograder for lesson 01 (tools/grade --pack-autograder), unpacks it
into a fresh /autograder-shaped folder (source/, submission/, results/; the
scripts find it through ILLUM_AUTOGRADER_ROOT), runs setup.sh once, then
run_autograder on six submissions, and checks each results.json against
Gradescope's documented format and the expected score:

  stub          the untouched stub                      0 / max
  correct       the reference unit as the student's     max / max
  failing       the reference with one bug              0 < score < max
  no-compile    a file that does not compile            graded as the stub, and said so
  endless-loop  one function never returns              only the tests that call it fail
  subfolder     "my work/lesson 01/sphere (1).cpp"      max / max, the rename explained
  broken-hidden the hidden tests' objects kept by setup.sh damaged afterwards, so that
                tests_hidden does not link: the visible tests graded, students told the grader
                is misconfigured, the linker's output only in an entry hidden from them

After setup.sh it also checks what setup promises: the reference units and the hidden
tests' sources are gone, and what it keeps for the runs is readable by root only.

Prints the time of setup.sh and of each run. ccache is used when installed,
so a second run reuses the first one's objects.

    python3 tests/e2e/autograder_e2e.py --work-dir DIR
"""
from __future__ import annotations

import argparse
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
LESSON = "01"
UNIT = "sphere.cpp"
STUB = ROOT / "exercises" / "01_ray_sphere" / UNIT
REFERENCE = ROOT / "lib" / "illum" / "geometry" / UNIT

# Gradescope's results.json (gradescope-autograders.readthedocs.io, "Autograder specifications").
VISIBILITIES = {"hidden", "after_due_date", "after_published", "visible"}
FORMATS = {"text", "html", "simple_format", "md", "ansi"}
TOP_KEYS = {"score", "max_score", "execution_time", "output", "output_format", "test_output_format",
            "test_name_format", "visibility", "stdout_visibility", "extra_data", "tests", "leaderboard"}
TEST_KEYS = {"score", "max_score", "status", "name", "name_format", "number", "output", "output_format", "tags",
             "visibility", "extra_data"}

failures: list[str] = []


def check(condition: bool, message: str) -> bool:
    if not condition:
        failures.append(message)
        print(f"  FAILED: {message}", flush=True)
    return condition


def check_schema(case: str, data: dict) -> None:
    """The shape Gradescope accepts, and sums that add up."""
    number = (int, float)
    check(isinstance(data, dict), f"{case}: results.json is not an object")
    check(set(data) <= TOP_KEYS, f"{case}: unknown top-level keys {sorted(set(data) - TOP_KEYS)}")
    check(isinstance(data.get("score"), number), f"{case}: score is missing or not a number")
    check(isinstance(data.get("output"), str), f"{case}: output is not a string")
    check(data.get("output_format") in FORMATS, f"{case}: output_format {data.get('output_format')!r}")
    check(data.get("test_output_format", "text") in FORMATS, f"{case}: test_output_format")
    check(data.get("visibility") in VISIBILITIES, f"{case}: visibility {data.get('visibility')!r}")
    check(data.get("stdout_visibility") in VISIBILITIES, f"{case}: stdout_visibility")
    tests = data.get("tests")
    if not check(isinstance(tests, list) and tests, f"{case}: no tests"):
        return
    for test in tests:
        name = test.get("name", "?")
        check(set(test) <= TEST_KEYS, f"{case}: test {name}: unknown keys {sorted(set(test) - TEST_KEYS)}")
        for key in ("name", "score", "max_score", "status", "output", "visibility"):
            check(key in test, f"{case}: test {name} has no {key}")
        check(isinstance(test.get("name"), str) and test.get("name"), f"{case}: a test without a name")
        check(isinstance(test.get("score"), number) and isinstance(test.get("max_score"), number),
              f"{case}: test {name}: score/max_score not numbers")
        check(0 <= test.get("score", 0) <= test.get("max_score", 0), f"{case}: test {name}: score out of range")
        check(test.get("status") in ("passed", "failed"), f"{case}: test {name}: status {test.get('status')!r}")
        check(test.get("visibility") in VISIBILITIES, f"{case}: test {name}: visibility")
        check(test.get("output_format", "text") in FORMATS, f"{case}: test {name}: output_format")
    total = sum(t.get("score", 0) for t in tests)
    check(abs(total - data.get("score", -1)) < 1e-9, f"{case}: score {data.get('score')} != sum of tests {total}")
    if "max_score" in data:
        check(abs(sum(t.get("max_score", 0) for t in tests) - data["max_score"]) < 1e-9,
              f"{case}: max_score is not the sum of the tests'")
    if any(t.get("visibility") == "hidden" for t in tests):
        # Gradescope hides the total from students while hidden tests exist; so must we.
        check("(hidden)" not in data["output"], f"{case}: the visible output shows the hidden tests' row")
        check(not re.search(r"(?m)^total", data["output"]), f"{case}: the visible output shows the total")


def mutate(text: str, pattern: str, replacement: str, what: str) -> str:
    changed, count = re.subn(pattern, replacement, text, count=1)
    if count != 1:
        sys.exit(f"autograder e2e: cannot make the '{what}' submission: {pattern!r} is not in {REFERENCE}")
    return changed


SECRET = "SECRET_EXPECTED_VALUE_42"
HIDDEN_NAME = "the 3-4-5 " + "triangle says"  # a hidden test's name (split: this file is in the tree too)


def submissions() -> dict[str, dict[str, str]]:
    """case -> {path inside the upload: content}."""
    reference = REFERENCE.read_text(encoding="utf-8")
    failing = mutate(reference, r"radius > 0\.0", "radius >= 0.0", "failing")  # a zero radius accepted
    broken = reference + "\nthis line is not C++\n"
    looping = mutate(reference, r"(SphereRoots<T> sphere_roots_notes\([^{]*\{)",
                     r"\1\n  for (volatile bool forever = true; forever;) {\n  }", "endless loop")
    return {
        "stub": {UNIT: STUB.read_text(encoding="utf-8")},
        "correct": {UNIT: reference, "notes.txt": "my notes"},
        "failing": {UNIT: failing},
        "no-compile": {UNIT: broken},
        "endless-loop": {UNIT: looping},
        "subfolder": {"my work/lesson 01/sphere (1).cpp": reference},
        "broken-hidden": {UNIT: reference},
    }


def run(command: list[str], env: dict[str, str], cwd: Path | None = None) -> tuple[int, float, str]:
    start = time.monotonic()
    completed = subprocess.run(command, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True, errors="replace", check=False)
    return completed.returncode, time.monotonic() - start, completed.stdout


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--work-dir", type=Path, required=True)
    parser.add_argument("--test-timeout", default="3", help="seconds per test case in the runs (default 3)")
    args = parser.parse_args(argv)
    work = args.work_dir.resolve()
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    ag = work / "autograder"

    # A grading user of its own (ILLUM_GRADE_USER): CTest runs the end-to-end tests side by side, and
    # every process of a grading user is killed at the end of each run.
    env = dict(os.environ, ILLUM_AUTOGRADER_ROOT=str(ag), CMAKE_BUILD_PARALLEL_LEVEL="2",
               ILLUM_GRADE_TEST_TIMEOUT=args.test_timeout, PYTHONDONTWRITEBYTECODE="1",
               ILLUM_GRADE_USER="illum-test-ag")
    if shutil.which("ccache"):
        env.update(CMAKE_CXX_COMPILER_LAUNCHER="ccache", CCACHE_BASEDIR=str(ag), CCACHE_NOHASHDIR="1",
                   ILLUM_GRADE_REFERENCE_CCACHE="1")

    zip_path = work / "autograder.zip"
    status, seconds, output = run([sys.executable, str(ROOT / "tools" / "grade"), "--pack-autograder",
                                   str(zip_path), LESSON], env)
    if status != 0:
        print(output)
        sys.exit(f"autograder e2e: packing failed (exit {status})")
    print(f"packed {zip_path.name} in {seconds:.1f} s", flush=True)
    with zipfile.ZipFile(zip_path) as archive:
        names = archive.namelist()
        check(f"reference/{UNIT}" in names, "the zip has no reference unit for setup.sh")
        check(not any(n.startswith("illum/lib/") and n.endswith("/" + UNIT) for n in names),
              "the student edition in the zip holds the reference unit")
        archive.extractall(ag / "source")
    for name in ("setup.sh", "run_autograder", "illum/tools/grade"):  # extractall drops the modes
        (ag / "source" / name).chmod(0o755)
    (ag / "results").mkdir()

    status, seconds, output = run(["bash", str(ag / "source" / "setup.sh")], env)
    times = {"setup.sh": seconds}
    print(output[-3000:])
    print(f"setup.sh: exit {status} in {seconds:.1f} s", flush=True)
    if not check(status == 0, f"setup.sh exited {status}"):
        return 1
    check("the reference scored" in output and "toolchain and libraries found" in output,
          "setup.sh did not show the versions and the reference's score")
    source = ag / "source"
    check(not (source / "reference").exists(), "setup.sh left the reference units in the image")
    check(not any((source / "hidden-tests").glob("*.cpp")), "setup.sh left the hidden tests' sources in the image")
    check(not list((source / "illum").rglob(f"lib/**/{UNIT}")), "the reference unit is in the student edition")
    grader = source / "grader"
    check(grader.is_dir() and (grader.stat().st_mode & 0o077) == 0,
          "the grader's data (trusted test list, hidden objects) is readable by others than root")
    check(any((grader / "hidden-objects").glob("*.o")), "setup.sh kept no hidden test objects")
    check((grader / "witness" / "tests_hidden").is_file(), "setup.sh kept no hidden witness program")
    # Nothing the student's user can read holds a hidden test: no source, object, program or
    # rewritten source of the observer (the hidden test's name is in each of them).
    readable = [p for p in (source / "illum").rglob("*") if p.is_file() and not p.is_symlink()
                and p.stat().st_mode & 0o004 and HIDDEN_NAME.encode() in p.read_bytes()]
    check(not readable, f"files readable by the student's user hold a hidden test: {readable[:3]}")

    expected_max = visible_max = None
    for case, files in submissions().items():
        submission = ag / "submission"
        if submission.exists():
            shutil.rmtree(submission)
        for relative, text in files.items():
            (submission / relative).parent.mkdir(parents=True, exist_ok=True)
            (submission / relative).write_text(text, encoding="utf-8")
        if case == "broken-hidden":
            damaged = sorted((ag / "source" / "grader" / "hidden-objects").glob("*.o"))[0]
            damaged.write_text(f"not an object file: {SECRET}\n", encoding="utf-8")
        status, seconds, output = run(["bash", str(ag / "source" / "run_autograder")], env)
        times[case] = seconds
        results = ag / "results" / "results.json"
        print(f"\n--- {case}: run_autograder exit {status} in {seconds:.1f} s", flush=True)
        if not check(results.exists(), f"{case}: no results.json"):
            print(output[-3000:])
            continue
        shutil.copyfile(results, work / f"results-{case}.json")  # kept for a look afterwards
        data = json.loads(results.read_text(encoding="utf-8"))
        check_schema(case, data)
        tests = [t for t in data.get("tests", []) if not t["name"].startswith("build")]
        visible = [t for t in tests if t["visibility"] == "visible"]
        score, max_score = data.get("score"), data.get("max_score")
        print(f"    score {score}/{max_score}; {sum(t['status'] == 'passed' for t in tests)}/{len(tests)} tests "
              "passed", flush=True)
        if case == "stub":
            expected_max = max_score
            visible_max = sum(t["max_score"] for t in visible)
            check(score == 0, f"stub: score {score}, expected 0")
            check(all("not implemented yet" in t["output"] for t in visible), "stub: a failure is not a NotImplemented")
        elif case in ("correct", "subfolder"):
            check(score == max_score == expected_max, f"{case}: score {score}/{max_score}, expected full marks")
            check("used `" in data["output"], f"{case}: results.json does not say which file was used")
            if case == "subfolder":
                check("taken as sphere.cpp" in data["output"], "subfolder: the renamed file is not explained")
            else:
                check("ignored `notes.txt`" in data["output"], "correct: the ignored file is not listed")
        elif case == "failing":
            check(0 < score < max_score, f"failing: score {score}/{max_score}, expected between")
            failed = [t for t in visible if t["status"] == "failed"]
            check(failed and all(t["output"] for t in failed), "failing: a failed test without an explanation")
        elif case == "no-compile":
            check(score == 0, f"no-compile: score {score}, expected the stub's 0")
            builds = [t for t in data["tests"] if t["name"].startswith("build:")]
            check(len(builds) == 1 and "this line is not C++" in builds[0]["output"],
                  "no-compile: no build entry with the compiler's message")
            check(data["output"].count("this line is not C++") == 0, "no-compile: compiler output shown twice")
            check(max_score == expected_max, "no-compile: the lesson's tests were not graded (on the stub)")
        elif case == "endless-loop":
            hung = [t for t in tests if "did not finish" in t["output"]]
            check(bool(hung), "endless-loop: no test reported as not finishing")
            check(0 < score < max_score, f"endless-loop: score {score}/{max_score}; only the looping tests may fail")
            check(max_score == expected_max, "endless-loop: some tests have no result")
            check(all("notes' form" in t["name"] or "hidden" in t["name"] for t in hung),
                  "endless-loop: a test that does not call sphere_roots_notes timed out")
        elif case == "broken-hidden":
            shown = [t for t in data["tests"] if t["visibility"] != "hidden"]
            entry = [t for t in data["tests"] if t["name"].startswith("hidden tests: build")]
            check(len(entry) == 1 and entry[0]["visibility"] == "hidden" and damaged.name in entry[0]["output"],
                  "broken-hidden: the linker's output is not in an entry hidden from students")
            check(damaged.name not in data["output"] and all(damaged.name not in t["output"] for t in shown),
                  "broken-hidden: students can read the hidden tests' file names")
            check(SECRET not in json.dumps(data), "broken-hidden: the damaged object's content reached the results")
            check("misconfigured" in data["output"] and "did not compile" not in data["output"],
                  "broken-hidden: the students' output does not say the grader is misconfigured")
            check(score == max_score == visible_max,
                  f"broken-hidden: score {score}/{max_score}; the {visible_max} visible points should all pass")
    print("\ntimes (s): " + ", ".join(f"{k} {v:.1f}" for k, v in times.items()))
    if failures:
        print(f"autograder e2e: {len(failures)} check(s) failed")
        return 1
    print("autograder e2e: every check passed")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
