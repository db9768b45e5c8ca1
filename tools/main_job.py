#!/usr/bin/env python3
"""The main job: every lesson's reference run, the slides and OUT/index.html.

    tools/main_job.py --bin build/release/bin --out out [--quick]

Steps (all by default; pick some with --only):
  lessons  runs every BIN/lessonNN with --out OUT/lessonNN (and --quick); the
           first failure stops the job with the program's exit code and name;
           OUT/run_log.json records each run's date, seconds, processor
           seconds (all its threads: a busy machine stretches the seconds,
           not these), cores, load average and the programs it ran beside.
           A program whose timings all use one thread (`lessonNN
           --timed-cores` prints "one") runs side by side with the others
           like it, as many at once as the machine has cores, longest first
           (by OUT/run_log.json's last record, else the later lessons first),
           each one's output printed whole when it ends. So does a "mixed"
           one, whose timings on more threads each ask for the whole machine
           first (lib/illum/io/whole_machine.hpp): it gets it, through a pipe,
           once the others are done. Then the others run one at a time,
           alone, in order (--alone: every program so);
  lab      screenshots of `BIN/illum lab`'s four views in headless Chromium,
           OUT/lab/*.png with a manifest.json (tools/lab/screenshots.py; the
           lab is started on a free port of 127.0.0.1 and stopped again);
  figures  refreshes the figures of the lesson texts and decks from the tables
           in OUT (tools/figures.py: timings and their labels; a figure whose
           other values changed is left for `tools/figures.py --update` and
           listed); skipped after a --quick run, whose tables are small;
  slides   builds every slides/NN_*.md deck to OUT/slides/NN_*.html (Marp);
  texts    renders every lesson text, exercise README and document to
           OUT/pages/ (HTML with KaTeX maths, the run's figures, links between
           the pages and to pages of the source files they cite;
           tools/gallery/render_texts.mjs), then checks every page's links;
  index    writes OUT/index.html, linking every lesson's outputs, deck, lesson
           text and exercise; --check-links then verifies every local link.

The steps run in the order above, except that the lab's screenshots and the
slides run side by side after the figures step (neither times anything; both
mostly wait on Chromium and Node). Lessons, programs and decks are
discovered, never listed. Every file is written atomically. `cmake --build --preset release --target gallery` runs it.
"""
from __future__ import annotations

import argparse
import fcntl
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import figures  # noqa: E402
from gallery.decks import DeckError, build_decks, find_decks  # noqa: E402
from gallery.fsutil import atomic_write_text  # noqa: E402
from gallery.index import check_links, write_index  # noqa: E402
from gallery.texts import TextsError, build_texts  # noqa: E402
from path_options import folder_problem, path_argument  # noqa: E402

SOURCE = Path(__file__).resolve().parent.parent
STEPS = ("lessons", "lab", "figures", "slides", "texts", "index")
PROGRAM = re.compile(r"^lesson(\d\d)$")


class JobError(Exception):
    pass


def say(message: str) -> None:
    print(f"main_job: {message}", flush=True)


def find_programs(bin_dir: Path) -> list[Path]:
    if not bin_dir.is_dir():
        return []
    return sorted(p for p in bin_dir.iterdir()
                  if PROGRAM.match(p.name) and p.is_file() and os.access(p, os.X_OK))


