#!/usr/bin/env python3
"""Runs one bad-input case of tests/badinput/cases.txt and checks the promise:
a non-zero exit code (not a signal, not a hang), an error message that holds
the case's words (file, field, value), and an output folder left exactly as
it was: no new file, no temporary file, an old file unchanged.

  run_case.py --cases cases.txt --case NAME --bin build/bin --scenes scenes/ --work DIR

A case:
  [name]
  run: PROGRAM ARG...      @OUT@ = the case's output folder, @SCENES@ = tests/badinput/scenes,
                           @DEEP_ARRAY@ / @DEEP_OBJECT@ = generated files nested 100,000 deep
  expect: WORD | WORD ...  each must appear in the program's stderr (or stdout)
  blocker: FILE            (optional) before the run, OUT holds old.txt and a folder named FILE,
                           so the program fails when it reaches FILE, after writing others
"""
import argparse
import os
import shlex
import shutil
import signal
import subprocess
import sys


def read_cases(path):
    cases, current = {}, None
    for line in open(path, encoding="utf-8"):
        line = line.rstrip("\n")
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if line.startswith("[") and line.endswith("]"):
            current = line[1:-1]
            cases[current] = {}
        else:
            key, _, value = line.partition(":")
            cases[current][key.strip()] = value.strip()
    return cases


def snapshot(folder):
    """Every file and folder under `folder`, with the contents of files."""
    seen = {}
    for root, dirs, files in os.walk(folder):
        for d in dirs:
            seen[os.path.relpath(os.path.join(root, d), folder) + "/"] = None
        for f in files:
            p = os.path.join(root, f)
            with open(p, "rb") as fh:
                seen[os.path.relpath(p, folder)] = fh.read()
    return seen


def main():
    ap = argparse.ArgumentParser()
    for a in ("--cases", "--case", "--bin", "--scenes", "--work"):
        ap.add_argument(a, required=True)
    ap.add_argument("--timeout", type=float, default=120, help="seconds before a run counts as a hang")
    args = ap.parse_args()
    case = read_cases(args.cases)[args.case]

    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "out")
    if "@DEEP_ARRAY@" in case["run"]:
        with open(os.path.join(work, "deep_array.json"), "w") as f:
            f.write("[" * 100000 + "]" * 100000)
    if "@DEEP_OBJECT@" in case["run"]:
        with open(os.path.join(work, "deep_object.json"), "w") as f:
            f.write('{"surfaces": ' + '{"a": ' * 100000 + "1" + "}" * 100001)
    if "blocker" in case:
        os.makedirs(os.path.join(out, case["blocker"]))
        with open(os.path.join(out, "old.txt"), "w") as f:
            f.write("from an earlier run\n")

    words = shlex.split(case["run"])
    subst = {"@OUT@": out, "@SCENES@": os.path.abspath(args.scenes),
             "@DEEP_ARRAY@": os.path.join(work, "deep_array.json"),
             "@DEEP_OBJECT@": os.path.join(work, "deep_object.json")}
    command = [os.path.join(args.bin, words[0])]
    for w in words[1:]:
        for k, v in subst.items():
            w = w.replace(k, v)
        command.append(w)

    before = snapshot(work)
    try:
        run = subprocess.run(command, cwd=work, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        sys.exit(f"FAIL: {args.case}: no answer within {args.timeout:g} s (a hang?): {' '.join(command)}")
    message = run.stderr + run.stdout
    print(f"$ {' '.join(command)}\nexit {run.returncode}\n{message}")
    failures = []
    if run.returncode < 0:
        failures.append(f"killed by signal {signal.Signals(-run.returncode).name}")
    elif run.returncode == 0:
        failures.append("exit code 0: the bad input was accepted")
    elif run.returncode >= 128:
        failures.append(f"exit code {run.returncode}: a crash, not a refusal")
    for word in [w.strip() for w in case["expect"].split("|")]:
        if word not in message:
            failures.append(f"the message does not contain '{word}'")
    after = snapshot(work)
    for p in sorted(set(after) - set(before)):
        failures.append(f"left a new file or folder behind: {p}")
    for p in sorted(set(before) - set(after)):
        failures.append(f"removed what was there before: {p}")
    for p in sorted(set(before) & set(after)):
        if before[p] != after[p]:
            failures.append(f"changed a file that was there before: {p}")
    if failures:
        sys.exit(f"FAIL: {args.case}:\n  " + "\n  ".join(failures))
    print(f"ok: {args.case}")


if __name__ == "__main__":
    main()
