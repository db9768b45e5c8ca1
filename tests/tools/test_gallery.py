#!/usr/bin/env python3
"""Unit tests of the main job's Python side: tools/gallery (output checks, the
index page, link checks, atomic writes), tests/checks/check_outputs.py and
tools/main_job.py, against the fake lesson program in tests/slides/fixtures/.

    python3 tests/tools/test_gallery.py        (ctest: gallery_tools)
"""
from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import zlib
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools"))
sys.path.insert(0, str(SOURCE / "tests" / "checks"))

import check_outputs  # noqa: E402
import main_job  # noqa: E402
from gallery import lesson_runs  # noqa: E402
from common import files as fsutil, png  # noqa: E402
from common.markdown import parse_tables  # noqa: E402
from gallery import index, outputs  # noqa: E402

FAKE_LESSON = SOURCE / "tests" / "slides" / "fixtures" / "fake_lesson.py"


def make_png(width: int = 3, height: int = 2) -> bytes:
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + b"\x10\x20\x30" * width for _ in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


GOOD_MD = "| n | error |\n|---|---:|\n| 1 | 0.5 |\n| 2 | 0.25 |\n"
GOOD_CSV = "n,error\n1,0.5\n2,0.25\n"


class TempDirTest(unittest.TestCase):
    def setUp(self) -> None:
        self._tmp = tempfile.TemporaryDirectory(prefix="illum-gallery-test-")
        self.tmp = Path(self._tmp.name)

    def tearDown(self) -> None:
        self._tmp.cleanup()

    def write(self, rel: str, data: bytes | str) -> Path:
        path = self.tmp / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data if isinstance(data, bytes) else data.encode())
        return path

    def write_lesson_output(self, folder: str, manifest: dict, files: dict[str, bytes | str]) -> Path:
        for name, data in files.items():
            self.write(f"{folder}/{name}", data)
        self.write(f"{folder}/manifest.json", json.dumps(manifest))
        return self.tmp / folder


# --- single-file checks -------------------------------------------------------------


class PngCheck(TempDirTest):
    def test_good_png_passes_and_reports_its_size(self):
        p = self.write("a.png", make_png(7, 5))
        self.assertEqual(check_outputs.check_png(p), [])
        self.assertEqual(png.size_of(p), (7, 5))

    def test_wrong_signature_is_named(self):
        p = self.write("a.png", b"GIF89a" + make_png()[6:])
        [problem] = check_outputs.check_png(p)
        self.assertIn("not a PNG", problem)

    def test_zero_size_is_rejected(self):
        problems = check_outputs.check_png(self.write("a.png", make_png(0, 4)))
        self.assertTrue(any("0x4" in p for p in problems), problems)

    def test_truncated_png_is_caught_by_the_missing_iend(self):
        problems = check_outputs.check_png(self.write("a.png", make_png()[:-12]))
        self.assertTrue(any("IEND" in p for p in problems), problems)

    def test_corrupt_ihdr_crc_is_caught(self):
        data = bytearray(make_png())
        data[30] ^= 0xFF
        problems = check_outputs.check_png(self.write("a.png", bytes(data)))
        self.assertTrue(any("CRC" in p for p in problems), problems)


class HdrCheck(TempDirTest):
    def test_radiance_header_passes(self):
        p = self.write("a.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n" + bytes(8))
        self.assertEqual(check_outputs.check_hdr(p), [])

    def test_other_format_fails(self):
        [problem] = check_outputs.check_hdr(self.write("a.hdr", b"P6\n1 1\n255\n\0\0\0"))
        self.assertIn("#?RADIANCE", problem)

    def test_bad_resolution_line_fails(self):
        [problem] = check_outputs.check_hdr(self.write("a.hdr", b"#?RADIANCE\n\n1x2\n" + bytes(8)))
        self.assertIn("resolution", problem)


class MeshCheck(TempDirTest):
    def test_binary_ply_header_passes(self):
        body = b"ply\nformat binary_little_endian 1.0\nelement vertex 0\nend_header\n" + bytes([0xFF, 0x00])
        self.assertEqual(check_outputs.check_mesh(self.write("a.ply", body)), [])

    def test_ply_without_end_header_fails(self):
        [problem] = check_outputs.check_mesh(self.write("a.ply", b"ply\nformat ascii 1.0\nelement vertex 0\n"))
        self.assertIn("end_header", problem)

    def test_obj_needs_a_vertex(self):
        self.assertEqual(check_outputs.check_mesh(self.write("a.obj", b"v 0 0 0 1 1 1\nf 1 1 1\n")), [])
        [problem] = check_outputs.check_mesh(self.write("b.obj", b"# nothing\n"))
        self.assertIn("without vertices", problem)


