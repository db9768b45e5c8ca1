#!/usr/bin/env python3
"""Unit tests of tools/compare_runs.py: two runs' tables agree but for timings.

    python3 tests/tools/test_compare_runs.py        (ctest: compare_runs_tool)

Each case writes two small --out folders and checks the exit code: 0 when
only timing cells differ, 1 when any other cell, a row count or a header
differs or a table is missing, 2 when a folder holds no table at all.
"""
from __future__ import annotations

import contextlib
import io
import sys
import tempfile
import unittest
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools"))

import compare_runs  # noqa: E402

TABLE = "method,error,ns per test,Mrays/s\nnotes,1.25e-06,12,3.5\nstable,2.5e-07,14,3.1\nmedian time,0,9,0\n"


class CompareRuns(unittest.TestCase):
    def run_on(self, first: dict[str, str], second: dict[str, str]) -> int:
        with tempfile.TemporaryDirectory() as temporary:
            folders = []
            for name, files in (("a", first), ("b", second)):
                folder = Path(temporary) / name
                folder.mkdir()
                for file, text in files.items():
                    (folder / file).write_text(text, encoding="utf-8")
                folders.append(str(folder))
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                return compare_runs.main(folders)

    def test_same_tables_agree(self):
        self.assertEqual(self.run_on({"t.csv": TABLE}, {"t.csv": TABLE}), 0)

    def test_timing_columns_and_rows_may_differ(self):
        # "ns per test" and "Mrays/s" are timing columns; the row "median time" is a timing row.
        other = TABLE.replace(",12,3.5", ",15,2.9").replace("median time,0,9,0", "median time,7,8,1")
        self.assertEqual(self.run_on({"t.csv": TABLE}, {"t.csv": other}), 0)

    def test_a_value_one_digit_off_differs(self):
        other = TABLE.replace("1.25e-06", "1.26e-06")
        self.assertEqual(self.run_on({"t.csv": TABLE}, {"t.csv": other}), 1)

    def test_the_same_number_written_otherwise_differs(self):
        # Byte for byte: 2.5e-07 and 2.50e-07 are the same value but not the same table cell.
        other = TABLE.replace("2.5e-07", "2.50e-07")
        self.assertEqual(self.run_on({"t.csv": TABLE}, {"t.csv": other}), 1)

    def test_a_missing_row_differs(self):
        other = "\n".join(TABLE.splitlines()[:-1]) + "\n"
        self.assertEqual(self.run_on({"t.csv": TABLE}, {"t.csv": other}), 1)

    def test_another_header_differs(self):
        other = TABLE.replace("method,error", "method,err")
        self.assertEqual(self.run_on({"t.csv": TABLE}, {"t.csv": other}), 1)

    def test_a_table_missing_from_either_run_differs(self):
        self.assertEqual(self.run_on({"t.csv": TABLE, "u.csv": TABLE}, {"t.csv": TABLE}), 1)
        self.assertEqual(self.run_on({"t.csv": TABLE}, {"t.csv": TABLE, "u.csv": TABLE}), 1)

    def test_no_table_at_all_cannot_be_compared(self):
        self.assertEqual(self.run_on({"notes.txt": "x"}, {"notes.txt": "x"}), 2)


if __name__ == "__main__":
    unittest.main()
