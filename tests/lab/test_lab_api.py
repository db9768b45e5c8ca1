#!/usr/bin/env python3
"""The lab's API against a real `illum lab` (CTest `lab_api`, label "lab"; docs/lab.md).

    test_lab_api.py --illum build/release/bin/illum --illum-stubs build/release/bin/illum_cli_stubs \\
                    --work build/release/test-out/lab-api

Checks, each against a server started for it on a free port of 127.0.0.1:
* every endpoint answers; GET /api/trace returns exactly the JSON that
  `illum trace SCENE --pixel X Y` writes (compared as parsed JSON, for three
  pixels and two depth limits);
* a bad request gets 400 (403 for another Host, 404 for what does not exist,
  405 for another method) with a JSON message naming the parameter and its
  value, never a crash: a table of hand-made cases, then 400 requests of a
  seeded fuzz of endpoints, parameter names and values (the server must
  answer every one with a status below 500 and still be alive);
* radiosity sessions: each method steps, the unshot power falls, sessions
  are independent, and the same session stepped 1 shot at a time from
  several threads at once ends where one 10-shot step ends;
* SIGINT (Ctrl-C) and SIGTERM stop the server with status 0 within 5 s,
  even with a client's connection open; a busy port and a bad scene are
  refused with status 1 and a message;
* long requests stop early: a 2048 × 2048 render stops (409) when the same
  tab asks for a newer one and (503) at Ctrl-C, and a 20,000-shot step when
  a newer step of its session comes, each within 3 s (they ran 13 to 30 s
  and more);
* slow clients: 40 half-sent requests leave the lab answering at once, and
  a client that sends a header line every 5 s is dropped after the 2 s read
  timeout (it held a worker for good);
* the documented largest mesh, patches=20000, is made (the mesher's
  overshoot was refused);
* a reference beside it (--reference): /api/reference/* answers as the
  reference's /api/*, a program that is not a lab is refused;
* the same `illum` built on every exercise stub (what a student edition
  runs first) answers 501 with the function to write, and keeps serving.

Exit status 0 when every check passes; prints "N passed, M failed".
"""
from __future__ import annotations

import argparse
import base64
import http.client
import json
import os
import random
import re
import select
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import traceback
from pathlib import Path
from urllib.parse import urlencode

SOURCE = Path(__file__).resolve().parents[2]


class Lab:
    """`illum lab ARGS --port 0` as a context manager; get() sends one request."""

    def __init__(self, illum: Path, *args: str):
        self.command = [str(illum), "lab", *args]
        if "--port" not in args:
            self.command += ["--port", "0"]
        self.process = None
        self.port = 0

    def __enter__(self) -> "Lab":
        self.process = subprocess.Popen(self.command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                        stdin=subprocess.DEVNULL, text=True)
        deadline = time.monotonic() + 30
        line = ""
        while time.monotonic() < deadline:
            ready, _, _ = select.select([self.process.stdout], [], [], 0.2)
            if ready:
                line = self.process.stdout.readline()
                break
            if self.process.poll() is not None:
                break
        match = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        if not match:
            self.process.kill()
            raise RuntimeError(f"{' '.join(self.command)} printed no URL: {line!r} {self.process.stderr.read()!r}")
        self.port = int(match.group(1))
        return self

    def __exit__(self, *exc) -> None:
        if self.process and self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()

    def get(self, path: str, params: dict | list | None = None, method: str = "GET",
            host: str | None = None, raw_query: str | None = None) -> tuple[int, dict, bytes]:
        query = raw_query if raw_query is not None else (urlencode(params) if params else "")
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=120)
        try:
            connection.putrequest(method, path + ("?" + query if query else ""), skip_host=True)
            connection.putheader("Host", host if host is not None else f"127.0.0.1:{self.port}")
            connection.endheaders()
            response = connection.getresponse()
            return response.status, dict(response.getheaders()), response.read()
        finally:
            connection.close()

    def json(self, path: str, params: dict | None = None) -> dict:
        status, _, body = self.get(path, params)
        if status != 200:
            raise AssertionError(f"GET {path} {params}: {status} {body[:300]!r}")
        return json.loads(body)


