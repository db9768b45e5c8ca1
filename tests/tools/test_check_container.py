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
With a stand-in engine, RunTest checks the steps themselves (see its docstring).
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



FAKE_ENGINE = """#!/bin/bash
# A stand-in for podman: records its arguments, one call per line, and plays the named outcome.
echo "$*" >> "$FAKE_ENGINE_LOG"
case "$1" in
  build) echo "built" ;;
  run) case "$*" in
         *tools/bootstrap*) echo "==> bootstrap: done in 0m01s"; exit "${FAKE_BOOTSTRAP_STATUS:-0}" ;;
         *) echo "test workflow done in 1 s" ;;
       esac ;;
esac
"""


class RunTest(unittest.TestCase):
    """The steps, with a stand-in engine first on PATH: the image is built from the fresh clone's
    Dockerfile, then each README command runs in it on the clone mounted at /workspaces/illum, in
    order; a failed command stops the run with exit 1, its exit status and the end of its log."""

    def run_with_fake_engine(self, bootstrap_status: int) -> tuple[subprocess.CompletedProcess, Path, list[str]]:
        parent = Path(tempfile.mkdtemp())
        self.addCleanup(lambda: subprocess.run(["rm", "-rf", str(parent)], check=True))
        fake = parent / "bin"
        fake.mkdir()
        (fake / "podman").write_text(FAKE_ENGINE)
        (fake / "podman").chmod(0o755)
        log = parent / "engine.log"
        env = dict(os.environ, PATH=f"{fake}:{os.environ['PATH']}", FAKE_ENGINE_LOG=str(log),
                   FAKE_BOOTSTRAP_STATUS=str(bootstrap_status))
        env.pop("ILLUM_CONTAINER_BUILD_ARGS", None)
        env.pop("ILLUM_CONTAINER_RUN_ARGS", None)
        folder = parent / "check"
        done = run("--engine", "podman", str(folder), env=env)
        return done, folder, log.read_text().splitlines() if log.exists() else []

    def test_build_then_both_commands_on_the_mounted_clone(self) -> None:
        done, folder, calls = self.run_with_fake_engine(0)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual([c.split()[0] for c in calls], ["build", "run", "run"])
        self.assertIn(f"-f {folder}/illum/.devcontainer/Dockerfile -t illum-dev-check {folder}/illum", calls[0])
        for call, command in zip(calls[1:], ("tools/bootstrap", "cmake --workflow --preset test")):
            self.assertIn(f"-v {folder}/illum:/workspaces/illum -w /workspaces/illum illum-dev-check bash -c", call)
            self.assertIn(command, call)
        self.assertTrue((folder / "illum" / ".devcontainer" / "Dockerfile").is_file(), "a clone of HEAD")
        self.assertEqual((folder / "bootstrap.log").read_text(), "==> bootstrap: done in 0m01s\n")
        self.assertEqual((folder / "test.log").read_text(), "test workflow done in 1 s\n")

    def test_a_failed_command_stops_the_run(self) -> None:
        done, folder, calls = self.run_with_fake_engine(3)
        self.assertEqual(done.returncode, 1)
        self.assertEqual([c.split()[0] for c in calls], ["build", "run"], "the test command is not run")
        self.assertIn("bootstrap failed (exit status 3)", done.stderr)
        self.assertIn("==> bootstrap: done in 0m01s", done.stderr, "the end of its log")
        self.assertFalse((folder / "test.log").exists())


if __name__ == "__main__":
    sys.exit(unittest.main())
