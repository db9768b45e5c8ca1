#!/usr/bin/env python3
"""Unit tests of tools/figures.py: figures in the texts follow the programs' tables.

    python3 tests/tools/test_figures.py        (ctest: figures_tool)
"""
from __future__ import annotations

import contextlib
import io
import json
import struct
import sys
import tempfile
import unittest
import zlib
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools"))

import figures  # noqa: E402
from common import png  # noqa: E402
from common.files import atomic_write_bytes  # noqa: E402
from gallery import figures as gallery_figures, kept_images, tables  # noqa: E402

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
        return gallery_figures.process(self.root, self.out, mode, log=self.messages.append)

    def text(self) -> str:
        return (self.root / "lessons/01_x/README.md").read_text(encoding="utf-8")

    def test_update_writes_the_table_and_a_label_naming_the_run(self):
        self.write("out/run_log.json", json.dumps({"lesson01": {
            "started": "2026-12-01 20:00 UTC", "cores": 2, "load_before": [3.5, 2, 1], "load_after": [4.25, 2, 1]}}))
        self.assertEqual(self.run_mode("update"), 0, self.messages)
        text = self.text()
        self.assertIn("| 2 | 0.25 | 13.4 |", text)
        self.assertIn("measured on 2 cores, load average 3.5 at the start", text)
        self.assertNotIn("2026", text)  # a reader's page holds no dated measurement (the run log does)
        self.assertIn("4.25 at its end", text)
        self.assertTrue(text.endswith("The end.\n"))
        self.assertEqual(self.run_mode("check"), 0, self.messages)

    def test_the_label_names_the_programs_a_run_was_side_by_side_with(self):
        self.write("out/run_log.json", json.dumps({"lesson01": {
            "started": "2026-12-01 20:00 UTC", "cores": 2, "load_before": [1, 1, 1], "load_after": [2, 1, 1],
            "beside": ["lesson03", "lesson12"]}}))
        self.assertEqual(self.run_mode("update"), 0, self.messages)
        self.assertIn("2 at its end, side by side with `lesson03` and `lesson12` (each timing one thread while they "
                      "overlapped)",
                      self.text())

    def test_the_label_of_a_mixed_program_says_its_timings_on_more_threads_had_the_machine(self):
        self.write("out/run_log.json", json.dumps({"lesson01": {
            "started": "2026-12-01 20:00 UTC", "cores": 2, "load_before": [1, 1, 1], "load_after": [2, 1, 1],
            "beside": ["lesson12"], "waited_seconds": 8.5, "whole_machine_seconds": 4.6}}))
        self.assertEqual(self.run_mode("update"), 0, self.messages)
        self.assertIn("side by side with `lesson12` (each timing one thread while they overlapped); its timings on "
                      "more threads had the machine to themselves", self.text())

    def test_a_run_alone_says_nothing_of_neighbours(self):
        self.write("out/run_log.json", json.dumps({"lesson01": {
            "started": "2026-12-01 20:00 UTC", "cores": 2, "load_before": [1, 1, 1], "load_after": [2, 1, 1],
            "beside": []}}))
        self.assertEqual(self.run_mode("update"), 0, self.messages)
        self.assertNotIn("side by side", self.text())

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
        self.assertTrue(tables.is_timing_name("seconds to 1e-6"))
        self.assertTrue(tables.is_timing_name("time_slope_res_ge_64"))
        self.assertFalse(tables.is_timing_name("s"))           # the ray parameter
        self.assertFalse(tables.is_timing_name("wall strip"))  # a configuration

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

    def value_text(self, sentence: str, definitions: str) -> None:
        if not hasattr(self, "base"):
            self.base = self.text()  # after update: the figure holds its table
        self.write("lessons/01_x/README.md", self.base + "\n" + sentence + "\n\n" + definitions + "\n")

    def test_a_value_in_a_sentence_is_checked_against_its_cell(self):
        self.run_mode("update")
        self.value_text("At n = 2 the error is 0.25<!--=e2-->, a quarter.",
                        '<!-- value e2: out/lesson01/t.md row="n=2" column=error -->')
        self.assertEqual(self.run_mode("check"), 0, self.messages)
        self.assertIn("1 value(s) in sentences", "\n".join(self.messages))
        self.write("out/lesson01/t.md", TABLE.replace("| 0.25 |", "| 0.3 |"))
        self.assertEqual(self.run_mode("check"), 1)
        self.assertIn("value e2: the text says 0.25, the program wrote 0.3", "\n".join(self.messages))
        # refresh leaves a changed value for --update, which writes it
        self.assertEqual(self.run_mode("refresh"), 0, self.messages)
        self.assertIn("is 0.25<!--=e2-->,", self.text())
        self.assertEqual(self.run_mode("update"), 0, self.messages)
        self.assertIn("is 0.3<!--=e2-->, a quarter.", self.text())

    def test_values_are_formatted_and_combined_and_timings_refresh(self):
        self.run_mode("update")
        self.value_text("Halving n halves the error (ratio 2.0<!--=r-->), 25<!--=p-->% at n = 2, "
                        "tests take `12.1`<!--=t--> and the run slows by 1.1<!--=slow-->×.",
                        '<!-- value e1: out/lesson01/t.md row="n=1" column=error -->\n'
                        '<!-- value e2: out/lesson01/t.md where="n=2" column=error -->\n'
                        '<!-- value r: e1 / e2 format=fixed:1 -->\n'
                        '<!-- value p: out/lesson01/t.md row="n=2" column=error format=percent:0 -->\n'
                        '<!-- value t: out/lesson01/t.md row="n=1" column=ns_per_test -->\n'
                        '<!-- value t2: out/lesson01/t.md row="n=2" column=ns_per_test -->\n'
                        '<!-- value slow: t2 / t format=fixed:1 -->')
        self.assertEqual(self.run_mode("check"), 0, self.messages)
        # Timings (and values computed from one) are not compared; refresh rewrites them.
        self.write("out/lesson01/t.md", TABLE.replace("12.1", "10.0"))
        self.assertEqual(self.run_mode("check"), 0, self.messages)
        self.assertEqual(self.run_mode("refresh"), 0, self.messages)
        self.assertIn("tests take `10.0`<!--=t--> and the run slows by 1.3<!--=slow-->×.", self.text())

    def test_a_formatted_value_takes_the_full_digits_of_the_csv_beside_the_md(self):
        # The .md shows 0.255 (four digits); the .csv beside it holds 0.25492, which is 25%, not 26%
        # (rounding the shown digits again gave 26). A value shown as its cell keeps the .md's text.
        self.run_mode("update")
        self.write("out/lesson01/p.md", "| n | rate |\n|---|---|\n| 1 | 0.255 |\n| 2 | 0.5 |\n")
        self.write("out/lesson01/p.csv", "n,rate\n1,0.25492\n2,0.5\n")
        self.value_text("It fails 25<!--=p-->% (0.255<!--=c--> of the rays).",
                        '<!-- value p: out/lesson01/p.md row="n=1" column=rate format=percent:0 -->\n'
                        '<!-- value c: out/lesson01/p.md row="n=1" column=rate -->')
        self.assertEqual(self.run_mode("check"), 0, self.messages)
        # Without the .csv the shown digits are all there is: 0.255 is 26%.
        (self.root / "out/lesson01/p.csv").unlink()
        self.assertEqual(self.run_mode("check"), 1)
        self.assertIn("value p: the text says 25, the program wrote 26", "\n".join(self.messages))

    def test_a_value_can_count_the_rows_of_a_source_tree_table(self):
        self.run_mode("update")
        self.write("exercises/01_x/README.md", "# Exercise\n\n| test | task |\n|---|---|\n| a | 1 |\n| b | 1 |\n"
                                               "| c | 2 |\n")
        self.value_text("The exercise has 3<!--=tests--> tests, 2<!--=task1--> for task 1.",
                        '<!-- value tests: exercises/01_x/README.md format=rows -->\n'
                        '<!-- value task1: exercises/01_x/README.md where="task=1" format=rows -->')
        self.assertEqual(self.run_mode("check"), 0, self.messages)
        self.write("exercises/01_x/README.md", "# Exercise\n\n| test | task |\n|---|---|\n| a | 1 |\n")
        self.assertEqual(self.run_mode("check"), 1)
        self.assertIn("value tests: the text says 3, the program wrote 1", "\n".join(self.messages))

    def test_bad_values_are_errors_naming_the_line(self):
        self.run_mode("update")
        cases = [
            ("the error is 0.25<!--=e-->.", "", "value e is used but not defined"),
            ("the error is 0.25.", '<!-- value e: out/lesson01/t.md row="n=2" column=error -->',
             "value e is defined but no sentence uses it"),
            ("the error is 0.25<!--=e-->.", '<!-- value e: out/lesson01/t.md column=error -->',
             "pick 3 rows"),
            ("the error is 0.25<!--=e-->.", '<!-- value e: out/lesson01/t.md row="n=2" column=err -->',
             "has no column 'err'"),
            ("the error is 0.25<!--=e-->.", '<!-- value e: out/lesson01/t.md row="n=2" column=error format=pct -->',
             "unknown format 'pct'"),
            ("the error is <!--=e-->.", '<!-- value e: out/lesson01/t.md row="n=2" column=error -->',
             "follows no value"),
            ("ratio 1<!--=r-->.", '<!-- value r: e1 / 2 -->', "needs a format="),
            ("ratio 1<!--=r-->.", '<!-- value r: __import__("os") format=int -->', "may use only"),
        ]
        for sentence, definition, message in cases:
            with self.subTest(message=message):
                self.value_text(sentence, definition)
                self.assertEqual(self.run_mode("check"), 1, sentence)
                self.assertIn(message, "\n".join(self.messages))

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