class Checks:
    def __init__(self) -> None:
        self.passed, self.failed = 0, 0

    def run(self, name: str, function, *args) -> None:
        print(f"--- {name}", flush=True)
        try:
            function(*args)
        except Exception as e:  # noqa: BLE001 - every failure is reported, the others still run
            self.failed += 1
            print(f"FAILED: {name}: {e}", flush=True)
            traceback.print_exc(limit=3)
            return
        self.passed += 1
        print(f"ok: {name}", flush=True)


def expect(condition: bool, message: str) -> None:
    if not condition:
        raise AssertionError(message)


def illum_trace(illum: Path, work: Path, x: int, y: int, *extra: str) -> dict:
    out = work / f"trace-{x}-{y}-{'-'.join(extra) or 'default'}"
    result = subprocess.run([str(illum), "trace", "whitted", "--pixel", str(x), str(y), "--out", str(out), *extra],
                            capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=120)
    expect(result.returncode == 0, f"illum trace failed: {result.stderr}")
    return json.loads((out / "ray_tree.json").read_text(encoding="utf-8"))


def check_endpoints(lab: Lab, illum: Path, work: Path) -> None:
    info = lab.json("/api/info")
    expect(info["scene"] == "whitted" and "cornell" in info["scenes"] and info["port"] == lab.port, f"info: {info}")
    # The JSON of `illum trace`: the glass ball (lesson 06's pixel), the floor, the sky; and another depth.
    for x, y, extra in [(285, 173, ()), (100, 300, ()), (5, 5, ()), (285, 173, ("--depth", "2"))]:
        params = {"x": x, "y": y}
        if extra:
            params["depth"] = extra[1]
        got = lab.json("/api/trace", params)
        want = illum_trace(illum, work, x, y, *extra)
        expect(got == want, f"/api/trace {params} differs from `illum trace --pixel {x} {y} {' '.join(extra)}`")
    status, headers, png = lab.get("/api/render")
    expect(status == 200 and png[:8] == b"\x89PNG\r\n\x1a\n", "render: not a PNG")
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    expect((width, height) == (480, 360), f"render: {width} x {height}, the whitted camera is 480 x 360")
    expect(headers.get("Content-Type", "").startswith("image/png"), f"render: type {headers.get('Content-Type')}")
    geometry = lab.json("/api/scene")
    expect(len(geometry["objects"]) == 114 and len(geometry["lights"]) == 1,
           f"scene: {len(geometry['objects'])} objects, {len(geometry['lights'])} lights (whitted: 114 and 1)")
    status, headers, page = lab.get("/")
    expect(status == 200 and b"illum lab" in page and "script-src" not in headers.get("Content-Security-Policy", "x")
           and "default-src 'self'" in headers.get("Content-Security-Policy", ""), "the page or its policy")
    for asset in ("/assets/lab.js", "/assets/lab.css", "/assets/three/three.module.js", "/assets/three/OrbitControls.js"):
        status, _, body = lab.get(asset)
        expect(status == 200 and len(body) > 100, f"{asset}: {status}")
    status, _, body = lab.get("/assets/three/OrbitControls.js")
    expect(b"from 'three'" not in body, "OrbitControls.js still imports the bare name 'three'")
    listing = lab.json("/api/compare")
    expect(any(lesson["lesson"] == "06" for lesson in listing["lessons"]), "compare: no lesson 06 figures listed")


