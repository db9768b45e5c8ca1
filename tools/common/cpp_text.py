"""C++ source as text: comments and string literals blanked, line breaks kept (so line numbers hold)."""

import re

# At each place in turn: a // or /* comment (an unclosed one runs to the end), a raw string R"d(…)d", or a
# string or character literal (a ' after a letter or digit is a digit separator, 1'000), which ends at its
# quote or at the end of its line (a backslash escapes the next character, a line break too).
_TOKEN = re.compile(r"//[^\n]*|/\*.*?(?:\*/|\Z)|(?<=R)\"([^(\s]{0,16})\((?:.*?\)\1\"|.*\Z)"
                    r"|(\"|(?<![^\W_])')(?:(?!\2)[^\\\n]|\\(?:.|\Z))*(?:\2|\n|\Z)", re.S)


def _blank(text: str) -> str:
    return re.sub(r"[^\n]", " ", text)


def blank_comments(text: str, strings: bool = True) -> str:
    """`text` with every comment replaced by spaces, and every string or character literal's contents
    too unless `strings` is False (its quotes stay; `#include <…>` is code and stays)."""
    def blanked(match: re.Match) -> str:
        piece, quote = match.group(), match.group()[0]
        if quote not in "\"'":
            return _blank(piece)
        return quote + _blank(piece[1:-1]) + (quote if len(piece) > 1 else "") if strings else piece

    return _TOKEN.sub(blanked, text)
