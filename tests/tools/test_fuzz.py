#!/usr/bin/env python3
"""tools/fuzz's arguments: a wrong command is refused with exit status 2, naming the option and the
value, before anything is built or run (CTest tools_fuzz_py). Every case passes --no-build and
--time 1, so that a regression shows as a failed assertion within seconds, not as a fuzz build."""
from __future__ import annotations

import subprocess
import sys
import unittest
from pathlib import Path

FUZZ = Path(__file__).resolve().parents[2] / "tools" / "fuzz"


def run(*argv: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(FUZZ), "--no-build", *argv], capture_output=True, text=True,
                          timeout=60, stdin=subprocess.DEVNULL)


class Arguments(unittest.TestCase):
    def assert_refused(self, argv: list[str], words: str) -> None:
        done = run(*argv)
        self.assertEqual(done.returncode, 2, (argv, done.stderr))
        self.assertIn(words, done.stderr, argv)
        self.assertNotIn("Traceback", done.stderr, argv)
        self.assertEqual(done.stdout, "", argv)  # no target ran

    def test_jobs_outside_one_or_two_is_refused_not_clamped(self) -> None:
        self.assert_refused(["--time", "1", "--jobs", "0"], "--jobs must be 1 or 2, got 0")
        self.assert_refused(["--time", "1", "--jobs", "-3"], "--jobs must be 1 or 2, got -3")
        self.assert_refused(["--time", "1", "--jobs", "3"], "--jobs must be 1 or 2, got 3")

    def test_time_must_be_positive(self) -> None:
        self.assert_refused(["--time", "0"], "--time must be positive, got 0")
        self.assert_refused(["--time", "-1"], "--time must be positive, got -1")
        self.assert_refused(["--time", "abc"], "invalid int value: 'abc'")

    def test_an_unknown_target_is_named(self) -> None:
        self.assert_refused(["--time", "1", "no_such_target"], "unknown target 'no_such_target'; the targets are")

    def test_list_names_the_targets(self) -> None:
        done = run("--list")
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("obj_mesh", done.stdout.split())


if __name__ == "__main__":
    unittest.main()
