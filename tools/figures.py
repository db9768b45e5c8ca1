#!/usr/bin/env python3
"""Figures in lesson texts and decks come from the programs' own tables and images.

    tools/figures.py [--out out]                 refresh timings (what the main job runs)
    tools/figures.py --check [--out out]         fail when a text's values or kept images differ (CI)
    tools/figures.py --update [--out out]        rewrite every figure and value from the tables
    tools/figures.py --update-images [--out out] keep the lesson texts' images in lessons/NN_topic/figures/
    tools/figures.py --links                     only check that the texts' links resolve (needs no OUT)

A figure is the table between `<!-- figure: out/lessonNN/x.md [options] -->` and `<!-- /figure -->`;
a value in a sentence is `43.6<!--=name-->` with its `<!-- value name: … -->`. Every cell but the
timings must match the program's table; --check also compares the kept images with what the programs
drew, and checks the texts' links and the plots. CONTRIBUTING.md ("Figures come from the run", "Numbers in
sentences come from the run too", "Images show where students read") says how to write them.
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common.path_options import path_argument  # noqa: E402
from gallery.figures import process, remove_stale_temporaries, text_link_problems  # noqa: E402
from gallery.kept_images import update_images  # noqa: E402

SOURCE = Path(__file__).resolve().parent.parent


def check_links_only(source: Path, log=print) -> int:
    problems, checked = text_link_problems(source)
    for p in problems:
        log(f"figures: {p}")
    if problems:
        log(f"figures: FAILED: {len(problems)} of {checked} links and images of the texts do not resolve")
        return 1
    log(f"figures: OK: the {checked} links and images of the texts resolve in {source}")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--check", action="store_true", help="compare, write nothing; exit 1 on a difference")
    group.add_argument("--update", action="store_true", help="rewrite every figure from its table")
    group.add_argument("--update-images", action="store_true",
                       help="keep a copy of every image the lesson texts show in lessons/NN_topic/figures/ and link it")
    group.add_argument("--links", action="store_true", help="only check the texts' links and images (needs no OUT)")
    parser.add_argument("--out", type=path_argument, default=None,
                        help="the main job's output folder (default: SOURCE/out)")
    parser.add_argument("--source", type=path_argument, default=SOURCE, help="the source tree (default: this checkout)")
    args = parser.parse_args(argv)
    source = args.source.resolve()
    out = (args.out or source / "out").resolve()
    if not (source / "lessons").is_dir():
        parser.error(f"--source {args.source}: not an illum source tree (no lessons/ folder in it)")
    # One clear line rather than a missing-file problem for each of the texts' figures.
    if not args.links and not out.is_dir():
        parser.error(f"--out {args.out or out}: not a folder of the main job's outputs (run tools/bootstrap, "
                     "or tools/main_job.py --bin build/release/bin --out out)")
    if not args.check and not args.links:  # the modes that write
        remove_stale_temporaries(source)
    if args.update_images:
        return update_images(source, out)
    if args.links:
        return check_links_only(source)
    return process(source, out, "check" if args.check else "update" if args.update else "refresh")


if __name__ == "__main__":
    sys.exit(main())
