"""Slide decks: slides/NN_topic.md -> OUT/slides/NN_topic.html with Marp from the repository's node_modules,
KaTeX's fonts copied beside them (OUT/slides/katex-fonts/): a deck needs no network."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from common.files import atomic_copy

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


def marp_command(source: Path, input_dir: Path, output: Path) -> list[str]:
    """Marp on every .md of `input_dir`, its pages written into the folder `output`."""
    source = Path(source)
    return [str(marp_executable(source)), "--no-stdin", "--html",
            "--config-file", str(source / "slides" / "marp.config.cjs"),
            "--theme-set", str(source / "slides" / "theme"),
            "--input-dir", str(input_dir), "--output", str(output)]


def build_deck(source: Path, deck: Path, out_slides: Path) -> Path:
    """Builds one deck, its page replaced atomically; DeckError with Marp's messages when it fails."""
    if problem := _marp(source, [deck], Path(out_slides)):
        raise DeckError(problem)
    return Path(out_slides) / (Path(deck).stem + ".html")


def _marp(source: Path, decks: list[Path], out_slides: Path) -> str:
    """One Marp run on copies of `decks` in a temporary folder beside OUT/slides (Marp builds every .md of an
    --input-dir; the slides folder also holds its README), each page then replacing the old one atomically:
    '' when every deck was built (and only then is a page replaced), else what went wrong. Marp leaves a
    deck's image paths as written, so a copy builds the same bytes as the original."""
    work = Path(tempfile.mkdtemp(prefix=".decks-", dir=out_slides))
    names = ", ".join(str(deck) for deck in decks)
    try:
        (work / "in").mkdir()
        for deck in decks:
            shutil.copyfile(deck, work / "in" / Path(deck).name)
        result = subprocess.run(marp_command(source, work / "in", work / "out"), cwd=source,
                                stdin=subprocess.DEVNULL, capture_output=True, text=True, errors="replace",
                                timeout=600)
        pages = [work / "out" / (Path(deck).stem + ".html") for deck in decks]
        if result.returncode != 0 or not all(page.is_file() for page in pages):
            return (f"marp failed on {names} (exit {result.returncode}):\n"
                    f"{result.stdout.strip()}\n{result.stderr.strip()}".rstrip())
        for page in pages:
            os.replace(page, out_slides / page.name)
        return ""
    except (OSError, subprocess.SubprocessError) as e:
        return f"marp failed on {names}: {e}"
    finally:
        shutil.rmtree(work, ignore_errors=True)


def build_decks(source: Path, decks: list[Path], out_slides: Path, jobs: int = 2) -> list[Path]:
    """Builds every deck; raises DeckError naming each deck that failed.

    One Marp run builds them all (Node and Marp start once: 13 decks took 2.8 s so, against 1.3 s
    for each deck alone). If that run fails, each deck is built alone, in `jobs` at once, so that
    the error names every deck that failed."""
    marp_executable(source)  # fail early, with the install hint
    out_slides = Path(out_slides)
    out_slides.mkdir(parents=True, exist_ok=True)
    copy_katex_fonts(source, out_slides)
    if not _marp(source, decks, out_slides):
        return [out_slides / (Path(deck).stem + ".html") for deck in decks]
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
