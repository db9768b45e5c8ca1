"""Exercise files that try to do more than compute, found outside the student's process (code in the
test's process can always lie to it); a finding is advice for the instructor's review, never a verdict
(docs/grading-defences.md).

* `scan_source`: an exercise unit includes only headers of illum/, the C++ standard library and GLM,
  and does not mention doctest, start processes, end the program, use assembly or system calls, open
  /proc, declare extern "C" functions, run code at load time or paste tokens;
* `scan_object`: the compiled unit defines only names of namespace illum (or shared template instances)
  that the library does not already have, and uses no doctest, process control, raw file access,
  environment, signals or dynamic loading; an unusual C function is only shown to instructors.
"""
from __future__ import annotations

import functools
import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from common.cpp_text import blank_comments


@dataclass
class Finding:
    file: str      # exercises/NN_topic/name.cpp
    line: int      # 0 when it comes from the object file
    what: str      # one line a student can act on
    serious: bool = True  # False: shown to instructors only, nothing fails

    def describe(self) -> str:
        return f"{self.file}:{self.line}: {self.what}" if self.line else f"{self.file}: {self.what}"


# C++20's standard library headers and the C headers it keeps (<cmath> and <math.h> alike).
STANDARD_HEADERS = set("""
algorithm any array atomic barrier bit bitset charconv chrono codecvt compare complex concepts
condition_variable coroutine deque exception execution filesystem format forward_list fstream functional
future initializer_list iomanip ios iosfwd iostream istream iterator latch limits list locale map memory
memory_resource mutex new numbers numeric optional ostream queue random ranges ratio regex scoped_allocator
semaphore set shared_mutex source_location span sstream stack stdexcept stop_token streambuf string
string_view strstream syncstream system_error thread tuple type_traits typeindex typeinfo unordered_map
unordered_set utility valarray variant vector version
cassert cctype cerrno cfenv cfloat cinttypes climits clocale cmath csetjmp csignal cstdarg cstddef cstdint
cstdio cstdlib cstring ctime cuchar cwchar cwctype
assert.h ctype.h errno.h fenv.h float.h inttypes.h limits.h locale.h math.h setjmp.h signal.h stdarg.h
stddef.h stdint.h stdio.h stdlib.h string.h time.h uchar.h wchar.h wctype.h
""".split())
# Standard headers that reach outside the computation (files, signals, jumps). Not <cstdlib>: it is fine for
# std::abs and friends, and its exit() and system() are caught by name below.
OUTSIDE_HEADERS = {"filesystem", "fstream", "csignal", "signal.h", "csetjmp", "setjmp.h"}

_SOURCE_RULES: list[tuple[re.Pattern, str]] = [
    (re.compile(r"doctest", re.I), "mentions doctest, the test framework: exercise code may not touch the tests"),
    (re.compile(r"\b(?:fork|vfork|clone3?|execv?p?e?|execl[ep]?|fexecve|posix_spawnp?|system|popen)\s*\("),
     "starts a process (fork/exec/system/popen): exercise code may only compute"),
    (re.compile(r"\b(?:exit|_exit|_Exit|quick_exit|atexit|at_quick_exit)\s*\("),
     "ends the program (exit): report an error by throwing an exception instead"),
    (re.compile(r"\b(?:asm|__asm__|__asm)\b"), "uses inline assembly"),
    (re.compile(r"\bsyscall\b"), "makes a system call (syscall)"),
    (re.compile(r"\bextern\s*\"C"), "declares extern \"C\" functions (such as its own write()): exercise code "
                                      "defines only the functions of its header"),  # on the text with strings
    (re.compile(r"\b(?:constructor|destructor)\b\s*\)\s*\)|\[\[\s*gnu::(?:constructor|destructor)"),
     "runs code when the program starts or ends (a constructor/destructor attribute)"),
    (re.compile(r"##"), "builds names by token pasting (##), which hides them from this check"),
    (re.compile(r"\b(?:dlopen|dlsym|dlmopen|ptrace|mprotect|getenv|secure_getenv|setenv|putenv)\b"),
     "loads code, changes memory protection or reads the environment"),
]
_PROC = re.compile(r"/proc\b|/dev/fd\b|/dev/std|/dev/tty")
_INCLUDE = re.compile(r"^\s*#\s*include\s*(.*)$")
_INCLUDE_NAME = re.compile(r"^([<\"])([^>\"]*)[>\"]")


