"""The images a lesson text shows, kept in lessons/NN_topic/figures/ as copies of what its program drew in
out/lessonNN/, so that they show before anything has run (CONTRIBUTING.md, "Images show where students
read"). A timing plot (a label of its gnuplot script names a time or a throughput) or a screenshot of the
lab (lab_*.png, drawn into out/lab/) differs on every run: its kept copy is compared by size only."""

import re
from dataclasses import dataclass
from pathlib import Path

from common import png
from common.files import atomic_write_bytes, atomic_write_text
from common.markdown import outside_fences

from .tables import TIMING_WORDS, words

FIGURES_FOLDER = "figures"
TAG = "figures"  # the texts' and kept images' temporaries: NAME.tmp-figures-PID (common/files.py)
LAB_SCREENSHOT = "lab_"
IMAGE_LINK = re.compile(r"!\[[^\]]*\]\((?P<target>[^()\s]+\.png)\)")
OUT_IMAGE = re.compile(r"\.\./\.\./out/lesson(?P<lesson>\d\d)/(?P<name>[\w.\-]+\.png)")
KEPT_IMAGE = re.compile(FIGURES_FOLDER + r"/(?P<name>[\w.\-]+\.png)")
PLOT_LABEL = re.compile(r'^\s*set\s+(?:title|[xy]2?label)\s+"(?P<label>(?:[^"\\]|\\.)*)"', re.M)
PLOT_TIMING_WORDS = TIMING_WORDS | {"mrays", "throughput"}
# Two drawings agree when their sizes match and at most PIXEL_SHARE of the pixels differ by more than
# PIXEL_LEVELS in a channel: a float's last bit moves an 8-bit value a level or two, a change of what
# the program draws moves many pixels by much more.
PIXEL_LEVELS = 4
PIXEL_SHARE = 0.001
KEPT_BUDGET_BYTES = 6_000_000  # all kept images together (CONTRIBUTING.md)


def lesson_texts(source: Path) -> list[Path]:
    return sorted(source.glob("lessons/[0-9][0-9]_*/README.md"))


@dataclass
class ImageLink:
    line: int    # 0-based
    start: int   # span of the link's target in the line
    end: int
    lesson: str  # the program that draws it: out/lesson<lesson>/<name>
    name: str
    kept: bool   # the text links figures/<name>


def image_links(text: Path, lines: list[str]) -> tuple[list[ImageLink], list[str]]:
    """The lesson text's image links to its program's outputs or its kept figures; problems."""
    lesson = text.parent.name[:2]
    links, problems = [], []
    for i, line in outside_fences(lines):
        for m in IMAGE_LINK.finditer(line):
            target = m.group("target")
            out_match, kept_match = OUT_IMAGE.fullmatch(target), KEPT_IMAGE.fullmatch(target)
            if kept_match or (out_match and out_match["lesson"] == lesson):
                name = (kept_match or out_match)["name"]
                links.append(ImageLink(i, m.start("target"), m.end("target"), lesson, name, bool(kept_match)))
            elif out_match:
                problems.append(f"{text}:{i + 1}: '{target}' is drawn by another lesson's program: a lesson text "
                                f"shows its own program's images (link that figure from lesson "
                                f"{out_match['lesson']}'s text)")
    return links, problems


def drawn_path(out: Path, link: ImageLink) -> Path:
    """Where the main job draws a linked image: OUT/lessonNN/, or OUT/lab/ for a screenshot of the lab."""
    return out / ("lab" if link.name.startswith(LAB_SCREENSHOT) else f"lesson{link.lesson}") / link.name


def timing_plot(out: Path, lesson: str, name: str) -> bool:
    """Whether out/lessonNN/<name> is a timing plot (its gnuplot script labels a time or a throughput)."""
    script = out / f"lesson{lesson}" / (Path(name).stem + ".gp")
    return script.is_file() and any(words(m.group("label")) & PLOT_TIMING_WORDS for m in PLOT_LABEL.finditer(
        script.read_text(encoding="utf-8", errors="replace")))


def image_difference(kept: bytes, drawn: bytes, size_only: bool = False) -> str | None:
    """None when two PNGs show the same picture (within PIXEL_LEVELS/PIXEL_SHARE), else how they differ."""
    if kept == drawn:
        return None
    if size_only:
        sizes = png.size(kept), png.size(drawn)
        return None if sizes[0] == sizes[1] else f"its size {sizes[0]} is now {sizes[1]}"
    (w1, h1, c1, p1), (w2, h2, c2, p2) = png.decode(kept), png.decode(drawn)
    if (w1, h1, c1) != (w2, h2, c2):
        return f"the kept figure is {w1}×{h1} with {c1} channel(s), the program drew {w2}×{h2} with {c2}"
    steps = [max(abs(a - b) for a, b in zip(p1[i:i + c1], p2[i:i + c1])) for i in range(0, len(p1), c1)]
    differing = sum(step > PIXEL_LEVELS for step in steps)
    if differing > PIXEL_SHARE * w1 * h1:
        return (f"{differing} of {w1 * h1} pixels differ by more than {PIXEL_LEVELS} levels "
                f"(largest difference {max(steps)}; at most {PIXEL_SHARE:.1%} may)")
    return None


