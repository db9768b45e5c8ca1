#!/usr/bin/env python3
"""Hostile submissions against the Gradescope autograder (docs/grading-defences.md, "Threat model").

Packs the autograder for lessons 01 and 02 from a grader tree (this one by
default; ``--grader-tree /path/to/an/older/checkout`` shows what an older
grader did with the same submissions), runs its setup.sh once, then
run_autograder on each hostile submission in a fresh copy of the prepared
tree, as Gradescope runs it (a fresh container per submission), and checks
that the submission got its honest score and achieved nothing else.

The submissions are built from tests/attacks/: each payload there is put
into the stub (a forgery must not turn 0 into full marks) or the reference
(a fault must cost only what it should) of an exercise file, with a call
to its ``attack_hook()`` at the start of a chosen function. The cases, one
per attack class of the threat model:

  fork_rewrites_results   a forked daemon rewrites results.json after the grader   stub: 0
  fake_reporter           its own doctest reporter under the grader's name         stub: 0
  rewrite_records         rewrites the records file named on the command line      stub: 0
  define_write            its own write() edits the records in flight              stub: 0
  include_reference       #include "../../../reference/sphere.cpp"                 0 (no reference to read)
  leak_hidden_exception   an exception message quoting the hidden tests            nothing hidden in the feedback
  leak_hidden_compile     a compile error quoting the hidden tests                 nothing hidden in the feedback
  gigabyte_stdout         1 GiB on stdout, then correct code                       full marks, in time
  segfault                a crash in the notes' form                               all but the notes' form tests
  duplicate_helper        a helper defined in both of lesson 02's files            lesson 01 full, 02 costs 0, linker's words shown
  exit_in_test            exit(0) in the notes' form                               the notes' form tests fail, saying so
  leave_processes         a daemon left running                                    nothing alive afterwards
  out_of_memory           3 GiB asked for in the notes' form                       those tests fail: "out of memory"
  forge_stream            before any test, a whole forged record stream on the     stub: 0
                          records channel (raw system calls behind a macro), then
                          exit, or sleep until the grader's limit
  repoint_stdout          stdout's FILE pointed at the records channel             stub: 0
  probe_grader_files      __has_include / #include of the grader's own files       0, nothing of the grader quoted
  shared_memory           7 x 100 MB of System V shared memory, 100 MB in          with namespaces: full marks (the
                          /dev/shm, a file in /run/lock (correct code otherwise)   IPC namespace's cap makes shmget
                                                                                   fail); without: the tests that
                                                                                   hold it fail, saying so; nothing
                                                                                   left behind either way
  rerun_forever           a forged record from a static constructor in every run   stub: 0, in bounded time
  unusual_but_honest      correct code that the scan notices                       full marks (the scan only advises)

Every case also checks that no file, shared memory segment or process of the
student's user is left when run_autograder ends.

The scan only advises (its findings reach the instructor's review, never a
score), so every case holds with it switched off (ILLUM_GRADE_NO_SCAN=1);
the cases marked so run again without namespaces as well
(ILLUM_GRADE_NO_PID_NAMESPACE=1, as in Docker's default profile), the harder
case: only the user, file permissions and the grader's own clean-up separate
them from the grader.

run_autograder runs under an address-space limit (``--grader-memory-mb``,
default 3072), standing in for the memory of Gradescope's container.

    python3 tests/e2e/attacks_e2e.py --work-dir DIR [--grader-tree DIR] [--jobs 2] [--only CASE]

Exit status 0 when every case holds; 1 with a table of what did not.
Needs root (a second user, a pid namespace); without it, exits 77 (skipped).
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from grading.batch import fresh_copy, unpack  # noqa: E402  (the batch grader's: a slot is prepared as it does)

ATTACKS = ROOT / "tests" / "attacks"
LESSONS = ["01", "02"]
MARKER = "3-4-5"  # in the hidden test's name (tests/hidden/lesson01_hidden.cpp): must never reach a student
HIDDEN_RANDOM = "new ones in every grading run"  # another hidden test's name
NOTES = "notes' form"  # the lesson 01 tests that call sphere_roots_notes

SPHERE = ("exercises/01_ray_sphere/sphere.cpp", "lib/illum/geometry/sphere.cpp")
PARITY = ("exercises/02_polygon_parity/parity.cpp", "lib/illum/geometry/parity.cpp")
PLANE = ("exercises/02_polygon_parity/plane.cpp", "lib/illum/geometry/plane.cpp")
HOOKS = {  # where attack_hook() is called: the start of this function's body
    "constructor": r"(Sphere::Sphere\([^{]*\{)",
    "notes": r"(SphereRoots<T> sphere_roots_notes\([^{]*\{)",
}


@dataclass
class Case:
    name: str
    payload: str
    base: str          # "stub", "reference" or "payload" (the payload is the whole file)
    hook: str | None   # a key of HOOKS, or None
    expect: str        # what the checks below test
    modes: tuple[str, ...] = ("scan",)
    files: tuple[tuple[str, str], ...] = (SPHERE,)
    inject: tuple[str, ...] = ("sphere.cpp",)  # the files that get the payload
    prefix: str = ""  # put before the payload (a #define that chooses a variant)


BASELINE = Case("reference", "", "reference", None, "full", files=(SPHERE, PARITY, PLANE), inject=())


CASES = [
    Case("fork_rewrites_results", "fork_rewrites_results.cpp", "stub", "constructor", "honest-zero",
         ("no-scan", "no-scan-no-ns")),
    Case("fake_reporter", "fake_reporter.cpp", "stub", None, "honest-zero", ("scan", "no-scan")),
    Case("rewrite_records", "rewrite_records.cpp", "stub", None, "honest-zero", ("no-scan",)),
    Case("define_write", "define_write.cpp", "stub", None, "honest-zero", ("no-scan",)),
    Case("include_reference", "include_reference.cpp", "payload", None, "honest-zero", ("no-scan",)),
    Case("leak_hidden_exception", "leak_hidden_exception.cpp", "stub", "constructor", "no-leak", ("no-scan",)),
    Case("leak_hidden_compile", "leak_hidden_compile_error.cpp", "payload", None, "no-leak", ("no-scan",)),
    Case("gigabyte_stdout", "gigabyte_stdout.cpp", "reference", "constructor", "full-01"),
    Case("segfault", "segfault.cpp", "reference", "notes", "notes-fail:SIGSEGV"),
    Case("duplicate_helper", "duplicate_helper.cpp", "reference", None, "link-02",
         files=(SPHERE, PARITY, PLANE), inject=("parity.cpp", "plane.cpp")),
    Case("exit_in_test", "exit_in_test.cpp", "reference", "notes", "notes-fail:exit(0)", ("scan",)),
    Case("leave_processes", "leave_processes.cpp", "reference", "constructor", "full-01", ("scan", "no-scan-no-ns")),
    Case("out_of_memory", "out_of_memory.cpp", "reference", "notes", "notes-fail:out of memory"),
    Case("forge_stream", "forge_stream.cpp", "stub", None, "honest-zero", ("no-scan", "no-scan-no-ns")),
    Case("forge_stream_sleep", "forge_stream.cpp", "stub", None, "honest-zero", ("no-scan",),
         prefix="#define FORGE_SLEEP 1\n"),
    Case("repoint_stdout", "repoint_stdout.cpp", "stub", "constructor", "honest-zero", ("no-scan",)),
    Case("probe_grader_files", "probe_grader_files.cpp", "payload", None, "no-leak", ("no-scan", "no-scan-no-ns")),
    Case("shared_memory", "shared_memory.cpp", "reference", "constructor", "full-01", ("no-scan",)),
    Case("shared_memory", "shared_memory.cpp", "reference", "constructor", "shared-memory-killed", ("no-scan-no-ns",)),
    Case("rerun_forever", "rerun_forever.cpp", "stub", None, "honest-zero", ("no-scan",)),
    Case("unusual_but_honest", "unusual_but_honest.cpp", "reference", "constructor", "full-01-reviewed", ("scan",)),
]
MODE_ENV = {"scan": {}, "no-scan": {"ILLUM_GRADE_NO_SCAN": "1"},
            "no-scan-no-ns": {"ILLUM_GRADE_NO_SCAN": "1", "ILLUM_GRADE_NO_PID_NAMESPACE": "1"}}


def submission_files(case: Case) -> dict[str, str]:
    payload = case.prefix + ((ATTACKS / case.payload).read_text(encoding="utf-8") if case.payload else "")
    files = {}
    for exercise, reference in case.files:
        name = Path(exercise).name
        if case.base == "payload":
            files[name] = payload
            continue
        text = (ROOT / (exercise if case.base == "stub" else reference)).read_text(encoding="utf-8")
        if name in case.inject:
            at = text.index("namespace illum {")
            text = text[:at] + payload + "\n" + text[at:]
            if case.hook and name == "sphere.cpp":
                text, count = re.subn(HOOKS[case.hook], r"\1\n  attack_hook();", text, count=1)
                if count != 1:
                    sys.exit(f"attacks: cannot call the hook in {exercise}: {HOOKS[case.hook]!r} not found")
        files[name] = text
    return files


def processes_under(folder: Path, uids: set[int]) -> list[tuple[int, str]]:
    """Processes running a program of ``folder`` (or with a cwd there), or of one of ``uids``."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == os.getpid():
            continue
        try:
            exe = os.readlink(f"/proc/{entry}/exe")
        except OSError:
            exe = ""
        try:
            cwd = os.readlink(f"/proc/{entry}/cwd")
        except OSError:
            cwd = ""
        try:
            uid = os.stat(f"/proc/{entry}").st_uid
        except OSError:
            continue
        if exe.startswith(str(folder)) or cwd.startswith(str(folder)) or uid in uids:
            found.append((int(entry), exe or cwd))
    return found


