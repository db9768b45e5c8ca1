#!/usr/bin/env python3
"""The lab in real headless Chromium (CTest `lab_browser`, labels "lab" and "browser"; docs/lab.md).

    run_browser_test.py --illum BIN/illum --illum-stubs BIN/illum_cli_stubs --illum-mutant BIN/illum_cli_mutant
                        --reference BIN/lab_reference --lesson11 BIN/lesson11 --work DIR

Starts `illum lab whitted`, drives the page with tools/lab/browser.mjs (a
click, buttons, inputs, as a student would) and compares what the page
shows with sources that are not the lab:
* the click on Whitted's glass ball: the tree the diagram draws, node by
  node (kind, depth, what it hit, t, why it stops, a shadow ray's segments),
  and the rays the 3D view draws, against the ray_tree.json that
  `illum trace whitted --pixel X Y` writes for the pixel the page resolved;
* 10 shots on the 2,124-patch Cornell box against the library's own
  progressive solver (lab_reference: progressive_on_demand, rows on demand
  on every thread), every shot; and 8 shots on lesson 11's quick figure
  (330 patches, hemicube 32) against the table `lesson11 --quick --figure`
  writes (figure_history.csv: shots 1, 2, 4, 8);
* the hemicube row of a floor patch near the open front of the box: the
  box is closed but for its front, and from that patch no block stands
  between it and the opening, so every direction either meets a patch or
  leaves through the opening, and the row sums to 1 − F(centroid → opening),
  Lambert's contour formula computed here;
* your pictures: an identical image matches with 0%, a different one of the
  same size does not, one of another size is reported as such;
* two more tabs at once get the same ten shots; the page fetches nothing
  from anywhere but the lab; no script error;
* what issue 47 found, one check each: the diagram fits its pane and no line
  is cut or leaves its box; the eye is a dot of a few pixels, in the legend;
  the rays' materials and shader programs are the same after more clicks
  (they were made anew, and compiled, on every click); the ambient term is
  off by default, "1 shot" is singular, the chart's ticks are whole shots,
  and painting the same shot another way keeps its solver time; a patch of
  the red wall explains its mean relative error with the targets seen
  edge-on, which lie within 1° of its plane by this test's own count, and
  its weighted error falls tenfold from 8 to 512 pixels; your pictures tell
  a diagram's new size (a .dot beside it) from a smaller --quick picture and
  from another shape;
* a student's build beside the reference (illum_cli_mutant: η inverted
  entering glass, reciprocity upside down in shoot): the first differing
  node the page marks is the first one in preorder where this test finds
  the two `illum trace` trees apart, and the first differing shot and what
  differs (shooter, row, update) are what this test finds stepping both
  labs; the stubs beside the reference show the reference's picture and,
  for a click, the reference's whole tree and that yours is not written;
  the stubs alone show no broken image and say why in the 3D view.

A missing Node.js, puppeteer-core or Chromium fails the test with the advice
to run tools/install-deps: it never passes by skipping.
"""
from __future__ import annotations

import argparse
import base64
import csv
import json
import math
import shutil
import struct
import subprocess
import sys
import zlib
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(SOURCE / "tools"))
from common.png import size_of as png_size  # noqa: E402  (the one PNG reader)
from test_lab_api import Lab  # noqa: E402

HINT = "run tools/install-deps (Debian packages chromium, nodejs, npm; then npm ci for puppeteer-core)"
GLASS_PIXEL = (285, 173)  # lesson 06's inspector pixel: on the glass ball, off its centre


GROUPS = ["the ray tree against illum trace", "radiosity against progressive_on_demand and lesson 11's table",
          "the hemicube row against its exact sum", "your pictures against the reference", "offline, no script error",
          "a student's build beside the reference", "a build on the stubs",
          "lesson 14's hierarchy: a click draws links, a bad ε refused"]


def fail(problems: list[tuple[int, str]], group: int, message: str) -> None:
    problems.append((group, message))
    print(f"PROBLEM ({GROUPS[group]}): {message}", flush=True)