class CsvCheck(TempDirTest):
    def test_good_csv_passes(self):
        self.assertEqual(check_outputs.check_csv(self.write("t.csv", GOOD_CSV)), [])

    def test_quoted_commas_are_one_field(self):
        self.assertEqual(check_outputs.check_csv(self.write("t.csv", 'name,value\n"a, b",1\n')), [])

    def test_ragged_row_names_its_line(self):
        [problem] = check_outputs.check_csv(self.write("t.csv", "a,b\n1,2\n3\n"))
        self.assertIn("line 3 has 1 fields, the header has 2", problem)

    def test_header_only_fails(self):
        [problem] = check_outputs.check_csv(self.write("t.csv", "a,b\n"))
        self.assertIn("no data rows", problem)

    def test_blank_file_fails(self):
        self.assertTrue(check_outputs.check_csv(self.write("t.csv", "\n")))


class MarkdownTables(TempDirTest):
    def test_good_table_parses_with_alignment(self):
        tables, problems = parse_tables(GOOD_MD.splitlines())
        self.assertEqual(problems, [])
        self.assertEqual(tables[0].header, ["n", "error"])
        self.assertEqual(tables[0].align, ["", "right"])
        self.assertEqual(tables[0].rows, [["1", "0.5"], ["2", "0.25"]])

    def test_escaped_pipe_stays_in_its_cell(self):
        tables, problems = parse_tables("| a | b |\n|---|---|\n| x \\| y | z |\n".splitlines())
        self.assertEqual(problems, [])
        self.assertEqual(tables[0].rows, [["x | y", "z"]])

    def test_missing_separator_is_reported(self):
        problems = check_outputs.check_markdown_table(self.write("t.md", "| a | b |\n| 1 | 2 |\n"))
        self.assertTrue(any("separator" in p for p in problems), problems)

    def test_row_with_wrong_cell_count_is_reported(self):
        problems = check_outputs.check_markdown_table(self.write("t.md", "| a | b |\n|---|---|\n| 1 |\n"))
        self.assertTrue(any("1 cells, the header has 2" in p for p in problems), problems)

    def test_file_without_table_fails(self):
        [problem] = check_outputs.check_markdown_table(self.write("t.md", "just words\n"))
        self.assertIn("no Markdown table", problem)

    def test_prose_around_a_table_is_fine(self):
        self.assertEqual(check_outputs.check_markdown_table(self.write("t.md", "Intro\n\n" + GOOD_MD + "\nDone.\n")), [])


# --- manifests and whole folders ----------------------------------------------------


class Manifests(TempDirTest):
    def manifest(self, **overrides):
        data = {"id": "lesson07", "title": "Primary rays",
                "outputs": [{"kind": "image", "file": "a.png", "caption": "A"}]}
        data.update(overrides)
        return data

    def test_missing_manifest(self):
        with self.assertRaisesRegex(outputs.ManifestError, "not found"):
            outputs.load_manifest(self.tmp)

    def test_invalid_json(self):
        self.write("manifest.json", "{nope")
        with self.assertRaisesRegex(outputs.ManifestError, "not valid JSON"):
            outputs.load_manifest(self.tmp)

    def test_unknown_kind_and_escaping_path_are_named(self):
        self.write("manifest.json", json.dumps(self.manifest(outputs=[
            {"kind": "video", "file": "a.mp4"}, {"kind": "image", "file": "../x.png"}])))
        with self.assertRaises(outputs.ManifestError) as ctx:
            outputs.load_manifest(self.tmp)
        self.assertIn("unknown kind 'video'", str(ctx.exception))
        self.assertIn("plain name inside the output folder", str(ctx.exception))

    def test_good_folder_has_no_problems(self):
        folder = self.write_lesson_output("o", self.manifest(outputs=[
            {"kind": "image", "file": "a.png", "caption": "A"},
            {"kind": "table", "file": "t.csv", "caption": "T"},
            {"kind": "markdown", "file": "t.md", "caption": "T"},
        ]), {"a.png": make_png(), "t.csv": GOOD_CSV, "t.md": GOOD_MD})
        self.assertEqual(check_outputs.check_output_folder(folder, "lesson07"), [])

    def test_folder_problems_are_all_reported(self):
        folder = self.write_lesson_output("o", self.manifest(id="lesson08", outputs=[
            {"kind": "image", "file": "a.png", "caption": ""},
            {"kind": "image", "file": "a.png", "caption": ""},
            {"kind": "image", "file": "gone.png", "caption": ""},
            {"kind": "image", "file": "pic.jpg", "caption": ""},
            {"kind": "text", "file": "empty.txt", "caption": ""},
        ]), {"a.png": make_png(), "pic.jpg": b"x", "empty.txt": b"", "b.png.tmp-123": b"x"})
        problems = "\n".join(check_outputs.check_output_folder(folder, "lesson07"))
        for expected in ("expected 'lesson07'", "listed twice", "gone.png: listed in manifest.json",
                         "needs a .png file", "empty.txt: empty file", "temporary files left behind"):
            self.assertIn(expected, problems)


