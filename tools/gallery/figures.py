"""The texts' figures: tables between `<!-- figure: out/… -->` and `<!-- /figure -->`, filled from the
programs' tables, checked cell by cell but for timings (CONTRIBUTING.md, "Figures come from the run")."""

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from common.files import atomic_write_text, remove_dead_temporaries
from common.markdown import link_problems, outside_fences

from . import kept_images, values
from .lesson_runs import read_log
from .plots import PlotCheckError, check_plots
from .tables import FigureError, Spec, Table, markdown_tables, parse_spec, read_table, select

# The Markdown files that may hold figures, relative to the source tree.
TEXT_GLOBS = ("lessons/*/README.md", "slides/*.md", "exercises/*/README.md", "docs/*.md")
OPEN = re.compile(r"^\s*<!--\s*figure:\s*(?P<spec>.*?)\s*-->\s*$")
CLOSE = re.compile(r"^\s*<!--\s*/figure\s*-->\s*$")
# Hand-typed timings outside figures: "16 ns", "0.58 ms", "2 seconds", "3.3 s on", "about 15 s".
HAND_TIMING = re.compile(
    r"(?<![\w.])\d[\d.,]*(?:\s*[–-]\s*\d[\d.,]*)?\s*(?:ns|µs|μs|ms|seconds?|minutes?)\b"
    r"|(?<![\w.])\d[\d.,]*(?:\s*[–-]\s*\d[\d.,]*)?\s?s\b(?=\s+(?:on|while|for|per|in|at)\b|[),;*]|\.(?:\s|$))")
# "erratum 4" not already the text of a link ([erratum 4](...)).
UNLINKED_ERRATUM = re.compile(r"(?<!\[)\b[Ee]rratum \d{1,2}\b(?!\])")


def run_label(out: Path, spec: Spec, table: Table) -> str:
    """The caption under a figure: its table, its program and, for timings, the machine they were
    measured on (no date: the run's own log, OUT/run_log.json, keeps that)."""
    program = spec.path.split("/")[1] if spec.path.count("/") >= 2 else ""
    head = f"*Table `{spec.path}`, written by `{program}`"
    if not table.has_timings():
        return head + ".*"
    run = read_log(out / "run_log.json").get(program)
    if isinstance(run, dict) and "started" in run:
        machine = (f"{run.get('cores', '?')} cores, load average {run.get('load_before', ['?'])[0]} at the start of "
                   f"the run and {run.get('load_after', ['?'])[0]} at its end")
        beside = run.get("beside")
        names = [f"`{name}`" for name in beside if isinstance(name, str)] if isinstance(beside, list) else []
        if names:
            machine += (f", side by side with {', '.join(names[:-1]) + ' and ' if len(names) > 1 else ''}"
                        f"{names[-1]} (each timing one thread while they overlapped)")
            if "whole_machine_seconds" in run:  # a "mixed" program (lib/illum/io/whole_machine.hpp)
                machine += "; its timings on more threads had the machine to themselves"
    else:
        machine = f"{os.cpu_count()} cores, load not recorded (run outside the main job)"
    return (f"{head}; its timings were measured on {machine}: rerun to measure yours, they vary with the "
            "machine and its load.*")


@dataclass
class Block:
    text: Path
    open_line: int   # 0-based index of the opening comment
    close_line: int  # 0-based index of the closing comment
    spec_text: str


def find_blocks(path: Path, lines: list[str]) -> list[Block]:
    blocks, current = [], None
    for i, line in outside_fences(lines):
        if m := OPEN.match(line):
            if current is not None:
                raise FigureError(f"{path}:{current[0] + 1}: figure not closed before the next one "
                                  f"(line {i + 1}); end it with <!-- /figure -->")
            current = (i, m.group("spec"))
        elif CLOSE.match(line):
            if current is None:
                raise FigureError(f"{path}:{i + 1}: <!-- /figure --> without an opening figure comment")
            blocks.append(Block(path, current[0], i, current[1]))
            current = None
    if current is not None:
        raise FigureError(f"{path}:{current[0] + 1}: figure never closed (add <!-- /figure -->)")
    return blocks


