"""Running a student's code apart from the grader (docs/grading-defences.md, "Isolation" and "Threat model").

The code runs as an unprivileged user (``--as-user``; setup.sh creates it) with a private HOME and TMPDIR
and a clean environment, in a process group and, where root may ``unshare``, pid (and mount and IPC)
namespaces of its own whose first process is sandbox_init.py, under resource limits (``Limits``); every
process of the user is killed after each program (``reap``). Without root there is no second user: the
code runs as whoever runs the grader, which is the student's own machine (``tools/grade --student``).
"""
from __future__ import annotations

import contextlib
import fcntl
import functools
import json
import os
import pwd
import resource
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

INIT = Path(__file__).resolve().with_name("sandbox_init.py")

# Environment variables a test program or a build may see; everything else
# the grader has (tokens, paths of the autograder) is left out.
_PASSED_ENVIRONMENT = ("PATH", "LANG", "LC_ALL", "TZ", "OMP_NUM_THREADS", "OMP_PROC_BIND", "OMP_WAIT_POLICY")


class SandboxError(Exception):
    """The sandbox cannot be set up as asked (a user missing, no root...)."""


@dataclass(frozen=True)
class Account:
    """The unprivileged user that runs students' code."""

    name: str
    uid: int
    gid: int
    home: str = "/nonexistent"

    @staticmethod
    def lookup(name: str) -> "Account | None":
        try:
            entry = pwd.getpwnam(name)
        except KeyError:
            return None
        return Account(entry.pw_name, entry.pw_uid, entry.pw_gid, entry.pw_dir)


def create_account(name: str) -> Account:
    """The user ``name``, created (a system user with its own group, no home,
    no login shell) if it does not exist yet. Needs root."""
    found = Account.lookup(name)
    if found is not None:
        if found.uid == 0:
            raise SandboxError(f"the user {name} is root; choose an unprivileged user")
        return found
    if os.geteuid() != 0:
        raise SandboxError(f"the user {name} does not exist, and only root can create it")
    useradd = shutil.which("useradd") or "/usr/sbin/useradd"
    shell = "/usr/sbin/nologin" if os.path.exists("/usr/sbin/nologin") else "/bin/false"
    command = [useradd, "--system", "--user-group", "--no-create-home", "--home-dir", "/nonexistent",
               "--shell", shell, name]
    try:
        done = subprocess.run(command, capture_output=True, text=True, check=False)
    except OSError as error:
        raise SandboxError(f"cannot create the user {name}: {error}") from error
    found = Account.lookup(name)
    if found is None:
        raise SandboxError(f"cannot create the user {name}: {' '.join(command)} said: "
                           f"{(done.stderr or done.stdout).strip() or f'exit status {done.returncode}'}")
    return found


def _megabytes(name: str, default: int) -> int:
    value = os.environ.get(name, "").strip()
    if not value:
        return default
    try:
        number = int(value)
    except ValueError:
        raise SandboxError(f"{name}={value!r} is not a whole number of megabytes") from None
    if number <= 0:
        raise SandboxError(f"{name}={value} must be positive")
    return number


@dataclass
class Limits:
    """What one test program, or one build, may use (environment variables in docs/grading-reference.md, "Options")."""

    memory_mb: int = 1024        # ILLUM_GRADE_MEMORY_MB: data memory of one test program
    processes: int = 256         # ILLUM_GRADE_PROCESSES: processes and threads of the user at once
    file_mb: int = 64            # largest file a test program may write
    output_bytes: int = 64 * 1024  # the tail of a program's output that is kept
    build_memory_mb: int = 4096  # one compiler or linker process

    @staticmethod
    def from_environment() -> "Limits":
        return Limits(memory_mb=_megabytes("ILLUM_GRADE_MEMORY_MB", 1024),
                      processes=_megabytes("ILLUM_GRADE_PROCESSES", 256),
                      build_memory_mb=_megabytes("ILLUM_GRADE_BUILD_MEMORY_MB", 4096))


