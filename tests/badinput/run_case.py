#!/usr/bin/env python3
"""Runs one bad-input case of tests/badinput/cases.txt and checks the promise:
a non-zero exit code (not a crash, not a hang), an error message that holds
the case's words (file, field, value), and a case folder left exactly as it
was: no new file, no temporary file, no staging folder or lock, an old file
unchanged, a link, FIFO or device still what it was.

  run_case.py --cases cases.txt --case NAME --bin build/bin --scenes scenes/ --work DIR [--sanitized]

A case:
  [name]
  run: PROGRAM ARG...      PROGRAM is a program of --bin, or tools/NAME of the source tree (run as it is);
                           @OUT@ = the case's output folder (WORK/out), @WORK@ = the case folder,
                           @SCENES@ = tests/badinput/scenes, @DEEP_ARRAY@ / @DEEP_OBJECT@ = generated
                           files nested 100,000 deep, @TRUNCATED_OBJ@ = a generated scene whose OBJ
                           mesh has 1,000,000 faces and a last line cut off
  expect: WORD | WORD ...  each must appear in the program's stderr (or stdout); @PID@ = the PID of
                           the run of `run:` (for `concurrent:`, `after-expect:`)
  blocker: FILE            (optional) before the run, OUT holds old.txt and a folder named FILE,
                           so the program fails when it reaches FILE, after writing others
  prepare: ACTION          (optional, repeatable) before the run, in order:
                             file PATH TEXT       a regular file
                             folder PATH          a folder
                             fifo PATH            a named pipe
                             device PATH MAJOR MINOR  a character device of its own (mknod: as root;
                                                  skipped otherwise), so that a faulty program
                                                  replaces no device of the system's
                             symlink PATH TARGET  a symbolic link
                             copy SOURCE PATH     a copy of a file
                             readonly PATH        chmod a-w
                             run PROGRAM ARG...   a run that must succeed (an earlier output)
                             env NAME VALUE       the run's environment variable NAME set to VALUE
                             tool NAME EXIT OUT   a fake NAME first on PATH that prints OUT
                                                  ("png-cut": a PNG cut short, else the text on
                                                  stderr) and exits with EXIT
  signal: INT|TERM|HUP|KILL  (optional) sent once the run has staged a file; the run must then end
                           by that signal (or exit non-zero), and the folder stay as it was
  concurrent: PROGRAM ARG...  (optional) started once the run holds its output folder's lock: it
                           must be refused with the words of `expect:`, and the run must succeed
                           with a complete manifest
  after: PROGRAM ARG...    (optional) a later run that must succeed and leave no staging or lock
  after-expect: WORD | ...  (optional, with after:) each must appear in the later run's stderr or stdout
  http: PATH?QUERY         (optional) `run:` is a server (`illum lab --port 0`): once it prints its URL,
                           GET PATH?QUERY (sent as written: %00 stays %00); the answer must be 400 and
                           hold the words of `expect:` ("HTTP 400" is put before its body, its JSON
                           "error" decoded after it); then the server is stopped with SIGTERM and
                           must exit 0 (skipped when the build has no lab)
  limit: fsize KIB | as BYTES   (optional) RLIMIT_FSIZE / RLIMIT_AS of the run (`as`: skipped when
                           --sanitized, as a sanitizer maps terabytes of shadow memory)
  tmpfs: SIZE              (optional) WORK is a tmpfs of SIZE (a full disk); needs `unshare -m`
  user: nobody             (optional) run as nobody (when this script runs as root, whom
                           permissions do not stop); needs setpriv
  keep: PATH               (optional, repeatable) a path outside WORK that must be left as it was
  timeout: SECONDS         (optional) default 120
  succeeds: yes            (optional) the run must exit 0 with the words of `expect:` and leave no
                           staging folder, lock or temporary (a run that cleans up after a killed one
                           that `prepare:` imitates); the folder is not compared

Exit status 77 (CTest's skip) when the machine cannot set a case up (no unshare, no setpriv).
"""
import argparse
import hashlib
import json
import os
import re
import resource
import shlex
import shutil
import signal
import stat
import subprocess
import sys
import time