# (path, query, expected status, a piece of the message)
BAD = [
    ("/api/trace", "x=1", 400, "'y' is missing"),
    ("/api/trace", "x=480&y=0", 400, "'x' = '480' is outside 0 … 479"),
    ("/api/trace", "x=-1&y=0", 400, "'x' = '-1' is outside"),
    ("/api/trace", "x=1.5&y=0", 400, "'x' = '1.5' is not an integer"),
    ("/api/trace", "x=0x10&y=0", 400, "is not an integer"),
    ("/api/trace", "x=99999999999999999999999&y=0", 400, "is outside"),
    ("/api/trace", "x=1&x=2&y=0", 400, "'x' is given twice"),
    ("/api/trace", "x=&y=0", 400, "'x' is empty"),
    ("/api/trace", "x=1&y=1&colour=red", 400, "unknown parameter 'colour'"),
    ("/api/trace", "x=1&y=1&depth=65", 400, "'depth' = '65' is outside"),
    ("/api/trace", "x=1&y=1&plan=maybe", 400, "'plan' = 'maybe' is not 0, 1"),
    ("/api/trace", "x=1&y=1&prune=nan", 400, "'prune' = 'nan' is not a finite number"),
    ("/api/trace", "x=1&y=1&prune=2", 400, "'prune' = '2' is outside"),
    ("/api/trace", "x=1&y=1&scene=nowhere", 400, "scene 'nowhere' is not one the lab can open"),
    ("/api/trace", "x=1&y=1&scene=..%2F..%2Fetc%2Fpasswd", 400, "holds a character other than"),
    ("/api/trace", "x=1&y=1&width=5000", 400, "'width' = '5000' is outside"),
    ("/api/render", "width=2049", 400, "'width' = '2049' is outside 1 … 2048"),
    ("/api/render", "width=0", 400, "'width' = '0' is outside 1 … 2048"),
    ("/api/scene", "height=0", 400, "'height' = '0' is outside 1 … 2048"),
    ("/api/scene", "scene=" + "a" * 200, 400, "longer than 80 bytes"),
    ("/api/radiosity/mesh", "scene=whitted", 400, "whitted"),
    ("/api/radiosity/mesh", "scene=spheres", 400, ""),
    ("/api/radiosity/mesh", "patches=0", 400, "'patches' = '0' is outside"),
    ("/api/radiosity/mesh", "patches=20001", 400, "'patches' = '20001' is outside"),
    ("/api/radiosity/mesh", "edge=0.5", 400, "more than 22000 patches"),
    ("/api/radiosity/mesh", "edge=-1", 400, "'edge' = '-1' is outside"),
    ("/api/radiosity/mesh", "patches=10&edge=100", 400, "not both"),
    ("/api/radiosity/start", "method=newton&patches=50", 400, "'method' = 'newton' is not one of"),
    ("/api/radiosity/start", "resolution=33&patches=50", 400, "'resolution' = 33 is odd"),
    ("/api/radiosity/start", "resolution=2000&patches=50", 400, "'resolution' = '2000' is outside"),
    ("/api/radiosity/start", "omega=1.5&patches=50", 400, "for method gauss_seidel only"),
    ("/api/radiosity/start", "method=gauss_seidel&omega=2&patches=50", 400, "'omega' = '2' is outside"),
    ("/api/radiosity/start", "method=jacobi&patches=3500", 400, "at most 3000 patches"),
    ("/api/radiosity/start", "method=southwell&patches=50&resolution=512", 400, "at most 256 pixels across"),
    ("/api/radiosity/step", "session=0123456789abcdef", 404, "no session '0123456789abcdef'"),
    ("/api/radiosity/step", "session=%2E%2E", 404, "no session"),
    ("/api/radiosity/step", "", 400, "'session' is missing"),
    ("/api/hemicube", "patch=100000&patches=50", 400, "'patch' = '100000' is outside"),
    ("/api/hemicube", "patch=0&resolution=7&patches=50", 400, "'resolution' = 7 is odd"),
    ("/api/hemicube", "patch=0&resolution=1024&patches=50", 400, "'resolution' = '1024' is outside"),
    ("/api/hemicube/study", "patches=50", 400, "'patch' is missing"),
    ("/api/hierarchy", "scene=cornell&epsilon_f=0", 400, "parameter 'epsilon_f' = '0' is outside"),
    ("/api/hierarchy", "scene=cornell&epsilon_bf=nan", 400, "parameter 'epsilon_bf' = 'nan' is not a finite number"),
    ("/api/hierarchy", "scene=cornell&min_edge=0.5", 400, "min_edge=0.5 lets scene 'cornell' split into"),
    ("/api/hierarchy", "scene=cornell&element=x", 400, "parameter 'element' = 'x' is not an integer"),
    ("/api/hierarchy", "scene=cornell&min_edge=150&element=100000", 400, "parameter 'element' = 100000 is outside 0 …"),
    ("/api/compare/stats", "lesson=6&name=whitted.png", 400, "'lesson' = '6' is not two digits"),
    ("/api/compare/stats", "lesson=06&name=..%2F..%2FREADME.md", 400, "holds a character other than"),
    ("/api/compare/stats", "lesson=06&name=nothing.png", 404, "keeps no reference image nothing.png"),
    ("/api/compare/image", "lesson=06&name=whitted.png&which=both", 400, "'which' = 'both' is not one of"),
    ("/api/compare", "lesson=06", 400, "unknown parameter 'lesson'"),
    ("/api/info", "x=1", 400, "unknown parameter 'x'"),
    ("/api/nothing", "", 404, "no such page or endpoint: /api/nothing"),
]