def _owner(entry: os.DirEntry) -> int | None:
    """The entry's owner, None when it is gone: other processes (a compiler's temporary files) come and go
    in the shared folders while they are listed."""
    try:
        return entry.stat(follow_symlinks=False).st_uid
    except FileNotFoundError:
        return None


def leftovers(uid: int) -> list[str]:
    """Files of ``uid`` in the shared folders and System V shared memory segments it still owns."""
    found = []
    for folder in ("/tmp", "/var/tmp", "/dev/shm", "/run/lock"):
        try:
            entries = list(os.scandir(folder))
        except OSError:
            continue
        found += [entry.path for entry in entries if _owner(entry) == uid]
    try:
        with open("/proc/sysvipc/shm", encoding="ascii") as table:
            next(table, None)
            found += [f"shared memory segment {line.split()[1]}" for line in table
                      if len(line.split()) > 7 and int(line.split()[7]) == uid]
    except OSError:
        pass
    return found


def student_visible(data: dict) -> str:
    return "\n".join([data.get("output", "")] + [t.get("output", "") + " " + t.get("name", "")
                                                  for t in data.get("tests", []) if t.get("visibility") != "hidden"])


def lesson_scores(data: dict) -> dict[str, tuple[float, float]]:
    scores: dict[str, tuple[float, float]] = {}
    for test in data.get("tests", []):
        match = re.match(r"lesson(\d\d)", test.get("name", ""))
        if match:
            got, top = scores.get(match.group(1), (0.0, 0.0))
            scores[match.group(1)] = (got + test.get("score", 0), top + test.get("max_score", 0))
    return scores


