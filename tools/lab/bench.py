#!/usr/bin/env python3
"""The lab's benchmark (a measurement, not a test; docs/lab.md, "How fast"): in headless Chromium, the time
from a click to the ray tree drawn on every shipped scene, and radiosity shots a second on the Cornell box
("1 step", then "run"), as a Markdown table with the machine's cores and load.

    tools/lab/bench.py --bin build/release/bin [--clicks 20] [--single 100] [--shots 2000]
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools" / "lab"))
from screenshots import start_lab  # noqa: E402

SCENES = ["whitted", "spheres", "primitives", "cornell", "cornell_spheres", "checkerboard", "fine_detail"]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bin", type=Path, required=True)
    parser.add_argument("--clicks", type=int, default=20)
    parser.add_argument("--single", type=int, default=100, help="shots stepped one by one (the \"1 step\" button)")
    parser.add_argument("--shots", type=int, default=2000, help="shots of the \"run\" button")
    args = parser.parse_args()
    node = shutil.which("node")
    if node is None:
        print("bench: Node.js is missing: run tools/install-deps", file=sys.stderr)
        return 1
    load_before = os.getloadavg()
    process, port = start_lab(args.bin.resolve() / "illum", SOURCE / "out")
    try:
        with tempfile.TemporaryDirectory(prefix="illum-lab-bench-") as work:
            options, results = Path(work) / "options.json", Path(work) / "results.json"
            options.write_text(json.dumps({"scenes": SCENES, "clicks": args.clicks, "shots": args.shots, "single": args.single}), encoding="utf-8")
            run = subprocess.run([node, str(SOURCE / "tools" / "lab" / "browser.mjs"), "bench", f"http://127.0.0.1:{port}/",
                                  str(options), str(results)], cwd=SOURCE, stdin=subprocess.DEVNULL, timeout=1800)
            if run.returncode != 0:
                return 1
            data = json.loads(results.read_text(encoding="utf-8"))
    finally:
        process.send_signal(signal.SIGINT)
        process.wait(10)
    load_after = os.getloadavg()
    print(f"\nillum lab benchmark: {os.cpu_count()} cores, load average {load_before[0]:.2f} before, "
          f"{load_after[0]:.2f} after\n")
    print("| scene | clicks | nodes (median) | ms to tree drawn: median | 95th percentile | largest |")
    print("|---|---|---|---|---|---|")
    for scene in SCENES:
        clicks = [c for c in data["clicks"] if c["scene"] == scene]
        ms = sorted(c["ms"] for c in clicks)
        if not ms:
            continue
        p95 = ms[min(len(ms) - 1, int(0.95 * len(ms)))]
        print(f"| {scene} | {len(ms)} | {statistics.median(c['nodes'] for c in clicks):.0f} | "
              f"{statistics.median(ms):.0f} | {p95:.0f} | {ms[-1]:.0f} |")
    for key, what in (("single", "one shot per press of \"1 step\" (the request, the repaint and the chart each time)"),
                      ("run", "\"run\" (as many shots per request as keep about seven pictures a second)")):
        s = data[key]
        print(f"progressive refinement, {data['patches']} patches, hemicube 128, {what}: {s['shots']} shots in "
              f"{s['seconds']:.2f} s = {s['shots'] / s['seconds']:.1f} shots a second")
    return 0


if __name__ == "__main__":
    sys.exit(main())