def flatten(node: dict, out: list[dict]) -> list[dict]:
    out.append(node)
    for child in node["children"]:
        flatten(child, out)
    return out


def lambert(x: list[float], normal: list[float], polygon: list[list[float]]) -> float:
    """F from the differential area at x (unit normal) to a polygon wholly above its plane:
    (1/2π) Σ_k γ_k n·(R_k × R_k+1)/|R_k × R_k+1|, R_k = v_k − x, γ_k the angle between R_k and R_k+1."""
    total = 0.0
    for k in range(len(polygon)):
        r1 = [polygon[k][i] - x[i] for i in range(3)]
        r2 = [polygon[(k + 1) % len(polygon)][i] - x[i] for i in range(3)]
        cross = [r1[1] * r2[2] - r1[2] * r2[1], r1[2] * r2[0] - r1[0] * r2[2], r1[0] * r2[1] - r1[1] * r2[0]]
        norm = math.sqrt(sum(c * c for c in cross))
        cosine = sum(a * b for a, b in zip(r1, r2)) / math.sqrt(sum(a * a for a in r1) * sum(b * b for b in r2))
        total += math.acos(max(-1.0, min(1.0, cosine))) * sum(n * c for n, c in zip(normal, cross)) / norm
    return abs(total) / (2 * math.pi)


def front_opening() -> tuple[list[list[float]], float]:
    """The Cornell box's open front: the vertices at z = 0 of scenes/cornell.json, in order round their
    centre; and the least z of the blocks' vertices (nothing of them is nearer the front)."""
    scene = json.loads((SOURCE / "scenes" / "cornell.json").read_text(encoding="utf-8"))
    front, blocks = [], []
    for p in scene["primitives"]:
        for v in p["vertices"]:
            if v[2] == 0 and v not in front:
                front.append(v)
            if "block" in p["name"]:
                blocks.append(v[2])
    cx, cy = sum(v[0] for v in front) / len(front), sum(v[1] for v in front) / len(front)
    front.sort(key=lambda v: math.atan2(v[1] - cy, v[0] - cx))
    return front, min(blocks)


def png(path: Path, width: int, height: int, seed: int) -> None:
    """A PNG of width × height RGB pixels in a pattern of `seed` (zlib, no image library)."""
    rows = b"".join(b"\0" + bytes((x * seed + y * 7) % 256 for x in range(3 * width)) for y in range(height))
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def keyed(node: dict) -> list[tuple[str, dict]]:
    """A node's children named by kind (and light) and their order among such siblings."""
    seen: dict[str, int] = {}
    out = []
    for child in node["children"]:
        key = f"shadow {child['light']}" if child["kind"] == "shadow" else child["kind"]
        seen[key] = seen.get(key, 0) + 1
        out.append((f"{key} {seen[key]}", child))
    return out


