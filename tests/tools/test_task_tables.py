#!/usr/bin/env python3
"""Unit tests of tools/task_tables.py's pure parts: reading test cases and their task tags
from doctest sources, the stubs' tasks, and the table. Run: python3 tests/tools/test_task_tables.py
(ctest: tools_task_tables_py)."""
from __future__ import annotations

import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))

import task_tables  # noqa: E402

SOURCE = '''
#include <doctest/doctest.h>
// TEST_CASE("in a comment") is not a test
TEST_SUITE("lesson07") {
  TEST_CASE("first: a \\"quoted\\" word, (parentheses)" * doctest::description("task=1")) {
    const char* text = "}";  // a brace in a string
    CHECK(text[0] == '}');
  }
  TEST_CASE("a long name that clang-format "
            "splits" *
            doctest::description("points=2 task=2,3a")) {}
  TEST_CASE("untagged") {}
}
TEST_SUITE("stability") {
  TEST_CASE("not graded") {}
}
'''

STUB = '''// Lesson 07 exercise: something.
// Task 1. One.
double one() { throw NotImplemented("one", "hint"); }
// Task 2. Two.
double two() { throw NotImplemented("two", "hint"); }
// Task 3a. Three.
double three() {
  throw NotImplemented(
      "three(a)", "hint");
}
'''


class ParseTest(unittest.TestCase):
    def test_suites_names_and_tags(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            source = Path(folder) / "grading.cpp"
            source.write_text(SOURCE, encoding="utf-8")
            tests = task_tables.parse_tests(source)
        self.assertEqual([(t.suite, t.name, t.tasks) for t in tests],
                         [("lesson07", 'first: a "quoted" word, (parentheses)', ["1"]),
                          ("lesson07", "a long name that clang-format splits", ["2", "3a"]),
                          ("lesson07", "untagged", []),
                          ("stability", "not graded", [])])
        self.assertEqual(task_tables._points(tests[1]), 2.0)

    def test_stub_tasks_and_table(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            exercise = Path(folder) / "exercises" / "07_x"
            exercise.mkdir(parents=True)
            (exercise / "unit.cpp").write_text(STUB, encoding="utf-8")
            tasks = task_tables.stub_tasks(exercise)
            self.assertEqual(tasks, {"1": ["one"], "2": ["two"], "3a": ["three(a)"]})
            source = Path(folder) / "grading.cpp"
            source.write_text(SOURCE, encoding="utf-8")
            tests = [t for t in task_tables.parse_tests(source) if t.tasks]
            text = task_tables.table("07", tasks, tests, Path(folder))
        self.assertIn("| a long name that clang-format splits | 2, 3a | 2 |", text)
        self.assertIn("2 tests, 3 points", text)
        self.assertIn("Task 3a: 1", text)

    def test_commands_are_one_set(self) -> None:
        block = task_tables.student_commands("03")
        self.assertIn("cmake --preset student", block)
        self.assertIn("--target tests_lesson03 lesson03", block)
        self.assertIn("tools/grade --student 03", block)
        self.assertNotIn("lesson03 --out", task_tables.student_commands("03", has_program=False))


if __name__ == "__main__":
    unittest.main()