def compare(block: Block, lines: list[str], new: Table) -> list[str]:
    """Differences in non-timing cells between the text's table and the program's."""
    where = f"{block.text}:{block.open_line + 1}"
    tables = markdown_tables(lines[block.open_line + 1:block.close_line])
    if len(tables) != 1:
        return [f"{where}: the figure holds {len(tables)} tables, expected one (run tools/figures.py --update)"]
    old = tables[0]
    if old.header != new.header:
        return [f"{where}: columns differ: text has {old.header}, the program writes {new.header}"]
    if len(old.rows) != len(new.rows):
        return [f"{where}: the text's table has {len(old.rows)} rows, the program's {len(new.rows)}"]
    problems, mask = [], new.timing_mask()
    for r, (a, b) in enumerate(zip(old.rows, new.rows)):
        if len(a) != len(b):
            problems.append(f"{where}: row {r + 1} has {len(a)} cells, the program's {len(b)}")
            continue
        line = block.open_line + old.start + r + 4
        problems += [f"{block.text}:{line}: row '{b[0]}', column '{new.header[c]}': the text says {x}, the program "
                     f"wrote {y}" for c, (x, y) in enumerate(zip(a, b)) if not mask[r][c] and x != y]
    return problems


def hand_timings(path: Path, lines: list[str], inside: set[int]) -> list[str]:
    """Timings typed outside the figures (the lines `inside` them)."""
    problems = [f"{path}:{table.start + 1}: a table with timings typed by hand: include it with a figure comment "
                "naming the program's table" for table in markdown_tables(lines)
                if table.start not in inside and table.has_timings()]
    for i, line in enumerate(lines):
        if i not in inside:
            problems += [f"{path}:{i + 1}: hand-typed timing '{m.group(0).strip()}': include the table with a "
                         "figure comment, or state a ratio or growth and name the table"
                         for m in HAND_TIMING.finditer(re.sub(r"`[^`]*`", "", line))]
    return problems


def unlinked_errata(path: Path, lines: list[str]) -> list[str]:
    if path.as_posix() == "docs/errata.md":
        return []
    return [f"{path}:{i + 1}: '{m.group(0)}' is not linked: write [{m.group(0)}](<relative path>/docs/errata.md#"
            f"{m.group(0).lower().replace(' ', '-')})"
            for i, line in outside_fences(lines) for m in UNLINKED_ERRATUM.finditer(re.sub(r"`[^`]*`", "", line))]


def texts(source: Path) -> list[Path]:
    return [path for pattern in TEXT_GLOBS for path in sorted(source.glob(pattern))]


@dataclass
class Run:
    """What one pass over the texts found and did (mode: 'refresh', 'check' or 'update')."""
    source: Path
    out: Path
    mode: str
    log: object = print
    problems: list[str] = field(default_factory=list)
    left: list[str] = field(default_factory=list)  # differences a refresh leaves for --update
    written: int = 0
    figures: int = 0
    values: int = 0

    def may_rewrite(self, differences: list[str]) -> bool:
        """Whether a text may take what the tables say: always on --update; on a refresh only when nothing
        but timings differs (the `differences` are left for --update); never on --check (they are problems)."""
        if self.mode != "update" and differences:
            (self.problems if self.mode == "check" else self.left).extend(differences)
            return False
        return self.mode != "check"


def _figures_of(run: Run, rel: Path, lines: list[str], blocks: list[Block]) -> None:
    """Checks or rewrites the figures of one text, bottom up (earlier line numbers stay valid)."""
    for block in reversed(blocks):
        run.figures += 1
        try:
            spec = parse_spec(block.spec_text)
            table = select(read_table(run.out / Path(spec.path).relative_to("out"), spec.table), spec, spec.path)
        except FigureError as e:
            run.problems.append(f"{rel}:{block.open_line + 1}: {e}")
            continue
        if run.may_rewrite(compare(block, lines, table)):
            lines[block.open_line + 1:block.close_line] = table.markdown() + ["", run_label(run.out, spec, table)]


