"""The checks a tool makes of a path one of its options names, before it writes anything (docs/bad-input.md,
"Options"): the classes of the programs' path_problem (lib/illum/io/program.hpp) - an empty path, which would
quietly mean the current folder, a symbolic link on the way that loops or leads nowhere - and a folder that is
a file. `type=path_argument` in argparse ("argument --out: the path is empty ..."); folder_problem before writing.
"""

import argparse
import errno
import os
from pathlib import Path


def path_problem(text: str) -> str:
    """What is wrong with the path `text` as written, or ''; opens and creates nothing."""
    if text == "":
        return "the path is empty (name a file or folder; '.' is the current folder)"
    step = ""
    for part in Path(text).parts:  # each step in turn, so that the message names the link that is wrong
        step = os.path.join(step, part)
        if not os.path.islink(step):  # a plain step, or missing from here on: the tool says what it needs
            continue
        try:
            os.stat(step)
        except OSError as error:
            what = f"'{step}' is a symbolic link"
            if error.errno == errno.ELOOP:
                return what + " that leads back to itself (a link loop)"
            if error.errno == errno.ENOENT:
                return what + f" to '{os.readlink(step)}', which does not exist (a dangling link)"
            return what + f" that cannot be followed: {error.strerror}"
    return ""


def path_argument(text: str) -> Path:
    """An argparse type: the path, or the option's error ("argument --out: the path is empty ...")."""
    if problem := path_problem(text):
        raise argparse.ArgumentTypeError(problem)
    return Path(text)


def folder_problem(path: Path) -> str:
    """Why `path` cannot be a folder or be made one, or '': it, or the nearest of its parents that
    exists, is something else ("afile is a file, not a folder")."""
    for p in [path, *path.parents]:
        if os.path.lexists(p):
            if p.is_dir():
                return ""
            kind = "a file" if p.is_file() else "a symbolic link" if p.is_symlink() else "not a regular file"
            return f"{'it' if p == path else p} is {kind}, not a folder"
    return ""
