"""out/index.html: one self-contained page (inline CSS, no external asset) showing every lesson found in
the source tree or OUT: its outputs (images as thumbnails, tables rendered, other files as links), its deck,
its text and its exercise (their rendered pages in OUT/pages/ when the main job's step "texts" wrote them)."""

import csv
import html
import io
import os
from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import quote, unquote, urlsplit

from common import png
from common.files import atomic_write_text
from common.markdown import parse_tables
from grading.project import lesson_folders

from .decks import find_decks
from .outputs import Manifest, ManifestError, Output, load_manifest


@dataclass
class Lesson:
    number: str  # "01"
    slug: str = ""  # "01_ray_sphere" (from the lesson folder or the deck), or ""
    title: str = ""
    output_dir: Path | None = None  # OUT/lessonNN
    manifest: Manifest | None = None
    manifest_error: str | None = None
    lesson_readme: Path | None = None
    exercise_readme: Path | None = None
    deck_source: Path | None = None
    deck_html: Path | None = None  # OUT/slides/NN_topic.html when it was built


def _read(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return ""


def _first_heading(readme: Path) -> str:
    return next((line[2:].strip() for line in _read(readme).splitlines() if line.startswith("# ")), "")


def discover_lessons(source: Path, out: Path, slides_dir: Path | None = None) -> list[Lesson]:
    """Every lesson found in the source tree (lessons/, exercises/, slides/) or OUT, by number."""
    source, out = Path(source), Path(out)
    slides_dir = Path(slides_dir) if slides_dir else source / "slides"
    lessons: dict[str, Lesson] = {}
    for kind, attr in (("lessons", "lesson_readme"), ("exercises", "exercise_readme")):
        for nn, folder in lesson_folders(source, kind).items():
            lesson = lessons.setdefault(nn, Lesson(nn))
            lesson.slug = lesson.slug or folder.name  # lessons/ first, then exercises/
            if (folder / "README.md").is_file():
                setattr(lesson, attr, folder / "README.md")
    for deck in find_decks(slides_dir):
        lesson = lessons.setdefault(deck.name[:2], Lesson(deck.name[:2]))
        lesson.deck_source, lesson.slug = deck, lesson.slug or deck.stem
        if (built := out / "slides" / (deck.stem + ".html")).is_file():
            lesson.deck_html = built
    for folder in out.glob("lesson[0-9][0-9]"):
        if (folder / "manifest.json").exists():
            lesson = lessons.setdefault(folder.name[-2:], Lesson(folder.name[-2:]))
            lesson.output_dir = folder
            try:
                lesson.manifest = load_manifest(folder)
            except ManifestError as e:
                lesson.manifest_error = str(e)
    for nn, lesson in lessons.items():
        words = lesson.slug[3:].replace("_", " ").replace("-", " ").strip()
        lesson.title = ((lesson.manifest.title if lesson.manifest else "")
                        or (_first_heading(lesson.lesson_readme) if lesson.lesson_readme else "")
                        or words[:1].upper() + words[1:] or f"Lesson {nn}")
    return [lessons[nn] for nn in sorted(lessons)]


CSS = Path(__file__).with_name("index.css")

_KIND_LABEL = {"hdr": "Radiance HDR image (linear radiance)", "table": "CSV table", "markdown": "Markdown table",
               "mesh": "mesh (PLY or OBJ, per-vertex colours)"}


def href(target: Path, base: Path) -> str:
    """A URL for `target` relative to the folder `base`, with each segment escaped."""
    rel = os.path.relpath(Path(target).resolve(), Path(base).resolve())
    return "/".join(quote(part) for part in Path(rel).parts)


_e = html.escape  # quotes too


def _html_table(header: list[str], rows: list[list[str]], align: list[str], more: str = "") -> str:
    """A table's cells escaped, right- and centre-aligned columns classed; `more` (HTML) ends its body."""
    def cell(tag: str, i: int, text: str) -> str:
        kind = f' class="{align[i]}"' if i < len(align) and align[i] in ("right", "center") else ""
        return f"<{tag}{kind}>{_e(text)}</{tag}>"

    body = "".join("<tr>" + "".join(cell("td", i, c) for i, c in enumerate(row)) + "</tr>\n" for row in rows)
    head = "".join(cell("th", i, c) for i, c in enumerate(header))
    return f"<table><thead><tr>{head}</tr></thead>\n<tbody>\n{body}{more}</tbody></table>"


def markdown_table_html(text: str) -> str:
    """The first Markdown pipe table in `text` as an HTML table ('' if there is none)."""
    tables, _ = parse_tables(text.splitlines())
    return _html_table(tables[0].header, tables[0].rows, tables[0].align) if tables else ""


def csv_table_html(text: str, max_rows: int = 40) -> str:
    """A CSV as an HTML table, its first `max_rows` rows and a note of the rest ('' if it is empty)."""
    rows = [r for r in csv.reader(io.StringIO(text)) if r]
    if not rows:
        return ""
    hidden = len(rows) - 1 - max_rows
    more = (f'<tr><td colspan="{len(rows[0])}" class="note">… {hidden} more rows in the CSV</td></tr>'
            if hidden > 0 else "")
    return _html_table(rows[0], rows[1:max_rows + 1], [], more)


def rendered_page(source: Path, out: Path, text: Path) -> Path | None:
    """OUT/pages/<text's path in the tree>.html when the main job rendered the text (gallery/texts.py), else None."""
    try:
        page = Path(out) / "pages" / Path(text).resolve().relative_to(Path(source).resolve()).with_suffix(".html")
    except ValueError:
        return None
    return page if page.is_file() else None


def _documents(source: Path, out: Path) -> str:
    """Links to the rendered README, CONTRIBUTING and docs/*.md, when the pages exist."""
    texts = [source / "README.md", source / "CONTRIBUTING.md", *sorted((source / "docs").glob("*.md"))]
    items = [f'<a href="{href(page, out)}">{_e(_first_heading(text) or text.name)}</a>'
             for text in texts if (page := rendered_page(source, out, text))]
    return ('<nav class="toc docs"><span class="note">Documents:</span> ' + " ".join(items) + "</nav>") if items else ""


def _lesson_links(lesson: Lesson, out: Path, source: Path) -> str:
    def link(path: Path | None, label: str, missing: str, text: bool = False) -> str:
        """A link to `path`, or to the rendered page of a text (main job step "texts") with its Markdown beside it."""
        page = rendered_page(source, out, path) if text and path is not None else None
        if page is not None:
            return (f'<li><a href="{href(page, out)}">{_e(label)}</a> '
                    f'<a class="raw" href="{href(path, out)}">(Markdown)</a></li>')
        if path is not None and path.exists():
            return f'<li><a href="{href(path, out)}">{_e(label)}</a></li>'
        return f'<li class="missing">{_e(missing)}</li>'

    items = [link(lesson.deck_html, "Slides", "") if lesson.deck_html else
             link(lesson.deck_source, "Slides (Markdown source; deck not built)", "") if lesson.deck_source else
             '<li class="missing">no slides yet</li>',
             link(lesson.lesson_readme, "Lesson text", "no lesson text yet", text=True),
             link(lesson.exercise_readme, "Exercise", "no exercise text yet", text=True)]
    if lesson.output_dir is not None:
        items.append(link(lesson.output_dir / "manifest.json", "manifest.json", ""))
    return '<ul class="links">' + "".join(items) + "</ul>"


# Tables longer than this are shown folded, so that one long study does not
# push the next lesson's figures several screens down.
FOLD_ROWS = 20


def _table_figure(caption_html: str, table_html: str, rows: int) -> str:
    """A table in a figure with its caption, folded when it has more than FOLD_ROWS rows."""
    body = f'<div class="table-wrap">{table_html}</div>'
    if rows > FOLD_ROWS:
        body = f"<details><summary>{rows} rows: show the table</summary>{body}</details>"
    return f"<figure><figcaption>{caption_html}</figcaption>{body}</figure>"


class _Outputs:
    """A lesson's outputs as HTML: images and plots as thumbnails, tables rendered, other files as links."""

    def __init__(self, folder: Path, manifest: Manifest, out: Path):
        self.folder, self.out, self.outputs = folder, out, manifest.outputs
        self.by_file = {o.file: o for o in self.outputs}
        self.used: set[str] = set()

    def href(self, o: Output) -> str:
        return href(self.folder / o.file, self.out)

    def sibling(self, o: Output, suffix: str, kinds: tuple[str, ...]) -> Output | None:
        s = self.by_file.get(str(Path(o.file).with_suffix(suffix)))
        return s if s is not None and s.kind in kinds and (self.folder / s.file).is_file() else None

    def figure(self, o: Output) -> str:
        url, size = self.href(o), png.size_of(self.folder / o.file)
        dims = f' width="{size[0]}" height="{size[1]}"' if size else ""
        pixel = ' class="pixel"' if size and max(size) <= 400 and o.kind == "image" else ""
        script = self.sibling(o, ".gp", ("script",)) if o.kind == "plot" else None
        extra = f' · <a href="{self.href(script)}">gnuplot script</a>' if script else ""
        self.used.update([o.file] + ([script.file] if script else []))
        return (f'<figure><a href="{url}"><img src="{url}" alt="{_e(o.caption or o.file)}"{dims}{pixel} '
                f'loading="lazy"></a><figcaption>{_e(o.caption)} <code>{_e(o.file)}</code>{extra}</figcaption>'
                "</figure>")

    def table(self, o: Output) -> str:
        """A Markdown table (with a link to its CSV twin), or a CSV that has none; '' for neither."""
        if o.kind == "markdown":
            csv_out = self.sibling(o, ".csv", ("table",))
            links = ([f'<a href="{self.href(csv_out)}">CSV</a>'] if csv_out else []) + [
                f'<a href="{self.href(o)}">Markdown</a>']
            self.used.update([csv_out.file] if csv_out else [])
            text = _read(self.folder / o.file)
            if table := markdown_table_html(text):
                self.used.add(o.file)
                return _table_figure(f"{_e(o.caption)} <code>{_e(Path(o.file).stem)}</code> · " + " · ".join(links),
                                     table, text.count("\n") - 2)
        elif o.kind == "table" and self.sibling(o, ".md", ("markdown",)) is None:
            if table := csv_table_html(_read(self.folder / o.file)):
                self.used.add(o.file)
                return _table_figure(f'{_e(o.caption)} · <a href="{self.href(o)}">CSV</a>', table, 0)
        return ""

    def html(self) -> str:
        present = [o for o in self.outputs if (self.folder / o.file).is_file()]
        figures = [self.figure(o) for o in present if o.kind in ("image", "plot")]
        tables = [t for o in present if o.file not in self.used and (t := self.table(o))]
        files = [f'<li><a href="{self.href(o)}"><code>{_e(o.file)}</code></a>'
                 + (f" — {_e(o.caption)}" if o.caption else "")
                 + f' <span class="note">({_e(_KIND_LABEL.get(o.kind, o.kind))})</span></li>'
                 for o in present if o.file not in self.used]
        files += [f'<li><code>{_e(o.file)}</code> <span class="note">(listed in manifest.json but missing)</span></li>'
                  for o in self.outputs if o not in present]
        parts = (['<h3>Figures</h3><div class="figures">' + "\n".join(figures) + "</div>"] if figures else []) + (
            ["<h3>Tables</h3>" + "\n".join(tables)] if tables else []) + (
            ['<h3>Other files</h3><ul class="files">' + "\n".join(files) + "</ul>"] if files else [])
        return "\n".join(parts) or '<p class="note">The manifest lists no outputs.</p>'


def _lab_section(out: Path) -> str:
    """OUT/lab, the screenshots of `illum lab` (tools/lab/screenshots.py), or '' when there are none."""
    folder = out / "lab"
    if not (folder / "manifest.json").is_file():
        return ""
    try:
        outputs = _Outputs(folder, load_manifest(folder), out).html()
    except ManifestError as e:
        return f'<section class="lesson" id="lab"><h2>The lab</h2><div class="error">{_e(str(e))}</div></section>'
    return ('<section class="lesson" id="lab"><h2>The lab: <code>illum lab</code></h2>'
            '<p>Run <code>build/release/bin/illum lab whitted</code> (or your build\'s) and open the address it '
            'prints: a pixel\'s ray tree, radiosity shot by shot, the hemicube, and your pictures against the '
            'reference, computed by the build it is part of (docs/lab.md).</p>'
            + outputs + "</section>")


def _lesson_outputs(lesson: Lesson, out: Path) -> str:
    if lesson.manifest_error:
        return f'<div class="error">{_e(lesson.manifest_error)}</div>'
    if lesson.manifest:
        return _Outputs(lesson.output_dir, lesson.manifest, out).html()
    return (f'<p class="note">No outputs yet: build and run <code>bin/lesson{lesson.number}</code> '
            "(the main job, <code>cmake --build --preset release --target gallery</code>, runs them all).</p>")


def render_index(lessons: list[Lesson], out: Path, source: Path, note: str = "") -> str:
    out, source = Path(out), Path(source)
    lab = _lab_section(out)
    toc = " ".join(f'<a href="#lesson{l.number}">{l.number} · {_e(l.title)}</a>' for l in lessons)
    if lab:
        toc += ' <a href="#lab">the lab</a>'
    sections = ["\n".join([f'<section class="lesson" id="lesson{lesson.number}">',
                           f'<h2><span class="num">{lesson.number}</span>{_e(lesson.title)}</h2>',
                           _lesson_links(lesson, out, source), _lesson_outputs(lesson, out), "</section>"])
                for lesson in lessons] or ['<p class="note">No lessons found.</p>']
    sections += [lab] if lab else []
    readme = source / "README.md"
    readme_link = f' · <a href="{href(readme, out)}">README</a>' if readme.is_file() else ""
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>illum — lessons and outputs</title>
<style>{CSS.read_text(encoding="utf-8")}</style>
</head>
<body>
<header>
<h1>illum — global illumination, step by step</h1>
<p>Every lesson's reference run, its slides, lesson text and exercise.{_e(' ' + note) if note else ''}</p>
<nav class="toc">{toc}</nav>
{_documents(source, out)}
</header>
<main>
{chr(10).join(sections)}
</main>
<footer>Written by <code>tools/main_job.py</code>{readme_link}. Thumbnails link to full-size files; paths to lesson texts and exercises point into the source tree.</footer>
</body>
</html>
"""


def write_index(source: Path, out: Path, slides_dir: Path | None = None, note: str = "") -> Path:
    target = Path(out) / "index.html"
    atomic_write_text(target, render_index(discover_lessons(source, out, slides_dir), Path(out), Path(source), note))
    return target


class _Links(HTMLParser):
    """Every href and src of a page, as (tag, attribute, value), and the ids of its elements."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.refs: list[tuple[str, str, str]] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        self.ids.update(value for name, value in attrs if name == "id" and value)
        self.refs += [(tag, name, value) for name, value in attrs if name in ("href", "src") and value is not None]


def check_links(page: Path) -> list[str]:
    """Problems with a page's links: local href/src that do not resolve, and
    external assets (the page must be self-contained)."""
    page, parser, problems = Path(page), _Links(), []
    parser.feed(page.read_text(encoding="utf-8"))
    for tag, attr, value in parser.refs:
        parts, where = urlsplit(value), f"<{tag} {attr}={value!r}>"
        if parts.scheme or value.startswith("//"):
            if attr == "src" or tag == "link":
                problems.append(f"{where}: an external asset; the page must be self-contained")
        elif not parts.path:
            if parts.fragment and parts.fragment not in parser.ids:
                problems.append(f"{where}: no element with id {parts.fragment!r} in the page")
        elif not (target := (page.parent / unquote(parts.path)).resolve()).exists():
            problems.append(f"{where}: {target} does not exist")
    return problems
