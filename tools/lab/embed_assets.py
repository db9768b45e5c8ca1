#!/usr/bin/env python3
"""Compiles the lab's page into the `illum` binary (run by the build, tools/lab/lab.cmake): a C++ file
defining illum::lab::lab_assets() with every file of tools/lab/web/ and the parts of three.js the page
uses (node_modules/three, its add-ons' bare 'three' imports rewritten to the module's path; without it,
lab_has_three() is false and the page says how to get it). Rewritten only when its text changes.

    embed_assets.py --source SOURCE_TREE --out BUILD/generated/lab_assets.cpp
"""

import argparse
import contextlib
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from common.files import atomic_write_bytes  # noqa: E402

# Under node_modules/three; served as /assets/three/NAME, a name without a suffix (LICENSE) with .txt.
THREE_FILES = ["build/three.module.js", "build/three.core.js", "examples/jsm/controls/OrbitControls.js",
               # Lines wider than one pixel (WebGL draws plain lines 1 pixel wide).
               "examples/jsm/lines/LineSegments2.js", "examples/jsm/lines/LineSegmentsGeometry.js",
               "examples/jsm/lines/LineMaterial.js", "LICENSE"]
# JavaScript as application/javascript with a charset: cpp-httplib compresses text/* (and the bare
# application/javascript) on the fly, with brotli when the browser offers it, which takes seconds for
# three.js; on 127.0.0.1 the bytes cost nothing.
TYPES = {".html": "text/html; charset=utf-8", ".js": "application/javascript; charset=utf-8",
         ".css": "text/css; charset=utf-8", ".txt": "text/plain; charset=utf-8", ".svg": "image/svg+xml"}
# GCC's -Wpedantic warns about string literals longer than 65,536 bytes.
CHUNK = 60_000


def chunks(data: bytes) -> list[bytes]:
    """Pieces of at most CHUNK bytes, never cut inside a UTF-8 sequence."""
    out, start = [], 0
    while start < len(data):
        end = min(len(data), start + CHUNK)
        while end < len(data) and (data[end] & 0xC0) == 0x80:
            end -= 1
        out.append(data[start:end])
        start = end
    return out


def delimiter(data: bytes) -> str:
    for n in range(1000):
        d = f"lab{n}"
        if f"){d}\"".encode() not in data:
            return d
    raise SystemExit("embed_assets.py: no raw-string delimiter fits")


def collect(source: Path) -> tuple[list[tuple[str, str, bytes]], bool]:
    assets = [("/" if path.name == "index.html" else f"/assets/{path.name}",
               TYPES.get(path.suffix, "application/octet-stream"), path.read_bytes())
              for path in sorted((source / "tools" / "lab" / "web").iterdir())
              if path.is_file() and not path.name.startswith(".")]
    three = source / "node_modules" / "three"
    if have_three := all((three / f).is_file() for f in THREE_FILES):
        for relative in THREE_FILES:
            data, name = (three / relative).read_bytes(), Path(relative).name
            name += "" if Path(name).suffix else ".txt"
            if name.endswith(".js") and not name.startswith("three."):  # an add-on: it imports 'three'
                data = data.replace(b"from 'three';", b"from './three.module.js';")
                if b"from 'three'" in data or b'from "three"' in data:
                    raise SystemExit(f"embed_assets.py: {name} still imports 'three'")
            assets.append((f"/assets/three/{name}", TYPES[Path(name).suffix], data))
    return assets, have_three


def cpp(assets: list[tuple[str, str, bytes]], have_three: bool) -> str:
    lines = ["// Written by tools/lab/embed_assets.py at build time: do not edit.",
             '#include "lab/lab_assets.hpp"', "", "namespace illum::lab {", "", "namespace {", ""]
    for i, (_, _, data) in enumerate(assets):
        d, pieces = delimiter(data), chunks(data)
        lines += [f"const char* const asset_{i}[] = {{",
                  *(f'R"{d}(' + piece.decode("utf-8", errors="surrogateescape") + f'){d}",' for piece in pieces), "};",
                  f"const std::size_t asset_{i}_sizes[] = {{{', '.join(str(len(p)) for p in pieces) or '0'}}};", ""]
    lines += ["std::string join(const char* const* pieces, const std::size_t* sizes, std::size_t count) {",
              "  std::string out;",
              "  for (std::size_t i = 0; i < count; ++i) out.append(pieces[i], sizes[i]);",
              "  return out;", "}", "", "}  // namespace", "",
              "const std::vector<LabAsset>& lab_assets() {",
              "  static const std::vector<LabAsset> assets = {"]
    lines += [f'      {{"{url}", "{kind}", join(asset_{i}, asset_{i}_sizes, {len(chunks(data))})}},'
              for i, (url, kind, data) in enumerate(assets)]
    lines += ["  };", "  return assets;", "}", "",
              f"bool lab_has_three() {{ return {'true' if have_three else 'false'}; }}", "",
              "}  // namespace illum::lab", ""]
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--source", type=Path, required=True)
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    assets, have_three = collect(args.source.resolve())
    text = cpp(assets, have_three)
    with contextlib.suppress(OSError):  # no file yet, or one that cannot be read: write it
        if args.out.read_text(encoding="utf-8", errors="surrogateescape") == text:
            return 0
    atomic_write_bytes(args.out, text.encode("utf-8", errors="surrogateescape"))
    if not have_three:
        print("embed_assets.py: node_modules/three is missing (run tools/install-deps): the lab's 3D views "
              "will say so", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