def run_lessons(bin_dir: Path, out: Path, quick: bool, alone: bool = False) -> None:
    programs = find_programs(bin_dir)
    if not programs:
        raise JobError(f"no lessonNN programs in {bin_dir} (build them first: cmake --build --preset release)")
    log_path = out / "run_log.json"
    all_start, all_cpu = time.monotonic(), children_cpu_seconds()
    numbers = {program: i for i, program in enumerate(programs, 1)}
    answers = {} if alone else {p: timed_cores(p) for p in programs}
    one_core = [p for p in programs if answers.get(p) in ("one", "mixed")]
    cores = os.cpu_count() or 1
    if len(one_core) < 2 or cores < 2 or not hasattr(os, "wait4"):
        one_core = []  # nothing to gain: every program runs alone, in order
    if one_core:
        mixed = [p.name for p in one_core if answers[p] == "mixed"]
        say(f"{len(one_core)} program(s) time one thread"
            + (f" ({', '.join(mixed)} but for the studies it runs with the whole machine)" if mixed else " only")
            + f": {', '.join(p.name for p in one_core)} run side by side, {min(cores, len(one_core))} at once")
        run_side_by_side(longest_first(one_core, log_path), min(cores, len(one_core)), answers, numbers,
                         len(programs), out, quick, log_path)
    for program in programs:
        if program in one_core:
            continue
        cmd = lesson_command(program, out, quick)
        say(f"[{numbers[program]}/{len(programs)}] {' '.join(cmd)}")
        start = time.monotonic()
        started = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
        load_before = load_average()
        cpu_before = children_cpu_seconds()
        # Output passes straight through: progress on stderr stays visible.
        code = subprocess.call(cmd, cwd=out, stdin=subprocess.DEVNULL)
        if code != 0:
            raise JobError(failure(program, code, cmd))
        seconds = time.monotonic() - start
        cpu = children_cpu_seconds() - cpu_before
        record_run(log_path, program.name, {
            "started": started, "seconds": round(seconds, 1), "cpu_seconds": round(cpu, 1),
            "cores": os.cpu_count(), "load_before": load_before, "load_after": load_average(), "quick": quick,
            "beside": []})
        say(f"{program.name} done in {seconds:.1f} s ({cpu:.1f} s of processor time, all its threads)")
    say(f"lessons done in {time.monotonic() - all_start:.1f} s "
        f"({children_cpu_seconds() - all_cpu:.1f} s of processor time; load average now {load_average()})")


def lesson_command(program: Path, out: Path, quick: bool) -> list[str]:
    return [str(program), "--out", str(out / program.name)] + (["--quick"] if quick else [])


def failure(program: Path, code: int, cmd: list[str]) -> str:
    return (f"{program.name} failed (exit code {code}); its messages are above. "
            f"Re-run it alone with: {' '.join(cmd)}")