def near(a, b) -> bool:
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(near(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return abs(a - b) <= 1e-9 + 1e-6 * max(abs(a), abs(b))
    return a == b


def first_apart(mine: dict, reference: dict) -> int | None:
    """The id, in `mine`, of the first ray in preorder (children in the tree's order) that differs from
    the reference's: its start, its direction or what it hits (primitive, face, t); or whose parent
    casts a child the other does not (then the parent's id)."""
    def ray(n: dict) -> tuple:
        return n["hit"] and (n["hit"]["primitive_index"], n["hit"]["front_face"])

    def walk(m: dict, r: dict) -> int | None:
        if not (near(m["origin"], r["origin"]) and near(m["direction"], r["direction"]) and ray(m) == ray(r)
                and (not m["hit"] or near(m["hit"]["t"], r["hit"]["t"]))):
            return m["id"]
        mk, rk = dict(keyed(m)), dict(keyed(r))
        for k, child in keyed(m):
            if k not in rk:
                return m["id"]
            found = walk(child, rk[k])
            if found is not None:
                return found
        return m["id"] if set(rk) - set(mk) else None
    return walk(mine["tree"], reference["tree"])


def step_apart(mutant: Lab, reference: Lab, shots: int) -> str:
    """'k|field': the first shot whose shooter, row or update differ between the two labs' sessions, stepped
    one shot at a time from the same start (floats within 1e-5 of the largest), or 'same'."""
    floats = lambda text: struct.unpack(f"<{len(base64.b64decode(text)) // 4}f", base64.b64decode(text))
    params = {"scene": "cornell", "patches": 2000, "resolution": 128}
    sessions = [lab.json("/api/radiosity/start", params)["session"] for lab in (mutant, reference)]
    for k in range(1, shots + 1):
        a, b = (lab.json("/api/radiosity/step", {"session": s, "steps": 1, "row": 1, "update": 1})
                for lab, s in zip((mutant, reference), sessions))
        if a["shooter"] != b["shooter"]:
            return f"{k}|shooter"
        for field in ("row", "update"):
            x, y = floats(a[field]), floats(b[field])
            scale = max(abs(v) for v in y)
            if max(abs(u - v) for u, v in zip(x, y)) > 1e-5 * scale + 1e-12:
                return f"{k}|{field}"
    return "same"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--illum", type=Path, required=True)
    parser.add_argument("--illum-stubs", type=Path, required=True)
    parser.add_argument("--illum-mutant", type=Path, help="illum with a student's mistakes (tests/e2e/lab.cmake)")
    parser.add_argument("--no-mutant", metavar="WHY", help="why this build has no illum_cli_mutant")
    parser.add_argument("--reference", type=Path, required=True)
    parser.add_argument("--lesson11", type=Path, required=True)
    parser.add_argument("--work", type=Path, required=True)
    args = parser.parse_args()
    node = shutil.which("node")
    if not node or not (SOURCE / "node_modules" / "puppeteer-core").is_dir():
        print(f"lab_browser: FAILED: Node.js or puppeteer-core is missing: {HINT}")
        return 1
    work = args.work
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    problems: list[tuple[int, str]] = []

    # Independent sources, before the page is opened.
    figure = work / "lesson11"
    run = subprocess.run([str(args.lesson11), "--quick", "--figure", "--out", str(figure)], capture_output=True, text=True,
                         stdin=subprocess.DEVNULL, timeout=300)
    if run.returncode != 0:
        print(f"lab_browser: FAILED: lesson11 --quick --figure: {run.stderr}")
        return 1
    with open(figure / "figure_history.csv", newline="", encoding="utf-8") as f:
        lesson11 = {int(r["shots"]): float(r["unshot_fraction"]) for r in csv.DictReader(f)}
    reference = json.loads(subprocess.run([str(args.reference), "cornell", "2000", "128", "10"], capture_output=True,
                                          text=True, check=True, timeout=300).stdout)
    # Your pictures: lesson 01's depth.png as drawn (a match), normals.png replaced by another picture of
    # the same size (no match), silhouette.png by one of another size.
    figures = SOURCE / "lessons" / "01_ray_sphere" / "figures"
    yours = work / "out" / "lesson01"
    yours.mkdir(parents=True)
    shutil.copy(figures / "depth.png", yours / "depth.png")
    shutil.copy(figures / "silhouette.png", yours / "normals.png")
    shutil.copy(figures / "far_sphere_notes_float.png", yours / "silhouette.png")
    # A smaller picture of the same shape (what --quick draws), and lesson 06's tree drawn larger with
    # its Graphviz source beside it (a student's tree with more nodes).
    width, height = png_size(figures / "far_sphere_stable_float.png")
    png(yours / "far_sphere_stable_float.png", width // 2, height // 2, 3)
    tree_yours = work / "out" / "lesson06"
    tree_yours.mkdir(parents=True)
    width, height = png_size(SOURCE / "lessons" / "06_ray_tree" / "figures" / "ray_tree.png")
    png(tree_yours / "ray_tree.png", width + 300, height + 100, 5)
    (tree_yours / "ray_tree.dot").write_text("digraph tree { a -> b; }\n", encoding="utf-8")

    opening, block_z = front_opening()
    with Lab(args.illum, "whitted", "--out", str(work / "out")) as lab:
        mesh = lab.json("/api/radiosity/mesh", {"scene": "cornell", "patches": 2000})
        c, n = mesh["centroid"], mesh["normal"]
        # A floor patch (normal +y) whose centroid lies in front of every block.
        floor = [i for i in range(mesh["patches"]) if n[3 * i + 1] > 0.999 and abs(c[3 * i + 1]) < 1e-9 and c[3 * i + 2] < block_z]
        patch = min(floor, key=lambda i: abs(c[3 * i] - 278) + abs(c[3 * i + 2] - 0.4 * block_z))
        # The middle patch of the red wall's first triangle, and by this test's own count the patches
        # of the wall's other triangle whose every corner lies within 1° of its plane.
        red = next(s for s in mesh["surfaces"] if s["name"] == "left wall (red), triangle 1")
        other = next(s for s in mesh["surfaces"] if s["name"] == "left wall (red), triangle 2")
        middle = [sum(c[3 * i + k] for i in range(red["first"], red["first"] + red["count"])) / red["count"] for k in range(3)]
        red_patch = min(range(red["first"], red["first"] + red["count"]),
                        key=lambda i: sum((c[3 * i + k] - middle[k]) ** 2 for k in range(3)))
        first = [0]
        for count in mesh["vertex_counts"]:
            first.append(first[-1] + count)
        v = mesh["vertices"]
        def within_one_degree(j: int) -> bool:
            for corner in range(first[j], first[j + 1]):
                d = [v[3 * corner + k] - c[3 * red_patch + k] for k in range(3)]
                if sum(n[3 * red_patch + k] * d[k] for k in range(3)) > math.sin(math.radians(1)) * math.sqrt(sum(x * x for x in d)):
                    return False
            return True
        coplanar = sum(1 for j in range(other["first"], other["first"] + other["count"]) if within_one_degree(j))
        options = {"pixel": list(GLASS_PIXEL), "patch": patch, "resolutions": [256, 512], "redPatch": red_patch,
                   "compare": [["01", "depth.png"], ["01", "normals.png"], ["01", "silhouette.png"],
                               ["01", "far_sphere_stable_float.png"], ["06", "ray_tree.png"]],
                   "hierarchyScene": "room"}
        (work / "options.json").write_text(json.dumps(options), encoding="utf-8")
        observed_file = work / "observed.json"
        browser = subprocess.run([node, str(SOURCE / "tools" / "lab" / "browser.mjs"), "test", f"http://127.0.0.1:{lab.port}/",
                                  str(work / "options.json"), str(observed_file)], cwd=SOURCE, timeout=540,
                                 stdin=subprocess.DEVNULL)
        if browser.returncode == 2:
            print(f"lab_browser: FAILED: the browser could not run: {HINT}")
            return 1
        if browser.returncode != 0:
            print("lab_browser: FAILED: the page did not do what was asked (above)")
            return 1
        origin = f"http://127.0.0.1:{lab.port}/"
    observed = json.loads(observed_file.read_text(encoding="utf-8"))

    # A student's builds beside the reference, each lab with the release build as its reference.
    student = None
    if args.illum_mutant:
        with Lab(args.illum_mutant, "whitted", "--reference", str(args.illum)) as mutant, \
                Lab(args.illum_stubs, "whitted", "--reference", str(args.illum)) as stubs, \
                Lab(args.illum_stubs, "whitted") as alone, Lab(args.illum, "whitted") as reference_lab:
            shots = 3
            expected_shot = step_apart(mutant, reference_lab, shots)
            labs = {"mutant": f"http://127.0.0.1:{mutant.port}/", "stubsReference": f"http://127.0.0.1:{stubs.port}/",
                    "stubsAlone": f"http://127.0.0.1:{alone.port}/"}
            (work / "student.json").write_text(json.dumps({"labs": labs, "pixel": list(GLASS_PIXEL), "shots": shots}), encoding="utf-8")
            run = subprocess.run([node, str(SOURCE / "tools" / "lab" / "browser.mjs"), "student", labs["mutant"],
                                  str(work / "student.json"), str(work / "student-observed.json")], cwd=SOURCE, timeout=540,
                                 stdin=subprocess.DEVNULL)
            if run.returncode != 0:
                print("lab_browser: FAILED: the student's pages did not do what was asked (above)")
                return 1
            student = json.loads((work / "student-observed.json").read_text(encoding="utf-8"))
            student_origins = tuple(labs.values())

    # 1. The tree of the clicked pixel against `illum trace`.
    x, y = observed["click"]["pixel"]
    if abs(x - GLASS_PIXEL[0]) > 1 or abs(y - GLASS_PIXEL[1]) > 1:
        fail(problems, 0, f"the click on pixel {GLASS_PIXEL} was read as ({x}, {y})")
    out = work / "trace"
    subprocess.run([str(args.illum), "trace", "whitted", "--pixel", str(x), str(y), "--out", str(out)], check=True,
                   capture_output=True, timeout=120)
    tree = json.loads((out / "ray_tree.json").read_text(encoding="utf-8"))
    want = flatten(tree["tree"], [])
    got = observed["tree"]["nodes"]
    if want[0]["hit"]["primitive"] != "glass sphere":
        fail(problems, 0, f"pixel ({x}, {y}) is not on the glass ball: {want[0]['hit']}")
    if len(got) != tree["nodes"] or len(got) != len(want):
        fail(problems, 0, f"the diagram draws {len(got)} nodes; illum trace has {tree['nodes']}")
    for g, w in zip(got, want):
        expected = {"id": w["id"], "kind": w["kind"], "depth": w["depth"], "stop": w["stop"]["reason"],
                    "primitive": w["hit"]["primitive"] if w["hit"] else "", "t": w["hit"]["t"] if w["hit"] else None,
                    "segments": len(w.get("segments", []))}
        actual = {k: g[k] for k in expected}
        if actual != expected:
            fail(problems, 0, f"node {w['id']}: the page shows {actual}, illum trace has {expected}")
    if observed["tree"]["drawnRays"] != tree["nodes"] or observed["tree"]["drawnSegments"] != tree["rays"]:
        fail(problems, 0, f"the 3D view draws {observed['tree']['drawnRays']} rays in {observed['tree']['drawnSegments']} "
                       f"segments; illum trace has {tree['nodes']} nodes from {tree['rays']} rays")
    if not any(w["kind"] == "shadow" and len(w["segments"]) >= 2 for w in want):
        fail(problems, 0, "no shadow ray of this pixel crosses the glass: the test lost its point")
    want_stubs = sorted((w["id"], b["kind"], b["fate"]) for w in want for b in w.get("branches", [])
                        if b["fate"] in ("total_internal_reflection", "pruned", "not_cast"))
    got_stubs = sorted((s["parent"], s["kind"], s["fate"]) for s in observed["tree"]["stubs"])
    if want_stubs != got_stubs:
        fail(problems, 0, f"stubs for children not cast: the page {got_stubs}, illum trace {want_stubs}")
    deepest = max(w["depth"] for w in want)
    hidden = sorted(w["id"] for w in want if w["depth"] > deepest - 1)
    if observed["depthDown"]["shown"] != str(deepest - 1) or sorted(observed["depthDown"]["hidden"]) != hidden:
        fail(problems, 0, f"one level back: the page shows depth {observed['depthDown']['shown']} hiding "
                       f"{observed['depthDown']['hidden']}; expected depth {deepest - 1} hiding {hidden}")

    d = observed["drawing"]
    if not d["svgWidth"] <= d["paneWidth"] + 1 or d["cut"] or d["overflowing"]:
        fail(problems, 0, f"the diagram: {d['svgWidth']:.0f} px in a {d['paneWidth']} px pane, lines cut {d['cut'][:3]}, "
                          f"lines out of their box {d['overflowing'][:3]}")
    if not (d["eye"] and d["eye"]["type"] == "Points" and d["eye"]["sizeAttenuation"] is False and d["eye"]["size"] <= 8
            and "eye" in d["legend"]):
        fail(problems, 0, f"the eye's marker {d['eye']}, legend {d['legend']!r}: a dot of at most 8 pixels, in the legend")
    later = observed["drawingLater"]
    if later["materials"] != d["materials"] or later["programs"] != d["programs"]:
        fail(problems, 0, f"two more clicks made new ray materials or shader programs: {d['programs']} -> {later['programs']}")
    if not d["clickMs"] > 0:
        fail(problems, 0, f"no time from the click to the frame: {d['clickMs']}")

    # 2. Radiosity, shot by shot.
    if observed["patches"] != reference["patches"] or observed["patches"] != 2124:
        fail(problems, 1, f"the page meshed {observed['patches']} patches; lab_reference {reference['patches']} (2,124 expected)")
    shots = dict(observed["tenShots"])
    for k, fraction in enumerate(reference["fractions"], 1):
        if k not in shots or not math.isclose(shots[k], fraction, rel_tol=1e-9):
            fail(problems, 1, f"shot {k}: the page shows unshot {shots.get(k)}, progressive_on_demand {fraction}")
    quick = dict(observed["quickShots"])
    if observed["quickPatches"] != 330:
        fail(problems, 1, f"lesson 11's quick figure has 330 patches; the page meshed {observed['quickPatches']}")
    for k in (1, 2, 4, 8):
        if k not in quick or not math.isclose(quick[k], lesson11[k], rel_tol=1e-9):
            fail(problems, 1, f"quick figure, shot {k}: the page shows {quick.get(k)}, lesson 11's table {lesson11[k]}")
    for method in ("jacobi", "gauss_seidel", "southwell"):
        points = observed[f"method_{method}"]
        if [s for s, _ in points] != list(range(1, 11)) or not points[-1][1] < points[0][1] < 1:
            fail(problems, 1, f"{method}: the page's history {points}")
    if observed["ambientChecked"]:
        fail(problems, 1, "the ambient term is on by default: after one shot the box looks evenly lit")
    one, eight, repainted = observed["oneShot"], observed["eightShots"], observed["afterRepaint"]
    if not one["status"].startswith("1 shot;") or "1 shots" in one["status"]:
        fail(problems, 1, f"after one shot the status says {one['status'][:40]!r}")
    if not one["ticks"] or any(not t.isdigit() for t in one["ticks"] + eight["ticks"]):
        fail(problems, 1, f"the chart's ticks are not whole shots: {one['ticks']} {eight['ticks']}")
    solver = lambda status: status[status.find("; ", status.find("unshot")):]
    if "ms in the solver" not in eight["status"] or solver(repainted["status"]) != solver(eight["status"]):
        fail(problems, 1, f"painting the shot again changed its times: {eight['status']!r} -> {repainted['status']!r}")
    for i, tab in enumerate(observed["twoTabs"]):
        if tab != observed["tenShots"]:
            fail(problems, 1, f"tab {i + 2}: its ten shots {tab} differ from the first tab's {observed['tenShots']}")

    # 3. The hemicube row's sum against 1 − F(centroid → opening).
    exact = 1 - lambert(c[3 * patch:3 * patch + 3], n[3 * patch:3 * patch + 3], opening)
    for h in observed["hemicube"]:
        # The error is the opening's outline aliased on the pixels (lesson 10, §5): at 256 pixels and more
        # it is below 2e-3, while a face or a delta formula gone wrong moves the sum by several per cent.
        if h["patch"] != patch or abs(h["sum"] - exact) > 2e-3:
            fail(problems, 2, f"hemicube on patch {h['patch']} at {h['resolution']}: the row sums to {h['sum']}; "
                           f"exactly 1 - F(opening) = {exact}")
        study = dict(h["study"])
        for r in (256, 512):
            if abs(study.get(r, -1) - exact) > 2e-3:
                fail(problems, 2, f"hemicube study at {r}: sum {study.get(r)}, exact {exact}")

    red = observed["redWall"]
    rows = {r["resolution"]: r for r in red["rows"]}
    if not (0 < red["edgeOn"] <= coplanar and f"{red['edgeOn']} of the" in red["why"] and "edge-on" in red["why"]):
        fail(problems, 2, f"red wall patch {red_patch}: {red['edgeOn']} targets edge-on ({coplanar} of the other triangle lie "
                          f"within 1°); the explanation: {red['why'][:120]!r}")
    if not (rows[512]["weighted"] < rows[8]["weighted"] / 10 and rows[512]["above"] < rows[8]["above"] / 10
            and rows[512]["mean"] > rows[512]["above"]):
        fail(problems, 2, f"red wall patch {red_patch}: errors at 8 and 512 pixels {rows[8]} {rows[512]}")

    # 4. Your pictures.
    cmp = observed["compare"]
    if not (cmp["01/depth.png"]["share"] == 0 and cmp["01/depth.png"]["matches"] == "true"):
        fail(problems, 3, f"an identical image: {cmp['01/depth.png']}")
    if not (cmp["01/normals.png"]["share"] > 0.001 and cmp["01/normals.png"]["matches"] == "false"):
        fail(problems, 3, f"a different image: {cmp['01/normals.png']}")
    if "sizes differ" not in cmp["01/silhouette.png"]["verdict"] or cmp["01/silhouette.png"]["sizes"] != "shape":
        fail(problems, 3, f"an image of another size and shape: {cmp['01/silhouette.png']}")
    quick = cmp["01/far_sphere_stable_float.png"]
    if quick["sizes"] != "quick" or "--quick" not in quick["verdict"]:
        fail(problems, 3, f"a smaller image of the same shape: {quick}")
    diagram = cmp["06/ray_tree.png"]
    if diagram["sizes"] != "diagram" or "--quick" in diagram["verdict"] or "ray_tree.dot" not in diagram["verdict"]:
        fail(problems, 3, f"a larger drawing of a tree, its .dot beside it: {diagram}")

    # 8. Lesson 14's hierarchy: the room at the page's defaults (the lesson's demonstration knobs) has the
    # elements and links of lesson 14's own table (README, written by `lesson14`); the click gathers on
    # links, each drawn as a line and its source's outline; ε_F = 0 is refused, naming it and the value.
    hr, refused = observed["hierarchy"], observed["hierarchyRefused"]
    table = (SOURCE / "lessons" / "14_hierarchical_radiosity" / "README.md").read_text(encoding="utf-8")
    row = next((line.split("|")[1:-1] for line in table.splitlines() if line.replace(" ", "").startswith("|0.4|0.0100|")), None)
    if row is None or (hr["elements"], hr["links"]) != (int(row[2]), int(row[4])):
        fail(problems, 7, f"the room at ε_F 0.4, ε_BF 0.01: {hr['elements']} elements, {hr['links']} links; lesson 14's table: {row}")
    # A link is a line and its source's outline (3 or 4 edges): 4 segments at least.
    if not (hr["selectedLinks"] > 0 and hr["drawnLines"] >= 4 * min(hr["selectedLinks"], 4000) and "of its ancestors" in hr["count"]):
        fail(problems, 7, f"the click on element {hr['element']}: {hr['selectedLinks']} links, {hr['drawnLines']} lines drawn: {hr['count']!r}")
    with Lab(args.illum, "whitted") as again:
        picked = again.json("/api/hierarchy", {"scene": "room", "element": hr["element"]})["selected"]
    chain = {c["element"] for c in picked["chain"]}
    if not (picked["links_total"] == hr["selectedLinks"] and all(l["receiver"] in chain and 0 < l["form_factor"] < 1
                                                                  for l in picked["links"])):
        fail(problems, 7, f"element {hr['element']}'s links: not all gathered by its chain {sorted(chain)}, or F outside (0, 1)")
    if not (refused["state"] == "error" and "'epsilon_f'" in refused["status"] and "'0'" in refused["status"]
            and len(refused["console"]) == 1 and "status of 400" in refused["console"][0]):
        fail(problems, 7, f"ε_F = 0: {refused}")

    # 5. Offline, and no script error.
    seen = observed["seen"]
    foreign = [u for u in seen["requests"] if not (u.startswith(origin) or u.startswith(("data:", "blob:")))]
    if foreign:
        fail(problems, 4, f"requests outside the lab: {foreign[:5]}")
    if seen["errors"] or seen["failed"]:
        fail(problems, 4, f"script errors {seen['errors'][:3]}, failed requests {seen['failed'][:3]}")
    console = seen["console"]
    if console:
        fail(problems, 4, f"console errors: {console[:3]}")

    # 6. A student's build beside the reference.
    if student is None:
        fail(problems, 5, f"no mutant build to test with: {args.no_mutant}")
    else:
        subprocess.run([str(args.illum_mutant), "trace", "whitted", "--pixel", *map(str, GLASS_PIXEL), "--out",
                        str(work / "mutant-trace")], check=True, capture_output=True, timeout=120)
        subprocess.run([str(args.illum), "trace", "whitted", "--pixel", *map(str, GLASS_PIXEL), "--out",
                        str(work / "reference-trace")], check=True, capture_output=True, timeout=120)
        mine = json.loads((work / "mutant-trace" / "ray_tree.json").read_text(encoding="utf-8"))
        theirs = json.loads((work / "reference-trace" / "ray_tree.json").read_text(encoding="utf-8"))
        expected = first_apart(mine, theirs)
        t = student["mutantTree"]
        if t["firstNode"] != expected or "η" not in t["summary"]:
            fail(problems, 5, f"the mutant's tree: the page marks node {t['firstNode']} ({t['first']}), the first ray apart is "
                              f"node {expected}; the page says {t['summary'][:160]!r}")
        if not t["referenceSegments"] > 0:
            fail(problems, 5, "the 3D view draws none of the reference's rays where the trees differ")
        if student["mutantShots"]["versus"] != expected_shot:
            fail(problems, 5, f"the mutant's shots: the page finds {student['mutantShots']['versus']}, stepping both labs "
                              f"finds {expected_shot}: {student['mutantShots']['text'][:160]!r}")
        # 7. The stubs, with the reference beside them and alone.
        r = student["stubsReference"]
        if not (r["drawnBy"] == "reference" and not r["imageHidden"] and r["imageWidth"] == 480 and "reference's picture" in r["note"]
                and not r["message3d"] and "Not written yet" in r["summary"] and r["rows"] == theirs["nodes"]
                and r["caption"].startswith("The reference's tree")):
            fail(problems, 6, f"the stubs beside the reference: {r}")
        a = student["stubsAlone"]
        if not (a["state"] == "error" and a["imageHidden"] and "Nothing to draw yet" in a["note"] and "Not written yet" in a["message3d"]):
            fail(problems, 6, f"the stubs alone: {a}")
        # Their pages fetch only from their labs; the 501s of the stubs are the only failed loads.
        seen2 = student["seen"]
        foreign = [u for u in seen2["requests"] if not (u.startswith(student_origins) or u.startswith(("data:", "blob:")))]
        console = [m for m in seen2["console"] if "status of 501" not in m]
        if foreign or seen2["errors"] or console:
            fail(problems, 5, f"the student's pages: foreign requests {foreign[:3]}, errors {seen2['errors'][:3]}, console {console[:3]}")

    print(f"lab_browser: clicked ({x}, {y}): {len(got)} nodes drawn {observed['click']['ms']:.0f} ms after the click; "
          f"hemicube on patch {patch}: {[round(h['sum'], 6) for h in observed['hemicube']]} against {exact:.6f}")
    failed = sorted({group for group, _ in problems})
    for i, name in enumerate(GROUPS):
        print(f"{'FAILED' if i in failed else 'ok'}: {name}")
    print(f"lab_browser: {len(GROUPS) - len(failed)} passed, {len(failed)} failed")
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main())