def check_images(source: Path, out: Path) -> tuple[list[str], int]:
    """Problems with the lesson texts' images, and how many kept figures were compared."""
    problems, compared, total = [], 0, 0
    for path in lesson_texts(source):
        rel = path.relative_to(source)
        links, found = image_links(rel, path.read_text(encoding="utf-8").splitlines())
        problems += found
        for link in links:
            problem, was_compared = _kept_problem(source, out, rel, link)
            compared += was_compared
            problems += [problem] if problem else []
        linked = {link.name for link in links if link.kept}
        for orphan in sorted((path.parent / FIGURES_FOLDER).glob("*")):
            total += orphan.stat().st_size
            if orphan.name not in linked:
                problems.append(f"{orphan.relative_to(source)} is not shown by {rel}: delete it "
                                "(tools/figures.py --update-images does)")
    if total > KEPT_BUDGET_BYTES:
        problems.append(f"the kept images of lessons/*/{FIGURES_FOLDER}/ take {total / 1e6:.1f} MB, more than "
                        f"{KEPT_BUDGET_BYTES / 1e6:.0f} MB: show fewer, or have the program draw them smaller")
    return problems, compared


def _kept_problem(source: Path, out: Path, rel: Path, link: ImageLink) -> tuple[str | None, bool]:
    """What is wrong with one image link of a lesson text (None: nothing), and whether it was compared."""
    where, drawn = f"{rel}:{link.line + 1}", drawn_path(out, link)
    kept_name = f"{rel.parent}/{FIGURES_FOLDER}/{link.name}"
    if not drawn.is_file():
        return f"{where}: {link.name}: the program wrote no {drawn.relative_to(out)} in {out}", False
    if not link.kept:
        return (f"{where}: {link.name} is linked in out/, which is empty until the program has run (and in a "
                "fresh clone): keep it with tools/figures.py --update-images"), False
    kept = source / kept_name
    if not kept.is_file():
        return f"{where}: {kept_name} is missing (tools/figures.py --update-images)", False
    size_only = link.name.startswith(LAB_SCREENSHOT) or timing_plot(out, link.lesson, link.name)
    try:
        difference = image_difference(kept.read_bytes(), drawn.read_bytes(), size_only)
    except png.PngError as e:
        difference = str(e)
    if difference:
        return (f"{where}: {kept_name} drifted from what lesson{link.lesson} draws: {difference}; review and "
                "refresh with tools/figures.py --update-images"), True
    return None, True


def _keep(out: Path, rel: Path, lines: list[str], links: list[ImageLink], folder: Path) -> tuple[set, int, list]:
    """Copies the drawn images of one text into `folder` and relinks them in `lines`: (kept names, copies, problems)."""
    keep, copied, problems = set(), 0, []
    for link in reversed(links):  # right to left: earlier spans on a line stay valid
        drawn = drawn_path(out, link)
        if not drawn.is_file():
            problems.append(f"{rel}:{link.line + 1}: {drawn.relative_to(out)} does not exist in {out} (run the "
                            "main job first)")
            if link.kept:
                keep.add(link.name)  # leave it as it is
            continue
        keep.add(link.name)
        data, kept = drawn.read_bytes(), folder / link.name
        if not kept.is_file() or kept.read_bytes() != data:
            folder.mkdir(exist_ok=True)
            atomic_write_bytes(kept, data, tag=TAG)
            copied += 1
        line = lines[link.line]
        lines[link.line] = line[:link.start] + f"{FIGURES_FOLDER}/{link.name}" + line[link.end:]
    return keep, copied, problems


def update_images(source: Path, out: Path, log=print) -> int:
    """Keeps a copy of every image the lesson texts show, links the texts to it, drops the rest."""
    problems, copied, relinked, kept_total = [], 0, 0, 0
    for path in lesson_texts(source):
        rel, text = path.relative_to(source), path.read_text(encoding="utf-8")
        lines, folder = text.splitlines(), path.parent / FIGURES_FOLDER
        links, found = image_links(rel, lines)
        keep, count, missing = _keep(out, rel, lines, links, folder)
        problems += found + missing
        copied += count
        for orphan in sorted(folder.glob("*")):
            if orphan.name not in keep:
                orphan.unlink()
                log(f"figures: removed {orphan.relative_to(source)} (no longer shown)")
        if folder.is_dir() and not any(folder.iterdir()):
            folder.rmdir()
        kept_total += len(keep)
        if lines != text.splitlines():
            atomic_write_text(path, "\n".join(lines) + "\n", tag=TAG)
            relinked += 1
            log(f"figures: relinked the images of {rel}")
    for p in problems:
        log(f"figures: {p}")
    log(f"figures: {kept_total} kept figure(s) in lessons/*/{FIGURES_FOLDER}/, {copied} copied from {out}, "
        f"{relinked} text(s) relinked")
    return 1 if problems else 0