@functools.cache
def _unshare_works(*flags: str) -> bool:
    """Whether ``unshare FLAGS --fork`` works here: root, and not forbidden by a container (Docker's default
    profile forbids mount and IPC namespaces) or by ILLUM_GRADE_NO_PID_NAMESPACE=1."""
    unshare = shutil.which("unshare")
    if not unshare or os.geteuid() != 0 or os.environ.get("ILLUM_GRADE_NO_PID_NAMESPACE") == "1":
        return False
    try:
        done = subprocess.run([unshare, *flags, "--fork", "--kill-child", "--", "true"],
                              capture_output=True, timeout=10, check=False)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return done.returncode == 0


@dataclass
class Launched:
    """A sandboxed program that was started: its launcher process and the pipes to read."""

    process: subprocess.Popen
    status_fd: int
    output_fd: int
    records_fd: int | None
    scratch: Path
    program_pid: int | None = None  # the program's pid as the grader sees it (None in a namespace)


@dataclass
class Sandbox:
    account: Account | None = None
    limits: Limits = field(default_factory=Limits)
    namespace: bool | None = None  # None: use one when available
    hide: list[str] = field(default_factory=list)  # folders a run must not see (the grader's own)
    private: bool | None = None  # mount and IPC namespaces; None: when available

    def __post_init__(self) -> None:
        if self.account is not None and os.geteuid() != 0:
            raise SandboxError(f"running code as the user {self.account.name} needs root")
        if self.namespace is None:
            self.namespace = _unshare_works("--pid")
        if self.private is None:
            self.private = bool(self.namespace) and _unshare_works("--pid", "--mount", "--ipc")

    # --- what the student's code sees -------------------------------------------------------

    def environment(self, home: Path, extra: dict[str, str] | None = None) -> dict[str, str]:
        env = {k: os.environ[k] for k in _PASSED_ENVIRONMENT if k in os.environ}
        env.setdefault("PATH", "/usr/local/bin:/usr/bin:/bin")
        # Each OpenMP thread's stack counts against the memory limit: on a machine with many cores
        # the default (one thread per core) would spend the limit on stacks alone.
        env.setdefault("OMP_NUM_THREADS", str(min(os.cpu_count() or 1, 4)))
        env.setdefault("LANG", "C.UTF-8")
        env.update(HOME=str(home), TMPDIR=str(home / "tmp"))
        if self.account is not None:
            env.update(USER=self.account.name, LOGNAME=self.account.name)
        env.update(extra or {})
        return env

    def make_scratch(self) -> Path:
        """A fresh private HOME (with TMPDIR inside) for one run, owned by the account."""
        folder = Path(tempfile.mkdtemp(prefix="illum-run-", dir=self._scratch_base()))
        home = folder / "home"
        (home / "tmp").mkdir(parents=True)
        if self.account is not None:
            folder.chmod(0o711)
            for path in (home, home / "tmp"):
                os.chown(path, self.account.uid, self.account.gid)
                path.chmod(0o700)
        return folder

    @contextlib.contextmanager
    def hidden_folders(self):
        """While the student's programs run: ``hide`` out of their reach. A private mount does it
        where there are namespaces; elsewhere the folders are closed to others (0700) meanwhile."""
        closed: list[tuple[str, int]] = []
        if self.account is not None and not self.private:
            for folder in self.hide:
                try:
                    closed.append((folder, stat.S_IMODE(os.stat(folder).st_mode)))
                    os.chmod(folder, 0o700)
                except OSError:
                    pass
        try:
            yield
        finally:
            for folder, mode in closed:
                os.chmod(folder, mode)

    def _scratch_base(self) -> str | None:
        """Where runs' HOMEs go: not /tmp when a run gets a private /tmp of its own (it would hide them)."""
        if not self.private:
            return None
        base = Path("/var/lib/illum-grade/runs")
        base.mkdir(parents=True, exist_ok=True)
        base.chmod(0o711)
        return str(base)

    # --- running a test program ------------------------------------------------------------

    def launch(self, argv: list[str], records: bool = True, cpu_seconds: float | None = None,
               extra_env: dict[str, str] | None = None) -> Launched:
        """Starts ``argv`` in the sandbox. Its stdout and stderr go to one pipe (``output_fd``), the
        reporter's records to another (``records_fd``), whose write end it finds in ILLUM_GRADE_RECORDS_FD."""
        argv = [os.path.abspath(argv[0]) if os.sep in str(argv[0]) else str(argv[0]), *argv[1:]]
        scratch = self.make_scratch()
        status_r, status_w = os.pipe()
        output_r, output_w = os.pipe()
        records_r, records_w = os.pipe() if records else (None, None)
        keep = [records_w] if records_w is not None else []
        extra = dict(extra_env or {})
        if records_w is not None:
            extra["ILLUM_GRADE_RECORDS_FD"] = str(records_w)
        limits = {
            "memory_bytes": self.limits.memory_mb * 1024 * 1024,
            "file_bytes": self.limits.file_mb * 1024 * 1024,
            "core_bytes": 0,
            "cpu_seconds": int(cpu_seconds) + 5 if cpu_seconds and cpu_seconds != float("inf") else None,
        }
        if self.account is not None:
            limits["processes"] = self.limits.processes
        config = {
            "argv": [str(a) for a in argv], "status_fd": status_w, "keep_fds": keep, "limits": limits,
            "cwd": str(scratch / "home"), "env": self.environment(scratch / "home", extra),
            "uid": self.account.uid if self.account else None, "gid": self.account.gid if self.account else None,
            "private": bool(self.private), "hide": self.hide, "shm_bytes": self.limits.memory_mb << 20,
            "scratch_mb": self.limits.file_mb,
        }
        command = [sys.executable, "-I", "-S", str(INIT), json.dumps(config)]
        if self.namespace:
            flags = ["--pid"] + (["--mount", "--ipc"] if self.private else [])
            command = [shutil.which("unshare") or "unshare", *flags, "--fork", "--kill-child", "--", *command]
        try:
            process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=output_w, stderr=output_w,
                                       pass_fds=[status_w, *keep], start_new_session=True, close_fds=True)
        except OSError:
            _close(status_r, status_w, output_r, output_w, records_r, records_w)
            shutil.rmtree(scratch, ignore_errors=True)
            raise
        _close(status_w, output_w, records_w)  # only the sandbox holds the write ends now
        return Launched(process, status_r, output_r, records_r, scratch)

    def stop(self, launched: Launched) -> None:
        """Kills a launched program and everything it started."""
        for target in (launched.process.pid, launched.program_pid):
            kill_group(target)
        with contextlib.suppress(ProcessLookupError):
            launched.process.kill()

    def finish(self, launched: Launched) -> list[str]:
        """After a run: the launcher waited for, the program's group and (with a user) every process of the
        user killed, the scratch folder removed. Returns a description of each process still alive."""
        if not self.namespace:
            kill_group(launched.program_pid)
        try:
            launched.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.stop(launched)
            launched.process.wait()
        survivors = self.reap()
        self.clean_shared_folders()  # nothing of one program's reaches the next
        _close(launched.status_fd, launched.output_fd, launched.records_fd)
        shutil.rmtree(launched.scratch, ignore_errors=True)
        return survivors

    # --- every process and file of the user -------------------------------------------------

    def reap(self, patience: float = 10.0) -> list[str]:
        """Kills every process of the account until none is left (fork bombs
        included); returns what was found alive. Without an account, nothing."""
        if self.account is None:
            return []
        found: list[str] = []
        deadline = time.monotonic() + patience
        while True:
            alive = user_processes(self.account.uid)
            if not alive:
                return found
            found.extend(f"pid {pid} ({name})" for pid, name in alive if f"pid {pid} ({name})" not in found)
            kill_all_of(self.account)
            if time.monotonic() > deadline:
                raise SandboxError(f"processes of {self.account.name} survive SIGKILL: {', '.join(found[:10])}")
            time.sleep(0.02)

    def shared_memory_bytes(self) -> int:
        """System V and POSIX shared memory the account holds outside a private IPC namespace
        (the memory limit of a process does not count it)."""
        if self.account is None or self.private:
            return 0
        return (sum(size for _, size in _shm_segments(self.account.uid))
                + sum(info.st_blocks * 512 for _, info in _owned("/dev/shm", self.account.uid)))

    def clean_shared_folders(self) -> None:
        """Removes what the account left in the world-writable folders and its shared memory
        (a channel from one run, or one student, to the next)."""
        if self.account is None:
            return
        ipcrm = shutil.which("ipcrm") or "/usr/bin/ipcrm"
        for shmid, _ in _shm_segments(self.account.uid):  # System V segments; POSIX ones are files
            subprocess.run([ipcrm, "-m", shmid], capture_output=True, check=False)
        for folder in ("/tmp", "/var/tmp", "/dev/shm", "/run/lock"):
            for entry, info in _owned(folder, self.account.uid):
                if stat.S_ISDIR(info.st_mode):
                    shutil.rmtree(entry.path, ignore_errors=True)
                else:
                    with contextlib.suppress(OSError):
                        os.unlink(entry.path)

    def can_reach(self, path: Path) -> bool:
        """Whether the account can list and enter ``path`` (every folder above it searchable)."""
        return self.account is None or _as_account(self.account, lambda: os.access(path, os.R_OK | os.X_OK))

    # --- builds ----------------------------------------------------------------------------

    def build_preexec(self):
        """For Popen(preexec_fn=...): a build step as the account, with the build's limits (a compiler fed
        /dev/zero stops at the memory limit)."""
        memory = self.limits.build_memory_mb * 1024 * 1024
        account = self.account

        def preexec() -> None:
            os.setsid()
            resource.setrlimit(resource.RLIMIT_DATA, (memory, memory))
            resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
            if account is not None:
                resource.setrlimit(resource.RLIMIT_NPROC, (self.limits.processes, self.limits.processes))
                _become(account)

        return preexec

    def build_environment(self, home: Path) -> dict[str, str]:
        """The environment of a build: the grader's, minus what the student's user must not see; ccache is
        off (a shared cache could carry one student's objects into another's build)."""
        env = dict(os.environ)
        if self.account is not None:
            env = self.environment(home)
            for key in ("CMAKE_BUILD_PARALLEL_LEVEL", "CXX", "CC", "CXXFLAGS", "LDFLAGS"):
                if key in os.environ:
                    env[key] = os.environ[key]
            env["CCACHE_DISABLE"] = "1"
        return env

    def give_tree(self, folder: Path) -> None:
        """Makes ``folder`` (a build tree) the account's, so that its build can write there."""
        if self.account is not None and folder.exists():
            chown_tree(folder, self.account.uid, self.account.gid)

    def take_tree(self, folder: Path) -> None:
        """Takes ``folder`` back: root's, and writable by nobody else (tests run next)."""
        if self.account is not None and folder.exists():
            chown_tree(folder, 0, 0, strip_write=True)