def check_bad_requests(lab: Lab) -> None:
    problems = []
    for path, query, status, message in BAD:
        got, headers, body = lab.get(path, raw_query=query)
        text = body.decode("utf-8", errors="replace")
        if got != status:
            problems.append(f"{path}?{query}: status {got}, expected {status}: {text[:200]}")
        elif status != 200:
            try:
                error = json.loads(text)["error"]
            except (ValueError, KeyError):
                problems.append(f"{path}?{query}: the {status} has no JSON error: {text[:200]}")
                continue
            if message not in error:
                problems.append(f"{path}?{query}: message {error!r} lacks {message!r}")
    for method in ("POST", "PUT", "DELETE", "PATCH"):
        got, headers, body = lab.get("/api/trace", raw_query="x=1&y=1", method=method)
        if got != 405 or "GET" not in headers.get("Allow", ""):
            problems.append(f"{method}: status {got} (expected 405 and Allow: GET), {body[:100]!r}")
    for host in ("evil.example:80", f"attacker.test:{lab.port}", ""):
        got, _, body = lab.get("/api/info", host=host)
        if got != 403:
            problems.append(f"Host {host!r}: status {got}, expected 403 (DNS rebinding)")
    got, _, _ = lab.get("/api/info", host=f"localhost:{lab.port}")
    if got != 200:
        problems.append(f"Host localhost:{lab.port}: status {got}, expected 200")
    for path in ("/assets/../../../etc/passwd", "/assets/%2e%2e/%2e%2e/etc/passwd", "/assets/nothing.js"):
        got, _, body = lab.get(path)
        if got not in (400, 404) or b"root:" in body:
            problems.append(f"{path}: status {got}")
    expect(not problems, "\n  " + "\n  ".join(problems))


def check_fuzz(lab: Lab) -> None:
    """Seeded random requests: every answer below 500, the server alive at the end."""
    rng = random.Random(27)
    endpoints = ["/api/info", "/api/scene", "/api/render", "/api/trace", "/api/radiosity/mesh",
                 "/api/radiosity/start", "/api/radiosity/step", "/api/hemicube", "/api/hemicube/study",
                 "/api/compare", "/api/compare/stats", "/api/compare/image", "/api/hierarchy", "/", "/api/", "/assets/"]
    names = ["x", "y", "scene", "width", "height", "depth", "plan", "prune", "patches", "edge", "method",
             "resolution", "omega", "session", "steps", "vertex", "rule", "patch", "lesson", "name", "which", "z",
             "epsilon_f", "epsilon_bf", "min_edge", "element", ""]
    values = ["0", "1", "-1", "2", "7", "64", "479", "1e308", "-0", "nan", "inf", "1e-320", "0.5", "99999999999",
              "cornell", "whitted", "checkerboard", "spheres", "progressive", "jacobi", "southwell", "06", "11",
              "whitted.png", "..", "%00", "%FF%FE", "\u00e9", "a" * 300, "", " ", "%20", "true", "extrapolate"]
    problems = []
    for i in range(400):
        path = rng.choice(endpoints)
        pairs = []
        for _ in range(rng.randint(0, 4)):
            pairs.append((rng.choice(names), rng.choice(values)))
        if path in ("/api/radiosity/mesh", "/api/radiosity/start", "/api/hemicube", "/api/hemicube/study") and rng.random() < 0.7:
            pairs.append(("patches", str(rng.choice([20, 60, 200]))))  # small meshes keep the fuzz quick
        if path == "/api/hierarchy" and rng.random() < 0.7:
            pairs.append(("min_edge", str(rng.choice([100, 150, 300]))))  # coarse elements, for the same reason
        query = "&".join(f"{k}={v}" if rng.random() < 0.9 else k for k, v in pairs)
        query = query.replace(" ", "%20").replace("\u00e9", "%C3%A9")
        try:
            status, _, body = lab.get(path, raw_query=query)
        except Exception as e:  # noqa: BLE001
            problems.append(f"{path}?{query[:120]}: no answer ({e})")
            break
        if status >= 500 and not (status == 501):
            problems.append(f"{path}?{query[:120]}: status {status}: {body[:200]!r}")
    expect(lab.process.poll() is None, "the server died during the fuzz")
    expect(lab.get("/api/info")[0] == 200, "the server does not answer after the fuzz")
    expect(not problems, "\n  " + "\n  ".join(problems[:20]))


