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
        self.assertEqual(tests[1].points, 2.0)

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
            text = task_tables.table("07", tasks, tests)
        self.assertIn("| a long name that clang-format splits | 2, 3a | 2 |", text)
        self.assertIn("2 tests, 3 points", text)
        self.assertIn("Task 3a: 1", text)

    def test_commands_are_one_set(self) -> None:
        block = task_tables.student_commands("03")
        self.assertIn("cmake --preset student", block)
        self.assertIn("--target tests_lesson03 lesson03", block)
        self.assertIn("tools/grade --student 03", block)
        self.assertNotIn("lesson03 --out", task_tables.student_commands("03", has_program=False))



import code_map  # noqa: E402

README = """# Lesson 01 — x

> Notes: x.

**Read in this order:**

1. The library: [`geometry/thing.hpp`](../../lib/illum/geometry/thing.hpp), [`core/util.hpp`](../../lib/illum/core/util.hpp).
2. The demonstration, [`main.cpp`](main.cpp).
3. The studies: [`s02_cost.cpp`](studies/s02_cost.cpp) (§2).

## 1. The idea

## 2. What it costs: a study

<!-- code-map: begin (written by tools/task_tables.py --update) -->
<!-- code-map: end -->
"""


class CodeMapTest(unittest.TestCase):
    """The lesson layout and its "Where the code is" blocks (tools/code_map.py)."""

    def tree(self, folder: str, readme: str = README, study: str = "// §2 What it costs: the cost.\n"
             "void s02_cost() {}\n", main: str = 'run_section(id, "§1 The idea", f);\n') -> Path:
        root = Path(folder)
        files = {
            "lessons/01_x/README.md": readme,
            "lessons/01_x/main.cpp": main,
            "lessons/01_x/studies/s02_cost.cpp": study,
            "lessons/01_x/shapes.hpp": "#pragma once\n",
            "exercises/01_x/README.md": "# Exercise 01\n\n" + code_map.BEGIN + "\n" + code_map.END + "\n",
            "exercises/01_x/thing.cpp": "// stub\n",
            "lib/illum/geometry/thing.hpp": "", "lib/illum/geometry/thing.cpp": "",
            "lib/illum/core/util.hpp": "", "lib/illum/core/util.cpp": "",
            "tests/01_x/grading.cpp": "", "tests/radiosity/util.cpp": "", "tests/radiosity/other.cpp": "",
            "slides/01_x.md": "",
        }
        for name, text in files.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text(text, encoding="utf-8")
        return root

    def test_block_links_everything_relative_to_its_readme(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            root = self.tree(folder)
            lesson = code_map.code_map(root, "01", root / "lessons/01_x/README.md")
            exercise = code_map.code_map(root, "01", root / "exercises/01_x/README.md")
        self.assertIn("[`main.cpp`](main.cpp) (the demonstration)", lesson)
        self.assertIn("[`studies/s02_cost.cpp`](studies/s02_cost.cpp) (§2)", lesson)
        self.assertIn("[`shapes.hpp`](shapes.hpp) (helpers)", lesson)
        # The unit's header, never its reference source (the student edition leaves it out).
        self.assertIn("[`geometry/thing.hpp`](../../lib/illum/geometry/thing.hpp) (exercise unit)", lesson)
        self.assertNotIn("geometry/thing.cpp", lesson)
        self.assertIn("[`core/util.hpp`](../../lib/illum/core/util.hpp) · [`.cpp`](../../lib/illum/core/util.cpp)",
                      lesson)
        self.assertIn("[`tests/01_x/grading.cpp`](../../tests/01_x/grading.cpp)", lesson)
        self.assertIn("also [`tests/radiosity/util.cpp`]", lesson)  # named after a library pair
        self.assertNotIn("other.cpp", lesson)
        self.assertIn("[`slides/01_x.md`](../../slides/01_x.md)", lesson)
        # The exercise's block links back to the lesson text and its program.
        self.assertIn("[`lessons/01_x/README.md`](../../lessons/01_x/README.md)", exercise)
        self.assertIn("[`main.cpp`](../../lessons/01_x/main.cpp)", exercise)
        self.assertIn("[`thing.cpp`](thing.cpp)", exercise)

    def test_update_then_check(self) -> None:
        with tempfile.TemporaryDirectory() as folder:
            root = self.tree(folder)
            # Both blocks stale, and the deck has no "Where the code is" slide yet.
            found = code_map.update(root, write=False)
            self.assertEqual(len(found), 3)
            self.assertTrue(any("slides/01_x.md" in p and "no \"Where the code is\" slide" in p for p in found))
            self.assertEqual(code_map.update(root, write=True), [])
            self.assertEqual(code_map.update(root, write=False), [])
            self.assertEqual(code_map.layout_problems(root), [])
            deck = (root / "slides/01_x.md").read_text(encoding="utf-8")
            self.assertTrue(deck.rstrip().endswith(code_map.END))
            self.assertIn("## Where the code is", deck)
            self.assertIn("[`thing.cpp`](../../exercises/01_x/thing.cpp)", deck)  # relative to out/slides/
            self.assertIn("[`geometry/thing.hpp`](../../lib/illum/geometry/thing.hpp)", deck)
            # A slide after it is refused: it must stay the deck's last.
            (root / "slides/01_x.md").write_text(deck + "\n---\n\n## More\n", encoding="utf-8")
            self.assertTrue(any("must be the deck's last" in p for p in code_map.update(root, write=False)))

    def test_layout_rules(self) -> None:
        cases = {
            "banner": (dict(study="// §2 Something else.\nvoid s02_cost() {}\n"), "the first line must be"),
            "entry point": (dict(study="// §2 What it costs.\nvoid run() {}\n"), "defines no function s02_cost"),
            "label": (dict(main='run_section(id, "§1 Another idea", f);\n'), "does not agree"),
            "no section": (dict(main='run_section(id, "§7 The idea", f);\n'), "names no section"),
            "no list": (dict(readme=README.replace("**Read in this order:**", "Read this.")), "must open"),
            "study unlisted": (dict(readme=README.replace("[`s02_cost.cpp`](studies/s02_cost.cpp) (§2)", "none")),
                               "in file-name order"),
            "main unlisted": (dict(readme=README.replace("[`main.cpp`](main.cpp)", "main")), "does not link main.cpp"),
            "unit unlisted": (dict(readme=README.replace("[`geometry/thing.hpp`](../../lib/illum/geometry/thing.hpp), ", "")),
                              "header of an exercise unit"),
            "unit source": (dict(readme=README.replace("geometry/thing.hpp`](../../lib/illum/geometry/thing.hpp)",
                                                       "geometry/thing.cpp`](../../lib/illum/geometry/thing.cpp)")),
                            "a reference unit"),
            "broken link": (dict(readme=README.replace("core/util.hpp)", "core/gone.hpp)")), "does not exist"),
        }
        for name, (change, words) in cases.items():
            with self.subTest(name), tempfile.TemporaryDirectory() as folder:
                problems = code_map.layout_problems(self.tree(folder, **change))
                self.assertTrue(any(words in p for p in problems), problems)

if __name__ == "__main__":
    unittest.main()