def _text(run: Run, path: Path) -> None:
    rel, text = path.relative_to(run.source), path.read_text(encoding="utf-8")
    lines = text.splitlines()
    try:
        blocks = find_blocks(rel, lines)
    except FigureError as e:
        run.problems.append(str(e))
        return
    inside = {i for b in blocks for i in range(b.open_line, b.close_line + 1)}
    if run.mode == "check":
        # Measured timings live in the lesson texts and decks; docs/ states settings and tool-written reports.
        if rel.parts[0] in ("lessons", "slides"):
            run.problems += hand_timings(rel, lines, inside)
        run.problems += unlinked_errata(rel, lines)
    # Values first: they change text within lines, the figures change the number of lines.
    run.values += values.process_values(run, rel, lines, inside)
    _figures_of(run, rel, lines, blocks)
    if lines != text.splitlines():
        atomic_write_text(path, "\n".join(lines) + "\n", tag=kept_images.TAG)
        run.written += 1
        run.log(f"figures: refreshed {rel}")


def process(source: Path, out: Path, mode: str, log=print, plots: bool = True) -> int:
    """Refreshes, checks (also the kept images, the links and, unless `plots` is False, the plots in
    OUT) or updates the figures and values of every text; returns the exit code."""
    run = Run(source, out, mode, log)
    for path in texts(source):
        _text(run, path)
    for p in run.problems:
        log(f"figures: {p}")
    if run.left:
        log(f"figures: {len(run.left)} value(s) in the texts differ from the programs' tables; those figures were "
            "left as they are. Review the change and accept it with tools/figures.py --update:")
        for p in run.left:
            log(f"figures:   {p}")
    if mode == "check":
        return _check_the_rest(run, plots)
    log(f"figures: {run.figures} figure(s), {run.written} file(s) rewritten")
    return 1 if run.problems else 0


def _check_the_rest(run: Run, plots: bool) -> int:
    images, compared = kept_images.check_images(run.source, run.out)
    links, link_count = text_link_problems(run.source)
    try:
        drawn, plot_count = check_plots(run.out) if plots else ([], 0)
    except PlotCheckError as e:
        drawn, plot_count = [f"cannot check the plots: {e}"], 0
    for p in images + links + drawn:
        run.log(f"figures: {p}")
    if run.problems or images or links or drawn:
        run.log(f"figures: FAILED: {len(run.problems + images + links + drawn)} problem(s) in {run.figures} "
                f"figure(s), {run.values} value(s), the lesson texts' images and links, and the plots")
        return 1
    run.log(f"figures: OK: the non-timing values of {run.figures} figure(s) and {run.values} value(s) in sentences "
            f"match the tables in {run.out}, no text quotes a timing by hand, the {compared} kept image(s) match "
            f"what the programs drew, the texts' {link_count} links resolve, and the {plot_count} plots show all "
            "their points")
    return 0


def remove_stale_temporaries(source: Path, log=print) -> None:
    """Removes the temporaries that runs killed without warning (SIGKILL) left beside the texts and their
    kept figures: those whose PID no longer runs (or that name none)."""
    folders = {p.parent for p in texts(source)} | {p.parent / kept_images.FIGURES_FOLDER
                                                    for p in kept_images.lesson_texts(source)}
    for folder in sorted(f for f in folders if f.is_dir()):
        for tmp in remove_dead_temporaries(folder, kept_images.TAG):
            log(f"figures: removed {tmp.relative_to(source)}, left by a run that was killed before it finished")


# The texts whose links must resolve in a fresh clone; decks link from out/slides/ (slides/README.md).
LINKED_TEXTS = ("README.md", "CONTRIBUTING.md", "lessons/*/README.md", "exercises/*/README.md", "docs/*.md",
                "slides/README.md", "tests/*/README.md", "tools/*/README.md", "bench/*/README.md")


def text_link_problems(source: Path) -> tuple[list[str], int]:
    files = [p for pattern in LINKED_TEXTS for p in sorted(Path(source).glob(pattern)) if p.is_file()]
    return link_problems(Path(source), files, generated_ok=False)