def check_radiosity(lab: Lab) -> None:
    base = {"scene": "cornell", "patches": 300, "resolution": 32}
    for method in ("progressive", "jacobi", "gauss_seidel", "southwell"):
        start = lab.json("/api/radiosity/start", {**base, "method": method})
        expect(start["patches"] == 330, f"{method}: {start['patches']} patches (lesson 11's quick figure has 330)")
        steps = 6 if method != "southwell" else 200
        r = lab.json("/api/radiosity/step", {"session": start["session"], "steps": steps, "vertex": 1, "row": 1})
        for key in ("radiosity", "row", "vertex"):  # little-endian float32, base64
            if r.get(key) is not None:
                raw = base64.b64decode(r[key])
                r[key] = list(struct.unpack(f"<{len(raw) // 4}f", raw))
        fractions = [f for _, f in r["points"]]
        expect(len(fractions) == steps and r["steps"] == steps, f"{method}: {len(fractions)} points")
        expect(fractions[-1] < 1.0 and abs(fractions[-1] - r["fraction"]) < 1e-15, f"{method}: {fractions[-5:]}")
        if method != "southwell":
            expect(all(b <= a * (1 + 1e-12) for a, b in zip(fractions, fractions[1:])),
                   f"{method}: the unshot power rises: {fractions}")
        expect(len(r["radiosity"]) == 3 * 330, f"{method}: {len(r['radiosity'])} radiosity values")
        expect("vertex" in r and len(r["vertex"]) % 3 == 0 and len(r["vertex"]) >= 3 * 3 * 330, f"{method}: vertex colours")
        if method in ("progressive", "southwell"):
            expect(r["shooter"] >= 0 and len(r["row"]) == 330, f"{method}: shooter {r['shooter']}")
    # Independent sessions, and one stepped from several threads at once: the session's lock keeps
    # the shots in order, so 10 single shots end where one 10-shot step ends.
    one = lab.json("/api/radiosity/start", base)["session"]
    many = lab.json("/api/radiosity/start", base)["session"]
    other = lab.json("/api/radiosity/start", {**base, "method": "jacobi"})["session"]
    want = lab.json("/api/radiosity/step", {"session": one, "steps": 10})
    errors = []

    def hit(params) -> None:
        try:
            lab.json(*params)
        except Exception as e:  # noqa: BLE001
            errors.append(str(e))

    jobs = [("/api/radiosity/step", {"session": many, "steps": 1}) for _ in range(10)]
    jobs += [("/api/radiosity/step", {"session": other, "steps": 1}) for _ in range(3)]
    jobs += [("/api/trace", {"x": 200 + i, "y": 200}) for i in range(4)]
    jobs += [("/api/hemicube", {"scene": "cornell", "patches": 300, "patch": 7, "resolution": 32}) for _ in range(3)]
    threads = [threading.Thread(target=hit, args=(job,)) for job in jobs]
    for t in threads:
        t.start()
    for t in threads:
        t.join(120)
    expect(not errors, f"concurrent requests failed: {errors[:3]}")
    got = lab.json("/api/radiosity/step", {"session": many, "steps": 0})
    expect(got["steps"] == 10 and got["fraction"] == want["fraction"],
           f"10 single shots from 10 threads: {got['steps']} shots, unshot {got['fraction']} (one step of 10: {want['fraction']})")
    expect(lab.json("/api/radiosity/step", {"session": other, "steps": 0})["steps"] == 3, "the Jacobi session's sweeps")
    h = lab.json("/api/hemicube", {"scene": "cornell", "patches": 300, "patch": 7, "resolution": 32})
    expect(0 < h["sum"] <= 1 + 1e-12 and len(h["faces"]) == 5 and h["exact"] is not None, f"hemicube: sum {h['sum']}")


