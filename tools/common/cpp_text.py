"""C++ source as text: comments and string literals blanked, line breaks kept (so line numbers hold)."""
from __future__ import annotations

import re

_RAW_OPEN = re.compile(r'"([^(\s]{0,16})\(')


def _blank(text: str) -> str:
    return re.sub(r"[^\n]", " ", text)


def blank_comments(text: str, strings: bool = True) -> str:
    """`text` with every comment replaced by spaces, and every string or character literal's contents
    too unless `strings` is False (its quotes stay; `#include <…>` is code and stays)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i) or text.startswith("/*", i):
            block = text[i + 1] == "*"
            end = text.find("*/" if block else "\n", i + 2)
            end = n if end < 0 else end + (2 if block else 0)
        elif c == '"' and i > 0 and text[i - 1] == "R" and (raw := _RAW_OPEN.match(text, i)):
            end = text.find(")" + raw.group(1) + '"', i)
            end = n if end < 0 else end + len(raw.group(1)) + 2
        elif c in "\"'" and not (c == "'" and i > 0 and text[i - 1].isalnum()):  # not a digit separator 1'000
            end = i + 1
            while end < n and text[end] != c and text[end] != "\n":
                end += 2 if text[end] == "\\" else 1
            end = min(end + 1, n)
        else:
            out.append(c)
            i += 1
            continue
        piece = text[i:end]
        if c in "\"'" and not strings:
            out.append(piece)
        elif c in "\"'":
            out.append(c + _blank(piece[1:-1]) + (c if len(piece) > 1 else ""))
        else:
            out.append(_blank(piece))
        i = end
    return "".join(out)