SKIP = 77
SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def read_cases(path):
    cases, current = {}, None
    for line in open(path, encoding="utf-8"):
        line = line.rstrip("\n")
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if line.startswith("[") and line.endswith("]"):
            current = line[1:-1]
            cases[current] = {"prepare": [], "keep": []}
        else:
            key, _, value = line.partition(":")
            key, value = key.strip(), value.strip()
            if key in ("prepare", "keep"):
                cases[current][key].append(value)
            else:
                cases[current][key] = value
    return cases


def describe(path):
    """What is at `path`, without opening anything but a regular file (a FIFO would block)."""
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return None
    if stat.S_ISREG(st.st_mode):
        with open(path, "rb") as fh:
            return ("file", hashlib.sha256(fh.read()).hexdigest(), stat.S_IMODE(st.st_mode))
    if stat.S_ISLNK(st.st_mode):
        return ("link", os.readlink(path))
    if stat.S_ISDIR(st.st_mode):
        return ("folder", stat.S_IMODE(st.st_mode))
    return ("special", stat.S_IFMT(st.st_mode), st.st_rdev)


def snapshot(folder):
    """Every entry under `folder` (links not followed), with what it is and holds."""
    seen = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            p = os.path.join(root, name)
            seen[os.path.relpath(p, folder)] = describe(p)
    return seen


def compare(before, after, failures):
    for p in sorted(set(after) - set(before)):
        failures.append(f"left a new file or folder behind: {p}")
    for p in sorted(set(before) - set(after)):
        failures.append(f"removed what was there before: {p}")
    for p in sorted(set(before) & set(after)):
        if before[p] != after[p]:
            failures.append(f"changed what was there before: {p} ({before[p][0]} -> {after[p][0]})")


# What a run killed without warning may leave: the programs' staging folders and locks, temporary files
# (NAME.tmp-…), the student edition's .NAME.new.XXXXXXXX / .NAME.old.XXXXXXXX and the decks' .decks-XXXXXXXX.
LEFTOVER = re.compile(r"\.illum-staging|\.illum-lock|\.tmp-|(^|/)\.[^/]+\.(new|old)\.[a-z0-9_]{8}(/|$)|"
                      r"(^|/)\.decks-[a-z0-9_]{8}(/|$)")


def leftovers(work):
    return sorted(p for p in snapshot(work) if LEFTOVER.search(p))


def clear(folder):
    """Removes a case folder, including one an earlier case made read-only."""
    for root, dirs, _ in os.walk(folder):
        for d in dirs:
            try:
                os.chmod(os.path.join(root, d), 0o755, follow_symlinks=False)
            except OSError:
                pass
    shutil.rmtree(folder, ignore_errors=True)


def substitute(text, subst):
    for k, v in subst.items():
        text = text.replace(k, v)
    return text


def command_of(words, args, subst):
    words = shlex.split(words)
    program = os.path.join(SOURCE, words[0]) if words[0].startswith("tools/") else os.path.join(args.bin, words[0])
    return [program] + [substitute(w, subst) for w in words[1:]]


def ask_server(process, path, timeout):
    """The URL the server prints first, then `path` asked of it: 'HTTP <status>' and the body."""
    import http.client
    import re
    import select
    end, line = time.monotonic() + timeout, ""
    while time.monotonic() < end and "http://" not in line:
        ready, _, _ = select.select([process.stdout], [], [], 0.2)
        if ready:
            line = process.stdout.readline()
        elif process.poll() is not None:
            break
    match = re.search(r"http://(127\.0\.0\.1):(\d+)/", line)
    if not match:
        return None
    connection = http.client.HTTPConnection(match.group(1), int(match.group(2)), timeout=timeout)
    connection.putrequest("GET", path, skip_accept_encoding=True)
    connection.endheaders()
    answer = connection.getresponse()
    body = answer.read().decode("utf-8", "replace")
    connection.close()
    try:  # the message as the page shows it, JSON's escapes undone
        body += "\n" + json.loads(body)["error"]
    except (ValueError, KeyError, TypeError):
        pass
    return answer.status, f"HTTP {answer.status}\n{body}"


def write_truncated_obj(work):
    """A mesh scene whose OBJ has 1,000,000 faces and a last line cut off (`f 1 2`)."""
    with open(os.path.join(work, "truncated.obj"), "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n")
        f.write("f 1 2 3\nf 2 4 3\n" * 500000)
        f.write("f 1 2")
    with open(os.path.join(work, "truncated.json"), "w") as f:
        f.write('{"format": 1, "camera": {"eye": [0.5, 0.5, 3], "target": [0.5, 0.5, 0], "up": [0, 1, 0],'
                ' "vertical_fov_degrees": 45, "width": 32, "height": 24},'
                ' "materials": {"grey": {"diffuse": [0.5, 0.5, 0.5]}},'
                ' "primitives": [{"type": "mesh", "material": "grey", "obj": "truncated.obj"}]}\n')