def timed_get(lab: Lab, path: str, tab: str | None, out: list) -> None:
    """GET in a thread: appends (status, seconds, body)."""
    connection = http.client.HTTPConnection("127.0.0.1", lab.port, timeout=120)
    headers = {"Host": f"127.0.0.1:{lab.port}"}
    if tab:
        headers["X-Lab-Tab"] = tab
    started = time.monotonic()
    try:
        connection.request("GET", path, headers=headers)
        response = connection.getresponse()
        out.append((response.status, time.monotonic() - started, response.read()))
    except OSError as e:
        out.append((0, time.monotonic() - started, str(e).encode()))
    finally:
        connection.close()


# A render that takes far longer than the checks below wait: the glass ball's ray trees at depth 64
# (over a minute on two cores; the primitives scene at depth 8, used before, can end within the 1.5 s wait).
LONG_RENDER = "/api/render?scene=whitted&width=2048&height=2048&depth=64"


def check_long_requests(illum: Path) -> None:
    with Lab(illum, "whitted") as lab:
        # A newer render from the same tab stops the one running.
        old: list = []
        thread = threading.Thread(target=timed_get, args=(lab, LONG_RENDER, "t1/tree", old))
        thread.start()
        time.sleep(1.5)

        new: list = []
        timed_get(lab, "/api/render?scene=whitted&width=64", "t1/tree", new)
        thread.join(30)
        expect(new and new[0][0] == 200, f"the newer render: {new}")
        expect(old and old[0][0] == 409 and b"newer request" in old[0][2], f"the older render: {old}")
        print(f"    the older render answered 409 {old[0][1] - 1.5:.2f} s after the newer one was asked")
        expect(old[0][1] - 1.5 < 3, "the older render ran on for 3 s after a newer one")
        # Another tab's render is not stopped by this tab's.
        a: list = []
        b: list = []
        thread = threading.Thread(target=timed_get, args=(lab, "/api/render?scene=whitted&width=400", "t2/tree", a))
        thread.start()
        timed_get(lab, "/api/render?scene=spheres&width=64", "t3/tree", b)
        thread.join(60)
        expect(a and a[0][0] == 200 and b and b[0][0] == 200, f"two tabs' renders: {a[:1]} {b[:1]}")
        # A newer step of a session stops its 20,000-shot step.
        session = lab.json("/api/radiosity/start", {"patches": 2000, "resolution": 256})["session"]
        long: list = []
        thread = threading.Thread(target=timed_get, args=(lab, f"/api/radiosity/step?session={session}&steps=20000", None, long))
        thread.start()
        time.sleep(1.5)
        short: list = []
        timed_get(lab, f"/api/radiosity/step?session={session}&steps=1", None, short)
        thread.join(30)
        expect(long and long[0][0] == 409 and short and short[0][0] == 200, f"steps: {long[:1]} {short[:1]}")
        print(f"    the 20,000-shot step answered 409 {long[0][1] - 1.5:.2f} s after a newer step was asked")
        expect(long[0][1] - 1.5 < 3, "the long step ran on for 3 s after a newer one")
    # Ctrl-C during a long render: the lab ends (status 0) and the render is answered 503.
    with Lab(illum, "whitted") as lab:
        out: list = []
        thread = threading.Thread(target=timed_get, args=(lab, LONG_RENDER, None, out))
        thread.start()
        time.sleep(1.5)
        started = time.monotonic()
        lab.process.send_signal(signal.SIGINT)
        code = lab.process.wait(10)
        took = time.monotonic() - started
        thread.join(10)
        print(f"    Ctrl-C during a 2048 × 2048 render: stopped {took:.2f} s after it")
        expect(code == 0 and took < 3, f"Ctrl-C during a render: status {code} after {took:.1f} s")
        expect(out and out[0][0] in (0, 503), f"the render at Ctrl-C: {out[:1]}")