# --- check_outputs.py against the fake lesson program --------------------------------


class CheckOutputsProgram(TempDirTest):
    def setUp(self):
        super().setUp()
        (self.tmp / "bin").mkdir()
        self.program = self.tmp / "bin" / "lesson01"
        self.program.symlink_to(FAKE_LESSON)

    def run_check(self, program: Path, env: dict | None = None) -> tuple[int, str]:
        old = dict(os.environ)
        os.environ.update(env or {})
        buffer = io.StringIO()
        try:
            with contextlib.redirect_stdout(buffer):
                code = check_outputs.main(["--run", str(program), "--out", str(self.tmp / "out" / "lesson01")])
        finally:
            os.environ.clear()
            os.environ.update(old)
        return code, buffer.getvalue()

    def test_good_program_passes(self):
        code, text = self.run_check(self.program)
        self.assertEqual(code, 0, text)
        self.assertIn("OK: lesson01", text)

    def test_stale_files_are_cleared_first(self):
        stale = self.write("out/lesson01/old.png", b"stale")
        code, text = self.run_check(self.program)
        self.assertEqual(code, 0, text)
        self.assertFalse(stale.exists())

    def test_each_broken_output_fails_with_its_reason(self):
        cases = {
            "png-signature": "not a PNG",
            "png-empty-size": "both must be non-zero",
            "csv-ragged": "fields, the header has 3",
            "md-table": "separator",
            "missing-file": "missing.png: listed in manifest.json",
            "hdr": "#?RADIANCE",
            "exit": "exited with code 1",
        }
        for what, reason in cases.items():
            with self.subTest(what):
                code, text = self.run_check(self.program, {"FAKE_LESSON_BREAK": what})
                self.assertEqual(code, 1, text)
                self.assertIn(reason, text)

    def test_help_and_unknown_flags_are_checked(self):
        sloppy = self.write("bin/lesson02", "#!/bin/sh\n"
                            "case \"$1\" in --help) echo 'usage: lesson02 [--out DIR]'; exit 0;; esac\n"
                            "[ \"$1\" = --quick ] || exit 0\n"
                            f"exec {sys.executable} {FAKE_LESSON} \"$@\"\n")
        sloppy.chmod(0o755)
        code, text = self.run_check(sloppy)
        self.assertEqual(code, 1, text)
        self.assertIn("--help does not mention --quick", text)
        self.assertIn("an unknown flag must be an error", text)

    def test_refuses_to_clear_a_source_tree(self):
        self.assertIsNotNone(check_outputs.safe_to_clear(SOURCE))
        self.assertIsNone(check_outputs.safe_to_clear(self.tmp))


# --- the index page ------------------------------------------------------------------


