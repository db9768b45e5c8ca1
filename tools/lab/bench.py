#!/usr/bin/env python3
"""The lab's benchmark (a measurement, not a test; docs/lab.md, "How fast", gives the targets): in headless
Chromium, the time from a click to the ray tree drawn on every shipped scene, and radiosity shots a second on
the Cornell box ("1 step", then "run"), as a Markdown table with the machine's cores and load.

    tools/lab/bench.py --bin build/release/bin [--clicks 20] [--single 100] [--shots 2000]
"""

import argparse
import json
import os
import shutil
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from screenshots import browser, running_lab  # noqa: E402

SCENES = ["whitted", "spheres", "primitives", "cornell", "cornell_spheres", "checkerboard", "fine_detail"]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bin", type=Path, required=True)
    parser.add_argument("--clicks", type=int, default=20)
    parser.add_argument("--single", type=int, default=100, help="shots stepped one by one (the \"1 step\" button)")
    parser.add_argument("--shots", type=int, default=2000, help="shots of the \"run\" button")
    args = parser.parse_args()
    if shutil.which("node") is None:
        print("bench: Node.js is missing: run tools/install-deps", file=sys.stderr)
        return 1
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory(prefix="illum-lab-bench-") as work:
        # An empty folder of lesson outputs: the benchmark does not look at your pictures (the
        # source tree's out/ may not exist yet).
        with running_lab(args.bin.resolve() / "illum", Path(work)) as (process, port):
            options, results = Path(work) / "options.json", Path(work) / "results.json"
            options.write_text(json.dumps({"scenes": SCENES, "clicks": args.clicks, "shots": args.shots,
                                           "single": args.single, "labPid": process.pid}), encoding="utf-8")
            if browser("bench", port, options, results, timeout=1800) != 0:
                return 1
            data = json.loads(results.read_text(encoding="utf-8"))
    print(f"\nillum lab benchmark: {os.cpu_count()} cores, load average {load_before[0]:.2f} before, "
          f"{os.getloadavg()[0]:.2f} after\n")
    print("| scene | clicks | nodes (median, largest) | ms from the click to the tree on the screen: median "
          "| 90th percentile | largest |\n|---|---|---|---|---|---|")
    for scene in SCENES + ["all"]:
        clicks = [c for c in data["clicks"] if c["scene"] == scene or scene == "all"]
        ms, nodes = sorted(c["ms"] for c in clicks), [c["nodes"] for c in clicks]
        if ms:
            print(f"| {scene} | {len(ms)} | {statistics.median(nodes):.0f}, {max(nodes)} | {statistics.median(ms):.0f} "
                  f"| {ms[min(len(ms) - 1, int(0.9 * len(ms)))]:.0f} | {ms[-1]:.0f} |")
    print(f"\nCPU time of Chromium's processes and the lab: {1000 * data['clickCpu'] / len(data['clicks']):.0f} ms "
          f"a click (the wall times above share {os.cpu_count()} cores with the machine's load)")
    for key, what in (("single", "one shot per press of \"1 step\" (the request, the repaint and the chart each time)"),
                      ("run", "\"run\" (as many shots per request as keep about seven pictures a second)")):
        s = data[key]
        cpu = f"; {1000 * s['cpu'] / s['shots']:.0f} ms of CPU a shot" if "cpu" in s else ""
        print(f"progressive refinement, {data['patches']} patches, hemicube 128, {what}: {s['shots']} shots in "
              f"{s['seconds']:.2f} s = {s['shots'] / s['seconds']:.1f} shots a second{cpu}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