@dataclass
class Outcome:
    case: str
    mode: str
    seconds: float
    summary: str
    problems: list[str] = field(default_factory=list)


def judge(case: Case, data: dict, changed_after: bool, survivors: list, maxima: dict[str, float]) -> list[str]:
    problems = []
    scores = lesson_scores(data)
    one = scores.get("01", (0.0, 0.0))[0]
    two = scores.get("02", (0.0, 0.0))[0]
    visible = student_visible(data)
    if changed_after:
        problems.append("results.json changed after run_autograder had finished")
    if survivors:
        problems.append(f"{len(survivors)} process(es), file(s) or segment(s) of the submission left afterwards: "
                        f"{survivors[:3]}")
    if MARKER in visible or HIDDEN_RANDOM in visible:
        problems.append("the hidden tests reached what the student reads")
    if "GRADER-FILE-VISIBLE" in visible or '"checks"' in visible:
        problems.append("the grader's own files reached what the student reads")
    expect = case.expect
    if expect == "full" and (one, two) != (maxima["01"], maxima["02"]):
        problems.append(f"the reference scored {one:g} + {two:g}, not full marks")
    elif expect == "honest-zero" and (one, two) != (0, 0):
        problems.append(f"scored {one:g} + {two:g}; the honest score is 0")
    elif expect == "no-leak" and (one, two) != (0, 0):
        problems.append(f"scored {one:g} + {two:g}; the honest score is 0")
    elif expect == "full-01" and (one, two) != (maxima["01"], 0):
        problems.append(f"scored {one:g} + {two:g}; the honest score is {maxima['01']:g} + 0")
    elif expect == "shared-memory-killed":
        lesson = [t for t in data["tests"] if t["name"].startswith("lesson01")]
        failed = [t for t in lesson if t["status"] != "passed"]
        if two != 0 or not failed:
            problems.append(f"scored {one:g} + {two:g}; the programs holding too much shared memory must be stopped")
        if not all("shared memory" in t.get("output", "") or "did not run" in t.get("output", "") for t in failed):
            problems.append("a failed test does not say that its program held too much shared memory")
    elif expect == "full-01-reviewed":
        if (one, two) != (maxima["01"], 0):
            problems.append(f"scored {one:g} + {two:g}; the honest score is {maxima['01']:g} + 0 (the scan advises)")
        review = [t for t in data["tests"] if t["name"].startswith("review")]
        if not review or any(t.get("visibility") != "hidden" for t in review):
            problems.append("the scan's findings are not in an instructors-only review entry")
    elif expect.startswith("notes-fail:"):
        words = expect.split(":", 1)[1]
        lesson = [t for t in data["tests"] if t["name"].startswith("lesson01")]
        failed = [t for t in lesson if t["status"] != "passed"]
        notes = [t for t in lesson if NOTES in t["name"]]
        if not notes or {t["name"] for t in failed} != {t["name"] for t in notes}:
            problems.append(f"failed: {sorted(t['name'][:50] for t in failed)}; only the {len(notes)} notes' form "
                            "tests may fail")
        if not all(words in t.get("output", "") for t in notes):
            problems.append(f"a notes' form test does not say '{words}'")
    elif expect == "link-02":
        if (one, two) != (maxima["01"], 0):
            problems.append(f"scored {one:g} + {two:g}; the honest score is {maxima['01']:g} + 0 (lesson 02 does "
                            "not link)")
        build = [t for t in data["tests"] if t["name"].startswith("build") and t.get("visibility") != "hidden"]
        if not any("multiple definition" in t.get("output", "") for t in build):
            problems.append("no visible build entry quotes the linker (multiple definition)")
        if "not your code's fault" in data.get("output", ""):
            problems.append("the link error is blamed on the grader")
    return problems