class IndexPage(TempDirTest):
    def setUp(self):
        super().setUp()
        self.source = self.tmp / "src"
        self.out = self.tmp / "src" / "out"
        self.write("src/lessons/01_ray_sphere/README.md", "# Ray and sphere (text)\n")
        self.write("src/exercises/01_ray_sphere/README.md", "# Exercise\n")
        self.write("src/slides/01_ray_sphere.md", "---\nmarp: true\n---\n# x\n")
        self.write("src/slides/README.md", "# not a deck\n")
        self.write("src/lessons/02_polygons/main.cpp", "int main() {}\n")
        self.write("src/slides/03_orientation.md", "# deck only\n")
        self.write("src/out/slides/01_ray_sphere.html", "<html></html>")
        self.write_lesson_output("src/out/lesson01", {
            "id": "lesson01", "title": "Ray & sphere",
            "outputs": [
                {"kind": "image", "file": "silhouette.png", "caption": "Hits <b>"},
                {"kind": "table", "file": "study.csv", "caption": "Study"},
                {"kind": "markdown", "file": "study.md", "caption": "Study"},
                {"kind": "plot", "file": "study.png", "caption": "Study plot"},
                {"kind": "script", "file": "study.gp", "caption": "script"},
                {"kind": "hdr", "file": "radiance.hdr", "caption": "HDR"},
                {"kind": "table", "file": "only csv.csv", "caption": "CSV alone"},
                {"kind": "image", "file": "never.png", "caption": "missing"},
            ]}, {"silhouette.png": make_png(), "study.csv": GOOD_CSV, "study.md": GOOD_MD,
                 "study.png": make_png(8, 4), "study.gp": "plot 1\n", "radiance.hdr": b"#?RADIANCE\n\n-Y 1 +X 1\n0000",
                 "only csv.csv": "a,b\n<x>,2\n"})
        self.write("src/out/lesson05/manifest.json", "{broken")

    def page(self) -> str:
        target = index.write_index(self.source, self.out)
        self.assertEqual(target, self.out / "index.html")
        return target.read_text()

    def test_lessons_are_discovered_from_every_source(self):
        lessons = index.discover_lessons(self.source, self.out)
        self.assertEqual([l.number for l in lessons], ["01", "02", "03", "05"])
        by = {l.number: l for l in lessons}
        self.assertEqual(by["01"].title, "Ray & sphere")  # the manifest wins
        self.assertEqual(by["02"].title, "Polygons")  # from the folder name
        self.assertEqual(by["03"].title, "Orientation")  # from the deck's name
        self.assertIsNotNone(by["05"].manifest_error)
        self.assertEqual(by["01"].deck_html, self.out / "slides" / "01_ray_sphere.html")
        self.assertIsNone(by["03"].deck_html)

    def test_page_shows_outputs_and_links(self):
        html = self.page()
        self.assertIn("Ray &amp; sphere", html)
        self.assertIn('<a href="lesson01/silhouette.png"><img src="lesson01/silhouette.png"', html)
        self.assertIn("Hits &lt;b&gt;", html)
        self.assertIn('<th class="right">error</th>', html)  # the Markdown table, rendered
        self.assertIn('<td class="right">0.25</td>', html)
        self.assertIn('<a href="lesson01/study.csv">CSV</a>', html)
        self.assertIn('<a href="lesson01/study.gp">gnuplot script</a>', html)
        self.assertIn('href="lesson01/radiance.hdr"', html)
        self.assertIn('href="lesson01/only%20csv.csv"', html)
        self.assertIn("<td>&lt;x&gt;</td>", html)  # a CSV without Markdown, rendered and escaped
        self.assertIn("never.png</code> <span class=\"note\">(listed in manifest.json but missing)", html)
        self.assertIn('href="slides/01_ray_sphere.html"', html)
        self.assertIn('href="../lessons/01_ray_sphere/README.md"', html)
        self.assertIn('href="../exercises/01_ray_sphere/README.md"', html)
        self.assertIn('href="../slides/03_orientation.md"', html)  # deck not built: its source
        self.assertIn("no lesson text yet", html)
        self.assertIn('class="error"', html)  # lesson 05's broken manifest, shown, not fatal
        self.assertIn("No outputs yet", html)

    def test_page_is_self_contained_and_every_link_resolves(self):
        self.page()
        html = (self.out / "index.html").read_text()
        self.assertNotIn("http://", html)
        self.assertNotIn("https://", html)
        self.assertNotIn("<link", html)
        self.assertNotIn("<script", html)
        self.assertEqual(index.check_links(self.out / "index.html"), [])

    def test_the_lab_s_screenshots_get_a_section_of_their_own(self):
        self.assertNotIn('id="lab"', self.page())  # no OUT/lab: no section
        self.write_lesson_output("src/out/lab", {
            "id": "lab", "title": "The lab", "outputs": [{"kind": "image", "file": "lab_view.png", "caption": "A view"}]},
            {"lab_view.png": make_png(8, 6)})
        html = self.page()
        self.assertIn('<section class="lesson" id="lab">', html)
        self.assertIn('<a href="#lab">the lab</a>', html)
        self.assertIn('<a href="lab/lab_view.png"><img src="lab/lab_view.png"', html)
        self.assertEqual(index.check_links(self.out / "index.html"), [])

    def test_index_outside_the_source_tree_links_back_into_it(self):
        out = self.tmp / "build" / "test-out"
        shutil.copytree(self.out / "lesson01", out / "lesson01")
        html = index.write_index(self.source, out).read_text()
        self.assertIn('href="../../src/lessons/01_ray_sphere/README.md"', html)
        self.assertEqual(index.check_links(out / "index.html"), [])

    def test_link_check_finds_broken_links_and_external_assets(self):
        page = self.write("p/index.html", '<a href="#top">x</a><a href="gone.html">y</a><img src="ok.png">'
                          '<img src="https://example.org/x.png"><a href="https://example.org">fine</a>'
                          '<h1 id="top"></h1><a href="#nowhere">z</a>')
        self.write("p/ok.png", make_png())
        problems = "\n".join(index.check_links(page))
        self.assertIn("gone.html", problems)
        self.assertIn("external asset", problems)
        self.assertIn("'nowhere'", problems)
        self.assertNotIn("ok.png", problems)
        self.assertNotIn("#top", problems)
        self.assertEqual(len(index.check_links(page)), 3)

    def test_markdown_table_html_escapes_cells(self):
        html = index.markdown_table_html("| a<b |\n|:-:|\n| <script> |\n")
        self.assertIn('<th class="center">a&lt;b</th>', html)
        self.assertIn("&lt;script&gt;", html)
        self.assertEqual(index.markdown_table_html("no table"), "")