def check_slow_clients(illum: Path) -> None:
    with Lab(illum, "whitted") as lab:
        half = []
        for _ in range(40):  # each sends a request line and one header, then nothing
            s = socket.create_connection(("127.0.0.1", lab.port))
            s.sendall(f"GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:{lab.port}\r\n".encode())
            half.append(s)
        time.sleep(0.3)
        out: list = []
        timed_get(lab, "/api/info", None, out)
        print(f"    with 40 half-sent requests, /api/info answered in {out[0][1]:.3f} s")
        expect(out[0][0] == 200 and out[0][1] < 1.5, f"with 40 half-sent requests: {out[0][:2]}")
        # One header line every 5 s: dropped after the read timeout, before the second line.
        slow = socket.create_connection(("127.0.0.1", lab.port))
        slow.sendall(b"GET /api/info HTTP/1.1\r\n")
        started = time.monotonic()
        slow.settimeout(8)
        try:  # the lab closes it (an empty read) or resets it; a timeout here means it kept it
            slow.recv(100)
            closed = True
        except ConnectionResetError:
            closed = True
        except socket.timeout:
            closed = False
        took = time.monotonic() - started
        print(f"    a client silent after its first line was dropped after {took:.2f} s")
        expect(closed and took < 4, f"a silent client: closed {closed} after {took:.1f} s")
        for s in half + [slow]:
            s.close()
        expect(lab.get("/api/info")[0] == 200, "the lab stopped answering")


def check_largest_mesh(lab: Lab) -> None:
    mesh = lab.json("/api/radiosity/mesh", {"scene": "cornell", "patches": 20000})
    print(f"    patches=20000 meshed the box into {mesh['patches']} patches")
    expect(20000 <= mesh["patches"] <= 22000, f"patches=20000: {mesh['patches']} patches")


def check_reference(illum: Path) -> None:
    with Lab(illum, "whitted", "--reference", str(illum)) as lab:
        info = lab.json("/api/info")
        expect(info["reference"]["available"] is True, f"info: {info['reference']}")
        for path, params in [("trace", {"x": 285, "y": 173}), ("radiosity/mesh", {"patches": 300})]:
            expect(lab.json(f"/api/reference/{path}", params) == lab.json(f"/api/{path}", params),
                   f"/api/reference/{path} differs from /api/{path} with the same build on both sides")
        status, _, body = lab.get("/api/reference/compare")
        expect(status == 404, f"/api/reference/compare (not forwarded): {status} {body[:100]!r}")
        status, _, body = lab.get("/api/reference/trace", {"x": 1})
        expect(status == 400 and b"'y' is missing" in body, f"the reference's 400 passed on: {status} {body[:100]!r}")
    with Lab(illum, "whitted") as lab:
        status, _, body = lab.get("/api/reference/trace", {"x": 1, "y": 1})
        expect(status == 404 and b"no reference" in body, f"no reference: {status} {body[:100]!r}")
    # Where an instructor puts it in a student edition: SOURCE/tools/lab/reference/illum, found unasked.
    edition = Path(tempfile.mkdtemp(prefix="illum-lab-edition-"))
    try:
        (edition / "lessons").mkdir()
        (edition / "tools" / "lab" / "reference").mkdir(parents=True)
        shutil.copy(illum, edition / "tools" / "lab" / "reference" / "illum")
        with Lab(illum, "whitted", "--source", str(edition)) as lab:
            info = lab.json("/api/info")["reference"]
            expect(info["available"] is True and info["program"] == str(edition / "tools/lab/reference/illum"),
                   f"the edition's reference: {info}")
    finally:
        shutil.rmtree(edition)
    for program, words in [("/bin/true", "did not start"), ("no/such/illum", "no such program")]:
        run = subprocess.run([str(illum), "lab", "--port", "0", "--reference", program], capture_output=True, text=True,
                             stdin=subprocess.DEVNULL, timeout=60)
        expect(run.returncode == 1 and words in run.stderr and "http://" not in run.stdout,
               f"--reference {program}: status {run.returncode}, {run.stderr!r}")


def check_tab_header(lab: Lab) -> None:
    connection = http.client.HTTPConnection("127.0.0.1", lab.port, timeout=30)
    connection.request("GET", "/api/info", headers={"Host": f"127.0.0.1:{lab.port}", "X-Lab-Tab": "a b"})
    response = connection.getresponse()
    body = response.read()
    expect(response.status == 400 and b"X-Lab-Tab" in body, f"a bad X-Lab-Tab: {response.status} {body[:100]!r}")


