#!/usr/bin/env python3
"""Writes the main job's latest run into docs/measurements.md, from the run's own log.

    tools/measurements.py [--out out] [--page docs/measurements.md]

Replaces the block between the page's `measurements` markers with a table of every program's record in
OUT/run_log.json (written by tools/main_job.py; docs/measurements.md, "The latest main job"). Exit 0, or 2
when the log or the markers are missing.
"""
import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from code_map import replace_between  # noqa: E402

BEGIN = "<!-- measurements: begin (written by tools/measurements.py from out/run_log.json) -->"
END = "<!-- measurements: end -->"
PAGE = Path(__file__).resolve().parent.parent / "docs" / "measurements.md"


def table(log: dict) -> str:
    rows = ["| program | started (UTC) | cores | seconds | processor seconds | ran beside "
            "| waited, held the machine (s) |", "|---|---|---|---|---|---|---|"]
    for name, run in sorted(log.items()):
        beside = ", ".join(b.removeprefix("lesson") for b in run.get("beside", [])) or "alone"
        machine = f"{run['waited_seconds']}, {run.get('whole_machine_seconds', '')}" if "waited_seconds" in run else ""
        quick = " (`--quick`)" if run.get("quick") else ""
        rows.append(f"| {name}{quick} | {run.get('started', '')} | {run.get('cores', '')} | {run.get('seconds', '')} "
                    f"| {run.get('cpu_seconds', '')} | {beside} | {machine} |")
    total = sum(run.get("seconds", 0) for run in log.values())
    cpu = sum(run.get("cpu_seconds", 0) for run in log.values())
    return "\n".join(rows) + f"\n\nSum over the programs: {total:.1f} s of wall time, {cpu:.1f} s of processor time.\n"


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("out"), help="the main job's output folder")
    parser.add_argument("--page", type=Path, default=PAGE)
    args = parser.parse_args(argv)
    log_path = args.out / "run_log.json"
    try:
        log = json.loads(log_path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        print(f"measurements: cannot read {log_path} ({e}); run the main job first (tools/bootstrap)", file=sys.stderr)
        return 2
    page = replace_between(args.page.read_text(encoding="utf-8"), BEGIN, END, f"{BEGIN}\n{table(log)}{END}")
    if page is None:
        print(f"measurements: {args.page} has no markers {BEGIN} … {END}", file=sys.stderr)
        return 2
    args.page.write_text(page, encoding="utf-8")
    print(f"updated {args.page}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
