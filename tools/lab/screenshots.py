#!/usr/bin/env python3
"""Screenshots of the lab's five views for the gallery and the lesson texts (docs/lab.md; the main job's
step "lab"): `BIN/illum lab whitted` on a free port of 127.0.0.1, driven in headless Chromium by
tools/lab/browser.mjs, writes OUT/lab/lab_*.png and a manifest.json. Exit 0 when every one was written.

    tools/lab/screenshots.py --bin build/release/bin --out out
"""

import argparse
import contextlib
import json
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools"))
from common.files import atomic_write_text  # noqa: E402

SHOTS = {
    "lab_ray_tree.png": "The lab's ray-tree view (illum lab whitted): a click on the glass ball, its rays in 3D over "
                        "the scene and its tree, node by node; a shadow ray through the glass is one node with its segments.",
    "lab_radiosity.png": "Radiosity shot by shot: the 2,124-patch Cornell box after ten shots of progressive refinement, "
                         "the shooter outlined, the unshot power against shots.",
    "lab_radiosity_row.png": "The same, painted with the last shooter's form-factor row (log scale).",
    "lab_hemicube.png": "The hemicube on a floor patch: its five item buffers and delta form factors unfolded, the row "
                        "they add up to, and its error against the exact factor as the resolution grows.",
    "lab_hierarchy.png": "Lesson 14's hierarchy on the room: the leaf elements coloured by their radiosity, and the "
                         "element clicked in the middle of the view with its own links and its ancestors', each a line "
                         "to the element it gathers from.",
    "lab_compare.png": "Your picture against the reference: the kept figure, the one your build drew, a difference map "
                       "and one number.",
}


@contextlib.contextmanager
def running_lab(illum: Path, out: Path):
    """`ILLUM lab whitted --out OUT` on a free port of 127.0.0.1: (its process, its port), stopped on leaving
    (SIGINT, then killed after 10 s); RuntimeError when it does not start within a minute."""
    process = subprocess.Popen([str(illum), "lab", "whitted", "--port", "0", "--out", str(out)], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True)
    deadline, match = time.monotonic() + 60, None
    while time.monotonic() < deadline:
        if select.select([process.stdout], [], [], 0.2)[0]:  # its first line names the port
            match = re.search(r"http://127\.0\.0\.1:(\d+)/", process.stdout.readline())
            break
        if process.poll() is not None:
            break
    if not match:
        process.kill()
        raise RuntimeError(f"illum lab did not start: {process.stderr.read()}")
    try:
        yield process, int(match.group(1))
    finally:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()


def browser(mode: str, port: int, options: Path, target: Path, timeout: int) -> int:
    """tools/lab/browser.mjs MODE on the lab at PORT, with its options and its output: its exit status."""
    return subprocess.run([shutil.which("node") or "node", str(SOURCE / "tools" / "lab" / "browser.mjs"), mode,
                           f"http://127.0.0.1:{port}/", str(options), str(target)], cwd=SOURCE,
                          stdin=subprocess.DEVNULL, timeout=timeout).returncode


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bin", type=Path, required=True, help="the build's bin/ folder (holds illum)")
    parser.add_argument("--out", type=Path, required=True, help="the main job's output folder (writes OUT/lab)")
    args = parser.parse_args(argv)
    if shutil.which("node") is None:
        print("screenshots: Node.js is missing: run tools/install-deps", file=sys.stderr)
        return 1
    illum = args.bin.resolve() / "illum"
    if not os.access(illum, os.X_OK):  # checked before OUT/lab is made
        parser.error(f"--bin {args.bin}: no illum program in it (build it first: "
                     "cmake --build --preset release --target illum_cli)")
    out = args.out.resolve()
    if out.exists() and not out.is_dir():
        parser.error(f"--out {args.out}: exists and is not a folder")
    folder = out / "lab"
    folder.mkdir(parents=True, exist_ok=True)
    try:
        with running_lab(illum, out) as (_, port):
            status = _shoot(port, folder)
    except RuntimeError as e:
        print(f"screenshots: {e}", file=sys.stderr)
        return 1
    missing = [name for name in SHOTS if not (folder / name).is_file()]
    if status != 0 or missing:
        print(f"screenshots: the browser failed (status {status}); missing: {', '.join(missing) or 'none'}",
              file=sys.stderr)
        return 1
    manifest = {"id": "lab", "title": "The lab (illum lab): its five views",
                "outputs": [{"kind": "image", "file": name, "caption": caption} for name, caption in SHOTS.items()]}
    atomic_write_text(folder / "manifest.json", json.dumps(manifest, indent=2) + "\n")
    print(f"screenshots: wrote {len(SHOTS)} screenshots of the lab in {folder}")
    return 0


def _shoot(port: int, folder: Path) -> int:
    """The browser's screenshots of the lab at PORT into FOLDER: its exit status."""
    # The hemicube on the floor patch nearest the middle of the box's open front: it sees the
    # whole box, and the opening shows as the directions that meet nothing.
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/api/radiosity/mesh?scene=cornell&patches=2000") as r:
        mesh = json.load(r)
    c, n = mesh["centroid"], mesh["normal"]
    floor = [i for i in range(mesh["patches"]) if n[3 * i + 1] > 0.999]
    patch = min(floor, key=lambda i: abs(c[3 * i] - 278) + abs(c[3 * i + 2] - 25)) if floor else None
    options = folder / "options.json"
    options.write_text(json.dumps({"pixel": [285, 173], "patch": patch, "compare": ["06", "whitted.png"]}),
                       encoding="utf-8")
    status = browser("screenshots", port, options, folder, timeout=600)
    options.unlink()
    (folder / "browser.json").unlink(missing_ok=True)
    return status


if __name__ == "__main__":
    sys.exit(main())