def fake_tool(work, name, exit_code, output):
    folder = os.path.join(work, "fakebin")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write("#!/bin/sh\n")
        if output == "png-cut":  # a PNG signature and the start of a header, then nothing
            f.write("printf '\\211PNG\\r\\n\\032\\n\\000\\000\\000\\rIHDR'\n")
        else:
            f.write(f"echo {shlex.quote(output)} >&2\n")
        f.write(f"exit {int(exit_code)}\n")
    os.chmod(path, 0o755)
    return folder


def prepare(case, args, work, subst, env):
    for action in case["prepare"]:
        words = shlex.split(action)
        kind, rest = words[0], [substitute(w, subst) for w in words[1:]]
        if kind == "file":
            os.makedirs(os.path.dirname(rest[0]), exist_ok=True)
            with open(rest[0], "w") as f:
                f.write(" ".join(rest[1:]) + "\n")
        elif kind == "folder":
            os.makedirs(rest[0], exist_ok=True)
        elif kind == "fifo":
            os.mkfifo(rest[0])
        elif kind == "device":
            try:
                os.mknod(rest[0], 0o666 | stat.S_IFCHR, os.makedev(int(rest[1]), int(rest[2])))
            except PermissionError:
                print(f"skipped: {args.case}: making a device needs root")
                sys.exit(SKIP)
        elif kind == "symlink":
            os.symlink(rest[1], rest[0])
        elif kind == "copy":
            shutil.copy(rest[0], rest[1])
        elif kind == "readonly":
            os.chmod(rest[0], 0o555)
        elif kind == "run":
            run = subprocess.run(command_of(" ".join(words[1:]), args, subst), cwd=work, capture_output=True,
                                 text=True, errors="replace", timeout=300)
            if run.returncode != 0:
                sys.exit(f"FAIL: prepare: {action} exited {run.returncode}:\n{run.stderr}")
        elif kind == "env":
            env[words[1]] = " ".join(words[2:])
        elif kind == "tool":
            folder = fake_tool(work, rest[0], rest[1], " ".join(rest[2:]))
            env["PATH"] = folder + os.pathsep + env.get("PATH", "")
        else:
            sys.exit(f"FAIL: unknown prepare action '{kind}'")


def limiter(case, args):
    """The preexec function that sets the case's resource limit, or None."""
    if "limit" not in case:
        return None
    kind, value = case["limit"].split()
    if kind == "fsize":
        which, amount = resource.RLIMIT_FSIZE, int(value) * 1024
    elif kind == "as":
        which, amount = resource.RLIMIT_AS, int(value)
    else:
        sys.exit(f"FAIL: unknown limit '{kind}'")
    return lambda: resource.setrlimit(which, (amount, amount))


def wait_for(condition, seconds, process=None):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if condition():
            return True
        if process is not None and process.poll() is not None:
            return condition()
        time.sleep(0.02)
    return False


def staged_something(work):
    for root, _, files in os.walk(work):
        if files and LEFTOVER.search(os.path.relpath(root, work)):
            return True
    return False


def holds_lock(work):
    return any(".illum-lock" in p for p in snapshot(work))