class AtomicWrites(TempDirTest):
    def test_write_replaces_and_leaves_no_temporary(self):
        target = self.tmp / "sub" / "f.txt"
        fsutil.atomic_write_text(target, "one")
        fsutil.atomic_write_text(target, "two")
        self.assertEqual(target.read_text(), "two")
        self.assertEqual(sorted(p.name for p in target.parent.iterdir()), ["f.txt"])

    def test_failed_write_keeps_the_old_file(self):
        target = self.tmp / "f.txt"
        fsutil.atomic_write_text(target, "old")

        class Boom(Exception):
            pass

        original = os.fsync

        def fail(_fd):
            raise Boom()

        os.fsync = fail
        try:
            with self.assertRaises(Boom):
                fsutil.atomic_write_text(target, "new")
        finally:
            os.fsync = original
        self.assertEqual(target.read_text(), "old")
        self.assertEqual([p.name for p in self.tmp.iterdir()], ["f.txt"])


# --- main_job.py ----------------------------------------------------------------------


class MainJob(TempDirTest):
    def run_job(self, *args: str) -> tuple[int, str]:
        result = subprocess.run([sys.executable, str(SOURCE / "tools" / "main_job.py"), *args],
                                capture_output=True, text=True)
        return result.returncode, result.stdout + result.stderr

    def test_runs_every_lesson_program_then_writes_the_index(self):
        (self.tmp / "bin").mkdir()
        for nn in ("01", "04"):
            (self.tmp / "bin" / f"lesson{nn}").symlink_to(FAKE_LESSON)
        self.write("bin/lesson_helper.txt", "not a program")
        out = self.tmp / "out"
        code, text = self.run_job("--bin", str(self.tmp / "bin"), "--out", str(out), "--quick",
                                  "--only", "lessons,index", "--check-links")
        self.assertEqual(code, 0, text)
        self.assertIn("[2/2]", text)
        for nn in ("01", "04"):
            self.assertEqual(check_outputs.check_output_folder(out / f"lesson{nn}", f"lesson{nn}"), [])
        html = (out / "index.html").read_text()
        self.assertIn('id="lesson04"', html)
        self.assertIn("Quick run", html)

    def test_a_wrong_folder_is_refused_before_the_output_folder_is_made(self):
        # Each case names the option and its value, exits 2 and leaves OUT unmade (or the file
        # that stands where OUT should be untouched).
        (self.tmp / "bin").mkdir()
        (self.tmp / "bin" / "lesson01").symlink_to(FAKE_LESSON)
        (self.tmp / "empty").mkdir()
        a_file = self.write("a_file", "keep me")
        out = self.tmp / "out"
        cases = [
            (["--bin", str(self.tmp / "empty"), "--out", str(out), "--only", "lessons"], "--bin", "no lessonNN"),
            (["--bin", str(self.tmp / "missing"), "--out", str(out), "--only", "lessons"], "--bin", "no lessonNN"),
            (["--bin", str(self.tmp / "missing"), "--out", str(out), "--only", "lab"], "--bin", "no illum program"),
            (["--bin", str(self.tmp / "bin"), "--out", str(out), "--only", "lab"], "--bin", "no illum program"),
            (["--out", str(out), "--only", "index", "--source", str(self.tmp / "empty")], "--source",
             "not an illum source tree"),
            (["--out", str(out), "--only", "index", "--slides", str(self.tmp / "missing")], "--slides",
             "not a folder"),
        ]
        for args, option, words in cases:
            with self.subTest(args=args):
                code, text = self.run_job(*args)
                self.assertEqual(code, 2, text)
                self.assertIn(option, text)
                self.assertIn(words, text)
                self.assertFalse(out.exists(), text)
        code, text = self.run_job("--bin", str(self.tmp / "bin"), "--out", str(a_file), "--only", "lessons")
        self.assertEqual(code, 2, text)
        self.assertIn(f"--out {a_file}: exists and is not a folder", text)
        self.assertNotIn("Traceback", text)
        self.assertEqual(a_file.read_text(), "keep me")

    def test_the_lab_screenshots_refuse_a_bin_without_illum_before_writing(self):
        (self.tmp / "bin").mkdir()
        a_file = self.write("a_file", "keep me")
        for args, words in ((["--bin", str(self.tmp / "bin"), "--out", str(self.tmp / "out")], "no illum program"),
                            (["--bin", str(self.tmp / "missing"), "--out", str(self.tmp / "out")], "no illum program")):
            result = subprocess.run([sys.executable, str(SOURCE / "tools" / "lab" / "screenshots.py"), *args],
                                    capture_output=True, text=True)
            self.assertEqual(result.returncode, 2, result.stderr)
            self.assertIn(words, result.stderr)
            self.assertNotIn("Traceback", result.stderr)
            self.assertFalse((self.tmp / "out").exists())
        fake_illum = self.write("bin/illum", "#!/bin/sh\nexit 1\n")
        fake_illum.chmod(0o755)
        result = subprocess.run([sys.executable, str(SOURCE / "tools" / "lab" / "screenshots.py"), "--bin",
                                 str(self.tmp / "bin"), "--out", str(a_file)], capture_output=True, text=True)
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn(f"--out {a_file}: exists and is not a folder", result.stderr)
        self.assertEqual(a_file.read_text(), "keep me")

    def test_the_run_log_records_each_programs_seconds_and_processor_seconds(self):
        # A fake lesson that burns processor time in a child it waits for (as a lesson waits for
        # gnuplot): the log counts the child's processor seconds too, and never more than the
        # program's own seconds times the cores (a wrong counter, e.g. the job's own, would).
        (self.tmp / "bin").mkdir()
        burner = self.write("bin/lesson05", "#!/bin/sh\n" + f"{sys.executable} -c "
                            "'import time\nend = time.process_time() + 0.4\n"
                            "while time.process_time() < end: pass'\n")
        burner.chmod(0o755)
        out = self.tmp / "out"
        code, text = self.run_job("--bin", str(self.tmp / "bin"), "--out", str(out), "--only", "lessons")
        self.assertEqual(code, 0, text)
        run = json.loads((out / "run_log.json").read_text())["lesson05"]
        self.assertGreaterEqual(run["cpu_seconds"], 0.3)
        self.assertLessEqual(run["cpu_seconds"], run["seconds"] * run["cores"] + 0.1)
        self.assertIn("of processor time", text)

    def test_side_by_side_runs_every_list_and_raises_the_first_error(self):
        done: list[str] = []

        def fail() -> None:
            raise main_job.JobError("the lab failed")

        main_job.side_by_side([lambda: done.append("lab")], [lambda: done.append("slides")], [])
        self.assertEqual(sorted(done), ["lab", "slides"])
        with self.assertRaisesRegex(main_job.JobError, "the lab failed"):
            main_job.side_by_side([lambda: done.append("figures"), fail], [lambda: done.append("decks")])
        self.assertIn("decks", done)  # the other list ran to its end before the error was raised

    def test_a_failing_lesson_stops_the_job_and_is_named(self):
        (self.tmp / "bin").mkdir()
        (self.tmp / "bin" / "lesson03").symlink_to(FAKE_LESSON)
        env = dict(os.environ, FAKE_LESSON_BREAK="exit")
        result = subprocess.run([sys.executable, str(SOURCE / "tools" / "main_job.py"), "--bin",
                                 str(self.tmp / "bin"), "--out", str(self.tmp / "out"), "--only", "lessons,index"],
                                capture_output=True, text=True, env=env)
        self.assertEqual(result.returncode, 1)
        self.assertIn("lesson03 failed (exit code 1)", result.stderr)
        self.assertFalse((self.tmp / "out" / "index.html").exists())

    def fake_lessons(self, *names: str) -> None:
        (self.tmp / "bin").mkdir()
        for name in names:
            (self.tmp / "bin" / name).symlink_to(FAKE_LESSON)

    def test_programs_that_time_one_thread_run_side_by_side_and_their_output_stays_whole(self):
        # Every fake lesson answers "one" but lesson04, which must run alone, after the others.
        self.fake_lessons("lesson01", "lesson02", "lesson03", "lesson04")
        out = self.tmp / "out"
        env = dict(os.environ, FAKE_LESSON_TIMED_CORES="one", FAKE_LESSON_ALONE="lesson04",
                   FAKE_LESSON_SLEEP="1.5")
        result = subprocess.run([sys.executable, str(SOURCE / "tools" / "main_job.py"), "--bin",
                                 str(self.tmp / "bin"), "--out", str(out), "--quick", "--only", "lessons"],
                                capture_output=True, text=True, env=env)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        log = json.loads((out / "run_log.json").read_text())
        self.assertEqual(sorted(log), ["lesson01", "lesson02", "lesson03", "lesson04"])
        self.assertEqual(log["lesson04"]["beside"], [])
        if (os.cpu_count() or 1) >= 2:
            self.assertIn("run side by side, 2 at once", result.stdout)
            # Later lessons first (no run log yet): lesson03 and lesson02 start together and run
            # 1.5 s each, so each overlaps the other whatever the load; lesson01 starts when one of
            # them ends, and whether it meets the other depends on the machine: not asserted.
            self.assertIn("lesson02", log["lesson03"]["beside"], log)
            self.assertIn("lesson03", log["lesson02"]["beside"], log)
            for name in ("lesson01", "lesson02", "lesson03"):
                self.assertNotIn(name, log[name]["beside"])
        # Each program's two lines are adjacent: outputs printed whole, never interleaved.
        lines = [l for l in result.stdout.splitlines() if l.endswith(("first line", "last line"))]
        self.assertEqual(len(lines), 8, result.stdout)
        for first, last in zip(lines[::2], lines[1::2]):
            self.assertEqual(first.split(":")[0], last.split(":")[0], result.stdout)
        # lesson04 ran after the side-by-side ones.
        self.assertTrue(lines[-1].startswith("lesson04:"), result.stdout)

    def test_alone_runs_every_program_alone_in_order(self):
        self.fake_lessons("lesson01", "lesson02", "lesson03")
        out = self.tmp / "out"
        env = dict(os.environ, FAKE_LESSON_TIMED_CORES="one", FAKE_LESSON_SLEEP="0.2")
        result = subprocess.run([sys.executable, str(SOURCE / "tools" / "main_job.py"), "--bin",
                                 str(self.tmp / "bin"), "--out", str(out), "--only", "lessons", "--alone"],
                                capture_output=True, text=True, env=env)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertNotIn("side by side", result.stdout)
        log = json.loads((out / "run_log.json").read_text())
        self.assertEqual([log[n]["beside"] for n in sorted(log)], [[], [], []])
        firsts = [l.split(":")[0] for l in result.stdout.splitlines() if l.endswith("first line")]
        self.assertEqual(firsts, ["lesson01", "lesson02", "lesson03"])

    def test_a_failure_side_by_side_starts_nothing_more_and_is_named(self):
        # Later lessons start first (no run log yet): lesson03 and lesson02 start, lesson02 fails at
        # once (lesson03 runs 1.5 s), so lesson01 must never start, nor lesson04 (alone, after them).
        self.fake_lessons("lesson01", "lesson02", "lesson03", "lesson04")
        out = self.tmp / "out"
        env = dict(os.environ, FAKE_LESSON_TIMED_CORES="one", FAKE_LESSON_ALONE="lesson04",
                   FAKE_LESSON_BREAK="exit", FAKE_LESSON_BREAK_ONLY="lesson02", FAKE_LESSON_SLEEP="1.5")
        result = subprocess.run([sys.executable, str(SOURCE / "tools" / "main_job.py"), "--bin",
                                 str(self.tmp / "bin"), "--out", str(out), "--only", "lessons"],
                                capture_output=True, text=True, env=env)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("lesson02 failed (exit code 1)", result.stderr)
        self.assertIn("lesson02: error: asked to fail", result.stdout)  # its own output, printed
        if (os.cpu_count() or 1) >= 2:
            self.assertFalse((out / "lesson01").exists(), result.stdout)
        self.assertFalse((out / "lesson04").exists(), result.stdout)
        # lesson03 finished and committed its outputs: its run is recorded (not left to a stale
        # record), and the failed lesson02's is not.
        log = json.loads((out / "run_log.json").read_text())
        self.assertIn("lesson03", log)
        self.assertNotIn("lesson02", log)

    def run_mixed(self, *extra: str, **env_extra: str) -> tuple[subprocess.CompletedProcess, dict]:
        """lesson01-03 answer "one" and sleep 1 s; lesson04 answers "mixed", works 1 s on one
        thread, then asks for the whole machine and holds it 0.6 s. Returns the job's result and
        each program's event times (fake_lesson.py)."""
        self.fake_lessons("lesson01", "lesson02", "lesson03", "lesson04")
        events = self.tmp / "events"
        events.mkdir()
        env = dict(os.environ, FAKE_LESSON_TIMED_CORES="one", FAKE_LESSON_MIXED="lesson04",
                   FAKE_LESSON_SLEEP="1", FAKE_LESSON_MACHINE="0.6", FAKE_LESSON_EVENTS=str(events), **env_extra)
        result = subprocess.run([sys.executable, str(SOURCE / "tools" / "main_job.py"), "--bin",
                                 str(self.tmp / "bin"), "--out", str(self.tmp / "out"), "--only", "lessons",
                                 *extra], capture_output=True, text=True, env=env)
        times = {f.stem: json.loads(f.read_text()) for f in events.glob("*.json")}
        return result, times

    def test_a_mixed_program_gets_the_whole_machine_once_the_others_are_done(self):
        if (os.cpu_count() or 1) < 2:
            self.skipTest("one core: every program runs alone")
        result, times = self.run_mixed()
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertEqual(sorted(times), ["lesson01", "lesson02", "lesson03", "lesson04"])
        mixed = times["lesson04"]
        self.assertIsNotNone(mixed["granted"], result.stdout)
        others = [t for name, t in times.items() if name != "lesson04"]
        # Granted only once every other program had ended (none was left to start), and nothing
        # ran while it held the machine.
        for other in others:
            self.assertLessEqual(other["end"], mixed["granted"], (other, mixed))
            self.assertFalse(other["start"] < mixed["released"] and mixed["granted"] < other["end"])
        # While it waited it took no place: lesson01 and lesson02 ran side by side meanwhile
        # (later lessons start first: lesson04 and lesson03 first, both ending about 1 s in).
        self.assertLess(times["lesson01"]["start"], mixed["granted"])
        self.assertLess(max(times["lesson01"]["start"], times["lesson02"]["start"]),
                        min(times["lesson01"]["end"], times["lesson02"]["end"]), times)
        # Never more programs on one thread at once than the cores the job uses (2 here): the
        # spans in which each works on one thread, lesson04's before it asked and after it released.
        spans = [(t["start"], t["end"]) for t in others] + [(mixed["start"], mixed["asked"]),
                                                             (mixed["released"], mixed["end"])]
        for start, _ in spans:
            self.assertLessEqual(sum(1 for s, e in spans if s <= start < e), 2, spans)
        log = json.loads((self.tmp / "out" / "run_log.json").read_text())
        self.assertGreaterEqual(log["lesson04"]["waited_seconds"], 0.5, log["lesson04"])
        self.assertGreaterEqual(log["lesson04"]["whole_machine_seconds"], 0.5, log["lesson04"])
        self.assertIn("lesson03", log["lesson04"]["beside"])
        self.assertIn("lesson04 has the whole machine", result.stdout)

    def test_a_mixed_program_run_alone_is_not_linked(self):
        # --alone: no pipes, no ILLUM_MAIN_JOB_FDS; the program never asks and runs as it would by hand.
        result, times = self.run_mixed("--alone")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIsNone(times["lesson04"]["asked"])
        self.assertNotIn("whole machine", result.stdout)

    def test_a_failure_beside_a_waiting_mixed_program_still_lets_it_finish(self):
        if (os.cpu_count() or 1) < 2:
            self.skipTest("one core: every program runs alone")
        result, times = self.run_mixed(FAKE_LESSON_BREAK="exit", FAKE_LESSON_BREAK_ONLY="lesson03")
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("lesson03 failed (exit code 1)", result.stderr)
        # lesson04 was waiting: it was given the machine and ended (no hang), and nothing new started.
        self.assertIsNotNone(times["lesson04"]["granted"], result.stdout)
        self.assertNotIn("lesson01", times)
        self.assertIn("lesson04", json.loads((self.tmp / "out" / "run_log.json").read_text()))

    def test_the_longest_recorded_run_starts_first(self):
        log = self.write("run_log.json", json.dumps({
            "lesson01": {"seconds": 11.2, "quick": False}, "lesson02": {"seconds": 4.8, "quick": False},
            "lesson12": {"seconds": 24.1, "quick": False}}))
        programs = [Path("lesson01"), Path("lesson02"), Path("lesson12")]
        self.assertEqual([p.name for p in lesson_runs.longest_first(programs, log)],
                         ["lesson12", "lesson01", "lesson02"])
        # A quick run's seconds say nothing of a full run's: the later lessons first, then.
        log.write_text(json.dumps({"lesson01": {"seconds": 11.2, "quick": True}}))
        self.assertEqual([p.name for p in lesson_runs.longest_first(programs, log)],
                         ["lesson12", "lesson02", "lesson01"])

    def test_an_empty_bin_folder_is_an_error(self):
        (self.tmp / "bin").mkdir()
        code, text = self.run_job("--bin", str(self.tmp / "bin"), "--out", str(self.tmp / "out"))
        self.assertEqual(code, 2)  # refused as a usage error, before anything is written
        self.assertIn("no lessonNN programs", text)
        self.assertFalse((self.tmp / "out").exists())

    def test_program_discovery_ignores_other_files(self):
        (self.tmp / "bin").mkdir()
        for name in ("lesson01", "lesson12", "lesson1", "lesson01.old", "illum"):
            p = self.write(f"bin/{name}", "#!/bin/sh\n")
            p.chmod(0o755)
        self.write("bin/lesson09", "#!/bin/sh\n")  # not executable
        self.assertEqual([p.name for p in main_job.find_programs(self.tmp / "bin")], ["lesson01", "lesson12"])


if __name__ == "__main__":
    unittest.main(verbosity=1)
