"""Every plot a lesson program drew shows all its data. gnuplot itself evaluates each OUT/*/NAME.gp (the
script beside NAME.png) into a table of its curves' points and its ranges; a plot fails on a line broken by
an undefined point, a curve with no point (or a line of one), or a point outside the frame or within EDGE
of it (where the border hides it)."""

import math
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

# A point must lie at least this share of the frame inside it.
EDGE = 0.01
_CLAUSE_STYLE = re.compile(r"\bwith\s+(?P<style>\w+)")
_CURVE = re.compile(r"^# Curve (?P<i>\d+) of (?P<n>\d+), (?P<k>\d+) points")
_TITLE = re.compile(r'^# Curve title: "(?P<title>.*)"')


class PlotCheckError(Exception):
    """gnuplot is missing or could not evaluate a script."""


@dataclass
class Curve:
    title: str = ""
    style: str = ""
    points: list[tuple[float, float, str]] = field(default_factory=list)
    breaks: int = 0  # blank lines inside the curve: gnuplot broke its line there


def _plot_clauses(script: str) -> list[str]:
    """The clauses of the script's `plot` command (its line continuations joined), split at the commas
    outside quotes and parentheses."""
    match = re.search(r"^plot (.*?)(?<!\\)$", re.sub(r"\\\n\s*", " ", script), re.M)
    if not match:
        return []
    clauses, depth, quote, current = [], 0, "", ""
    for c in match.group(1):
        if quote or c in "'\"":
            quote = "" if c == quote else quote or c
        elif c in "()":
            depth += 1 if c == "(" else -1
        elif c == "," and depth == 0:
            clauses.append(current.strip())
            current = ""
            continue
        current += c
    return clauses + ([current.strip()] if current.strip() else [])


def evaluate(gp: Path, gnuplot: str) -> tuple[list[Curve], dict[str, float], dict[str, bool]]:
    """gnuplot's own reading of a plot script: its curves' points and the frame's ranges."""
    script = gp.read_text(encoding="utf-8")
    with tempfile.TemporaryDirectory(prefix="illum-plots-") as tmp:
        table, body = Path(tmp) / "points.txt", []
        for line in script.splitlines():
            if line.startswith("plot "):
                # The table is written in the axes' formats: full precision, not the tic labels'.
                body += ["set format x '%.17g'", "set format y '%.17g'", f"set table '{table}'"]
            if not line.startswith(("set terminal", "if (ARGC", "set output")):
                body.append(line)
        body += ["unset table",
                 'print sprintf("RANGE %.17g %.17g %.17g %.17g", GPVAL_X_MIN, GPVAL_X_MAX, GPVAL_Y_MIN, GPVAL_Y_MAX)']
        run = subprocess.run([gnuplot], input="\n".join(body) + "\n", cwd=gp.parent, capture_output=True,
                             text=True, errors="replace", timeout=60)
        ranges = re.search(r"RANGE (\S+) (\S+) (\S+) (\S+)", run.stderr)
        if run.returncode != 0 or not ranges or not table.is_file():
            raise PlotCheckError(f"gnuplot could not evaluate {gp}: {run.stderr.strip()[-400:]}")
        text = table.read_text(encoding="utf-8", errors="replace")
    styles = [m.group("style") if (m := _CLAUSE_STYLE.search(c)) else "" for c in _plot_clauses(script)]
    curves: list[Curve] = []
    pending_blank = False  # a blank line after a point: the line breaks there if another point follows
    for line in text.splitlines():
        parts = line.split()
        if _CURVE.match(line):
            curves.append(Curve(style=styles[len(curves)] if len(curves) < len(styles) else ""))
            pending_blank = False
        elif (m := _TITLE.match(line)) and curves:
            curves[-1].title = m.group("title")
        elif not parts:
            pending_blank = bool(curves and curves[-1].points)
        elif curves and len(parts) >= 3 and not line.startswith("#"):
            curves[-1].breaks += pending_blank
            pending_blank = False
            try:
                curves[-1].points.append((float(parts[0]), float(parts[1]), parts[-1]))
            except ValueError:
                curves[-1].points.append((math.nan, math.nan, "u"))
    frame = dict(zip(("xmin", "xmax", "ymin", "ymax"), (float(v) for v in ranges.groups())))
    return curves, frame, {axis: bool(re.search(rf"^set logscale [^\n]*{axis}", script, re.M)) for axis in "xy"}


def _position(value: float, lo: float, hi: float, log: bool) -> float:
    """Where `value` sits in [lo, hi], as a share of the frame (0 at lo, 1 at hi)."""
    if log:
        if value <= 0 or lo <= 0 or hi <= 0:
            return math.nan
        value, lo, hi = math.log10(value), math.log10(lo), math.log10(hi)
    return (value - lo) / (hi - lo) if hi != lo else math.nan


def _gnuplot() -> str:
    if gnuplot := shutil.which("gnuplot"):
        return gnuplot
    raise PlotCheckError("gnuplot is not installed (tools/install-deps installs gnuplot-nox)")


def check_plot(gp: Path, gnuplot: str | None = None) -> list[str]:
    """Problems with one plot (an empty list when it shows all its data)."""
    curves, frame, logs = evaluate(gp, gnuplot or _gnuplot())
    problems = []
    name = gp.with_suffix(".png").name
    for k, curve in enumerate(curves, 1):
        label = f"{gp.parent.name}/{name}: curve {k} '{curve.title}'"
        lines = curve.style in ("lines", "linespoints", "l", "lp")
        defined = [p for p in curve.points if p[2] != "u"]
        undefined = len(curve.points) - len(defined)
        if not curve.points:
            problems.append(f"{label} has no point: no row of its table passes its filter")
            continue
        if lines and (undefined or curve.breaks):
            problems.append(f"{label}: its line is broken {undefined + curve.breaks} time(s) by undefined points "
                            "(1/0, an infinity, or a value ≤ 0 on a log axis): write NaN, which "
                            "`set datafile missing NaN` skips without breaking the line")
        if curve.style in ("lines", "l") and len(defined) < 2:
            problems.append(f"{label} is drawn with lines but has {len(defined)} point: it draws nothing")
        for x, y, kind in defined:
            px = _position(x, frame["xmin"], frame["xmax"], logs["x"])
            py = _position(y, frame["ymin"], frame["ymax"], logs["y"])
            if kind == "o" or not (EDGE <= px <= 1 - EDGE) or not (EDGE <= py <= 1 - EDGE):
                problems.append(f"{label}: the point ({x:g}, {y:g}) is {'outside' if kind == 'o' else 'on'} the "
                                f"frame x [{frame['xmin']:g}, {frame['xmax']:g}], y [{frame['ymin']:g}, "
                                f"{frame['ymax']:g}]: it does not show")
                break
    return problems


def check_plots(out: Path, scripts: list[Path] | None = None) -> tuple[list[str], int]:
    """Problems with every plot in OUT (or the given scripts) and how many were checked."""
    gnuplot = _gnuplot()
    if scripts is None:  # every plot script the lesson programs wrote into OUT (a .gp beside a .png)
        scripts = sorted(gp for gp in Path(out).glob("*/*.gp") if gp.with_suffix(".png").is_file())
    problems = []
    for gp in scripts:
        try:
            problems += check_plot(gp, gnuplot)
        except PlotCheckError as e:
            problems.append(str(e))
    return problems, len(scripts)