LOCK_FOLDER = Path("/run/illum-grade")  # root's, 0700: a student's process can neither open nor hold a lock


@contextlib.contextmanager
def user_lock(name: str):
    """Holds the grading lock of the user ``name`` for the block (as root; without root, nothing). A run kills
    every process of its user after each program, so a second run sharing the user (two batches, two CI jobs)
    waits, saying so. An flock: released when its holder exits however it ends, and not inherited."""
    if os.geteuid() != 0:
        yield
        return
    with contextlib.suppress(FileExistsError):
        LOCK_FOLDER.mkdir(mode=0o700)
    info = os.lstat(LOCK_FOLDER)
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != 0 or info.st_mode & 0o077:
        raise SandboxError(f"{LOCK_FOLDER} must be a folder that only root may enter (found mode "
                           f"{stat.filemode(info.st_mode)}, owner {info.st_uid}): remove it and run again")
    fd = os.open(LOCK_FOLDER / f"{name}.lock", os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o600)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            print(f"grade: another grading run uses the user {name}; waiting until it ends "
                  f"(ILLUM_GRADE_USER gives a run a user of its own)", file=sys.stderr, flush=True)
            fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def chown_tree(folder: Path, uid: int, gid: int, strip_write: bool = False) -> None:
    """chown -R without following links; ``strip_write`` also removes group and other write and set-id bits."""
    for path in [folder, *folder.rglob("*")]:
        try:
            info = path.lstat()
            os.chown(path, uid, gid, follow_symlinks=False)
            if strip_write and not stat.S_ISLNK(info.st_mode):
                path.chmod(stat.S_IMODE(info.st_mode) & ~0o7022)
        except OSError:
            pass


