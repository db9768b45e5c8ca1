"""A lesson program's output folder: its manifest.json (`{"id": "lesson01", "title": …, "outputs": [{"kind":
"image", "file": "x.png", "caption": …}, …]}`) and a check of each file for its kind; each check returns
the problems, written for a person (an empty list: fine)."""
from __future__ import annotations

import csv
import io
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

from common import png
from common.markdown import Table, parse_tables

# Each kind of output and the extensions its file must have (None: any).
KIND_EXTENSIONS = {"image": (".png",), "hdr": (".hdr",), "table": (".csv",), "markdown": (".md",), "plot": (".png",),
                   "script": None, "text": None, "mesh": (".ply", ".obj")}
KINDS = tuple(KIND_EXTENSIONS)


class ManifestError(Exception):
    """manifest.json is missing, is not JSON or does not have the expected shape."""


@dataclass
class Output:
    kind: str
    file: str
    caption: str = ""

    @property
    def stem(self) -> str:
        return Path(self.file).stem

    @property
    def suffix(self) -> str:
        return Path(self.file).suffix.lower()


@dataclass
class Manifest:
    id: str
    title: str
    outputs: list[Output] = field(default_factory=list)


def load_manifest(folder: Path | str) -> Manifest:
    """Reads and validates <folder>/manifest.json; raises ManifestError with the reason."""
    path = Path(folder) / "manifest.json"
    if not path.is_file():
        raise ManifestError(f"{path}: not found (the program must write it last, via OutputFolder::finish())")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise ManifestError(f"{path}: not valid JSON: {e}") from None
    if not isinstance(data, dict):
        raise ManifestError(f"{path}: the top level must be an object, found {type(data).__name__}")
    problems = []
    for key in ("id", "title"):
        if not isinstance(data.get(key), str) or not data.get(key).strip():
            problems.append(f'"{key}" must be a non-empty string, found {data.get(key)!r}')
    outputs = data.get("outputs")
    if not isinstance(outputs, list):
        problems.append(f'"outputs" must be a list, found {type(outputs).__name__}')
        outputs = []
    parsed = []
    for i, entry in enumerate(outputs):
        where = f"outputs[{i}]"
        if not isinstance(entry, dict):
            problems.append(f"{where} must be an object")
            continue
        kind, file, caption = entry.get("kind"), entry.get("file"), entry.get("caption", "")
        if kind not in KINDS:
            problems.append(f'{where}: unknown kind {kind!r} (expected one of {", ".join(KINDS)})')
            continue
        if not isinstance(file, str) or not file:
            problems.append(f'{where}: "file" must be a non-empty string')
            continue
        if not isinstance(caption, str):
            problems.append(f'{where}: "caption" must be a string')
            continue
        if Path(file).is_absolute() or ".." in Path(file).parts or "\\" in file:
            problems.append(f"{where}: file {file!r} must be a plain name inside the output folder")
            continue
        parsed.append(Output(kind, file, caption))
    if problems:
        raise ManifestError(f"{path}:\n  " + "\n  ".join(problems))
    return Manifest(data["id"], data["title"], parsed)


def check_png(path: Path) -> list[str]:
    return [f"{path.name}: {p}" for p in png.problems(Path(path).read_bytes())]


def png_size(path: Path) -> tuple[int, int] | None:
    """(width, height), or None if the file is not a PNG."""
    with open(path, "rb") as f:
        head = f.read(33)
    try:
        return png.size(head)
    except png.PngError:
        return None


_HDR_RESOLUTION = re.compile(rb"^[-+][YX] (\d+) [-+][XY] (\d+)$")


def check_hdr(path: Path) -> list[str]:
    data = Path(path).read_bytes()
    if not data.startswith(b"#?RADIANCE") and not data.startswith(b"#?RGBE"):
        return [f"{path.name}: not a Radiance HDR file (it must start with '#?RADIANCE')"]
    # Header lines, a blank line, then the resolution line ("-Y h +X w").
    end = data.find(b"\n\n")
    if end < 0:
        return [f"{path.name}: the Radiance header never ends (no blank line)"]
    line_end = data.find(b"\n", end + 2)
    resolution = data[end + 2 : line_end if line_end >= 0 else len(data)].strip()
    m = _HDR_RESOLUTION.match(resolution)
    if not m:
        return [f"{path.name}: bad resolution line {resolution[:40]!r} (expected e.g. '-Y 240 +X 320')"]
    if int(m.group(1)) == 0 or int(m.group(2)) == 0:
        return [f"{path.name}: image size is zero ({resolution.decode()})"]
    if line_end < 0 or line_end + 1 >= len(data):
        return [f"{path.name}: no pixel data after the resolution line"]
    return []


