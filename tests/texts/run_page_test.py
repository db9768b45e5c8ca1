#!/usr/bin/env python3
"""The ctest entry points of the page test (registered in tests/e2e/slides.cmake).

    run_page_test.py pages          --out BUILD/test-out
        renders every text into OUT/pages as the main job does (step "texts",
        over the e2e runs' outputs in OUT/lessonNN), then opens lesson 06's
        page, lesson 09's (inline maths), the errata and lesson 11's exercise
        in headless Chromium with
        check_pages.mjs: their formulas render in KaTeX's fonts, their images
        load, their links name files and anchors that exist;
    run_page_test.py expect-failure --out BUILD/test-out/pages-fixture
        writes a page with a formula KaTeX rejected, a missing image and a
        link to a missing anchor, and asserts the checker names all three.

A missing Node.js, npm package or Chromium fails with the advice to run
tools/install-deps: these tests never pass by skipping.
"""
from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools"))
from gallery.texts import TextsError, build_texts  # noqa: E402

CHECKER = SOURCE / "tests" / "texts" / "check_pages.mjs"
HINT = "run tools/install-deps (installs chromium, nodejs, npm, then npm ci)"


def fail(message: str) -> int:
    print(f"page test: FAILED: {message}", flush=True)
    return 1


def check(*args: str) -> subprocess.CompletedProcess:
    node = shutil.which("node")
    result = subprocess.run([node, str(CHECKER), *args], cwd=SOURCE, capture_output=True, text=True,
                            errors="replace", stdin=subprocess.DEVNULL, timeout=600)
    print(result.stdout, end="")
    print(result.stderr, end="", file=sys.stderr)
    return result


def pages(out: Path) -> int:
    if shutil.which("node") is None:
        return fail(f"Node.js is not installed: {HINT}")
    try:
        for line in build_texts(SOURCE, out):
            print(f"page test: {line}")
    except TextsError as e:
        return fail(str(e))
    root = out / "pages"
    result = check("--min-maths", "8", "--min-images", "8", str(root / "lessons/06_ray_tree/README.html"))
    if result.returncode == 2:
        return fail(f"the page checker could not run: {HINT}")
    if result.returncode != 0:
        return fail("lesson 06's page (above)")
    result = check("--min-maths", "20", str(root / "lessons/09_radiosity_form_factors/README.html"))
    if result.returncode != 0:
        return fail("lesson 09's page, inline maths (above)")
    result = check(str(root / "docs/errata.html"), str(root / "exercises/11_radiosity_solvers/README.html"))
    if result.returncode != 0:
        return fail("the errata or exercise 11's page (above)")
    print("page test: OK")
    return 0


BROKEN = """<!DOCTYPE html><html><head><meta charset="utf-8"></head><body>
<p>good: <span class="katex">x</span></p>
<p>bad: <span class="katex-error" title="ParseError: KaTeX parse error: Undefined control sequence: \\frcа">\\frcа</span></p>
<p><img src="missing.png"></p>
<p><a href="#nowhere">a missing anchor</a> <a href="gone.html">a missing page</a></p>
</body></html>
"""


def expect_failure(out: Path) -> int:
    if shutil.which("node") is None:
        return fail(f"Node.js is not installed: {HINT}")
    out.mkdir(parents=True, exist_ok=True)
    page = out / "broken.html"
    page.write_text(BROKEN, encoding="utf-8")
    result = check(str(page))
    if result.returncode == 2:
        return fail(f"the page checker could not run: {HINT}")
    expected = ["KaTeX could not render a formula: ParseError", "image failed to load: missing.png",
                "link to a missing anchor", "link to a missing file", "KaTeX's fonts did not load"]
    missing = [e for e in expected if e not in result.stdout]
    if result.returncode != 1 or missing:
        return fail(f"the checker exited {result.returncode} and did not report: {missing}")
    print("page test: OK: the checker caught every planted fault")
    return 0


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("mode", choices=["pages", "expect-failure"])
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    return pages(args.out.resolve()) if args.mode == "pages" else expect_failure(args.out.resolve())


if __name__ == "__main__":
    sys.exit(main())