def stop_with(illum: Path, sig: int) -> None:
    with Lab(illum, "whitted") as lab:
        # A client with its connection kept open, as a browser tab keeps it.
        keep = http.client.HTTPConnection("127.0.0.1", lab.port, timeout=10)
        keep.request("GET", "/api/info", headers={"Host": f"127.0.0.1:{lab.port}"})
        keep.getresponse().read()
        started = time.monotonic()
        lab.process.send_signal(sig)
        try:
            code = lab.process.wait(5)
        except subprocess.TimeoutExpired:
            lab.process.kill()
            raise AssertionError(f"{signal.Signals(sig).name}: still running 5 s later")
        stderr = lab.process.stderr.read()
        keep.close()
        expect(code == 0, f"{signal.Signals(sig).name}: exit status {code}: {stderr}")
        expect("stopped" in stderr, f"{signal.Signals(sig).name}: no 'stopped' on stderr: {stderr!r}")
        print(f"    stopped {time.monotonic() - started:.2f} s after {signal.Signals(sig).name}")


def check_stop(illum: Path) -> None:
    stop_with(illum, signal.SIGINT)
    stop_with(illum, signal.SIGTERM)


def check_refusals(illum: Path) -> None:
    with Lab(illum, "whitted") as lab:
        busy = subprocess.run([str(illum), "lab", "--port", str(lab.port)], capture_output=True, text=True,
                              stdin=subprocess.DEVNULL, timeout=60)
        expect(busy.returncode == 1 and "--port" in busy.stderr and str(lab.port) in busy.stderr,
               f"a busy port: status {busy.returncode}, {busy.stderr!r}")
    missing = subprocess.run([str(illum), "lab", "no/such/scene.json", "--port", "0"], capture_output=True, text=True,
                             stdin=subprocess.DEVNULL, timeout=60)
    expect(missing.returncode == 1 and "no/such/scene.json" in missing.stderr and "http://" not in missing.stdout,
           f"a missing scene: status {missing.returncode}, {missing.stderr!r}")
    port = subprocess.run([str(illum), "lab", "--port", "70000"], capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, timeout=60)
    expect(port.returncode != 0 and "70000" in port.stderr + port.stdout, f"--port 70000: {port.returncode}")


def check_stubs(illum_stubs: Path) -> None:
    with Lab(illum_stubs, "whitted") as lab:
        # Loading Whitted's scene already needs lesson 01's Sphere; the radiosity views need lessons 11 and 10.
        cases = [("/api/trace", {"x": 1, "y": 1}, None), ("/api/render", {}, None), ("/api/scene", {}, None),
                 ("/api/radiosity/start", {"patches": 50}, "progressive_start"),
                 ("/api/hemicube", {"patches": 50, "patch": 0}, "make_hemicube_deltas")]
        for path, params, function in cases:
            status, _, body = lab.get(path, params)
            answer = json.loads(body)
            expect(status == 501 and answer.get("not_implemented") and "NotImplemented" in answer["error"]
                   and (function is None or answer["not_implemented"] == function), f"{path} on the stubs: {status} {answer}")
        expect(lab.get("/api/info")[0] == 200 and lab.process.poll() is None, "the stubs' server stopped answering")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--illum", type=Path, required=True)
    parser.add_argument("--illum-stubs", type=Path, required=True)
    parser.add_argument("--work", type=Path, required=True)
    args = parser.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)
    checks = Checks()
    with Lab(args.illum, "whitted") as lab:
        checks.run("every endpoint answers; /api/trace is illum trace's JSON", check_endpoints, lab, args.illum, args.work)
        checks.run("bad requests: 400/403/404/405 with a message", check_bad_requests, lab)
        checks.run("radiosity sessions: every method, independent, concurrent", check_radiosity, lab)
        checks.run("a seeded fuzz of 400 requests: no 500, no crash", check_fuzz, lab)
        checks.run("the documented largest mesh, patches=20000", check_largest_mesh, lab)
        checks.run("a bad X-Lab-Tab header is refused", check_tab_header, lab)
    checks.run("long requests stop at a newer one and at Ctrl-C", check_long_requests, args.illum)
    checks.run("slow and half-sent requests do not hold the lab", check_slow_clients, args.illum)
    checks.run("a reference beside it", check_reference, args.illum)
    checks.run("SIGINT and SIGTERM stop the server cleanly", check_stop, args.illum)
    checks.run("a busy port, a missing scene, a bad port are refused", check_refusals, args.illum)
    checks.run("a build on the stubs answers 501 with the function to write", check_stubs, args.illum_stubs)
    print(f"\nlab_api: {checks.passed} passed, {checks.failed} failed")
    return 0 if checks.failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