def _utf8(path: Path) -> str | None:
    try:
        return Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return None


def check_csv(path: Path) -> list[str]:
    if (text := _utf8(path)) is None:
        return [f"{path.name}: not UTF-8 text"]
    try:
        rows = list(csv.reader(io.StringIO(text)))
    except csv.Error as e:
        return [f"{path.name}: not valid CSV: {e}"]
    blank = [i + 1 for i, r in enumerate(rows) if not r]
    numbered = [(i + 1, r) for i, r in enumerate(rows) if r]
    problems = [f"{path.name}: blank line(s) at {', '.join(map(str, blank[:5]))}"] if blank else []
    if not numbered:
        return [f"{path.name}: empty (a CSV needs a header line and at least one row)"]
    header = numbered[0][1]
    if any(not h.strip() for h in header):
        problems.append(f"{path.name}: the header {header!r} has an empty column name")
    if len(numbered) < 2:
        problems.append(f"{path.name}: only a header, no data rows")
    if ragged := next(((n, row) for n, row in numbered[1:] if len(row) != len(header)), None):
        problems.append(f"{path.name}: line {ragged[0]} has {len(ragged[1])} fields, the header has {len(header)}")
    return problems


def parse_markdown_tables(text: str) -> tuple[list[Table], list[str]]:
    return parse_tables(text.splitlines())


def check_markdown_table(path: Path) -> list[str]:
    if (text := _utf8(path)) is None:
        return [f"{path.name}: not UTF-8 text"]
    tables, problems = parse_markdown_tables(text)
    if not tables and not problems:
        return [f"{path.name}: no Markdown table found (expected '| a | b |', '|---|---|', rows)"]
    return [f"{path.name}: {p}" for p in problems]


def check_text(path: Path) -> list[str]:
    return [] if _utf8(path) is not None else [f"{path.name}: not UTF-8 text"]


def check_mesh(path: Path) -> list[str]:
    """A PLY opens with 'ply' and a format line and closes its header; an OBJ is text with vertices."""
    data = Path(path).read_bytes()
    if path.suffix == ".ply":
        ok = data.startswith(b"ply\n") and b"\nformat " in data[:64] and b"end_header\n" in data
        return [] if ok else [f"{path.name}: not a PLY file (no 'ply', format line or end_header)"]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return [f"{path.name}: not UTF-8 text"]
    return [] if any(line.startswith("v ") for line in text.splitlines()) else [
        f"{path.name}: an OBJ file without vertices"]


CHECKS = {"image": check_png, "plot": check_png, "hdr": check_hdr, "table": check_csv, "markdown": check_markdown_table,
          "script": check_text, "text": check_text, "mesh": check_mesh}


def check_output_folder(folder: Path | str, expected_id: str | None = None) -> list[str]:
    """Every problem with a lesson program's output folder (empty list: all good)."""
    folder = Path(folder)
    try:
        manifest = load_manifest(folder)
    except ManifestError as e:
        return [str(e)]
    problems = []
    if expected_id is not None and manifest.id != expected_id:
        problems.append(f'manifest.json: "id" is {manifest.id!r}, expected {expected_id!r} (the program\'s name)')
    if not manifest.outputs:
        problems.append("manifest.json: lists no outputs")
    seen = set()
    for out in manifest.outputs:
        if out.file in seen:
            problems.append(f"manifest.json: {out.file} is listed twice")
            continue
        seen.add(out.file)
        allowed = KIND_EXTENSIONS[out.kind]
        if allowed and out.suffix not in allowed:
            problems.append(f"{out.file}: kind '{out.kind}' needs a {' or '.join(allowed)} file")
            continue
        path = folder / out.file
        if not path.is_file():
            problems.append(f"{out.file}: listed in manifest.json ({out.kind}) but not written")
            continue
        if path.stat().st_size == 0:
            problems.append(f"{out.file}: empty file")
            continue
        problems.extend(CHECKS[out.kind](path))
    leftovers = sorted(p.name for p in folder.rglob("*.tmp-*"))
    if leftovers:
        problems.append(f"temporary files left behind (an atomic write never finished): {', '.join(leftovers)}")
    return problems
