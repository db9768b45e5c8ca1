#!/usr/bin/env python3
"""Unit tests of tools/figures.py: figures in the texts follow the programs' tables.

    python3 tests/tools/test_figures.py        (ctest: figures_tool)
"""
from __future__ import annotations

import json
import sys
import tempfile
import unittest
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools"))

import figures  # noqa: E402

TABLE = ("| n | error | ns_per_test |\n|---|---|---|\n"
         "| 1 | 0.5 | 12.1 |\n| 2 | 0.25 | 13.4 |\n| 4 | 0.125 | 15.9 |\n")
TEXT = ("# Lesson 01\n\nThe errors halve.\n\n"
        "<!-- figure: out/lesson01/t.md -->\n<!-- /figure -->\n\nThe end.\n")


class FiguresTest(unittest.TestCase):
    def setUp(self) -> None:
        self._tmp = tempfile.TemporaryDirectory(prefix="illum-figures-test-")
        self.root = Path(self._tmp.name)
        self.out = self.root / "out"
        self.write("out/lesson01/t.md", TABLE)
        self.write("lessons/01_x/README.md", TEXT)
        self.messages: list[str] = []

    def tearDown(self) -> None:
        self._tmp.cleanup()

    def write(self, rel: str, text: str) -> Path:
        path = self.root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        return path

    def run_mode(self, mode: str) -> int:
        self.messages = []
        return figures.process(self.root, self.out, mode, log=self.messages.append)

    def text(self) -> str:
        return (self.root / "lessons/01_x/README.md").read_text(encoding="utf-8")

    def test_update_writes_the_table_and_a_label_naming_the_run(self):
        self.write("out/run_log.json", json.dumps({"lesson01": {
            "started": "2026-12-01 20:00 UTC", "cores": 2, "load_before": [3.5, 2, 1], "load_after": [4.25, 2, 1]}}))
        self.assertEqual(self.run_mode("update"), 0, self.messages)
        text = self.text()
        self.assertIn("| 2 | 0.25 | 13.4 |", text)
        self.assertIn("2026-12-01 20:00 UTC on 2 cores, load average 3.5 at the start", text)
        self.assertIn("4.25 at its end", text)
        self.assertTrue(text.endswith("The end.\n"))
        self.assertEqual(self.run_mode("check"), 0, self.messages)

    def test_check_fails_on_a_changed_value_and_names_row_column_and_both_values(self):
        self.run_mode("update")
        self.write("out/lesson01/t.md", TABLE.replace("| 0.25 |", "| 0.3 |"))
        self.assertEqual(self.run_mode("check"), 1)
        joined = "\n".join(self.messages)
        self.assertIn("row '2', column 'error': the text says 0.25, the program wrote 0.3", joined)
        self.assertIn("README.md:9:", joined)  # the line of that row in the text

    def test_timings_are_not_compared_and_refresh_updates_them(self):
        self.run_mode("update")
        self.write("out/lesson01/t.md", TABLE.replace("13.4", "99.9"))
        self.assertEqual(self.run_mode("check"), 0, self.messages)
        self.assertEqual(self.run_mode("refresh"), 0, self.messages)
        self.assertIn("| 2 | 0.25 | 99.9 |", self.text())

    def test_refresh_leaves_a_figure_whose_values_changed_and_lists_it(self):
        self.run_mode("update")
        self.write("out/lesson01/t.md", TABLE.replace("| 0.25 | 13.4 |", "| 0.3 | 99.9 |"))
        self.assertEqual(self.run_mode("refresh"), 0)
        self.assertIn("| 2 | 0.25 | 13.4 |", self.text())
        self.assertTrue(any("--update" in m for m in self.messages), self.messages)

    def test_a_timing_row_is_recognised_by_its_first_cell(self):
        self.write("out/lesson01/t.md", "| d | a | b |\n|---|---|---|\n| 1 | 2e-7 | 3e-16 |\n"
                                        "| median ns per test | 14 | 12 |\n")
        self.run_mode("update")
        self.write("out/lesson01/t.md", "| d | a | b |\n|---|---|---|\n| 1 | 2e-7 | 3e-16 |\n"
                                        "| median ns per test | 22 | 19 |\n")
        self.assertEqual(self.run_mode("check"), 0, self.messages)
        self.assertTrue(figures.is_timing_name("seconds to 1e-6"))
        self.assertTrue(figures.is_timing_name("time_slope_res_ge_64"))
        self.assertFalse(figures.is_timing_name("s"))           # the ray parameter
        self.assertFalse(figures.is_timing_name("wall strip"))  # a configuration

    def test_columns_where_and_row_select_from_a_csv(self):
        self.write("out/lesson01/c.csv", "n,error,kind\n1,0.5,a\n2,0.25,b\n4,0.125,a\n")
        self.write("lessons/01_x/README.md",
                   '<!-- figure: out/lesson01/c.csv columns="error,n" where="kind=a" -->\n<!-- /figure -->\n'
                   '<!-- figure: out/lesson01/c.csv row="n=2 & kind=b" row="n=4" -->\n<!-- /figure -->\n')
        self.assertEqual(self.run_mode("update"), 0, self.messages)
        text = self.text()
        self.assertIn("| error | n |\n|---|---|\n| 0.5 | 1 |\n| 0.125 | 4 |\n", text)
        self.assertIn("| n | error | kind |\n|---|---|---|\n| 2 | 0.25 | b |\n| 4 | 0.125 | a |\n", text)

    def test_a_missing_table_column_or_closing_comment_is_an_error(self):
        self.write("lessons/01_x/README.md", "<!-- figure: out/lesson01/none.md -->\n<!-- /figure -->\n")
        self.assertEqual(self.run_mode("check"), 1)
        self.assertIn("does not exist", "\n".join(self.messages))
        self.write("lessons/01_x/README.md", '<!-- figure: out/lesson01/t.md columns="nope" -->\n<!-- /figure -->\n')
        self.assertEqual(self.run_mode("check"), 1)
        self.assertIn("has no column 'nope'", "\n".join(self.messages))
        self.write("lessons/01_x/README.md", "<!-- figure: out/lesson01/t.md -->\n")
        self.assertEqual(self.run_mode("check"), 1)
        self.assertIn("never closed", "\n".join(self.messages))
        self.write("lessons/01_x/README.md", "<!-- figure: ../etc/passwd.md -->\n<!-- /figure -->\n")
        self.assertEqual(self.run_mode("check"), 1)
        self.assertIn("under out/", "\n".join(self.messages))

    def test_check_flags_timings_typed_by_hand(self):
        self.run_mode("update")
        self.write("slides/01_x.md", "- about 0.2 s on this machine\n- 19 ns against 12 ns\n"
                                     "- s ≥ 0, and f = s³ − 2s + 2 are not timings\n"
                                     "| n | seconds |\n|---|---|\n| 1 | 0.5 |\n")
        self.assertEqual(self.run_mode("check"), 1)
        joined = "\n".join(self.messages)
        self.assertIn("hand-typed timing '0.2 s'", joined)
        self.assertIn("hand-typed timing '19 ns'", joined)
        self.assertIn("a table with timings typed by hand", joined)
        self.assertNotIn("2s", joined)

    def test_check_flags_an_erratum_cited_without_a_link(self):
        self.run_mode("update")
        self.write("exercises/01_x/README.md", "Mind erratum 2. Also [erratum 1](../../docs/errata.md#erratum-1).\n")
        self.assertEqual(self.run_mode("check"), 1)
        joined = "\n".join(self.messages)
        self.assertIn("'erratum 2' is not linked", joined)
        self.assertNotIn("'erratum 1'", joined)


if __name__ == "__main__":
    unittest.main(verbosity=1)
