"""Atomic file writes: a temporary name beside the target, then a rename; never half a file."""
from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path


def temp_path_beside(target: Path | str) -> Path:
    """A fresh temporary file next to `target` (its name matches the repository's `*.tmp-*` ignore)."""
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, name = tempfile.mkstemp(prefix=target.name + ".tmp-", dir=target.parent)
    os.close(fd)
    return Path(name)


def _replace(target: Path | str, fill, mode: int) -> None:
    tmp = temp_path_beside(target)
    try:
        fill(tmp)
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def atomic_write_bytes(target: Path | str, data: bytes, mode: int = 0o644) -> None:
    def fill(tmp: Path) -> None:
        with open(tmp, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())

    _replace(target, fill, mode)


def atomic_write_text(target: Path | str, text: str, mode: int = 0o644) -> None:
    atomic_write_bytes(target, text.encode("utf-8"), mode)


def atomic_copy(source: Path | str, target: Path | str) -> None:
    _replace(target, lambda tmp: shutil.copyfile(source, tmp), 0o644)
