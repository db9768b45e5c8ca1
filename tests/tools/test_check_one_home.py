#!/usr/bin/env python3
"""Unit tests of tests/checks/check_one_home.py: each pattern is found in code, with its file and
line, and not in comments, strings or the helper's own home. Run: python3
tests/tools/test_check_one_home.py (ctest: tools_check_one_home_py)."""
from __future__ import annotations

import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "checks"))

import check_one_home  # noqa: E402


class OneHomeTest(unittest.TestCase):
    def problems(self, files: dict[str, str]) -> list[str]:
        with tempfile.TemporaryDirectory() as folder:
            root = Path(folder)
            for name, text in files.items():
                (root / name).parent.mkdir(parents=True, exist_ok=True)
                (root / name).write_text(text, encoding="utf-8")
            return check_one_home.problems_found(root)

    def test_each_pattern_is_found_with_file_and_line(self) -> None:
        found = self.problems({"lessons/01_x/main.cpp": "\n".join([
            "#include <omp.h>",                                   # 1
            "double best = 1e9;",                                  # 2
            "for (int repeat = 0; repeat < 3; ++repeat) {",       # 3
            "  best = std::min(best, watch.seconds());",          # 4
            "}",                                                   # 5
            "const double area = 3.14159 * r * r;",                # 6
            "constexpr double pi = std::numbers::pi;",             # 7
            "const int n = omp_get_max_threads();",                # 8
            "omp_set_num_threads(1);",                             # 9
            "double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {}",  # 10
            "const double half_turn = std::acos(-1.0);",           # 11
        ])})
        lines = sorted({int(p.split(":")[1]) for p in found})
        self.assertEqual(lines, [1, 3, 4, 6, 7, 8, 9, 10, 11])
        self.assertTrue(all(p.startswith("lessons/01_x/main.cpp:") for p in found))

    def test_comments_strings_and_homes_are_not_code(self) -> None:
        found = self.problems({
            "lessons/01_x/main.cpp": "\n".join([
                "// for (int repeat = 0; repeat < 3; ++repeat) std::min(best, w.seconds());",
                "/* omp_set_num_threads(2); 3.14159 */",
                'const char* text = "omp_get_max_threads() and M_PI";',
                "using std::numbers::pi;",
                "for (int trial = 0; trial < 500; ++trial) {}",
                "const std::span<const Point3> vertices_i = part.vertices;",
            ]),
            "lib/illum/core/threads.hpp": "#include <omp.h>\ninline int n() { return omp_get_max_threads(); }\n",
            "lib/illum/core/stopwatch.hpp": "for (int run = 0; run < runs; ++run) best = std::min(best, w.seconds());\n",
        })
        self.assertEqual(found, [])

    def test_platform_calls_are_found_outside_their_homes(self) -> None:
        code = "\n".join([
            "#include <unistd.h>",                                    # 1
            "#include <sys/stat.h>",                                  # 2
            "const int k = __builtin_ctz(mask);",                     # 3
            "__attribute__((flatten)) void f();",                     # 4
            "__extension__ typedef __int128 Int128;",                 # 5
            "asm volatile(\"\" : : \"r\"(x));",                       # 6
            "void* p = std::aligned_alloc(64, n);",                   # 7
            "clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);",            # 8
            "const bool tty = ::isatty(2) != 0;",                     # 9
            "const int k2 = std::countr_zero(mask);",                 # 10: standard C++
            "// isatty(2) and __builtin_ctz in a comment",            # 11
            "#include <csignal>",                                     # 12: standard C++
        ])
        found = self.problems({"lessons/01_x/main.cpp": code, "lib/illum/system/platform.cpp": code,
                               "tests/io/x.cpp": code})
        self.assertEqual(sorted({int(p.split(":")[1]) for p in found if p.startswith("lessons/")}),
                         [1, 2, 3, 4, 5, 6, 7, 8, 9])
        # platform.cpp may call the system, not use compiler extensions; tests are not checked.
        self.assertEqual(sorted({int(p.split(":")[1]) for p in found if p.startswith("lib/")}), [3, 4, 5, 6])
        self.assertFalse([p for p in found if p.startswith("tests/")])

    def test_the_tree_has_every_helper_in_its_home(self) -> None:
        self.assertEqual(check_one_home.problems_found(check_one_home.ROOT), [])


if __name__ == "__main__":
    unittest.main()
