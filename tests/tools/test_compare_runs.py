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


def write_runs(parent: Path, first: dict[str, str], second: dict[str, str]) -> list[str]:
    """Two --out folders, PARENT/a and PARENT/b, holding the given files."""
    folders = []
    for name, files in (("a", first), ("b", second)):
        folder = parent / name
        folder.mkdir()
        for file, text in files.items():
            (folder / file).write_text(text, encoding="utf-8")
        folders.append(str(folder))
    return folders


class CompareRuns(unittest.TestCase):
    def run_on(self, first: dict[str, str], second: dict[str, str]) -> int:
        with tempfile.TemporaryDirectory() as temporary:
            folders = write_runs(Path(temporary), first, second)
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

    def test_bad_arguments_are_refused_and_help_is_not(self):
        # The usage goes to stderr with exit 2 for a wrong call, to stdout with exit 0 when asked for.
        for argv, code, stream in ((["only_one"], 2, "err"), (["a", "b", "c"], 2, "err"), ([], 2, "err"),
                                   (["-h"], 0, "out"), (["--help", "x"], 0, "out")):
            with contextlib.redirect_stdout(io.StringIO()) as out, contextlib.redirect_stderr(io.StringIO()) as err:
                self.assertEqual(compare_runs.main(argv), code, argv)
            said = {"out": out, "err": err}
            self.assertIn("--speed FIRST_FOLDER OTHER_FOLDER", said[stream].getvalue(), argv)
            self.assertEqual(said["err" if stream == "out" else "out"].getvalue(), "", argv)
        with tempfile.TemporaryDirectory() as temporary:
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()) as err:
                self.assertEqual(compare_runs.main([temporary, "/nonexistent/b"]), 2)
            self.assertIn("/nonexistent/b is not a folder", err.getvalue())


class Speed(unittest.TestCase):
    """compare_runs.py --speed: each timing cell's speed of the second run against the first (a time
    divided the first by the second, a rate the second by the first), speed-ups and counts left out."""

    def speed_of(self, first: dict[str, str], second: dict[str, str], *extra: str) -> tuple[int, str, str]:
        with tempfile.TemporaryDirectory() as temporary:
            folders = write_runs(Path(temporary), first, second)
            out, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                code = compare_runs.main(["--speed", *folders, *extra])
            return code, out.getvalue(), err.getvalue()

    def test_times_and_rates_each_count_the_right_way_round(self):
        # Row 1: seconds 2 → 1 (speed 2), ms per shot 4 → 4 (1), Mrays per second 10 → 5 (0.5).
        # Row 2: 1 → 1 (1), 1 → 1 (1), 8 → 10 (1.25). The speedup column (3 → 9) and the
        # timing-dependent count (5 → 50) are not speeds. Sorted by hand: 0.5, 1, 1, 1, 1.25, 2;
        # the median is 1; inclusive deciles: 10th 0.5 + 0.5·(1 − 0.5) = 0.75, 90th 1.25 + 0.5·0.75 = 1.625.
        header = "seconds,seconds per shot (ms),Mrays per second (1 thread),speedup,rows computed (timing-dependent)\n"
        first = header + "2,4,10,3,5\n1,1,8,1,1\n"
        second = header + "1,4,5,9,50\n1,1,10,1,1\n"
        with tempfile.TemporaryDirectory() as temporary:
            a, b = write_runs(Path(temporary), {"t.csv": first}, {"t.csv": second})
            self.assertEqual(sorted(compare_runs.speed_factors(Path(a), Path(b))), [0.5, 1.0, 1.0, 1.0, 1.25, 2.0])
        code, out, _ = self.speed_of({"t.csv": first}, {"t.csv": second})
        self.assertEqual(code, 0)
        self.assertIn("6 timing cells", out)
        self.assertIn("median 1.00, 10th-90th percentile 0.75-1.62", out)

    def test_only_tables_alike_in_both_runs_count(self):
        table = "method,ns per test\nnotes,12\nstable,14\n"
        faster = "method,ns per test\nnotes,6\nstable,7\n"
        code, out, _ = self.speed_of({"t.csv": table, "u.csv": table},
                                     {"t.csv": faster, "u.csv": "method,ns\nnotes,1\nstable,1\n"})
        self.assertEqual(code, 0)
        self.assertIn("2 timing cells", out)
        self.assertIn("median 2.00, 10th-90th percentile 2.00-2.00", out)

    def test_no_timing_cell_or_no_folder_is_an_error(self):
        code, _, err = self.speed_of({"t.csv": "a,error\nx,1\ny,2\n"}, {"t.csv": "a,error\nx,1\ny,2\n"})
        self.assertEqual(code, 2)
        self.assertIn("0 timing cell(s)", err)
        code, _, err = self.speed_of({"t.csv": TABLE}, {"t.csv": TABLE}, "extra")
        self.assertEqual(code, 2)
        self.assertIn("--speed FIRST_FOLDER OTHER_FOLDER", err)
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()) as err:
            self.assertEqual(compare_runs.main(["--speed", "/nonexistent/a", "/nonexistent/b"]), 2)
        self.assertIn("is not a folder", err.getvalue())


if __name__ == "__main__":
    unittest.main()
