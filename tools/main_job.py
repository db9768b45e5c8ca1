#!/usr/bin/env python3
"""The main job: every lesson's reference run, the slides and OUT/index.html.

    tools/main_job.py --bin build/release/bin --out out [--quick] [--only STEP,...]

Steps, in this order (`cmake --build --preset release --target gallery` runs them all):
  lessons  every BIN/lessonNN --out OUT/lessonNN, recorded in OUT/run_log.json; those whose timings use
           one thread side by side (tools/gallery/lesson_runs.py; --alone: every program alone);
  figures  refreshes the texts' figures from OUT's tables (tools/figures.py; not after --quick);
  lab      screenshots of `BIN/illum lab` into OUT/lab/ (tools/lab/screenshots.py) and
  slides   every slides/NN_*.md deck to OUT/slides/ (Marp), these two side by side;
  texts    every text rendered to OUT/pages/ (tools/gallery/render_texts.mjs), their links checked;
  index    OUT/index.html, linking every lesson's outputs, deck, text and exercise.
"""

import argparse
import os
import re
import shutil
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common.files import lock_folder  # noqa: E402
from common.path_options import folder_problem, path_argument  # noqa: E402
from gallery.decks import build_decks, find_decks  # noqa: E402
from gallery.figures import process as refresh_figures, remove_stale_temporaries  # noqa: E402
from gallery.index import check_links, write_index  # noqa: E402
from gallery.lesson_runs import PROGRAM, JobError, find_programs, run_lessons, say  # noqa: E402
from gallery.texts import build_texts  # noqa: E402

SOURCE = Path(__file__).resolve().parent.parent
STEPS = ("lessons", "lab", "figures", "slides", "texts", "index")
# What the job's own atomic writes leave when it is killed without warning (SIGKILL): a temporary beside its
# target (common/files.py, mkstemp: NAME.tmp-XXXXXXXX) and the folder of a Marp run
# (OUT/slides/.decks-XXXXXXXX). A lesson's leftovers are its own (its next run removes them).
STALE_FILE = re.compile(r".+\.tmp-[a-z0-9_]{8}")
STALE_FOLDER = re.compile(r"\.decks-[a-z0-9_]{8}")


def run_lab(bin_dir: Path, out: Path) -> None:
    from lab import screenshots  # only when the step runs
    say("lab: screenshots of illum lab's five views")
    start = time.monotonic()
    if screenshots.main(["--bin", str(bin_dir), "--out", str(out)]) != 0:
        raise JobError("the lab's screenshots failed (above); re-run them alone with: "
                       f"tools/lab/screenshots.py --bin {bin_dir} --out {out}")
    say(f"lab done in {time.monotonic() - start:.1f} s")


def run_figures(source: Path, out: Path, quick: bool) -> None:
    if quick:
        say("figures: skipped (a --quick run's tables are not the ones the texts quote)")
        return
    remove_stale_temporaries(source, log=say)
    if refresh_figures(source, out, "refresh", log=say) != 0:
        say("warning: some figures could not be refreshed (above); `tools/figures.py --check` fails on them")


def run_slides(source: Path, slides_dir: Path, out: Path) -> None:
    decks = find_decks(slides_dir)
    if not decks:
        say(f"no decks (NN_*.md) in {slides_dir}")
        return
    say(f"building {len(decks)} deck(s) from {slides_dir} into {out / 'slides'}")
    start = time.monotonic()
    for path in build_decks(source, decks, out / "slides"):  # a DeckError is a JobError
        say(f"  {path}")
    say(f"slides done in {time.monotonic() - start:.1f} s")


def side_by_side(*steps: list) -> None:
    """Runs each list of steps at once, each in its order; once all have ended, raises the first list's error."""
    with ThreadPoolExecutor() as pool:
        runs = [pool.submit(lambda todo=todo: [step() for step in todo]) for todo in steps if todo]
    for run in runs:
        run.result()


def run_texts(source: Path, out: Path) -> None:
    say("texts: rendering the lesson texts, exercises and documents into " + str(out / "pages"))
    start = time.monotonic()
    for line in build_texts(source, out):  # a TextsError is a JobError
        say(f"  {line}")
    say(f"texts done in {time.monotonic() - start:.1f} s")


def run_index(source: Path, out: Path, slides_dir: Path, quick: bool, strict: bool) -> None:
    index = write_index(source, out, slides_dir, "(Quick run: small sizes.)" if quick else "")
    if problems := check_links(index):
        message = f"{index} has {len(problems)} broken link(s):\n  " + "\n  ".join(problems)
        if strict:
            raise JobError(message)
        say("warning: " + message)
    elif strict:
        say("every local link and image in index.html resolves")
    say(f"wrote {index}")


def check_pages(out: Path, index_written: bool) -> None:
    """Every link and image of the rendered pages resolves (after the index step: every page links back to
    OUT/index.html; a run that leaves the index out does not count links to a missing one)."""
    index = out / "index.html"
    broken = [f"{page.relative_to(out)}: {problem}" for page in sorted((out / "pages").rglob("*.html"))
              for problem in check_links(page)
              if index_written or index.exists() or f"{index} does not exist" not in problem]
    if broken:
        raise JobError(f"{len(broken)} broken link(s) in the rendered texts:\n  " + "\n  ".join(broken[:40]))
    say("every local link and image of the rendered texts resolves")


