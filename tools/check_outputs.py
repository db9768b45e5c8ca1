#!/usr/bin/env python3
"""End-to-end check of one lesson program (ctest e2e_lessonNN): `PROGRAM --quick --out DIR` (DIR cleared
first) exits 0; every file of DIR/manifest.json exists, is not empty and is well formed for its kind;
`PROGRAM --help` names --out and --quick; an unknown flag is an error. Exit 0, or 1 with the problems.

    tools/check_outputs.py --run build/release/bin/lesson01 --out build/release/test-out/lesson01
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from gallery.outputs import check_output_folder  # noqa: E402

RUN_TIMEOUT = 600  # seconds; --quick should take a few


def safe_to_clear(folder: Path) -> str | None:
    """Why `folder` must not be deleted, or None when it may be."""
    folder = folder.resolve()
    if folder == Path(folder.anchor) or folder == Path.home().resolve():
        return "it is the root or home folder"
    for marker in (".git", "CMakeLists.txt", "CMakeCache.txt"):
        if (folder / marker).exists():
            return f"it holds {marker} (a source or build tree, not an output folder)"
    return None


def tail(text: str, lines: int = 25) -> str:
    rows = text.rstrip().splitlines()
    shown = rows[-lines:]
    prefix = [f"    ... ({len(rows) - lines} earlier lines)"] if len(rows) > lines else []
    return "\n".join(prefix + ["    " + r for r in shown])


def run(cmd: list[str], cwd: Path, timeout: int) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, errors="replace", timeout=timeout)


def quick_run(program: Path, out: Path, timeout: int) -> str:
    """`PROGRAM --quick --out OUT` into a cleared folder (stale files must not hide a missing one): '' when
    it exits 0, else why not."""
    if out.exists():
        if reason := safe_to_clear(out):
            return f"refusing to clear {out}: {reason}"
        shutil.rmtree(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    cmd = [str(program), "--quick", "--out", str(out)]
    print("check_outputs: running", " ".join(cmd), flush=True)
    start = time.monotonic()
    try:
        result = run(cmd, cwd=out.parent, timeout=timeout)
    except subprocess.TimeoutExpired:
        return f"FAILED: {program.name} --quick did not finish within {timeout} s (--quick must take a few seconds)"
    seconds = time.monotonic() - start
    if result.returncode != 0:
        return (f"FAILED: {program.name} --quick exited with code {result.returncode} after {seconds:.1f} s"
                + (f"\n  stdout:\n{tail(result.stdout)}" if result.stdout.strip() else "")
                + (f"\n  stderr:\n{tail(result.stderr)}" if result.stderr.strip() else ""))
    print(f"check_outputs: {program.name} --quick finished in {seconds:.1f} s")
    return ""


def command_line_problems(program: Path) -> list[str]:
    """--help exits 0 and names --out and --quick; an unknown flag is an error. Run in a scratch folder, so
    that a program ignoring the flag cannot write into the source or build tree."""
    name, problems, bad_flag = program.name, [], "--no-such-flag-for-illum"
    with tempfile.TemporaryDirectory(prefix="illum-check-") as scratch:
        try:
            help_run = run([str(program), "--help"], cwd=Path(scratch), timeout=60)
            if help_run.returncode != 0:
                problems.append(f"{name} --help exited with code {help_run.returncode}, expected 0")
            problems += [f"{name} --help does not mention {flag}" for flag in ("--out", "--quick")
                         if flag not in help_run.stdout + help_run.stderr]
            if run([str(program), bad_flag], cwd=Path(scratch), timeout=60).returncode == 0:
                problems.append(f"{name} {bad_flag} exited with 0; an unknown flag must be an error (non-zero)")
        except subprocess.TimeoutExpired:
            problems.append(f"{name} --help (or an unknown flag) did not return within 60 s")
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--run", required=True, metavar="PROGRAM", help="the lesson program to run")
    parser.add_argument("--out", required=True, metavar="DIR", help="its output folder (cleared first)")
    parser.add_argument("--timeout", type=int, default=RUN_TIMEOUT, help="seconds allowed for the --quick run")
    args = parser.parse_args(argv)
    program = Path(args.run).absolute()  # not resolve(): keep a symlink's name
    out = Path(args.out).resolve()
    if not program.is_file() or not os.access(program, os.X_OK):
        print(f"check_outputs: {program} is not an executable program (was it built?)")
        return 1
    if failed := quick_run(program, out, args.timeout):
        print(f"check_outputs: {failed}")
        return 1
    problems = check_output_folder(out, expected_id=program.name if re.fullmatch(r"lesson\d\d", program.name) else None)
    problems += command_line_problems(program)
    if problems:
        print(f"check_outputs: FAILED: {len(problems)} problem(s) with {program.name}'s outputs in {out}:")
        for p in problems:
            for i, line in enumerate(p.splitlines()):
                print(("  - " if i == 0 else "    ") + line)
        return 1
    print(f"check_outputs: OK: {program.name}: every file in {out / 'manifest.json'} is present and well formed; "
          "--help and unknown flags behave")
    return 0


if __name__ == "__main__":
    sys.exit(main())