def run_case(case: Case, mode: str, slot_dir: Path, user: str, memory_mb: int,
             test_timeout: str) -> tuple[dict | None, bool, list, float, str]:
    ag = slot_dir / "autograder"
    fresh_copy(slot_dir / "snapshot", ag)
    submission = ag / "submission"
    for name, text in submission_files(case).items():
        (submission / name).write_text(text, encoding="utf-8")
    results = ag / "results" / "results.json"
    env = dict(os.environ, ILLUM_AUTOGRADER_ROOT=str(ag), ILLUM_GRADE_TEST_TIMEOUT=test_timeout,
               PYTHONDONTWRITEBYTECODE="1", ILLUM_GRADE_USER=user, **MODE_ENV[mode])
    env.pop("CMAKE_CXX_COMPILER_LAUNCHER", None)

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (memory_mb << 20, memory_mb << 20))

    start = time.monotonic()
    done = subprocess.run(["bash", str(ag / "source" / "run_autograder")], env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, preexec_fn=limit, check=False, timeout=900)
    seconds = time.monotonic() - start
    log = done.stdout.decode("utf-8", errors="replace")
    (slot_dir / f"{case.name}-{mode}.log").write_text(log[-200000:], encoding="utf-8")
    first = results.read_bytes() if results.exists() else b""
    time.sleep(2.5)  # an attack that acts after the grader has finished has had time to
    second = results.read_bytes() if results.exists() else b""
    uids = set()
    try:
        import pwd
        uids.add(pwd.getpwnam(user).pw_uid)
    except KeyError:
        pass
    survivors = processes_under(ag, uids) + [(0, left) for uid in uids for left in leftovers(uid)]
    for pid, _ in survivors:  # clean up for the next case (an older grader leaves them)
        if not pid:
            continue  # a file or a segment, not a process
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    data = json.loads(second) if second else None
    if data is not None:
        shutil.copyfile(results, slot_dir / f"results-{case.name}-{mode}.json")
    changed = hashlib.sha256(first).digest() != hashlib.sha256(second).digest()
    return data, changed, survivors, seconds, log


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--work-dir", type=Path, required=True)
    parser.add_argument("--grader-tree", type=Path, default=ROOT,
                        help="the checkout whose tools/grade packs the autograder (default: this one)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--only", action="append", help="run only this case (repeatable)")
    parser.add_argument("--test-timeout", default="10")
    parser.add_argument("--grader-memory-mb", type=int, default=3072)
    args = parser.parse_args(argv)
    if os.geteuid() != 0:
        print("attacks e2e: skipped: needs root (a second user for the students' code, a pid namespace)")
        return 77
    work = args.work_dir.resolve()
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    work.chmod(0o755)
    grader_tree = args.grader_tree.resolve()
    env = dict(os.environ, CMAKE_BUILD_PARALLEL_LEVEL="2", PYTHONDONTWRITEBYTECODE="1")
    if shutil.which("ccache"):  # the prepared trees reuse earlier objects (autograder_e2e's, batch_e2e's too)
        env.update(CMAKE_CXX_COMPILER_LAUNCHER="ccache", CCACHE_NOHASHDIR="1", ILLUM_GRADE_REFERENCE_CCACHE="1")
    zip_path = work / "autograder.zip"
    done = subprocess.run([sys.executable, str(grader_tree / "tools" / "grade"), "--pack-autograder", str(zip_path),
                           *LESSONS], env=env, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        print(done.stdout + done.stderr)
        return 1
    plan = [(case, mode) for case in CASES for mode in case.modes if not args.only or case.name in args.only]
    slots = [work / f"slot-{k}" for k in range(1, max(1, args.jobs) + 1)]
    # Users of its own: CTest runs the end-to-end tests side by side, and every process of a grading
    # user is killed at the end of each run.
    users = [f"illum-test-at{k}" for k in range(1, len(slots) + 1)]

    def prepare(k: int) -> tuple[int, float, str]:
        """A slot: the autograder unpacked and set up at the path where its submissions are graded
        (a CMake build tree cannot move), and a snapshot to restore before each submission."""
        ag = slots[k] / "autograder"
        unpack(zip_path, ag)
        for folder in (slots[k], ag):
            folder.chmod(0o755)
        start = time.monotonic()
        done = subprocess.run(["bash", str(ag / "source" / "setup.sh")],
                              env=dict(env, ILLUM_AUTOGRADER_ROOT=str(ag), ILLUM_GRADE_USER=users[k],
                                       CCACHE_BASEDIR=str(ag)),
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace",
                              check=False)
        (slots[k] / "setup.log").write_text(done.stdout, encoding="utf-8")
        if done.returncode == 0:
            subprocess.run(["cp", "-a", "--reflink=auto", str(ag), str(slots[k] / "snapshot")], check=True)
        return done.returncode, time.monotonic() - start, done.stdout

    for slot in slots:
        slot.mkdir()
    with ThreadPoolExecutor(max_workers=len(slots)) as pool:  # each finds build/release's objects in ccache
        prepared_slots = list(pool.map(prepare, range(len(slots))))
    for k, (status, seconds, output) in enumerate(prepared_slots):
        print(f"setup.sh in {slots[k].name} ({grader_tree}): exit {status} in {seconds:.1f} s", flush=True)
        if status != 0:
            print(output[-4000:])
            return 1
    free = list(range(len(slots)))
    import threading
    lock = threading.Lock()

    def one(item: tuple[Case, str]) -> tuple[Case, str, tuple]:
        with lock:
            k = free.pop(0)
        try:
            return item[0], item[1], run_case(item[0], item[1], slots[k], users[k], args.grader_memory_mb,
                                              args.test_timeout)
        finally:
            with lock:
                free.append(k)

    # The reference first: the maxima every other case is judged by.
    baseline = one((BASELINE, "scan"))
    data = baseline[2][0]
    maxima = {nn: top for nn, (_, top) in lesson_scores(data or {}).items()}
    if set(maxima) != set(LESSONS):
        print(f"attacks e2e: the reference run gave no score for lessons {', '.join(LESSONS)}; see {slots[0]}")
        return 1
    outcomes: list[Outcome] = []
    with ThreadPoolExecutor(max_workers=len(slots)) as pool:
        finished = [baseline] + list(pool.map(one, plan))
    for case, mode, (data, changed, survivors, seconds, log) in finished:
        if data is None:
            outcomes.append(Outcome(case.name, mode, seconds, "no results.json", ["no results.json was written"]))
            continue
        scores = lesson_scores(data)
        summary = ", ".join(f"{nn}: {got:g}/{top:g}" for nn, (got, top) in sorted(scores.items()))
        effects = []
        if changed:
            effects.append("results.json rewritten afterwards")
        if survivors:
            effects.append(f"{len(survivors)} process(es) left alive")
        if MARKER in student_visible(data):
            effects.append("hidden tests shown to the student")
        if "not your code's fault" in data.get("output", "") or "grader itself failed" in student_visible(data):
            effects.append("blamed on the grader")
        summary += ("; " + "; ".join(effects)) if effects else ""
        outcomes.append(Outcome(case.name, mode, seconds, summary, judge(case, data, changed, survivors, maxima)))
    print(f"\n{'case':<24} {'mode':<17} {'time':>6}  result")
    for o in outcomes:
        verdict = "ok" if not o.problems else "FAILED: " + "; ".join(o.problems)
        print(f"{o.case:<24} {o.mode:<17} {o.seconds:5.1f}s  {o.summary}  -> {verdict}")
    failed = [o for o in outcomes if o.problems]
    print(f"\nattacks e2e: {len(outcomes) - len(failed)} of {len(outcomes)} cases hold"
          + (f"; {len(failed)} FAILED" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
