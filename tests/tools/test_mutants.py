#!/usr/bin/env python3
"""Unit tests of the mutant generator of `tools/grade --mutants` (tools/grading/mutants.py):
which changes it makes, which it must not make (template brackets, comments,
lines the stub provides), the equivalent-mutant list and the seeded sample.
Nothing is built here; the CI stage "mutation smoke" runs the tool for real.

Run: python3 tests/tools/test_mutants.py   (ctest: tools_mutants_py)
"""
from __future__ import annotations

import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))

from grading import mutants  # noqa: E402

UNIT = Path("lib/illum/x/unit.cpp")

SOURCE = """\
#include <vector>
namespace illum {
// a < b in a comment is not code
double f(const std::vector<double>& a, std::size_t n) {
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) s += a[i] * 2.0;
  if (s > 1.0) return std::abs(-s);
  return std::min(s, static_cast<double>(n));
}
}  // namespace illum
"""


def changes(source: str = SOURCE, stub_lines: set[str] | None = None) -> list[tuple[str, str, str]]:
    return [(m.operator, m.original, m.replacement)
            for m in mutants.generate("99", UNIT, source, stub_lines or set())]


class GeneratorTest(unittest.TestCase):
    def test_every_operator_class_appears(self):
        found = changes()
        self.assertIn(("relational", "<", "<="), found)
        self.assertIn(("relational", ">", ">="), found)
        self.assertIn(("arithmetic", "*", "/"), found)
        self.assertIn(("arithmetic", "+=", "-="), found)
        self.assertIn(("constant", "0.0", "1.0"), found)
        self.assertIn(("constant", "2.0", "1.0"), found)
        self.assertIn(("constant", "0", "1"), found)
        self.assertIn(("sign", "-", ""), found)
        self.assertIn(("min/max", "min", "max"), found)
        self.assertIn(("abs/clamp removed", "std::abs(-s)", "(-s)"), found)
        self.assertIn(("condition negated", "(s > 1.0)", "(!(s > 1.0))"), found)
        self.assertIn(("loop bound", " n", " n - 1"), found)

    def test_template_brackets_comments_and_includes_are_left_alone(self):
        lines = [m.source_line for m in mutants.generate("99", UNIT, SOURCE, set())]
        self.assertFalse(any("#include" in line for line in lines))
        self.assertFalse(any("comment" in line for line in lines))
        # The signature (outside any body) and the casts' angle brackets are never mutated.
        self.assertFalse(any(line.startswith("double f(") for line in lines))
        casts = [m for m in mutants.generate("99", UNIT, SOURCE, set()) if "static_cast" in m.source_line
                 and m.operator == "relational"]
        self.assertEqual(casts, [])

    def test_lines_the_stub_provides_are_not_mutated(self):
        stub = {"double s = 0.0;"}
        lines = {m.source_line for m in mutants.generate("99", UNIT, SOURCE, stub)}
        self.assertNotIn("double s = 0.0;", lines)
        self.assertIn("if (s > 1.0) return std::abs(-s);", lines)

    def test_index_swap_needs_the_partner_in_scope(self):
        source = "namespace illum {\nvoid g(double* m, int n) {\n  for (int i = 0; i < n; ++i)\n" \
                 "    for (int j = 0; j < n; ++j) m[i] = m[j] + f(i, j);\n}\n}\n"
        found = changes(source)
        self.assertIn(("index swap", "i", "j"), found)
        self.assertIn(("index swap", "j", "i"), found)
        self.assertIn(("index swap", "i, j", "j, i"), found)

    def test_applying_a_mutant_changes_only_its_range(self):
        m = next(m for m in mutants.generate("99", UNIT, SOURCE, set()) if m.operator == "min/max")
        mutated = m.apply(SOURCE)
        self.assertEqual(len(mutated), len(SOURCE))
        self.assertIn("std::max(s, static_cast<double>(n))", mutated)
        self.assertIn("-  return std::min", m.diff())


class EquivalentsTest(unittest.TestCase):
    def test_an_entry_matches_by_line_text_and_needs_a_reason(self):
        m = next(m for m in mutants.generate("99", UNIT, SOURCE, set()) if m.operator == "min/max")
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "equivalent.txt"
            path.write_text(f"# comment\n\n{m.equivalence_key()} -- both are s here\n", encoding="utf-8")
            equivalents = mutants.read_equivalents(path)
            self.assertEqual(equivalents.problems, [])
            self.assertEqual(equivalents.reason(m), "both are s here")
            path.write_text(f"{m.equivalence_key()}\n", encoding="utf-8")
            self.assertEqual(len(mutants.read_equivalents(path).problems), 1)

    def test_an_entry_ignores_trailing_comments(self):
        m = next(m for m in mutants.generate("99", UNIT, SOURCE, set()) if m.operator == "min/max")
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "equivalent.txt"
            path.write_text(f"{UNIT.as_posix()}: {m.source_line}  // old comment => {m.mutated_line} // x -- r\n",
                            encoding="utf-8")
            self.assertEqual(mutants.read_equivalents(path).reason(m), "r")

    def test_the_checked_in_list_parses(self):
        root = Path(__file__).resolve().parents[2]
        self.assertEqual(mutants.read_equivalents(root / mutants.EQUIVALENT_FILE).problems, [])


class ScoreTest(unittest.TestCase):
    def test_score_leaves_out_unbuildable_mutants_and_counts_timeouts_as_caught(self):
        report = mutants.LessonReport("99")
        for status in ["killed", "killed", "timed out", "survived", "did not build"]:
            m = mutants.Mutant("99", UNIT, 1, "x", 0, 0, "", "")
            m.status = status
            report.mutants.append(m)
        self.assertEqual(report.scored(), 4)
        self.assertAlmostEqual(report.score(), 75.0)


class SyncTest(unittest.TestCase):
    def test_sync_rewrites_only_changed_files_and_removes_deleted_ones(self):
        with tempfile.TemporaryDirectory() as folder:
            src, dst = Path(folder) / "src", Path(folder) / "dst"
            (src / "lib").mkdir(parents=True)
            (src / "build").mkdir()
            (src / "lib" / "a.cpp").write_text("a")
            (src / "lib" / "b.cpp").write_text("b")
            (src / "build" / "big.o").write_text("o")
            (src / "node_modules").symlink_to(src / "node_modules")  # a link loop, as a checkout can hold
            (src / "lib" / "link.cpp").symlink_to("a.cpp")
            mutants.sync_tree(src, dst)
            self.assertFalse((dst / "node_modules").exists() or (dst / "node_modules").is_symlink())
            self.assertEqual(str((dst / "lib" / "link.cpp").readlink()), "a.cpp")
            self.assertFalse((dst / "build" / "big.o").exists())
            stamp = (dst / "lib" / "a.cpp").stat().st_mtime_ns
            (src / "lib" / "b.cpp").unlink()
            mutants.sync_tree(src, dst)
            self.assertEqual((dst / "lib" / "a.cpp").stat().st_mtime_ns, stamp)
            self.assertFalse((dst / "lib" / "b.cpp").exists())


if __name__ == "__main__":
    unittest.main()
