#!/usr/bin/env python3
"""End-to-end check of one lesson program (ctest e2e_lessonNN): `PROGRAM --quick --out DIR` (DIR cleared
first) exits 0; every file of DIR/manifest.json (tools/gallery/outputs.py) exists, is not empty and is
well formed for its kind; `PROGRAM --help` names --out and --quick; an unknown flag is an error. Exit 0,
or 1 with the problems. Each check of a file returns its problems, written for a person (none: fine).

    tests/checks/check_outputs.py --run build/release/bin/lesson01 --out build/release/test-out/lesson01
"""
from __future__ import annotations

import argparse
import csv
import io
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import repo  # noqa: F401  (tools/ on the path)
from common import png
from common.markdown import parse_tables
from gallery.outputs import KIND_EXTENSIONS, ManifestError, load_manifest

RUN_TIMEOUT = 600  # seconds; --quick should take a few


def check_png(path: Path) -> list[str]:
    return [f"{path.name}: {p}" for p in png.problems(Path(path).read_bytes())]


_HDR_RESOLUTION = re.compile(rb"^[-+][YX] (\d+) [-+][XY] (\d+)$")


def check_hdr(path: Path) -> list[str]:
    data = Path(path).read_bytes()
    if not data.startswith(b"#?RADIANCE") and not data.startswith(b"#?RGBE"):
        return [f"{path.name}: not a Radiance HDR file (it must start with '#?RADIANCE')"]
    # Header lines, a blank line, then the resolution line ("-Y h +X w").
    end = data.find(b"\n\n")
    if end < 0:
        return [f"{path.name}: the Radiance header never ends (no blank line)"]
    line_end = data.find(b"\n", end + 2)
    resolution = data[end + 2 : line_end if line_end >= 0 else len(data)].strip()
    m = _HDR_RESOLUTION.match(resolution)
    if not m:
        return [f"{path.name}: bad resolution line {resolution[:40]!r} (expected e.g. '-Y 240 +X 320')"]
    if int(m.group(1)) == 0 or int(m.group(2)) == 0:
        return [f"{path.name}: image size is zero ({resolution.decode()})"]
    if line_end < 0 or line_end + 1 >= len(data):
        return [f"{path.name}: no pixel data after the resolution line"]
    return []


def _utf8(path: Path) -> str | None:
    try:
        return Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return None


def check_csv(path: Path) -> list[str]:
    if (text := _utf8(path)) is None:
        return [f"{path.name}: not UTF-8 text"]
    try:
        rows = list(csv.reader(io.StringIO(text)))
    except csv.Error as e:
        return [f"{path.name}: not valid CSV: {e}"]
    blank = [i + 1 for i, r in enumerate(rows) if not r]
    numbered = [(i + 1, r) for i, r in enumerate(rows) if r]
    problems = [f"{path.name}: blank line(s) at {', '.join(map(str, blank[:5]))}"] if blank else []
    if not numbered:
        return [f"{path.name}: empty (a CSV needs a header line and at least one row)"]
    header = numbered[0][1]
    if any(not h.strip() for h in header):
        problems.append(f"{path.name}: the header {header!r} has an empty column name")
    if len(numbered) < 2:
        problems.append(f"{path.name}: only a header, no data rows")
    if ragged := next(((n, row) for n, row in numbered[1:] if len(row) != len(header)), None):
        problems.append(f"{path.name}: line {ragged[0]} has {len(ragged[1])} fields, the header has {len(header)}")
    return problems


def check_markdown_table(path: Path) -> list[str]:
    if (text := _utf8(path)) is None:
        return [f"{path.name}: not UTF-8 text"]
    tables, problems = parse_tables(text.splitlines())
    if not tables and not problems:
        return [f"{path.name}: no Markdown table found (expected '| a | b |', '|---|---|', rows)"]
    return [f"{path.name}: {p}" for p in problems]


def check_text(path: Path) -> list[str]:
    return [] if _utf8(path) is not None else [f"{path.name}: not UTF-8 text"]


def check_mesh(path: Path) -> list[str]:
    """A PLY opens with 'ply' and a format line and closes its header; an OBJ is text with vertices."""
    data = Path(path).read_bytes()
    if path.suffix == ".ply":
        ok = data.startswith(b"ply\n") and b"\nformat " in data[:64] and b"end_header\n" in data
        return [] if ok else [f"{path.name}: not a PLY file (no 'ply', format line or end_header)"]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return [f"{path.name}: not UTF-8 text"]
    return [] if any(line.startswith("v ") for line in text.splitlines()) else [
        f"{path.name}: an OBJ file without vertices"]


CHECKS = {"image": check_png, "plot": check_png, "hdr": check_hdr, "table": check_csv, "markdown": check_markdown_table,
          "script": check_text, "text": check_text, "mesh": check_mesh}


def check_output_folder(folder: Path | str, expected_id: str | None = None) -> list[str]:
    """Every problem with a lesson program's output folder (empty list: all good)."""
    folder = Path(folder)
    try:
        manifest = load_manifest(folder)
    except ManifestError as e:
        return [str(e)]
    problems = []
    if expected_id is not None and manifest.id != expected_id:
        problems.append(f'manifest.json: "id" is {manifest.id!r}, expected {expected_id!r} (the program\'s name)')
    if not manifest.outputs:
        problems.append("manifest.json: lists no outputs")
    seen = set()
    for out in manifest.outputs:
        if out.file in seen:
            problems.append(f"manifest.json: {out.file} is listed twice")
            continue
        seen.add(out.file)
        allowed = KIND_EXTENSIONS[out.kind]
        if allowed and out.suffix not in allowed:
            problems.append(f"{out.file}: kind '{out.kind}' needs a {' or '.join(allowed)} file")
            continue
        path = folder / out.file
        if not path.is_file():
            problems.append(f"{out.file}: listed in manifest.json ({out.kind}) but not written")
            continue
        if path.stat().st_size == 0:
            problems.append(f"{out.file}: empty file")
            continue
        problems.extend(CHECKS[out.kind](path))
    leftovers = sorted(p.name for p in folder.rglob("*.tmp-*"))
    if leftovers:
        problems.append(f"temporary files left behind (an atomic write never finished): {', '.join(leftovers)}")
    return problems


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