def hold_and_clean(out: Path) -> list[str]:
    """Locks OUT for this job (an flock on the folder, held until the process ends: a second job on it is
    refused) and removes what a job killed there left; one note per thing removed."""
    if lock_folder(out) is None:  # its descriptor stays open, and the lock held, until the process ends
        raise JobError(f"--out {out} is in use by another main job; wait for it to end, or give this one "
                       "another --out")
    notes, left = [], "left by a main job that was killed before it finished"
    for root, dirs, files in os.walk(out):
        here = Path(root)
        dirs[:] = [d for d in dirs if not PROGRAM.match(d) and ".illum-" not in d]  # a lesson's are its runs'
        for name in [d for d in dirs if STALE_FOLDER.fullmatch(d) and not (here / d).is_symlink()]:
            shutil.rmtree(here / name, ignore_errors=True)
            dirs.remove(name)
            notes.append(f"removed {here / name}, {left}")
        for name in files:
            if STALE_FILE.fullmatch(name) and os.lstat(here / name).st_uid == os.geteuid():
                (here / name).unlink()
                notes.append(f"removed {here / name}, {left}")
    return notes


def parse_arguments(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", type=path_argument, help="the build's bin/ folder (needed by the lessons step)")
    parser.add_argument("--out", type=path_argument, required=True, help="the output folder (e.g. out)")
    parser.add_argument("--quick", action="store_true", help="run each lesson with --quick")
    parser.add_argument("--alone", action="store_true", help="run every lesson alone, in order, even those whose "
                        "timings use one core (slower; timings free of a neighbour's load)")
    parser.add_argument("--only", default=",".join(STEPS),
                        help=f"comma-separated steps to run, of {','.join(STEPS)} (default: all)")
    parser.add_argument("--source", type=path_argument, default=SOURCE, help="the source tree (default: this checkout)")
    parser.add_argument("--slides", type=path_argument, help="the folder of NN_*.md decks (default: SOURCE/slides)")
    parser.add_argument("--check-links", action="store_true",
                        help="after writing index.html, fail if any local link or image in it does not resolve")
    args = parser.parse_args(argv)
    args.steps = [s.strip() for s in args.only.split(",") if s.strip()]
    if unknown := [s for s in args.steps if s not in STEPS]:
        parser.error(f"unknown step(s) {', '.join(unknown)}; choose from {', '.join(STEPS)}")
    if ("lessons" in args.steps or "lab" in args.steps) and args.bin is None:
        parser.error("--bin is needed to run the lessons and the lab (or leave them out with --only slides,index)")
    args.source, args.out_dir = args.source.resolve(), args.out.resolve()
    args.slides_dir = (args.slides or args.source / "slides").resolve()
    # Every folder named is checked before OUT is made: a wrong one stops the job with nothing written.
    if not (args.source / "lessons").is_dir():
        parser.error(f"--source {args.source}: not an illum source tree (no lessons/ folder in it)")
    if ("slides" in args.steps or "index" in args.steps) and not args.slides_dir.is_dir():
        parser.error(f"--slides {args.slides or args.slides_dir}: not a folder")
    if "lessons" in args.steps and not find_programs(args.bin.resolve()):
        parser.error(f"--bin {args.bin}: no lessonNN programs in it (build them first: cmake --build --preset release)")
    if "lab" in args.steps and not os.access(args.bin.resolve() / "illum", os.X_OK):
        parser.error(f"--bin {args.bin}: no illum program in it for the lab's screenshots (build it first: "
                     "cmake --build --preset release --target illum_cli)")
    if args.out_dir.exists() and not args.out_dir.is_dir():
        parser.error(f"--out {args.out}: exists and is not a folder")
    if problem := folder_problem(args.out):  # afile/out: a traceback from mkdir otherwise
        parser.error(f"--out {args.out}: {problem}")
    return args


def main(argv: list[str] | None = None) -> int:
    args = parse_arguments(argv)
    steps, out, source = args.steps, args.out_dir, args.source
    out.mkdir(parents=True, exist_ok=True)
    start = time.monotonic()
    try:
        for note in hold_and_clean(out):
            say(f"note: {note}")
        if "lessons" in steps:
            run_lessons(args.bin.resolve(), out, args.quick, args.alone)
        # The figures first (they rewrite the decks); then the lab's screenshots and the decks side by side:
        # both wait on Chromium and Node, time nothing and follow every timed lesson run.
        if "figures" in steps:
            run_figures(source, out, args.quick)
        side_by_side([lambda: run_lab(args.bin.resolve(), out)] if "lab" in steps else [],
                     [lambda: run_slides(source, args.slides_dir, out)] if "slides" in steps else [])
        if "texts" in steps:
            run_texts(source, out)
        if "index" in steps:
            run_index(source, out, args.slides_dir, args.quick, args.check_links)
        if "texts" in steps:
            check_pages(out, "index" in steps)
    except JobError as e:
        print(f"main_job: error: {e}", file=sys.stderr, flush=True)
        return 1
    say(f"finished in {time.monotonic() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
