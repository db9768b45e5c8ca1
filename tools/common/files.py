"""Atomic file writes: a temporary beside the target, then a rename; never half a file. A temporary is named
NAME.tmp-XXXXXXXX (mkstemp: the repository's `*.tmp-*` ignore), or NAME.tmp-TAG-PID when the writer tags it,
so that a later run can tell the temporary of a run killed without warning by its PID (remove_dead_temporaries)."""

import fcntl
import os
import tempfile
from pathlib import Path


def atomic_write_bytes(target: Path | str, data: bytes, mode: int = 0o644, tag: str = "") -> None:
    """Writes `target` through a temporary beside it: the data, synced to disk, its mode set, then a rename."""
    target = Path(target)
    if tag:
        tmp = target.with_name(f"{target.name}.tmp-{tag}-{os.getpid()}")
    else:
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, name = tempfile.mkstemp(prefix=target.name + ".tmp-", dir=target.parent)
        os.close(fd)
        tmp = Path(name)
    try:
        with open(tmp, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def atomic_write_text(target: Path | str, text: str, mode: int = 0o644, tag: str = "") -> None:
    atomic_write_bytes(target, text.encode("utf-8"), mode, tag)


def atomic_copy(source: Path | str, target: Path | str) -> None:
    atomic_write_bytes(target, Path(source).read_bytes())


def lock_folder(folder: Path) -> int | None:
    """An exclusive lock on `folder` (an flock, held until the process ends: its descriptor stays open), or
    None when another process holds it."""
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(fd)
        return None
    return fd


def remove_dead_temporaries(folder: Path, tag: str) -> list[Path]:
    """Removes the folder's NAME.tmp-TAG-PID temporaries whose PID no longer runs (and those that name none);
    returns them. A live run's stay."""
    removed = []
    for tmp in sorted(folder.glob(f"*.tmp-{tag}*")):
        pid = tmp.name.rpartition(f".tmp-{tag}-")[2]
        try:
            if pid.isdigit():
                os.kill(int(pid), 0)
                continue  # another run, still writing
        except ProcessLookupError:
            pass
        except PermissionError:
            continue
        tmp.unlink()
        removed.append(tmp)
    return removed
