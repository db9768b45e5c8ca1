"""The first process of a sandboxed run: ``python3 -I -S sandbox_init.py CONFIG_JSON`` (sandbox.py starts it).

It runs as the grader, as pid 1 of a fresh pid namespace where the platform allows one, and forks the
test program, which before exec gets a process group of its own, only the descriptors the grader handed
it, the config's resource limits, the unprivileged user (when there is one) and its private HOME with a
clean environment. With ``"private": true`` (mount and IPC namespaces) it first mounts private,
size-limited ``/tmp``, ``/var/tmp``, ``/dev/shm`` and ``/run/lock``, hides the grader's folders under
empty read-only mounts and caps System V shared memory, which the memory limit does not count
(docs/grading-defences.md, "Isolation").

Over the status descriptor, which the program never holds and so cannot forge, it writes one JSON line
``{"pid": N}`` at the start and ``{"exited": CODE}`` or ``{"signal": NUMBER}`` once the program ended and
its group was killed. Standard library only: it must start in milliseconds and trust nothing on the path.
"""
import json
import os
import resource
import signal
import sys

_LIMITS = {
    "memory_bytes": resource.RLIMIT_DATA,
    "processes": resource.RLIMIT_NPROC,
    "file_bytes": resource.RLIMIT_FSIZE,
    "cpu_seconds": resource.RLIMIT_CPU,
    "core_bytes": resource.RLIMIT_CORE,
}


def _say(fd, record):
    try:
        os.write(fd, (json.dumps(record) + "\n").encode())
    except OSError:
        pass


def _kill_group(pid):
    try:
        os.killpg(pid, signal.SIGKILL)
    except OSError:
        pass


_MS_RDONLY, _MS_NOSUID, _MS_NODEV, _MS_REC, _MS_PRIVATE = 1, 2, 4, 16384, 1 << 18


def _mount(source, target, kind, flags, data):
    import ctypes

    libc = ctypes.CDLL(None, use_errno=True)
    libc.mount.argtypes = [ctypes.c_char_p] * 3 + [ctypes.c_ulong, ctypes.c_char_p]
    if libc.mount(source and source.encode(), target.encode(), kind and kind.encode(), flags,
                  data and data.encode()) != 0:
        raise OSError(ctypes.get_errno(), f"mount {target}")


def _write(path, text):
    with open(path, "w", encoding="ascii") as file:
        file.write(text)


def _private(config):
    """Private scratch folders, the grader's folders hidden, shared memory capped (module doc)."""
    _mount(None, "/", None, _MS_REC | _MS_PRIVATE, None)
    megabytes = int(config.get("scratch_mb", 64))
    program = os.path.realpath(config["argv"][0])
    for folder in ("/tmp", "/var/tmp", "/dev/shm", "/run/lock"):
        # Not over the program itself (a tree under /tmp): the grader's clean-up covers that folder then.
        if os.path.isdir(folder) and not program.startswith(os.path.realpath(folder) + "/"):
            _mount("tmpfs", folder, "tmpfs", _MS_NOSUID | _MS_NODEV, f"size={megabytes}m,mode=1777")
    for folder in config.get("hide", []):
        if os.path.isdir(folder):
            _mount("tmpfs", folder, "tmpfs", _MS_RDONLY | _MS_NOSUID | _MS_NODEV, "size=4k,mode=000")
    pages = max(1, int(config.get("shm_bytes", 64 << 20)) // os.sysconf("SC_PAGE_SIZE"))
    _write("/proc/sys/kernel/shmall", str(pages))
    _write("/proc/sys/kernel/shmmax", str(pages * os.sysconf("SC_PAGE_SIZE")))
    _write("/proc/sys/kernel/shm_rmid_forced", "1")


def _child(config):
    keep = sorted(int(fd) for fd in config.get("keep_fds", []))
    os.setpgid(0, 0)
    low = 3  # everything but stdin, stdout, stderr and the records pipe
    for fd in keep + [resource.getrlimit(resource.RLIMIT_NOFILE)[0]]:
        os.closerange(low, fd)
        low = fd + 1
    for fd in keep:
        os.set_inheritable(fd, True)
    for name, value in config.get("limits", {}).items():
        if value is not None and name in _LIMITS:
            resource.setrlimit(_LIMITS[name], (int(value), int(value)))
    if config.get("uid") is not None:
        os.setgroups([])
        os.setgid(int(config["gid"]))
        os.setuid(int(config["uid"]))
        if os.getuid() == 0 or os.geteuid() == 0:
            raise OSError("could not drop root privileges")
    os.umask(0o077)
    if config.get("cwd"):
        os.chdir(config["cwd"])
    argv = config["argv"]
    os.execve(argv[0], argv, config.get("env", {}))


def main():
    config = json.loads(sys.argv[1])
    status_fd = int(config["status_fd"])
    if config.get("private"):
        try:
            _private(config)
        except OSError as error:
            os.write(2, f"illum sandbox: cannot make the run's private folders: {error}\n".encode())
            _say(status_fd, {"exited": 125})
            os._exit(0)
    pid = os.fork()
    if pid == 0:
        try:
            os.close(status_fd)
            _child(config)
        except BaseException as error:  # noqa: BLE001 -- nothing may escape the child
            os.write(2, f"illum sandbox: cannot start {config['argv'][0]}: {error}\n".encode())
        os._exit(127)
    # The grader keeps the only other copies of the pipes; ours would hide the end of the run.
    for fd in config.get("keep_fds", []):
        try:
            os.close(int(fd))
        except OSError:
            pass
    _say(status_fd, {"pid": pid})

    for signum in (signal.SIGTERM, signal.SIGINT):  # the grader's time-out: the program's whole group goes
        signal.signal(signum, lambda *_: _kill_group(pid))
    status = None
    while True:
        try:
            waited, raw = os.wait()
        except ChildProcessError:
            break
        except InterruptedError:
            continue
        if waited == pid:
            status = raw
            break
    _kill_group(pid)  # after a normal exit too: nothing it started may outlive it
    if status is None:
        _say(status_fd, {"lost": True})
    elif os.WIFSIGNALED(status):
        _say(status_fd, {"signal": os.WTERMSIG(status)})
    else:
        _say(status_fd, {"exited": os.waitstatus_to_exitcode(status)})
    os._exit(0)


if __name__ == "__main__":
    main()