def timed_cores(program: Path) -> str:
    """"one" when every timing of the program runs on one thread (it says so: --timed-cores),
    "mixed" when those on more threads each ask for the whole machine first (WholeMachine), else
    "all". A program that cannot answer (an older build, a crash) is "all": it runs alone."""
    try:
        answer = subprocess.run([str(program), "--timed-cores"], capture_output=True, text=True,
                                errors="replace", stdin=subprocess.DEVNULL, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return "all"
    word = answer.stdout.strip()
    return word if answer.returncode == 0 and word in ("one", "mixed") else "all"


def longest_first(programs: list[Path], log_path: Path) -> list[Path]:
    """The programs in the order that finishes a side-by-side run soonest: longest first, by their
    seconds in the last run_log.json; without a record, the later lessons first (they run longer)."""
    try:
        log = json.loads(log_path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        log = {}
    if not isinstance(log, dict):
        log = {}

    def seconds(program: Path) -> float:
        """Its seconds of work: a "mixed" program's time spent waiting for the machine left out."""
        run = log.get(program.name)
        value = run.get("seconds") if isinstance(run, dict) and not run.get("quick") else None
        if not isinstance(value, (int, float)):
            return -1.0
        waited = run.get("waited_seconds", 0)
        return max(0.0, value - waited) if isinstance(waited, (int, float)) else value

    if all(seconds(p) >= 0 for p in programs):
        return sorted(programs, key=lambda p: (-seconds(p), p.name))
    return sorted(programs, key=lambda p: p.name, reverse=True)


def run_side_by_side(queue: list[Path], width: int, answers: dict[Path, str], numbers: dict, total: int,
                     out: Path, quick: bool, log_path: Path) -> None:
    """Runs the programs of `queue`, `width` at a time, each as soon as a place is free, and records
    each run with the programs it overlapped. A program's output goes to a file of its own and is
    printed whole when it ends, so two programs' lines never mix.

    A "mixed" program (answers[program]) gets a pair of pipes, named in ILLUM_MAIN_JOB_FDS
    (lib/illum/io/whole_machine.hpp). When it asks for the whole machine it waits, blocked, and
    stops taking a place; the first to ask gets the machine once no program is left to start and
    none runs on one thread (so the one-thread work is packed first, with no core left idle while
    there is some); while it holds the machine nothing starts; after "release" it runs on as a
    one-thread program. After a failure no new program starts; the ones running finish (a waiting
    one is still given the machine), the runs that succeeded are recorded, and the first failure
    (in lesson order) is raised."""
    import tempfile

    cond = threading.Condition()
    todo = list(queue)
    state: dict[Path, str] = {}  # each running program: "one", "waiting" or "holding"
    waiting: list[Path] = []  # in the order they asked
    grant_fds: dict[Path, int] = {}
    asked: dict[Path, float] = {}
    waited: dict[Path, float] = {}
    held: dict[Path, float] = {}
    spans: dict[Path, tuple[float, float]] = {}
    runs: dict[Path, dict] = {}
    failures: list[tuple[Path, int, list[str]]] = []

    def listen(program: Path, requests_fd: int) -> None:
        """Reads the program's requests until it closes its end (it ended)."""
        with open(requests_fd, "r", encoding="utf-8", errors="replace") as requests:
            for line in requests:
                word = line.strip()
                with cond:
                    now, current = time.monotonic(), state.get(program)
                    if word == "machine" and current == "one":
                        state[program] = "waiting"
                        waiting.append(program)
                        asked[program] = now
                    elif word == "release" and current == "holding":
                        state[program] = "one"
                        held[program] = held.get(program, 0.0) + now - asked.pop(program)
                    else:
                        say(f"warning: {program.name} sent {word[:40]!r} while {current or 'ended'}; ignored")
                    cond.notify_all()

    def run(program: Path) -> None:
        cmd = lesson_command(program, out, quick)
        env, pass_fds, requests_fd = None, (), -1
        if answers[program] == "mixed":
            from_job_r, from_job_w = os.pipe()  # the job's answers
            requests_fd, to_job_w = os.pipe()  # the program's requests
            env = dict(os.environ, ILLUM_MAIN_JOB_FDS=f"{from_job_r},{to_job_w}")
            pass_fds = (from_job_r, to_job_w)
        with tempfile.TemporaryFile(mode="w+b") as log:
            start = time.monotonic()
            started = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
            load_before = load_average()
            try:
                proc = subprocess.Popen(cmd, cwd=out, stdin=subprocess.DEVNULL, stdout=log,
                                        stderr=subprocess.STDOUT, env=env, pass_fds=pass_fds)
            except OSError as e:  # it could not start: a failure like any other, never a hang
                proc = None
                log.write(f"{program.name}: cannot start {cmd[0]}: {e}\n".encode())
            finally:
                for fd in pass_fds:
                    os.close(fd)  # the program's ends: its exit then closes the requests pipe
            if proc is None:
                for fd in (requests_fd, from_job_w) if pass_fds else ():
                    os.close(fd)
                pass_fds = ()
            if pass_fds:
                with cond:
                    grant_fds[program] = from_job_w
                threading.Thread(target=listen, args=(program, requests_fd), daemon=True).start()
            if proc is None:
                code, usage = 127, None
            else:
                # wait4, not wait: this child's own processor time, whatever its neighbours use.
                _, status, usage = os.wait4(proc.pid, 0)
                proc.returncode = code = os.waitstatus_to_exitcode(status)
            end = time.monotonic()
            log.seek(0)
            text = log.read().decode("utf-8", errors="replace")
        with cond:
            if state.get(program) == "holding":
                held[program] = held.get(program, 0.0) + end - asked.pop(program)
            if program in waiting:
                waiting.remove(program)
            state.pop(program, None)
            if program in grant_fds:
                os.close(grant_fds.pop(program))
            sys.stdout.write(text)
            sys.stdout.flush()
            spans[program] = (start, end)
            if code != 0:
                failures.append((program, code, cmd))
            else:
                cpu = usage.ru_utime + usage.ru_stime
                runs[program] = {
                    "started": started, "seconds": round(end - start, 1), "cpu_seconds": round(cpu, 1),
                    "cores": os.cpu_count(), "load_before": load_before, "load_after": load_average(),
                    "quick": quick}
                extra = ""
                if answers[program] == "mixed":
                    runs[program]["waited_seconds"] = round(waited.get(program, 0.0), 1)
                    runs[program]["whole_machine_seconds"] = round(held.get(program, 0.0), 1)
                    extra = (f"; it waited {waited.get(program, 0.0):.1f} s for the whole machine and held it "
                             f"{held.get(program, 0.0):.1f} s")
                say(f"{program.name} done in {end - start:.1f} s ({cpu:.1f} s of processor time, all its "
                    f"threads{extra})")
            cond.notify_all()

    try:
        with cond:
            while True:
                busy = sum(1 for s in state.values() if s == "one")
                holder = "holding" in state.values()
                while todo and not failures and not holder and busy < width:
                    program = todo.pop(0)
                    state[program] = "one"
                    busy += 1
                    say(f"[{numbers[program]}/{total}] {' '.join(lesson_command(program, out, quick))} "
                        "(side by side; its output when it ends)")
                    threading.Thread(target=run, args=(program,)).start()
                if waiting and not holder and busy == 0 and (not todo or failures):
                    program = waiting.pop(0)
                    now = time.monotonic()
                    waited[program] = waited.get(program, 0.0) + now - asked[program]
                    asked[program] = now
                    state[program] = "holding"
                    say(f"{program.name} has the whole machine (no other program runs until it gives it back)")
                    try:
                        os.write(grant_fds[program], b"go\n")
                    except OSError:
                        pass  # it ended meanwhile: run() records that
                if not state and (not todo or failures):
                    break
                cond.wait()
    except BaseException:  # Ctrl-C: start nothing more (the running programs got the signal too)
        with cond:
            todo.clear()
        raise
    # Every run that finished is recorded, even when another failed: its outputs were committed, and a
    # stale record would give their figures the date and load of an earlier run.
    for program, run_record in sorted(runs.items()):
        start, end = spans[program]
        run_record["beside"] = sorted(other.name for other, (s, e) in spans.items()
                                      if other != program and s < end and start < e)
        record_run(log_path, program.name, run_record)
    if failures:
        program, code, cmd = min(failures, key=lambda f: f[0].name)
        raise JobError(failure(program, code, cmd))


def children_cpu_seconds() -> float:
    """Processor seconds (user + system) of every finished child so far, all their threads and
    their own waited-for children (gnuplot) included: what a program cost, whatever else the
    machine was running, unlike its seconds, which a busy machine stretches."""
    try:
        import resource  # POSIX only
    except ImportError:
        return 0.0
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def load_average() -> list[float]:
    try:
        return [round(x, 2) for x in os.getloadavg()]
    except OSError:
        return []


def record_run(log_path: Path, name: str, run: dict) -> None:
    """Adds one program's run to OUT/run_log.json (the figures' timing labels)."""
    try:
        log = json.loads(log_path.read_text(encoding="utf-8"))
        if not isinstance(log, dict):
            log = {}
    except (OSError, ValueError):
        log = {}
    log[name] = run
    atomic_write_text(log_path, json.dumps(log, indent=2, sort_keys=True) + "\n")


def run_lab(bin_dir: Path, out: Path) -> None:
    spec = importlib.util.spec_from_file_location("lab_screenshots", SOURCE / "tools" / "lab" / "screenshots.py")
    screenshots = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(screenshots)
    say("lab: screenshots of illum lab's four views")
    start = time.monotonic()
    if screenshots.main(["--bin", str(bin_dir), "--out", str(out)]) != 0:
        raise JobError("the lab's screenshots failed (above); re-run them alone with: "
                       f"tools/lab/screenshots.py --bin {bin_dir} --out {out}")
    say(f"lab done in {time.monotonic() - start:.1f} s")


def run_figures(source: Path, out: Path, quick: bool) -> None:
    if quick:
        say("figures: skipped (a --quick run's tables are not the ones the texts quote)")
        return
    figures.remove_stale_temporaries(source, log=lambda m: say(m))
    code = figures.process(source, out, "refresh", log=lambda m: say(m))
    if code != 0:
        say("warning: some figures could not be refreshed (above); `tools/figures.py --check` fails on them")


def run_slides(source: Path, slides_dir: Path, out: Path) -> None:
    decks = find_decks(slides_dir)
    if not decks:
        say(f"no decks (NN_*.md) in {slides_dir}")
        return
    say(f"building {len(decks)} deck(s) from {slides_dir} into {out / 'slides'}")
    start = time.monotonic()
    try:
        built = build_decks(source, decks, out / "slides")
    except DeckError as e:
        raise JobError(str(e)) from None
    for path in built:
        say(f"  {path}")
    say(f"slides done in {time.monotonic() - start:.1f} s")


def side_by_side(*steps: list) -> None:
    """Runs each list of steps at once, the first in this thread and the others in threads of their
    own, waits for all, and raises the first JobError (or other exception) any of them raised."""
    steps = [s for s in steps if s]
    errors: list[BaseException] = []

    def run(todo: list) -> None:
        try:
            for step in todo:
                step()
        except BaseException as e:  # re-raised below, in this thread
            errors.append(e)

    threads = [threading.Thread(target=run, args=(todo,)) for todo in steps[1:]]
    for thread in threads:
        thread.start()
    if steps:
        run(steps[0])
    for thread in threads:
        thread.join()
    if errors:
        raise errors[0]


def run_texts(source: Path, out: Path) -> None:
    say("texts: rendering the lesson texts, exercises and documents into " + str(out / "pages"))
    start = time.monotonic()
    try:
        for line in build_texts(source, out):
            say(f"  {line}")
    except TextsError as e:
        raise JobError(str(e)) from None
    say(f"texts done in {time.monotonic() - start:.1f} s")


def check_pages(out: Path, index_written: bool) -> None:
    """Every link and image of the rendered pages resolves. Runs after the index step, since every
    page links back to OUT/index.html, which a fresh clone's first run has not written before it;
    when this run leaves the index out, links to a missing index.html are not counted."""
    index = out / "index.html"
    broken = []
    for page in sorted((out / "pages").rglob("*.html")):
        for problem in check_links(page):
            if not index_written and not index.exists() and f"{index} does not exist" in problem:
                continue
            broken.append(f"{page.relative_to(out)}: {problem}")
    if broken:
        raise JobError(f"{len(broken)} broken link(s) in the rendered texts:\n  " + "\n  ".join(broken[:40]))
    say("every local link and image of the rendered texts resolves")


# What the job's own atomic writes leave when it is killed without warning (SIGKILL): a temporary
# file beside its target (gallery/fsutil.py, mkstemp: NAME.tmp-XXXXXXXX, a deck's also .html) and
# the folder of the one Marp run (OUT/slides/.decks-XXXXXXXX). A lesson's leftovers are its own
# (the next run of it removes them; `illum clean --out OUT`).
STALE_FILE = re.compile(r".+\.tmp-[a-z0-9_]{8}(\.html)?")
STALE_FOLDER = re.compile(r"\.decks-[a-z0-9_]{8}")


def hold_and_clean(out: Path) -> tuple[int, list[str]]:
    """Locks OUT for this job (an flock on the folder, held until the process ends: a second job on
    it is refused) and removes what a job killed there left; one note per thing removed."""
    fd = os.open(out, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(fd)
        raise JobError(f"--out {out} is in use by another main job; wait for it to end, or give this one "
                       "another --out") from None
    notes = []
    for root, dirs, files in os.walk(out):
        here = Path(root)
        # Not into a lesson's folders: their files are their runs' (each cleans its own).
        dirs[:] = [d for d in dirs if not PROGRAM.match(d) and ".illum-" not in d]
        for name in [d for d in dirs if STALE_FOLDER.fullmatch(d) and not (here / d).is_symlink()]:
            shutil.rmtree(here / name, ignore_errors=True)
            dirs.remove(name)
            notes.append(f"removed {here / name}, left by a main job that was killed before it finished")
        for name in files:
            if STALE_FILE.fullmatch(name) and os.lstat(here / name).st_uid == os.geteuid():
                (here / name).unlink()
                notes.append(f"removed {here / name}, left by a main job that was killed before it finished")
    return fd, notes


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    parser.add_argument("--bin", type=path_argument, help="the build's bin/ folder (needed by the lessons step)")
    parser.add_argument("--out", type=path_argument, required=True, help="the output folder (e.g. out)")
    parser.add_argument("--quick", action="store_true", help="run each lesson with --quick")
    parser.add_argument("--alone", action="store_true",
                        help="run every lesson alone, in order, even those whose timings use one core "
                             "(slower; timings free of a neighbour's load)")
    parser.add_argument("--only", default=",".join(STEPS),
                        help=f"comma-separated steps to run, of {','.join(STEPS)} (default: all)")
    parser.add_argument("--source", type=path_argument, default=SOURCE,
                        help="the source tree (default: this checkout)")
    parser.add_argument("--slides", type=path_argument,
                        help="the folder of NN_*.md decks (default: SOURCE/slides)")
    parser.add_argument("--check-links", action="store_true",
                        help="after writing index.html, fail if any local link or image in it does not resolve")
    args = parser.parse_args(argv)

    steps = [s.strip() for s in args.only.split(",") if s.strip()]
    unknown = [s for s in steps if s not in STEPS]
    if unknown:
        parser.error(f"unknown step(s) {', '.join(unknown)}; choose from {', '.join(STEPS)}")
    if ("lessons" in steps or "lab" in steps) and args.bin is None:
        parser.error("--bin is needed to run the lessons and the lab (or leave them out with --only slides,index)")
    source = args.source.resolve()
    out = args.out.resolve()
    slides_dir = (args.slides or source / "slides").resolve()
    # Every folder named is checked before OUT is made: a wrong one stops the job with nothing written.
    if not (source / "lessons").is_dir():
        parser.error(f"--source {args.source}: not an illum source tree (no lessons/ folder in it)")
    if ("slides" in steps or "index" in steps) and not slides_dir.is_dir():
        parser.error(f"--slides {args.slides or slides_dir}: not a folder")
    if "lessons" in steps and not find_programs(args.bin.resolve()):
        parser.error(f"--bin {args.bin}: no lessonNN programs in it (build them first: "
                     "cmake --build --preset release)")
    if "lab" in steps and not os.access(args.bin.resolve() / "illum", os.X_OK):
        parser.error(f"--bin {args.bin}: no illum program in it for the lab's screenshots (build it first: "
                     "cmake --build --preset release --target illum_cli)")
    if out.exists() and not out.is_dir():
        parser.error(f"--out {args.out}: exists and is not a folder")
    if folder_problem(args.out):  # afile/out: a traceback from mkdir otherwise
        parser.error(f"--out {args.out}: {folder_problem(args.out)}")
    out.mkdir(parents=True, exist_ok=True)
    start = time.monotonic()
    try:
        _, notes = hold_and_clean(out)
        for note in notes:
            say(f"note: {note}")
        if "lessons" in steps:
            run_lessons(args.bin.resolve(), out, args.quick, args.alone)
        # The figures first (they rewrite the decks); then the lab's screenshots and the decks side by
        # side: both wait on Chromium and Node, time nothing, write to folders of their own, and
        # follow every timed lesson run (on a two-core machine they would slow its timings).
        if "figures" in steps:
            run_figures(source, out, args.quick)
        side_by_side([lambda: run_lab(args.bin.resolve(), out)] if "lab" in steps else [],
                     [lambda: run_slides(source, slides_dir, out)] if "slides" in steps else [])
        if "texts" in steps:
            run_texts(source, out)
        if "index" in steps:
            note = "(Quick run: small sizes.)" if args.quick else ""
            index = write_index(source, out, slides_dir, note)
            problems = check_links(index)
            if problems:
                message = f"{index} has {len(problems)} broken link(s):\n  " + "\n  ".join(problems)
                if args.check_links:
                    raise JobError(message)
                say("warning: " + message)
            elif args.check_links:
                say("every local link and image in index.html resolves")
            say(f"wrote {index}")
        if "texts" in steps:
            check_pages(out, "index" in steps)
    except JobError as e:
        print(f"main_job: error: {e}", file=sys.stderr, flush=True)
        return 1
    say(f"finished in {time.monotonic() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
