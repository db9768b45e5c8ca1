#!/usr/bin/env python3
"""Unit tests of tools/gallery/plots.py: the plot check catches broken lines and lost points.

    python3 tests/tools/test_plots.py        (ctest: plots_tool)

Each case writes a small CSV and a gnuplot script of the form io/plot.cpp
writes, and asserts what gnuplot's own evaluation of it shows.
"""
from __future__ import annotations

import sys
import tempfile
import unittest
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools"))

from gallery.plots import check_plot, check_plots  # noqa: E402

# Two series whose rows interleave, as a study writes them (one row per knob and method).
DATA = "method,n,error\na,1,0.5\nb,1,0.7\na,2,0.25\nb,2,0.3\na,4,0.125\nb,4,0.2\n"
HEAD = "set datafile separator ','\n"


def clause(method: str, undefined: str, style: str = "linespoints") -> str:
    return (f"'t.csv' skip 1 using (column(2)):(((strcol(1) eq '{method}')) ? column(3) : {undefined}) "
            f"with {style} title '{method}'")


class PlotCheckTest(unittest.TestCase):
    def setUp(self) -> None:
        self._tmp = tempfile.TemporaryDirectory(prefix="illum-plots-test-")
        self.folder = Path(self._tmp.name) / "lesson01"
        self.folder.mkdir()
        (self.folder / "t.csv").write_text(DATA, encoding="utf-8")

    def tearDown(self) -> None:
        self._tmp.cleanup()

    def script(self, text: str) -> Path:
        gp = self.folder / "p.gp"
        gp.write_text(text, encoding="utf-8")
        (self.folder / "p.png").write_bytes(b"")
        return gp

    def test_one_over_zero_breaks_interleaved_lines(self):
        gp = self.script(HEAD + "set xrange [0.5:4.5]\nset yrange [0:1]\nplot " + clause("a", "1/0") + ", "
                         + clause("b", "1/0") + "\n")
        problems = check_plot(gp)
        self.assertEqual(len(problems), 2, problems)
        self.assertIn("curve 1 'a': its line is broken", problems[0])

    def test_nan_as_missing_joins_them(self):
        gp = self.script(HEAD + "set datafile missing NaN\nset xrange [0.5:4.5]\nset yrange [0:1]\nplot "
                         + clause("a", "NaN") + ", " + clause("b", "NaN") + "\n")
        self.assertEqual(check_plot(gp), [])
        problems, checked = check_plots(self.folder.parent)
        self.assertEqual((problems, checked), ([], 1))

    def test_a_point_on_the_frame_or_outside_it_is_lost(self):
        # autoscaled x ends at the tics 1 and 4, where the first and last points sit
        gp = self.script(HEAD + "set datafile missing NaN\nset yrange [0:1]\nplot " + clause("a", "NaN") + "\n")
        problems = check_plot(gp)
        self.assertEqual(len(problems), 1, problems)
        self.assertIn("the point (1, 0.5) is on the frame", problems[0])
        gp = self.script(HEAD + "set datafile missing NaN\nset xrange [0.5:4.5]\nset yrange [0:0.6]\nplot "
                         + clause("b", "NaN") + "\n")
        problems = check_plot(gp)
        self.assertIn("the point (1, 0.7) is outside the frame", problems[0])

    def test_zero_on_a_log_axis_is_lost_and_an_empty_curve_is_reported(self):
        (self.folder / "t.csv").write_text(DATA + "a,8,0\n", encoding="utf-8")
        gp = self.script(HEAD + "set datafile missing NaN\nset logscale y\nset xrange [0.5:9]\n"
                         "set yrange [0.05:1]\nplot " + clause("a", "NaN") + ", " + clause("c", "NaN") + "\n")
        problems = check_plot(gp)
        self.assertTrue(any("curve 1 'a': the point (8, 0) is outside" in p for p in problems), problems)
        self.assertTrue(any("curve 2 'c' has no point" in p for p in problems), problems)

    def test_a_line_of_one_point_draws_nothing(self):
        (self.folder / "t.csv").write_text("method,n,error\na,1,0.5\n", encoding="utf-8")
        gp = self.script(HEAD + "set xrange [0:2]\nset yrange [0:1]\nplot " + clause("a", "NaN", "lines") + "\n")
        self.assertIn("has 1 point: it draws nothing", check_plot(gp)[0])


if __name__ == "__main__":
    unittest.main(verbosity=1)
