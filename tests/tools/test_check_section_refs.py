#!/usr/bin/env python3
"""Unit tests of tests/checks/check_section_refs.py: a "lesson NN, §M" that names no section, a label that
is not the section's title, and a file cited in a section other than the one that teaches it are
each found with file and line; a book's section and a correct reference are not. Run: python3
tests/tools/test_check_section_refs.py (ctest: tools_check_section_refs_py)."""
from __future__ import annotations

import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "checks"))

import check_section_refs  # noqa: E402

TEXT = """# Lesson 08 — Structures

## 1. Visibility

The library: `slab_test.hpp`, `bvh.hpp`, `octree.hpp`.

## 2. Bounding volumes and the slab test

The slab test (`slab_test.hpp`).

### 2.1 Parallel rays

## 4. Octrees

illum's octree (`octree.hpp`).

## 5. Bounding volume hierarchies: "comprobar (nodo, rayo)"

The BVH (`bvh.hpp`).

## Further reading

- M. Pharr et al., *Physically Based Rendering*, §7.3.
"""


class SectionRefsTest(unittest.TestCase):
    def problems(self, files: dict[str, str]) -> list[str]:
        with tempfile.TemporaryDirectory() as folder:
            root = Path(folder)
            files = {"lessons/08_structures/README.md": TEXT, **files}
            for name, text in files.items():
                (root / name).parent.mkdir(parents=True, exist_ok=True)
                (root / name).write_text(text, encoding="utf-8")
            return check_section_refs.problems(root)

    def test_correct_references_pass(self) -> None:
        self.assertEqual(self.problems({
            "lib/illum/accel/slab_test.hpp": "// The slab test, lesson 08 (§2). Parallel rays: §2.1.\n",
            "lib/illum/accel/octree.hpp": "// The octree (lesson 08, §4); pbrt-v4 §6.8.6 bounds its error.\n",
            "exercises/08_structures/bvh.cpp": 'throw NotImplemented("f", "(lesson 08, §5 \\"comprobar (nodo, rayo)\\")");\n',
            "lessons/08_structures/main.cpp": "// §4 and §5\n",
        }), [])

    def test_a_missing_section_is_found_with_its_line(self) -> None:
        found = self.problems({"lib/illum/trace/x.hpp": "// one\n// lesson 08, §3 and §5.2\n"})
        self.assertEqual(len(found), 2)
        self.assertTrue(all(p.startswith("lib/illum/trace/x.hpp:2:") for p in found))
        self.assertIn("no §3", found[0])
        self.assertIn("no §5.2", found[1])

    def test_a_bare_section_belongs_to_the_files_lesson(self) -> None:
        found = self.problems({"exercises/08_structures/README.md": "Task 1 (§7).\n"})
        self.assertEqual(len(found), 1)
        self.assertIn("exercises/08_structures/README.md:1", found[0])

    def test_a_label_must_be_the_sections_title(self) -> None:
        found = self.problems({"lib/illum/accel/grid.hpp": '// lesson 08, §4 "the slab test"\n'})
        self.assertEqual(len(found), 1)
        self.assertIn('§4 is "Octrees"', found[0])

    def test_a_file_is_cited_where_the_text_teaches_it(self) -> None:
        found = self.problems({
            "lib/illum/accel/slab_test.hpp": "// The slab test, lesson 08 (§4).\n",
            "exercises/08_structures/bvh.cpp": "// lesson 08, §2\n",
        })
        self.assertEqual(len(found), 2)
        self.assertTrue(any("names slab_test in §2" in p for p in found))
        self.assertTrue(any("names bvh in §5" in p for p in found))

    def test_a_reference_with_no_lesson_is_found(self) -> None:
        found = self.problems({"lib/illum/core/x.hpp": "// see §2\n"})
        self.assertEqual(len(found), 1)
        self.assertIn("names no lesson", found[0])


if __name__ == "__main__":
    unittest.main()
