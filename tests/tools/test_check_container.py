#!/usr/bin/env python3
"""tools/check_container refuses bad arguments before it writes anything.

The run itself (an image build, then both README commands inside the container) needs a container
engine, the network and about 25 minutes, so CI does not run it; these cases check only what
happens before any of that starts. Each stops the tool with exit code 2 and a message naming the
problem (the option and its value, or the folder), and nothing is created beside or inside FOLDER:
  - no folder, two folders, an unknown option, or --engine without a value: the usage line;
  - --engine with a value other than docker or podman: that value;
  - a folder whose path holds ':' or ',' (the engine's -v option would split it there): that folder;
  - a folder (or a dangling link) that already exists: that folder, left as it was;
  - no engine on PATH at all: says so, and what to install.
"""
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

TOOL = Path(__file__).resolve().parents[2] / "tools" / "check_container"
USAGE = "usage: tools/check_container [--engine docker|podman] [--debootstrap-base] FOLDER"


def run(*args: str, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([str(TOOL), *args], capture_output=True, text=True, timeout=60, env=env)


class ArgumentsTest(unittest.TestCase):
    def setUp(self) -> None:
        self.parent = Path(tempfile.mkdtemp())
        self.addCleanup(lambda: subprocess.run(["rm", "-rf", str(self.parent)], check=True))

    def assert_nothing_written(self) -> None:
        self.assertEqual(sorted(p.name for p in self.parent.iterdir()), [])

    def test_usage_errors(self) -> None:
        new = str(self.parent / "new")
        for args in ((), (new, new + "2"), ("--no-such-option", new), (new, "--engine")):
            done = run(*args)
            self.assertEqual(done.returncode, 2, args)
            self.assertIn(USAGE, done.stderr, args)
            self.assertEqual(done.stdout, "", args)
        self.assertIn("unknown option '--no-such-option'", run("--no-such-option", new).stderr)
        self.assert_nothing_written()

    def test_an_engine_other_than_docker_or_podman_is_named(self) -> None:
        done = run("--engine", "lxc", str(self.parent / "new"))
        self.assertEqual(done.returncode, 2)
        self.assertIn("--engine: 'lxc' is neither docker nor podman", done.stderr)
        self.assert_nothing_written()

    def test_a_folder_the_engine_would_misread_is_refused(self) -> None:
        for name in ("a:b", "a,b"):
            done = run(str(self.parent / name))
            self.assertEqual(done.returncode, 2, name)
            self.assertIn(f"{self.parent / name}: a folder without ':' or ','", done.stderr)
        self.assert_nothing_written()

    def test_an_existing_folder_or_link_is_refused_and_left_as_it_was(self) -> None:
        folder = self.parent / "root"
        folder.mkdir()
        (folder / "keep").write_text("mine")
        dangling = self.parent / "link"
        dangling.symlink_to(self.parent / "nowhere")
        for target in (folder, dangling):
            done = run(str(target))
            self.assertEqual(done.returncode, 2, target)
            self.assertIn(f"{target} exists; give a new folder", done.stderr)
        self.assertEqual(sorted(p.name for p in self.parent.iterdir()), ["link", "root"])
        self.assertEqual([p.name for p in folder.iterdir()], ["keep"])
        self.assertEqual((folder / "keep").read_text(), "mine")

    def test_no_engine_on_path(self) -> None:
        # A PATH holding only what the tool needs before its engine check (bash, for its #! line).
        tools = self.parent / "bin"
        tools.mkdir()
        for name in ("bash", "env"):
            found = next(Path(d) / name for d in os.environ["PATH"].split(":") if (Path(d) / name).exists())
            (tools / name).symlink_to(found)
        target = self.parent / "new"
        done = run(str(target), env={"PATH": str(tools)})
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertIn("neither docker nor podman is on PATH", done.stderr)
        done = run("--engine", "podman", str(target), env={"PATH": str(tools)})
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertIn("--engine podman: not on PATH", done.stderr)
        self.assertEqual(sorted(p.name for p in self.parent.iterdir()), ["bin"])


if __name__ == "__main__":
    sys.exit(unittest.main())
