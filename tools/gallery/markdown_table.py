"""Reading Markdown pipe tables: the one home of the row and separator rules.

Both readers of tables use it: tools/figures.py (figures in the lesson texts
and decks) and tools/gallery/outputs.py (checks of the programs' .md outputs).
"""
from __future__ import annotations

import re

# One cell of the separator line: dashes, with a colon at either end for alignment.
SEPARATOR_CELL = re.compile(r"^:?-+:?$")


def split_table_row(line: str) -> list[str]:
    """The cells of a Markdown table row '| a | b |' (pipes escaped as \\| stay in the cell)."""
    body = line.strip()
    if body.startswith("|"):
        body = body[1:]
    if body.endswith("|") and not body.endswith("\\|"):
        body = body[:-1]
    cells, current, i = [], "", 0
    while i < len(body):
        if body[i] == "\\" and i + 1 < len(body) and body[i + 1] == "|":
            current += "|"
            i += 2
            continue
        if body[i] == "|":
            cells.append(current.strip())
            current = ""
        else:
            current += body[i]
        i += 1
    cells.append(current.strip())
    return cells


def is_separator_cells(cells: list[str]) -> bool:
    """True when every cell is a separator cell ('---', ':--', '--:', ':-:')."""
    return bool(cells) and all(SEPARATOR_CELL.match(c.replace(" ", "")) for c in cells)


def is_separator_line(line: str) -> bool:
    """True for a table's separator line ('|---|:--:|')."""
    return line.lstrip().startswith("|") and is_separator_cells(split_table_row(line))


def alignment(cell: str) -> str:
    """'left', 'right', 'center' or '' for one separator cell."""
    c = cell.replace(" ", "")
    return ("center" if c.startswith(":") and c.endswith(":") else
            "right" if c.endswith(":") else "left" if c.startswith(":") else "")
