"""The texts as pages: OUT/pages/X.html for each Markdown text X.md, rendered by render_texts.mjs with the
repository's node_modules (markdown-it, KaTeX, highlight.js; `npm ci`): nothing fetched, no script needed."""

import shutil
import subprocess
from pathlib import Path

from . import JobError

RENDERER = Path(__file__).resolve().parent / "render_texts.mjs"
INSTALL_HINT = "run tools/install-deps (it installs Node.js and runs `npm ci` in the repository root)"


class TextsError(JobError):
    """Node.js or the renderer's packages are missing, or a text did not render cleanly."""


def build_texts(source: Path, out: Path) -> list[str]:
    """Renders every text into OUT/pages; returns the renderer's report (one line per note).

    The pages are written into a fresh folder beside OUT/pages (links are relative, so they
    hold there too), which then replaces it: no page of a removed text stays behind, and a
    failed run leaves the previous pages as they were."""
    node = shutil.which("node")
    if node is None:
        raise TextsError(f"Node.js is not installed: {INSTALL_HINT}")
    if not (Path(source) / "node_modules" / "markdown-it").is_dir():
        raise TextsError(f"markdown-it is not installed in {Path(source) / 'node_modules'}: {INSTALL_HINT}")
    fresh, old, pages = Path(out) / "pages.new", Path(out) / "pages.old", Path(out) / "pages"
    for folder in (fresh, old):
        shutil.rmtree(folder, ignore_errors=True)
    try:
        result = subprocess.run([node, str(RENDERER), "--source", str(source), "--out", str(out),
                                 "--pages", fresh.name], cwd=source, stdin=subprocess.DEVNULL,
                                capture_output=True, text=True, errors="replace", timeout=600)
        lines = [line for line in (result.stdout + result.stderr).splitlines() if line.strip()]
        if result.returncode != 0:
            raise TextsError("the texts did not render cleanly:\n  " + "\n  ".join(lines))
        if pages.exists():
            pages.rename(old)
        fresh.rename(pages)
        shutil.rmtree(old, ignore_errors=True)
        return lines
    finally:
        shutil.rmtree(fresh, ignore_errors=True)