def main():
    ap = argparse.ArgumentParser()
    for a in ("--cases", "--case", "--bin", "--scenes", "--work"):
        ap.add_argument(a, required=True)
    ap.add_argument("--sanitized", action="store_true", help="the programs run under sanitizers")
    ap.add_argument("--inside-tmpfs", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    args.bin = os.path.abspath(args.bin)
    case = read_cases(args.cases)[args.case]
    timeout = float(case.get("timeout", 120))
    work = os.path.abspath(args.work)

    if "tmpfs" in case and not args.inside_tmpfs:
        # A private mount namespace in which WORK is a tmpfs of the case's size: a full disk.
        if shutil.which("unshare") is None:
            print(f"skipped: {args.case}: needs unshare")
            sys.exit(SKIP)
        clear(work)
        os.makedirs(work)
        script = (f"mount -t tmpfs -o size={shlex.quote(case['tmpfs'])} tmpfs {shlex.quote(work)} && "
                  f"exec {shlex.quote(sys.executable)} " + " ".join(shlex.quote(a) for a in sys.argv) +
                  " --inside-tmpfs")
        probe = subprocess.run(["unshare", "--mount", "--propagation", "private", "true"], capture_output=True)
        if probe.returncode != 0:
            print(f"skipped: {args.case}: cannot make a mount namespace (unshare -m needs privileges)")
            sys.exit(SKIP)
        sys.exit(subprocess.run(["unshare", "--mount", "--propagation", "private", "sh", "-c", script]).returncode)
    if "limit" in case and case["limit"].startswith("as") and args.sanitized:
        print(f"skipped: {args.case}: an address-space limit cannot hold a sanitizer's shadow memory")
        sys.exit(SKIP)
    as_nobody = case.get("user") == "nobody" and os.geteuid() == 0
    if as_nobody and shutil.which("setpriv") is None:
        print(f"skipped: {args.case}: runs as root and needs setpriv to run as nobody")
        sys.exit(SKIP)

    if not args.inside_tmpfs:
        clear(work)
        os.makedirs(work)
    out = os.path.join(work, "out")
    subst = {"@OUT@": out, "@WORK@": work, "@SCENES@": os.path.abspath(args.scenes),
             "@DEEP_ARRAY@": os.path.join(work, "deep_array.json"),
             "@DEEP_OBJECT@": os.path.join(work, "deep_object.json"),
             "@TRUNCATED_OBJ@": os.path.join(work, "truncated.json")}
    every = " ".join(case.get(k, "") for k in ("run", "concurrent", "after")) + " ".join(case["prepare"])
    if "@DEEP_ARRAY@" in every:
        with open(subst["@DEEP_ARRAY@"], "w") as f:
            f.write("[" * 100000 + "]" * 100000)
    if "@DEEP_OBJECT@" in every:
        with open(subst["@DEEP_OBJECT@"], "w") as f:
            f.write('{"surfaces": ' + '{"a": ' * 100000 + "1" + "}" * 100001)
    if "@TRUNCATED_OBJ@" in every:
        write_truncated_obj(work)
    if "blocker" in case:
        os.makedirs(os.path.join(out, case["blocker"]))
        with open(os.path.join(out, "old.txt"), "w") as f:
            f.write("from an earlier run\n")
    env = dict(os.environ)
    prepare(case, args, work, subst, env)
    command = command_of(case["run"], args, subst)
    if as_nobody:
        os.chmod(work, 0o777)
        command = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"] + command

    before = snapshot(work)
    kept = {p: describe(p) for p in case["keep"]}
    failures = []
    start = time.monotonic()
    process = subprocess.Popen(command, cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, errors="replace", preexec_fn=limiter(case, args))
    other = None
    subst["@PID@"] = str(process.pid)
    if "succeeds" in case:
        stdout, stderr = process.communicate(timeout=timeout)
        print(f"$ {' '.join(command)}\nexit {process.returncode}\n{stderr}{stdout}")
        if process.returncode != 0:
            failures.append(f"exit code {process.returncode}: the run failed")
        for word in [substitute(w.strip(), subst) for w in case["expect"].split("|")]:
            if word not in stderr + stdout:
                failures.append(f"the message does not contain '{word}'")
        failures += [f"left behind: {p}" for p in leftovers(work)]
        if failures:
            sys.exit(f"FAIL: {args.case}:\n  " + "\n  ".join(failures))
        print(f"ok: {args.case}")
        return
    if "http" in case:
        try:
            asked = ask_server(process, substitute(case["http"], subst), timeout)
        finally:
            if process.poll() is None:
                process.send_signal(signal.SIGTERM)
        stdout, stderr = process.communicate(timeout=timeout)
        print(f"$ {' '.join(command)}\nGET {case['http']}\n{asked[1] if asked else '(no answer)'}\n{stderr}")
        if asked is None and "this build has no lab" in stderr:  # the libcxx preset's illum (README)
            print(f"skipped: {args.case}: this build of illum has no lab")
            sys.exit(SKIP)
        if asked is None:
            failures.append("the server printed no URL")
        else:
            if asked[0] != 400:
                failures.append(f"status {asked[0]}, not 400")
            for word in [w.strip() for w in case["expect"].split("|")]:
                if word not in asked[1]:
                    failures.append(f"the answer does not contain '{word}'")
        if process.returncode != 0:
            failures.append(f"the server exited {process.returncode} after SIGTERM, not 0")
        compare(before, snapshot(work), failures)
        if failures:
            sys.exit(f"FAIL: {args.case}:\n  " + "\n  ".join(failures))
        print(f"ok: {args.case}")
        return
    if "signal" in case:
        sig = getattr(signal, "SIG" + case["signal"])
        if not wait_for(lambda: staged_something(work), 60, process):
            failures.append("the run staged no file before it ended (the signal came too late to test)")
        process.send_signal(sig)
    if "concurrent" in case:
        if not wait_for(lambda: holds_lock(work), 60, process):
            failures.append("the run never took its output folder's lock")
        other = subprocess.run(command_of(case["concurrent"], args, subst), cwd=work, env=env,
                               capture_output=True, text=True, errors="replace", timeout=timeout)
    try:
        stdout, stderr = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        sys.exit(f"FAIL: {args.case}: no answer within {timeout:g} s (a hang?): {' '.join(command)}")
    seconds = time.monotonic() - start
    code = process.returncode
    message = stderr + stdout
    print(f"$ {' '.join(command)}\nexit {code} after {seconds:.1f} s\n{message}")
    if other is not None:
        print(f"$ (concurrent) {case['concurrent']}\nexit {other.returncode}\n{other.stderr}{other.stdout}")

    if "concurrent" in case:
        # The first run keeps its folder and finishes it; the second is refused and touches nothing.
        if code != 0:
            failures.append(f"the first run exited {code}: a second run must not break it")
        if other is None or other.returncode == 0:
            failures.append("the second run on the same folder was accepted")
        elif other.returncode >= 128 or other.returncode < 0:
            failures.append(f"the second run crashed ({other.returncode})")
        said = (other.stderr + other.stdout) if other else ""
        for word in [substitute(w.strip(), subst) for w in case["expect"].split("|")]:
            if word not in said:
                failures.append(f"the second run's message does not contain '{word}'")
        failures += [f"left behind: {p}" for p in leftovers(work)]
        manifest = os.path.join(out, "manifest.json")
        if not os.path.isfile(manifest):
            failures.append("the first run wrote no manifest.json")
        else:
            for entry in json.load(open(manifest, encoding="utf-8"))["outputs"]:
                if not os.path.isfile(os.path.join(out, entry["file"])):
                    failures.append(f"manifest.json lists {entry['file']}, which is missing")
    else:
        expected_signal = getattr(signal, "SIG" + case["signal"]) if "signal" in case else None
        if code < 0 and -code != expected_signal:
            failures.append(f"killed by signal {signal.Signals(-code).name}")
        elif code == 0:
            failures.append("exit code 0: the bad input was accepted" if expected_signal is None else
                            "exit code 0: the run was not interrupted")
        elif code >= 128:
            failures.append(f"exit code {code}: a crash, not a refusal")
        if expected_signal != signal.SIGKILL:
            for word in [w.strip() for w in case["expect"].split("|")]:
                if word not in message:
                    failures.append(f"the message does not contain '{word}'")
        after = snapshot(work)
        if expected_signal == signal.SIGKILL:
            # Nothing runs after SIGKILL: its staging and lock stay beside the folder until the next run.
            after = {p: v for p, v in after.items() if not LEFTOVER.search(p)}
        compare(before, after, failures)
    for p, was in kept.items():
        if describe(p) != was:
            failures.append(f"changed {p}")
    if "after" in case:
        later = subprocess.run(command_of(case["after"], args, subst), cwd=work, env=env, capture_output=True,
                               text=True, errors="replace", timeout=300)
        print(f"$ (after) {case['after']}\nexit {later.returncode}\n{later.stderr}{later.stdout}")
        if later.returncode != 0:
            failures.append(f"the later run exited {later.returncode}: {later.stderr[-400:]}")
        for word in [substitute(w.strip(), subst) for w in case.get("after-expect", "").split("|") if w.strip()]:
            if word not in later.stderr + later.stdout:
                failures.append(f"the later run's message does not contain '{word}'")
        failures += [f"the later run left behind: {p}" for p in leftovers(work)]
    if failures:
        sys.exit(f"FAIL: {args.case}:\n  " + "\n  ".join(failures))
    print(f"ok: {args.case}")


if __name__ == "__main__":
    main()
