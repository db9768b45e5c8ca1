#!/usr/bin/env python3
"""tools/bootstrap (the README's first command) takes no arguments: a typo is refused before any
step starts, with exit code 2 and a message naming the argument; --help prints the steps.

The script runs from a copy in a temporary tree whose tools/install-deps only records that it was
called and fails: a bootstrap that ignored its arguments would reach it (and nothing else), so a
regression shows as that record instead of a four-minute build.
"""
import shutil
import subprocess
import tempfile
import unittest
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]


class ArgumentsTest(unittest.TestCase):
    def setUp(self) -> None:
        self.tree = Path(tempfile.mkdtemp(prefix="illum-bootstrap-test-"))
        (self.tree / "tools").mkdir()
        shutil.copy2(SOURCE / "tools" / "bootstrap", self.tree / "tools" / "bootstrap")
        self.marker = self.tree / "install-deps-ran"
        fake = self.tree / "tools" / "install-deps"
        fake.write_text(f"#!/bin/sh\ntouch '{self.marker}'\nexit 1\n")
        fake.chmod(0o755)

    def tearDown(self) -> None:
        shutil.rmtree(self.tree)

    def run_bootstrap(self, *args: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(self.tree / "tools" / "bootstrap"), *args], capture_output=True, text=True,
                              timeout=60, cwd=self.tree)

    def test_an_unknown_argument_is_refused_before_any_step(self) -> None:
        for args in (("--quik",), ("--ci",), ("out",), ("--help-me",), ("-j4", "--help")):
            with self.subTest(args=args):
                done = self.run_bootstrap(*args)
                self.assertEqual(done.returncode, 2, done.stderr)
                self.assertIn(f"bootstrap: unknown argument '{args[0]}'", done.stderr)
                self.assertEqual(done.stdout, "")
                self.assertFalse(self.marker.exists(), "install-deps ran after a refused argument")

    def test_help_prints_the_steps_and_runs_none(self) -> None:
        for flag in ("-h", "--help"):
            done = self.run_bootstrap(flag)
            self.assertEqual(done.returncode, 0, done.stderr)
            for step in ("tools/install-deps", "cmake --preset release", "tools/main_job.py"):
                self.assertIn(step, done.stdout)
            self.assertFalse(self.marker.exists())

    def test_without_arguments_the_first_step_runs(self) -> None:
        # The fake install-deps fails, and the bootstrap stops there (set -e) with its status.
        done = self.run_bootstrap()
        self.assertTrue(self.marker.exists())
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("==> bootstrap: installing dependencies", done.stdout)
        self.assertNotIn("configuring", done.stdout)


if __name__ == "__main__":
    unittest.main()
