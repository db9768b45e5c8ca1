#!/usr/bin/env python3
"""The ctest entry points of the slide tests (registered in tests/e2e/slides.cmake).

    run_slide_test.py decks            --out BUILD/test-out
        builds every slides/NN_*.md into OUT/slides/ (as the main job does),
        then opens each in headless Chromium with check_decks.mjs;
    run_slide_test.py expect-failure   --out BUILD/test-out/slides-fixture
        builds tests/slides/fixtures/99_broken.md and asserts the checker
        rejects it for exactly the planted reasons (bad maths on slide 2, a
        missing image on slide 3, a missing background on slide 4, content
        running off the bottom of slide 5 and off the right of slide 6)
        and not the good first slide (whose wide code line Marp scales to
        fit, and whose over-wide box a script narrows eight frames after
        parsing: the checker measures the page once it has settled).

A missing Marp, Node.js, puppeteer-core or Chromium is a failure with the
advice to run tools/install-deps: these tests never pass by skipping.
"""
from __future__ import annotations

import argparse
import re
import shutil
import struct
import subprocess
import sys
import zlib
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools"))
from gallery.decks import DeckError, build_decks, find_decks  # noqa: E402

CHECKER = SOURCE / "tests" / "slides" / "check_decks.mjs"
FIXTURES = SOURCE / "tests" / "slides" / "fixtures"
HINT = "run tools/install-deps (installs chromium, nodejs, npm, then npm ci for marp-cli and puppeteer-core)"


def fail(message: str) -> int:
    print(f"slide test: FAILED: {message}", flush=True)
    return 1


def node() -> str | None:
    return shutil.which("node")


def run_checker(slides: Path) -> subprocess.CompletedProcess:
    return subprocess.run([node(), str(CHECKER), str(slides)], cwd=SOURCE, capture_output=True, text=True,
                          errors="replace", stdin=subprocess.DEVNULL, timeout=900)


def build(decks_dir: Path, out: Path) -> list[Path]:
    decks = find_decks(decks_dir)
    if not decks:
        raise DeckError(f"no decks (NN_*.md) in {decks_dir}")
    print(f"slide test: building {len(decks)} deck(s) from {decks_dir} into {out / 'slides'}", flush=True)
    return build_decks(SOURCE, decks, out / "slides")


def tiny_png() -> bytes:
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + b"\x80\x80\x80" * 4 for _ in range(4))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def decks(out: Path) -> int:
    if node() is None:
        return fail(f"Node.js is not installed: {HINT}")
    try:
        build(SOURCE / "slides", out)
    except DeckError as e:
        return fail(str(e))
    result = run_checker(out / "slides")
    print(result.stdout, end="")
    print(result.stderr, end="", file=sys.stderr)
    if result.returncode == 2:
        return fail(f"the slide checker could not run: {HINT}")
    if result.returncode != 0:
        return fail("a deck has problems (listed above: deck, slide, reason). Images come from the lessons' "
                    f"quick runs in {out}/lessonNN; a missing one means the deck names a file the lesson "
                    "does not write.")
    return 0


def expect_failure(out: Path) -> int:
    if node() is None:
        return fail(f"Node.js is not installed: {HINT}")
    if out.exists():
        shutil.rmtree(out)
    # The good first slide shows ../lesson01/silhouette.png: provide one, so the
    # fixture does not depend on lesson 01 having run.
    (out / "lesson01").mkdir(parents=True)
    (out / "lesson01" / "silhouette.png").write_bytes(tiny_png())
    try:
        build(FIXTURES, out)
    except DeckError as e:
        return fail(str(e))
    result = run_checker(out / "slides")
    report = result.stdout + result.stderr
    print(report, end="")
    if result.returncode == 2:
        return fail(f"the slide checker could not run, so it proved nothing: {HINT}")
    if result.returncode != 1:
        return fail(f"the checker accepted a broken deck (exit {result.returncode}, expected 1)")
    expected = {
        "bad maths on slide 2": r"99_broken\.html slide 2: ParseError",
        "undefined command on slide 2": r"99_broken\.html slide 2: KaTeX: undefined command \\notacommand",
        "missing image on slide 3": r"99_broken\.html slide 3: image failed to load: \.\./lesson01/no_such_image\.png",
        "missing background on slide 4": r"99_broken\.html slide 4: background image failed to load",
        "overflow at the bottom of slide 5": r"99_broken\.html slide 5: content overflows the slide by \d+px at the bottom",
        "overflow on the right of slide 6": r"99_broken\.html slide 6: content overflows the slide by \d+px on the right",
    }
    missed = [what for what, pattern in expected.items() if not re.search(pattern, report)]
    if missed:
        return fail(f"the checker failed, but did not report: {', '.join(missed)}")
    if re.search(r"99_broken\.html slide 1:", report):
        return fail("the checker reported the good first slide (a false alarm)")
    print("slide test: the checker rejects the broken fixture for each planted reason, and only those")
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mode", choices=("decks", "expect-failure"))
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    out = args.out.resolve()
    return decks(out) if args.mode == "decks" else expect_failure(out)


if __name__ == "__main__":
    sys.exit(main())