def encode_png(width: int, height: int, pixels: bytes, filters: list[int]) -> bytes:
    """An 8-bit RGB PNG whose row y is written with filter filters[y] (PNG spec, section 9),
    an encoder written here so that the tool's decoder is tested against the specification."""
    stride, rows, previous = width * 3, [], bytes(width * 3)
    for y in range(height):
        row = pixels[y * stride:(y + 1) * stride]
        kind = filters[y]
        left = lambda i, r=row: r[i - 3] if i >= 3 else 0  # noqa: E731
        upper_left = lambda i, p=previous: p[i - 3] if i >= 3 else 0  # noqa: E731

        def paeth(a: int, b: int, c: int) -> int:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            return a if pa <= pb and pa <= pc else b if pb <= pc else c
        predictor = {0: lambda i: 0, 1: left, 2: lambda i: previous[i],
                     3: lambda i: (left(i) + previous[i]) // 2,
                     4: lambda i: paeth(left(i), previous[i], upper_left(i))}[kind]
        rows.append(bytes([kind]) + bytes((row[i] - predictor(i)) % 256 for i in range(stride)))
        previous = row

    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b""))


def picture(width: int, height: int, shift: int = 0) -> bytes:
    """Distinct, non-monotonic values, so that every predictor matters."""
    return bytes((37 * i + 11 * (i // 7) + shift) % 251 for i in range(width * height * 3))


class OptionsTest(unittest.TestCase):
    """A wrong --out or --source is one line naming the option and the value, exit status 2, before
    any text is read (not one missing-file problem per figure of every text)."""

    def refused(self, argv: list[str]) -> str:
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as stop:
            figures.main(argv)
        self.assertEqual(stop.exception.code, 2)
        return err.getvalue()

    def test_an_out_that_is_no_folder_is_refused(self):
        with tempfile.TemporaryDirectory() as folder:
            a_file = Path(folder) / "out.txt"
            a_file.write_text("x")
            for out in (Path(folder) / "missing", a_file):
                text = self.refused(["--check", "--out", str(out)])
                self.assertIn(f"--out {out}: not a folder of the main job's outputs", text)
                self.assertEqual(text.count("error:"), 1, text)
                self.assertNotIn("wrote no", text)  # no problem listed per figure
            self.assertEqual(a_file.read_text(), "x")

    def test_a_source_without_lessons_is_refused(self):
        with tempfile.TemporaryDirectory() as folder:
            text = self.refused(["--links", "--source", folder])
            self.assertIn(f"--source {folder}: not an illum source tree", text)


    def test_an_empty_path_or_a_link_loop_is_refused_naming_the_option(self):
        self.assertIn("argument --out: the path is empty", self.refused(["--check", "--out", ""]))
        self.assertIn("argument --source: the path is empty", self.refused(["--links", "--source", ""]))
        with tempfile.TemporaryDirectory() as folder:
            loop = Path(folder) / "loop"
            loop.symlink_to("loop")
            self.assertIn(f"argument --out: '{loop}' is a symbolic link that leads back to itself",
                          self.refused(["--check", "--out", str(loop)]))


class KilledRunTest(unittest.TestCase):
    """A run killed without warning (SIGKILL) leaves its temporary beside a text: the next writing
    run removes it once its PID is gone, and names it; a live run's stays."""

    def test_a_dead_runs_temporaries_are_removed_and_named_a_live_runs_kept(self):
        import os
        import subprocess
        with tempfile.TemporaryDirectory() as folder:
            root = Path(folder)
            text = root / "lessons" / "01_x" / "README.md"
            (root / "lessons" / "01_x" / "figures").mkdir(parents=True)
            text.write_text(TEXT)
            gone = subprocess.Popen(["true"])  # a PID that has ended
            gone.wait()
            stale = text.with_name(f"README.md.tmp-figures-{gone.pid}")
            older = text.with_name("README.md.tmp-figures")  # this tool's name before it held a PID
            image = root / "lessons" / "01_x" / "figures" / f"a.png.tmp-figures-{gone.pid}"
            live = text.with_name(f"README.md.tmp-figures-{os.getpid()}")
            for p in (stale, older, image, live):
                p.write_text("half")
            said: list[str] = []
            gallery_figures.remove_stale_temporaries(root, log=said.append)
            self.assertFalse(stale.exists() or older.exists() or image.exists())
            self.assertTrue(live.exists())
            self.assertEqual(len(said), 3, said)
            self.assertIn(f"figures: removed lessons/01_x/README.md.tmp-figures-{gone.pid}, left by a run that was "
                          "killed before it finished", said)

    def test_a_file_is_written_whole_through_a_temporary_named_with_the_pid(self):
        import os
        from unittest import mock
        with tempfile.TemporaryDirectory() as folder:
            target, renamed, replace = Path(folder) / "a.png", [], os.replace
            with mock.patch("os.replace", lambda src, dst: (renamed.append(Path(src).name), replace(src, dst))):
                atomic_write_bytes(target, b"picture", tag=kept_images.TAG)  # how the texts and images are written
            self.assertEqual(target.read_bytes(), b"picture")
            self.assertEqual(sorted(p.name for p in Path(folder).iterdir()), ["a.png"])
            self.assertEqual(renamed, [f"a.png.tmp-figures-{os.getpid()}"])


class KeptImagesTest(unittest.TestCase):
    """Lesson texts show their images from figures/, kept copies of what the programs drew."""

    def setUp(self) -> None:
        self._tmp = tempfile.TemporaryDirectory(prefix="illum-figures-images-")
        self.root = Path(self._tmp.name)
        self.out = self.root / "out"
        self.messages: list[str] = []
        self.render = encode_png(20, 10, picture(20, 10), [0, 1, 2, 3, 4] * 2)
        self.write("out/lesson01/render.png", self.render)
        self.write("out/lesson01/cost.png", encode_png(4, 5, picture(4, 5), [4] * 5))
        self.write("out/lesson01/cost.gp", b'set title "Cost"\nset ylabel "ns per query"\n')
        self.write("out/lesson01/error.png", encode_png(4, 5, picture(4, 5, 3), [1] * 5))
        self.write("out/lesson01/error.gp", b'set title "Error against n"\nset ylabel "max error"\n')
        self.write("lessons/01_x/README.md", b"# One\n\n![a render](../../out/lesson01/render.png)\n"
                                             b"![cost](../../out/lesson01/cost.png) "
                                             b"![error](../../out/lesson01/error.png)\n\n```\n"
                                             b"![in code](../../out/lesson01/none.png)\n```\n")

    def tearDown(self) -> None:
        self._tmp.cleanup()

    def write(self, rel: str, data: bytes) -> Path:
        path = self.root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
        return path

    def update(self) -> int:
        self.messages = []
        return kept_images.update_images(self.root, self.out, log=self.messages.append)

    def check(self) -> int:
        self.messages = []
        # The fixture's gnuplot scripts hold labels only: the plots are tested in test_plots.py.
        return gallery_figures.process(self.root, self.out, "check", log=self.messages.append, plots=False)

    def test_the_decoder_undoes_each_of_the_five_row_filters(self):
        width, height, channels, pixels = png.decode(self.render)
        self.assertEqual((width, height, channels), (20, 10, 3))
        self.assertEqual(pixels, picture(20, 10))

    def test_update_keeps_every_image_a_text_shows(self):
        self.assertEqual(self.update(), 0, self.messages)
        text = (self.root / "lessons/01_x/README.md").read_text(encoding="utf-8")
        self.assertIn("![a render](figures/render.png)", text)
        self.assertIn("![error](figures/error.png)", text)
        self.assertIn("![cost](figures/cost.png)", text)                # a timing plot is kept too
        self.assertIn("![in code](../../out/lesson01/none.png)", text)  # inside a code fence: not a link
        kept = sorted(p.name for p in (self.root / "lessons/01_x/figures").iterdir())
        self.assertEqual(kept, ["cost.png", "error.png", "render.png"])
        self.assertEqual(self.check(), 0, self.messages)

    def test_a_kept_timing_plot_is_checked_by_its_size_only(self):
        self.update()
        self.write("out/lesson01/cost.png", encode_png(4, 5, picture(4, 5, 90), [4] * 5))  # another run
        self.assertEqual(self.check(), 0, self.messages)
        self.write("out/lesson01/cost.png", encode_png(5, 5, picture(5, 5), [4] * 5))
        self.assertEqual(self.check(), 1)
        self.assertIn("cost.png drifted from what lesson01 draws: its size (4, 5) is now (5, 5)",
                      "\n".join(self.messages))

    def test_check_accepts_a_level_of_rounding_and_fails_on_a_changed_drawing(self):
        self.update()
        nudged = bytes(min(v + 1, 255) for v in picture(20, 10))  # every value one level up
        self.write("out/lesson01/render.png", encode_png(20, 10, nudged, [4] * 10))
        self.assertEqual(self.check(), 0, self.messages)
        changed = bytearray(picture(20, 10))
        changed[0:30] = bytes(30)  # ten pixels black: 5% of the picture
        self.write("out/lesson01/render.png", encode_png(20, 10, bytes(changed), [0] * 10))
        self.assertEqual(self.check(), 1)
        joined = "\n".join(self.messages)
        self.assertIn("render.png drifted from what lesson01 draws: 10 of 200 pixels differ", joined)
        self.write("out/lesson01/render.png", encode_png(10, 20, picture(20, 10), [0] * 20))
        self.assertEqual(self.check(), 1)
        self.assertIn("the kept figure is 20×10 with 3 channel(s), the program drew 10×20", "\n".join(self.messages))

    def test_check_fails_on_an_image_linked_in_out_and_an_orphan_and_update_repairs(self):
        self.update()
        readme = self.root / "lessons/01_x/README.md"
        text = readme.read_text(encoding="utf-8")
        readme.write_text(text.replace("figures/render.png", "../../out/lesson01/render.png")
                          .replace("figures/cost.png", "../../out/lesson01/cost.png"), encoding="utf-8")
        self.write("lessons/01_x/figures/old.png", b"")
        self.assertEqual(self.check(), 1)
        joined = "\n".join(self.messages)
        self.assertIn("render.png is linked in out/", joined)
        self.assertIn("cost.png is linked in out/", joined)
        self.assertIn("the image '../../out/lesson01/render.png' points into out/", joined)
        self.assertIn("lessons/01_x/figures/old.png is not shown by lessons/01_x/README.md", joined)
        self.assertEqual(self.update(), 0, self.messages)
        self.assertEqual(readme.read_text(encoding="utf-8"), text)
        self.assertFalse((self.root / "lessons/01_x/figures/old.png").exists())
        self.assertEqual(self.check(), 0, self.messages)

    def test_a_screenshot_of_the_lab_is_kept_from_out_lab_and_checked_by_its_size_only(self):
        self.write("out/lab/lab_view.png", encode_png(6, 4, picture(6, 4), [0] * 4))
        readme = self.root / "lessons/01_x/README.md"
        readme.write_text(readme.read_text(encoding="utf-8") + "![the lab](figures/lab_view.png)\n", encoding="utf-8")
        self.assertEqual(self.update(), 0, self.messages)
        self.assertEqual((self.root / "lessons/01_x/figures/lab_view.png").read_bytes(),
                         (self.out / "lab/lab_view.png").read_bytes())
        self.assertEqual(self.check(), 0, self.messages)
        # Another run's screenshot: every pixel different (its timings moved), the same size: still kept.
        self.write("out/lab/lab_view.png", encode_png(6, 4, picture(6, 4, 100), [0] * 4))
        self.assertEqual(self.check(), 0, self.messages)
        self.write("out/lab/lab_view.png", encode_png(7, 4, picture(7, 4), [0] * 4))
        self.assertEqual(self.check(), 1)
        self.assertIn("lab_view.png drifted", "\n".join(self.messages))
        (self.out / "lab/lab_view.png").unlink()
        self.assertEqual(self.check(), 1)
        self.assertIn("the program wrote no lab/lab_view.png", "\n".join(self.messages))


class TextLinksTest(unittest.TestCase):
    """Every link and image of a text resolves in the source tree, headings included."""

    def setUp(self) -> None:
        self._tmp = tempfile.TemporaryDirectory(prefix="illum-figures-links-")
        self.root = Path(self._tmp.name)
        for rel, text in {
            "lessons/01_x/README.md": "# Lesson 01\n\n## 2. The slab test: \"comprobar (nodo, rayo)\"\n\n"
                                      "## Hard cases\n\n## Hard cases\n",
            "lessons/01_x/figures/a.png": "",
            "lib/illum/core/x.hpp": "",
            "docs/errata.md": "# Errata\n\n## Erratum 4\n",
        }.items():
            path = self.root / rel
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8")

    def tearDown(self) -> None:
        self._tmp.cleanup()

    def links(self, text: str) -> list[str]:
        path = self.root / "exercises/01_x/README.md"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        messages: list[str] = []
        figures.check_links_only(self.root, log=messages.append)
        return [m for m in messages if "exercises/01_x/README.md" in m]

    def test_links_into_the_tree_and_to_headings_resolve(self):
        good = ("[text](../../lessons/01_x/README.md#2-the-slab-test-comprobar-nodo-rayo) "
                "[again](../../lessons/01_x/README.md#hard-cases-1) ![a](../../lessons/01_x/figures/a.png) "
                "[h](../../lib/illum/core/x.hpp) [folder](../../lib/illum/) [erratum 4](../../docs/errata.md#erratum-4) "
                "[web](https://example.org/x) [top](#exercise)\n\n# Exercise\n\n`[not a link](nowhere.md)`\n"
                "```\n[in code](nowhere.md)\n```\n")
        self.assertEqual(self.links(good), [])

    def test_missing_files_out_and_unknown_headings_are_named(self):
        problems = "\n".join(self.links(
            "![plot](../../out/lesson01/p.png) [gone](../../lib/illum/core/y.hpp) "
            "[h](../../lessons/01_x/README.md#2-the-slab-test) [up](../../../etc/passwd) [self](#nothing)\n"))
        self.assertIn("'../../out/lesson01/p.png' points into out/", problems)
        self.assertIn("names lib/illum/core/y.hpp, which does not exist", problems)
        self.assertIn("'../../lessons/01_x/README.md#2-the-slab-test' names no heading", problems)
        self.assertIn("'../../../etc/passwd' leaves the repository", problems)
        self.assertIn("'#nothing' names no heading", problems)


if __name__ == "__main__":
    unittest.main(verbosity=1)