_TICKS = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


def descendants_cpu_seconds(root_pid: int) -> float:
    """utime + stime of ``root_pid`` and every process below it, from /proc (children that ended
    and were waited for count in their parent's cutime + cstime): what the per-test limits count,
    every thread's processor time, so that a loaded machine does not fail a test."""
    children: dict[int, list[int]] = {}
    times: dict[int, float] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as stat_file:
                fields = stat_file.read().rsplit(b")", 1)[1].split()
        except (OSError, IndexError):
            continue
        children.setdefault(int(fields[1]), []).append(int(entry))
        times[int(entry)] = sum(int(f) for f in fields[11:15]) / _TICKS  # utime stime cutime cstime
    below: set[int] = set()
    todo = [root_pid]
    while todo:  # a set, not a walk: a pid reused while /proc is read can make a loop
        pid = todo.pop()
        if pid not in below:
            below.add(pid)
            todo += children.get(pid, [])
    return sum(times.get(pid, 0.0) for pid in below)


def user_processes(uid: int) -> list[tuple[int, str]]:
    """(pid, name) of every process whose real or effective user is ``uid``."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/status", encoding="utf-8", errors="replace") as status:
                fields = dict(line.split(":", 1) for line in status if ":" in line)
        except OSError:
            continue
        uids = fields.get("Uid", "").split()
        if fields.get("State", "").strip()[:1] in ("Z", "X"):
            continue  # a zombie is dead already; only its parent can make it go
        if uids and str(uid) in uids[:2]:
            found.append((int(entry), fields.get("Name", "?").strip()))
    return found


def kill_all_of(account: Account) -> None:
    """kill(-1, SIGKILL) as the account: the kernel sends it to every process of that user at once, so a
    process that forks or changes its group cannot slip through between a listing and a kill."""
    _as_account(account, lambda: os.kill(-1, signal.SIGKILL))


def _close(*fds: int | None) -> None:
    for fd in fds:
        if fd is not None:
            with contextlib.suppress(OSError):
                os.close(fd)


def kill_group(pid: int | None) -> None:
    """SIGKILL to the process group ``pid`` leads, if there is one still."""
    if pid:
        with contextlib.suppress(OSError):
            os.killpg(pid, signal.SIGKILL)


def _become(account: Account) -> None:
    """This process (a child about to act for the student) becomes the account, with no other group."""
    os.setgroups([])
    os.setgid(account.gid)
    os.setuid(account.uid)


def _as_account(account: Account, action) -> bool:
    """Runs ``action`` in a child process that has become the account; whether it returned a true value
    (False when it raised, or the child could not become the account)."""
    pid = os.fork()
    if pid == 0:
        try:
            _become(account)
            os._exit(0 if action() else 1)
        except BaseException:  # noqa: BLE001 -- the child must end here, whatever happened
            os._exit(2)
    _, status = os.waitpid(pid, 0)
    return os.waitstatus_to_exitcode(status) == 0


def _owned(folder: str, uid: int) -> list[tuple[os.DirEntry, os.stat_result]]:
    """The entries of ``folder`` that ``uid`` owns, with their lstat (none where it cannot be read)."""
    found = []
    with contextlib.suppress(OSError):
        for entry in os.scandir(folder):
            with contextlib.suppress(OSError):
                info = entry.stat(follow_symlinks=False)
                if info.st_uid == uid:
                    found.append((entry, info))
    return found


def _shm_segments(uid: int) -> list[tuple[str, int]]:
    """(id, bytes) of every System V shared memory segment ``uid`` owns (/proc/sysvipc/shm)."""
    try:
        with open("/proc/sysvipc/shm", encoding="ascii") as table:
            next(table, None)
            rows = [line.split() for line in table]
    except OSError:
        return []
    return [(fields[1], int(fields[3])) for fields in rows if len(fields) > 7 and int(fields[7]) == uid]
