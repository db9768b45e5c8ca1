#!/usr/bin/env python3
"""Every plot the lesson programs drew shows all its data: lines join, no point is lost on the frame
(tools/gallery/plots.py). Exit 0 when every plot is whole, 1 otherwise, 2 when gnuplot is missing.

    tests/checks/check_plots.py [--out out] [SCRIPT.gp ...]
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from repo import ROOT
from gallery.plots import PlotCheckError, check_plots  # tools/ is on the path (repo)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "out",
                        help="the folder of the programs' outputs (default: out/)")
    parser.add_argument("scripts", nargs="*", type=Path, help="check only these .gp scripts")
    args = parser.parse_args(argv)
    try:
        problems, checked = check_plots(args.out, [p.resolve() for p in args.scripts] or None)
    except PlotCheckError as e:
        print(f"check_plots: cannot run: {e}", file=sys.stderr)
        return 2
    for p in problems:
        print(f"check_plots: {p}")
    if not checked:
        print(f"check_plots: FAILED: no plot scripts (*/NAME.gp beside NAME.png) in {args.out}")
        return 1
    if problems:
        print(f"check_plots: FAILED: {len(problems)} problem(s) in {checked} plot(s)")
        return 1
    print(f"check_plots: OK: the {checked} plot(s) in {args.out} draw every point inside their frame, "
          "and their lines are unbroken")
    return 0


if __name__ == "__main__":
    sys.exit(main())