def _include_problem(argument: str) -> str:
    """Why an #include may not be in an exercise file, or ''."""
    match = _INCLUDE_NAME.match(argument.strip())
    if not match:
        return f"computes the name of an #include ({argument.strip()[:60]}); name the header itself"
    bracket, name = match.groups()
    parts = PurePosixPath(name).parts
    if ".." in parts or name.startswith("/"):
        return f"includes \"{name}\" by a path that leaves the include folders"
    if parts[:1] == ("illum",):
        return "" if name.endswith((".hpp", ".h")) else f"includes {name}, a source file: include only headers"
    if parts[:1] == ("glm",) or (bracket == "<" and name in STANDARD_HEADERS - OUTSIDE_HEADERS):
        return ""
    if bracket == "<" and name in OUTSIDE_HEADERS:
        return f"includes <{name}>: exercise code may not touch files, signals or jumps"
    shown = f"<{name}>" if bracket == "<" else f"\"{name}\""
    return f"includes {shown}, which is outside illum/, the C++ standard library and GLM"


def scan_source(text: str, file: str) -> list[Finding]:
    """The serious findings of one exercise file's text (module doc), one per kind, at its first line, naming the
    other lines where it comes back."""
    grouped: dict[str, list[int]] = {}
    for finding in _scan_lines(text, file):
        grouped.setdefault(finding.what, []).append(finding.line)
    out = []
    for what, found in grouped.items():
        lines = sorted(set(filter(None, found)))
        extra = f" (also line{'s' if len(lines) > 2 else ''} {', '.join(map(str, lines[1:8]))}" \
                f"{', …' if len(lines) > 8 else ''})" if len(lines) > 1 else ""
        out.append(Finding(file, found[0], what + extra))
    return sorted(out, key=lambda f: f.line)


def _scan_lines(text: str, file: str) -> list[Finding]:
    code, plain = blank_comments(text), blank_comments(text, strings=False)
    findings = []
    for number, (line, plain_line) in enumerate(zip(code.splitlines(), plain.splitlines()), start=1):
        if _INCLUDE.match(line):
            # The header's name is a string to the scanner: read it from the uncommented text.
            if problem := _include_problem(_INCLUDE.match(plain_line).group(1)):
                findings.append(Finding(file, number, problem))
            continue
        for pattern, why in _SOURCE_RULES:
            if pattern.search(plain_line if "extern" in pattern.pattern else line):
                findings.append(Finding(file, number, why))
        if _PROC.search(plain_line):
            findings.append(Finding(file, number, "names /proc or a descriptor's device (/dev/fd): exercise "
                                                  "code may not look into the running program"))
    # "doctest" split over a line ("doc\\\n test") or hidden in a macro is still found on the joined text.
    joined = re.sub(r"\\\n", "", code)
    if re.search(r"doctest", joined, re.I) and not any("doctest" in f.what for f in findings):
        findings.append(Finding(file, 0, _SOURCE_RULES[0][1]))
    return findings


# C functions an exercise may call (the compiler calls most of them by itself).
_HARMLESS_C = set("""
sqrt sqrtf sqrtl cbrt cbrtf pow powf exp expf exp2 exp2f expm1 log logf log2 log2f log10 log10f log1p log1pf
sin sinf cos cosf tan tanf asin asinf acos acosf atan atanf atan2 atan2f sinh cosh tanh asinh acosh atanh
sincos sincosf hypot hypotf fma fmaf fmod fmodf remainder floor floorf ceil ceilf trunc truncf round roundf
lround llround nearbyint rint lrint llrint modf frexp ldexp scalbn copysign nextafter fmin fmax fdim erf erfc
tgamma lgamma fabs fabsf abs labs llabs div ldiv
memcpy memmove memset memcmp memchr strlen strcmp strncmp strchr strrchr strstr strtod strtof strtold strtol
strtoll strtoul strtoull __errno_location
printf puts putchar fputs fputc putc fwrite fflush fprintf vprintf vfprintf snprintf sprintf vsnprintf vsprintf
stdout stderr __printf_chk __fprintf_chk __sprintf_chk __snprintf_chk __vsnprintf_chk __vfprintf_chk
__memcpy_chk __memmove_chk __memset_chk __strcpy_chk __strcat_chk
abort __assert_fail __stack_chk_fail __cxa_atexit __cxa_guard_acquire __cxa_guard_release __cxa_guard_abort
__cxa_allocate_exception __cxa_free_exception __cxa_throw __cxa_begin_catch __cxa_end_catch __cxa_rethrow
__cxa_pure_virtual __cxa_deleted_virtual __cxa_bad_cast __cxa_bad_typeid __cxa_thread_atexit
__cxa_get_exception_ptr __cxa_call_unexpected __cxa_current_exception_type __dynamic_cast
_Unwind_Resume __gxx_personality_v0 __dso_handle _GLOBAL_OFFSET_TABLE_ __tls_get_addr
pthread_mutex_lock pthread_mutex_unlock pthread_mutex_trylock pthread_once pthread_key_create
pthread_getspecific pthread_setspecific __pthread_key_create pthread_cond_wait pthread_cond_signal
pthread_cond_broadcast pthread_self pthread_equal nanosleep sched_yield
rand srand qsort bsearch isalpha isdigit isspace toupper tolower __ctype_b_loc __ctype_toupper_loc
__ctype_tolower_loc
""".split())
_HARMLESS_C_PREFIXES = ("GOMP_", "omp_", "__atomic_", "__sync_", "DW.ref.", "__isinf", "__isnan", "__finite",
                        "__fpclassify", "__signbit")
