"""Slide decks: slides/NN_topic.md -> OUT/slides/NN_topic.html with Marp.

Marp comes from the repository's node_modules (package-lock.json, `npm ci`,
done by tools/install-deps). KaTeX renders the maths; its fonts are copied
next to the decks (OUT/slides/katex-fonts/) so a deck needs no network.
"""
from __future__ import annotations

import os
import re
import subprocess
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from .fsutil import atomic_copy, temp_path_beside

DECK_NAME = re.compile(r"^\d\d_[A-Za-z0-9_\-]+\.md$")
FONT_FOLDER = "katex-fonts"
INSTALL_HINT = "run tools/install-deps (it runs `npm ci` in the repository root)"


class DeckError(Exception):
    """Marp is missing or a deck did not build."""


def find_decks(slides_dir: Path) -> list[Path]:
    slides_dir = Path(slides_dir)
    if not slides_dir.is_dir():
        return []
    return sorted(p for p in slides_dir.iterdir() if p.is_file() and DECK_NAME.match(p.name))


def marp_executable(source: Path) -> Path:
    marp = Path(source) / "node_modules" / ".bin" / "marp"
    if not os.access(marp, os.X_OK):
        raise DeckError(f"Marp is not installed ({marp} is missing): {INSTALL_HINT}")
    return marp


def copy_katex_fonts(source: Path, out_slides: Path) -> int:
    """Copies KaTeX's fonts beside the decks; returns how many files were (re)copied."""
    fonts = Path(source) / "node_modules" / "katex" / "dist" / "fonts"
    if not fonts.is_dir():
        raise DeckError(f"KaTeX's fonts are missing ({fonts}): {INSTALL_HINT}")
    target = Path(out_slides) / FONT_FOLDER
    target.mkdir(parents=True, exist_ok=True)
    copied = 0
    for f in sorted(fonts.iterdir()):
        dest = target / f.name
        if not dest.is_file() or dest.stat().st_size != f.stat().st_size:
            atomic_copy(f, dest)
            copied += 1
    return copied


def marp_command(source: Path, deck: Path, output: Path) -> list[str]:
    source = Path(source)
    return [str(marp_executable(source)), "--no-stdin", "--html",
            "--config-file", str(source / "slides" / "marp.config.cjs"),
            "--theme-set", str(source / "slides" / "theme"),
            "--output", str(output), str(deck)]


def build_deck(source: Path, deck: Path, out_slides: Path) -> Path:
    """Builds one deck atomically (Marp writes a temporary .html, then it is renamed)."""
    target = Path(out_slides) / (Path(deck).stem + ".html")
    # Marp picks the format from the extension, so the temporary name ends in .html.
    placeholder = temp_path_beside(target)
    tmp = placeholder.with_name(placeholder.name + ".html")
    try:
        result = subprocess.run(marp_command(source, deck, tmp), cwd=source, stdin=subprocess.DEVNULL,
                                capture_output=True, text=True, errors="replace", timeout=300)
        if result.returncode != 0 or not tmp.is_file():
            raise DeckError(f"marp failed on {deck} (exit {result.returncode}):\n"
                            f"{result.stdout.strip()}\n{result.stderr.strip()}".rstrip())
        os.replace(tmp, target)
    finally:
        placeholder.unlink(missing_ok=True)
        tmp.unlink(missing_ok=True)
    return target


def build_decks(source: Path, decks: list[Path], out_slides: Path, jobs: int = 2) -> list[Path]:
    """Builds every deck; raises DeckError naming each deck that failed."""
    marp_executable(source)  # fail early, with the install hint
    out_slides = Path(out_slides)
    out_slides.mkdir(parents=True, exist_ok=True)
    copy_katex_fonts(source, out_slides)
    built, errors = [], []
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        futures = [(deck, pool.submit(build_deck, source, deck, out_slides)) for deck in decks]
        for deck, future in futures:
            try:
                built.append(future.result())
            except DeckError as e:
                errors.append(str(e))
    if errors:
        raise DeckError("\n".join(errors))
    return built
