#!/usr/bin/env python3
"""Unit tests of tests/checks/check_unity_units.py on units written by hand: a private helper of an
earlier member called bare by a later member is found, with the caller's file and line; a call
in an earlier member, a member call, a qualified call, a declaration of a variable of that name,
a prototype and a helper of a named namespace are not; a build that must have units and has
none fails. Run: python3
tests/tools/test_check_unity_units.py (ctest: tools_check_unity_units_py)."""
from __future__ import annotations

import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "checks"))

import check_unity_units  # noqa: E402

EARLIER = "\n".join([
    "namespace illum {",
    "namespace {",
    "",
    "double mean(const Color& c) { return (c.r + c.g + c.b) / 3.0; }",
    "",
    "template <class T>",
    "std::vector<T> split(const std::vector<T>& v,",
    "                     std::size_t at) {",
    "  return v;",
    "}",
    "",
    "int declared_only(int x);",
    "",
    "}  // namespace",
    "",
    "static int twice(int x) { return 2 * x; }",
    "",
    "double shared(double x) { return x; }  // external linkage: a one-home helper",
    "",
    "}  // namespace illum",
])

LATER = "\n".join([
    "namespace illum {",                                   # 1
    "double brightness(const Color& c) {",                 # 2
    "  return mean(c);",                                   # 3  found
    "}",                                                   # 4
    "void f(const Box& box, const Box* p) {",              # 5
    "  Point3 mean(0.0);",                                 # 6  a variable
    "  const double m = box.mean(1) + p->mean(2);",        # 7  members
    "  const double q = stats::mean(3);",                  # 8  qualified
    "  const auto parts = split(v, 2);",                   # 9  found
    "  const int d = declared_only(3) + shared(1.0);",     # 10 a prototype, a one-home helper
    "  // mean(c) in a comment, and \"mean(c)\" in a string",  # 11
    "  if (twice(1) > 0) {}",                              # 12 found
    "}",                                                   # 13
    "}  // namespace illum",                               # 14
])


class UnityUnitsTest(unittest.TestCase):
    def check(self, order: list[str]) -> list[str]:
        with tempfile.TemporaryDirectory() as folder:
            source = Path(folder) / "src"
            unit = Path(folder) / "build" / "unity" / "target" / "unit_0.cpp"
            source.mkdir()
            unit.parent.mkdir(parents=True)
            (source / "earlier.cpp").write_text(EARLIER, encoding="utf-8")
            (source / "later.cpp").write_text(LATER, encoding="utf-8")
            unit.write_text("".join(f'#include "{name}"\n' for name in order), encoding="utf-8")
            return check_unity_units.problems_in_unit(unit, source)

    def test_private_definitions_are_read_from_the_code(self) -> None:
        code = check_unity_units.blank_comments(EARLIER)
        self.assertEqual(check_unity_units.private_functions(code), {"mean", "split", "twice"})

    def test_a_later_members_bare_calls_are_found_with_file_and_line(self) -> None:
        found = self.check(["earlier.cpp", "later.cpp"])
        self.assertEqual(sorted((p.split(":")[0], int(p.split(":")[1])) for p in found),
                         [("later.cpp", 3), ("later.cpp", 9), ("later.cpp", 12)])
        self.assertTrue(all("earlier.cpp" in p and "target/unit_0.cpp" in p for p in found))

    def test_an_earlier_member_does_not_see_a_later_ones_helpers(self) -> None:
        self.assertEqual(self.check(["later.cpp", "earlier.cpp"]), [])

    def test_a_missing_member_is_reported(self) -> None:
        found = self.check(["earlier.cpp", "gone.cpp"])
        self.assertEqual(len(found), 1)
        self.assertIn("gone.cpp", found[0])

    def test_no_units_passes_only_when_none_are_required(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            self.assertEqual(check_unity_units.main(["--build-dir", folder]), 0)
            self.assertEqual(check_unity_units.main(["--build-dir", folder, "--require-units"]), 1)

    def test_a_bad_build_dir_is_an_error(self) -> None:
        self.assertEqual(check_unity_units.main(["--build-dir", "/nonexistent/illum-build"]), 2)


if __name__ == "__main__":
    unittest.main()
