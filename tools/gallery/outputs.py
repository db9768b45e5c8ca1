"""A lesson program's output folder: its manifest.json (`{"id": "lesson01", "title": …, "outputs": [{"kind":
"image", "file": "x.png", "caption": …}, …]}`), read and validated (each file's check for its kind:
tests/checks/check_outputs.py)."""

import json
from dataclasses import dataclass, field
from pathlib import Path

# Each kind of output and the extensions its file must have (None: any).
KIND_EXTENSIONS = {"image": (".png",), "hdr": (".hdr",), "table": (".csv",), "markdown": (".md",), "plot": (".png",),
                   "script": None, "text": None, "mesh": (".ply", ".obj")}


class ManifestError(Exception):
    """manifest.json is missing, is not JSON or does not have the expected shape."""


@dataclass
class Output:
    kind: str
    file: str
    caption: str = ""

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
    problems = [f'"{key}" must be a non-empty string, found {data.get(key)!r}' for key in ("id", "title")
                if not isinstance(data.get(key), str) or not data.get(key).strip()]
    outputs = data.get("outputs")
    if not isinstance(outputs, list):
        problems.append(f'"outputs" must be a list, found {type(outputs).__name__}')
        outputs = []
    parsed = []
    for i, entry in enumerate(outputs):
        if not isinstance(entry, dict):
            problems.append(f"outputs[{i}] must be an object")
            continue
        kind, file, caption = entry.get("kind"), entry.get("file"), entry.get("caption", "")
        problem = (f'unknown kind {kind!r} (expected one of {", ".join(KIND_EXTENSIONS)})'
                   if kind not in KIND_EXTENSIONS else
                   '"file" must be a non-empty string' if not isinstance(file, str) or not file else
                   '"caption" must be a string' if not isinstance(caption, str) else
                   f"file {file!r} must be a plain name inside the output folder"
                   if Path(file).is_absolute() or ".." in Path(file).parts or "\\" in file else "")
        if problem:
            problems.append(f"outputs[{i}]: {problem}")
        else:
            parsed.append(Output(kind, file, caption))
    if problems:
        raise ManifestError(f"{path}:\n  " + "\n  ".join(problems))
    return Manifest(data["id"], data["title"], parsed)

