#!/usr/bin/env python3
"""tools/check_fresh_debian refuses bad arguments before it writes anything.

The run itself (debootstrap, a chroot, both README commands) needs root, the network and half an
hour, so CI does not run it; these cases check only what happens before any of that starts: a wrong
number of arguments, or a folder that already exists, stops it with exit code 2 and a message
naming the problem, and nothing is created beside or inside the folder.
"""
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

TOOL = Path(__file__).resolve().parents[2] / "tools" / "check_fresh_debian"


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(TOOL), *args], capture_output=True, text=True, timeout=60)


class ArgumentsTest(unittest.TestCase):
    def test_no_folder_or_two_folders_is_a_usage_error(self) -> None:
        for args in ((), ("a", "b")):
            done = run(*args)
            self.assertEqual(done.returncode, 2, args)
            self.assertIn("usage: tools/check_fresh_debian FOLDER", done.stderr)
            self.assertEqual(done.stdout, "")

    def test_an_existing_folder_is_refused_and_left_as_it_was(self) -> None:
        with tempfile.TemporaryDirectory() as parent:
            folder = Path(parent) / "root"
            folder.mkdir()
            (folder / "keep").write_text("mine")
            done = run(str(folder))
            self.assertEqual(done.returncode, 2)
            if os.geteuid() == 0:
                self.assertIn(f"{folder} exists; give a new folder", done.stderr)
            else:
                self.assertIn("run it as root", done.stderr)
            self.assertEqual(sorted(p.name for p in Path(parent).iterdir()), ["root"])
            self.assertEqual([p.name for p in folder.iterdir()], ["keep"])
            self.assertEqual((folder / "keep").read_text(), "mine")


if __name__ == "__main__":
    sys.exit(unittest.main())