# C functions that reach outside the computation: a file using one is flagged.
_FORBIDDEN_C = {
    "process": """fork vfork clone clone3 execl execle execlp execv execve execvp execvpe fexecve posix_spawn
        posix_spawnp system popen pclose wait waitpid kill killpg raise ptrace prctl setsid setpgid unshare daemon
        pthread_atfork""",
    "exit": "exit _exit _Exit quick_exit atexit at_quick_exit on_exit",
    "system call": "syscall",
    "file": """open open64 openat openat64 creat creat64 fopen fopen64 freopen fdopen write writev pwrite pwrite64
        read pread readv dprintf vdprintf close dup dup2 dup3 pipe pipe2 mkfifo unlink rename remove truncate
        ftruncate sendfile splice tee socket connect send sendto sendmsg fcntl ioctl mmap mmap64 munmap mprotect
        chdir chmod chown symlink link opendir readdir""",
    "environment": "getenv secure_getenv setenv putenv unsetenv environ __environ",
    "signal": """signal sigaction sigprocmask setjmp _setjmp __sigsetjmp longjmp siglongjmp __longjmp_chk alarm
        setitimer""",
    "dynamic loading": "dlopen dlsym dlvsym dlmopen dladdr",
}
_FORBIDDEN_BY_NAME = {name: kind for kind, names in _FORBIDDEN_C.items() for name in names.split()}
# C++ library parts that reach outside the computation (demangled prefixes).
_FORBIDDEN_CXX = [
    ("doctest::", "uses doctest, the test framework"),
    ("std::basic_ofstream", "writes files (std::ofstream)"),
    ("std::basic_ifstream", "reads files (std::ifstream)"),
    ("std::basic_fstream", "opens files (std::fstream)"),
    ("std::basic_filebuf", "opens files (std::filebuf)"),
    ("std::filesystem::", "uses std::filesystem"),
    ("std::__cxx11::filesystem::", "uses std::filesystem"),
    ("__gnu_cxx::stdio_filebuf", "opens descriptors as streams"),
    ("__gnu_cxx::stdio_sync_filebuf", "opens descriptors as streams"),
]
_ILLUM_DEFINED = ("illum::", "vtable for illum::", "typeinfo for illum::", "typeinfo name for illum::",
                  "guard variable for illum::", "VTT for illum::", "construction vtable for illum::",
                  "non-virtual thunk to illum::", "virtual thunk to illum::", "covariant return thunk to illum::",
                  "reference temporary #", "TLS init function for illum::", "TLS wrapper function for illum::")


