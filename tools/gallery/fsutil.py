"""Atomic file writes: a temporary name in the same folder, then a rename.

An interrupted run never leaves a half-written index or deck behind; the
temporary names match the repository's `*.tmp-*` ignore pattern.
"""
from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path


def _temp_beside(target: Path) -> Path:
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, name = tempfile.mkstemp(prefix=target.name + ".tmp-", dir=target.parent)
    os.close(fd)
    return Path(name)


def atomic_write_bytes(target: Path | str, data: bytes) -> None:
    target = Path(target)
    tmp = _temp_beside(target)
    try:
        with open(tmp, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def atomic_write_text(target: Path | str, text: str) -> None:
    atomic_write_bytes(target, text.encode("utf-8"))


def atomic_copy(source: Path | str, target: Path | str) -> None:
    target = Path(target)
    tmp = _temp_beside(target)
    try:
        shutil.copyfile(source, tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def temp_path_beside(target: Path | str) -> Path:
    """A fresh temporary file name next to `target` (for tools that write it)."""
    return _temp_beside(Path(target))