def object_symbols(path: Path) -> tuple[list[tuple[str, str, str]], list[tuple[str, str]]]:
    """([(type, mangled, demangled) defined globally], [(mangled, demangled) used]) of an object file."""
    nm = shutil.which("nm")
    if nm is None:
        raise FileNotFoundError("nm (binutils) is not installed")
    done = subprocess.run([nm, "-P", "--no-sort", str(path)], capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise OSError(f"nm {path}: {done.stderr.strip()}")
    defined, used = [], []
    for line in done.stdout.splitlines():
        parts = line.split()
        if len(parts) < 2:
            continue
        name, kind = parts[0], parts[1]
        if kind in "Uwv" and len(parts) == 2:  # undefined (weak undefined too)
            used.append(name)
        elif kind in "TDBRWVGSCui":  # defined and global
            defined.append((kind, name))
    demangled = names = [n for _, n in defined] + used
    if names and (cxxfilt := shutil.which("c++filt")):  # without c++filt, or if it answers oddly: the raw names
        done = subprocess.run([cxxfilt], input="\n".join(names) + "\n", capture_output=True, text=True, check=False)
        demangled = out if len(out := done.stdout.splitlines()) == len(names) else names
    return [(k, n, d) for (k, n), d in zip(defined, demangled)], list(zip(used, demangled[len(defined):]))


@functools.cache
def runtime_symbols() -> set[str]:
    """The names the C, maths, C++, GCC and OpenMP runtime libraries export: a program that defines one of them
    replaces it for every caller (interposition)."""
    found: set[str] = set()
    nm, compiler = shutil.which("nm"), shutil.which("c++") or shutil.which("g++")
    for library in ("libc.so.6", "libm.so.6", "libstdc++.so.6", "libgcc_s.so.1", "libgomp.so.1"):
        path = subprocess.run([compiler, f"-print-file-name={library}"], capture_output=True, text=True,
                              check=False).stdout.strip() if compiler else ""
        if nm and path and Path(path).is_file():
            done = subprocess.run([nm, "-D", "-P", "--defined-only", path], capture_output=True, text=True,
                                  check=False)
            found.update(line.split()[0].split("@", 1)[0] for line in done.stdout.splitlines() if line.strip())
    # Whatever the libraries found, these are never an exercise's to define.
    return found | set(_FORBIDDEN_BY_NAME) | {"main", "malloc", "free", "calloc", "realloc", "stdout", "stderr",
                                              "stdin"}


_NM_MEMBER = re.compile(r"^.*\[([^\]]+)\]:\s+(\S+)\s+([A-Za-z])")


def library_definitions(archive: Path, skip_members: set[str]) -> dict[str, str]:
    """Strong symbol -> archive member, for every member of the library but ``skip_members``."""
    nm = shutil.which("nm")
    if nm is None or not archive.is_file():
        return {}
    done = subprocess.run([nm, "-P", "--defined-only", "--extern-only", "-A", str(archive)], capture_output=True,
                          text=True, check=False)
    found: dict[str, str] = {}
    for line in done.stdout.splitlines():  # archive[member]: name type ...
        if (match := _NM_MEMBER.match(line)) and match[1] not in skip_members and match[3] in "TDBR":
            found.setdefault(match[2], match[1])
    return found


def scan_object(path: Path, file: str, library: dict[str, str] | None = None) -> list[Finding]:
    """The findings of one exercise unit's compiled object (module doc)."""
    defined, used = object_symbols(path)
    findings: dict[str, Finding] = {}  # each finding once, in the order found

    def add(what: str, serious: bool = True) -> None:
        findings.setdefault(what, Finding(file, 0, what, serious))

    for kind, name, shown in defined:
        if name.startswith("DW.ref."):
            continue
        if "doctest::" in shown or "doctest" in name:
            add(f"defines {shown[:120]}, part of doctest, the test framework")
        elif not name.startswith("_Z"):
            if name in runtime_symbols():
                add(f"defines `{name}`, which the C or C++ runtime already has: the program would call this "
                    "one instead (exercise code defines only the functions of its header, in namespace illum)")
            else:
                add(f"defines the C-linkage name `{name}` (not failed; put helpers in namespace illum or an "
                    "unnamed namespace)", serious=False)
        elif shown.startswith(("operator new", "operator delete")):
            add(f"defines {shown[:120]}: exercise code may not replace the memory allocator")
        elif shown.startswith(("std::", "__gnu_cxx::", "__cxxabiv1::", "glm::", "vtable for std::",
                               "typeinfo for std::")) and kind in "TDBR":
            add(f"defines {shown[:120]}, which belongs to a library the tests use")
        elif not shown.startswith(_ILLUM_DEFINED) and kind in "TDBR":
            add(f"defines {shown[:120]} outside namespace illum (not failed; put helpers in namespace illum or an "
                "unnamed namespace)", serious=False)
        elif library and kind in "TDBR" and name in library:
            add(f"defines {shown[:120]}, which the library already has (in {library[name]}): exercise code may "
                "not replace the library's functions")
    for name, shown in used:
        if name.startswith("_Z"):
            if why := next((why for prefix, why in _FORBIDDEN_CXX if prefix in shown), None):
                add(f"{why} ({shown[:100]})")
            continue
        base = name.split("@", 1)[0]
        if kind := _FORBIDDEN_BY_NAME.get(base):
            add(f"calls {base}() ({kind}): exercise code may only compute")
        elif base not in _HARMLESS_C and not base.startswith(_HARMLESS_C_PREFIXES) and not base.endswith("_finite"):
            add(f"calls the C function {base}(), unusual in an exercise (not failed; for the instructor to review)",
                serious=False)
    return list(findings.values())


def object_of(build_dir: Path, relative: str) -> Path | None:
    """The object file CMake compiled ``exercises/NN_topic/name.cpp`` into, in ``build_dir``."""
    unit = PurePosixPath(relative)
    return next(iter(sorted(p for p in build_dir.glob(f"CMakeFiles/*/**/{unit.parent.name}/{unit.name}.o")
                            if p.is_file())), None)
