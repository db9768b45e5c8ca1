"""The observer's sources: each test file with the expected side of every check cut away, so that the
expected values and their tolerances are not in the program that runs the student's code at all
(docs/grading-defences.md, "How a test is judged").

`CHECK(got == doctest::Approx(want))` becomes `ILLUM_OBSERVE_VALUE(CHECK, (got))`, `CHECK(hit)`
`ILLUM_OBSERVE_CHECK(CHECK, (hit))`, a CHECK_THROWS* an ILLUM_OBSERVE_THROWS; INFO, CAPTURE, MESSAGE and a
CHECK_MESSAGE's message are cut. A REQUIRE keeps its right side: the observer must stop a test where the
reference's run would (the judge still decides on the left side it reports). Lines keep their numbers and
a ``#line`` names the original file, so records and compiler messages point at the test as written. A
check this tool cannot split unambiguously is an error naming its file and line: the build stops instead
of keeping an expected value.

    python3 tools/grading/observer_sources.py --out DIR FILE...   (each FILE into DIR/<its folder>/<its name>,
    so that both "support.hpp" and "13_two_pass/support.hpp" find the rewritten header first)
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path


class SourceError(Exception):
    """A check this tool cannot rewrite."""


# The macros rewritten, by how; the kind a record carries is the macro's name without _UNARY and _MESSAGE.
_VALUE = {"CHECK", "CHECK_FALSE", "CHECK_MESSAGE", "CHECK_FALSE_MESSAGE", "WARN", "WARN_FALSE"}
_WHOLE = {"REQUIRE", "REQUIRE_FALSE", "REQUIRE_MESSAGE", "REQUIRE_FALSE_MESSAGE", "CHECK_UNARY", "CHECK_UNARY_FALSE",
          "REQUIRE_UNARY", "REQUIRE_UNARY_FALSE"}
_BINARY = {"EQ": "==", "NE": "!=", "LT": "<", "LE": "<=", "GT": ">", "GE": ">="}
_THROWS = {"CHECK_THROWS", "REQUIRE_THROWS", "CHECK_NOTHROW", "REQUIRE_NOTHROW", "CHECK_THROWS_AS", "REQUIRE_THROWS_AS"}
_CUT = {"INFO", "CAPTURE", "MESSAGE", "WARN_MESSAGE", "WARN_THROWS", "WARN_THROWS_AS", "WARN_NOTHROW"}
_APPROX = {"ILLUM_CHECK_APPROX", "ILLUM_CHECK_APPROX_MESSAGE"}
_ANY_TYPE = "::illum::test::NothingThrowsThis"

_NAMES = (_VALUE | _WHOLE | _THROWS | _CUT | _APPROX
          | {f"{level}_{name}" for level in ("CHECK", "REQUIRE", "WARN") for name in _BINARY}
          | {"FAIL", "FAIL_CHECK", "ILLUM_CHECK_THROWS_CONTAINING"})
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")
_OPENING = re.compile(r"[ \t]*\(")


# A comment, a raw string R"d(…)d" or a string or character literal, each to its end (or the text's). A raw
# string's prefix right after a name's character is part of the name, a ' right after a digit or letter a digit
# separator (1'000): code, both.
_LITERAL = re.compile(r'''//[^\n]*|/\*.*?(?:\*/|\Z)|(?<![\w])(?:u8|u|U|L)?R"([^()\\ ]{0,16})\((?:.*?\)\1"|.*\Z)
                          |(?<![^\W_])'(?:\\.?|[^'\\])*(?:'|\Z)|"(?:\\.?|[^"\\])*(?:"|\Z)''', re.S | re.X)


def _code(text: str, i: int = 0):
    """(index, character) of every character of ``text`` from ``i`` on outside literals and comments."""
    while i < len(text):
        if literal := _LITERAL.match(text, i):
            i = literal.end()
        else:
            yield i, text[i]
            i += 1


def _arguments(text: str, open_paren: int) -> tuple[list[str], int]:
    """The macro arguments after ``(`` at ``open_paren`` split as the preprocessor splits them
    (at commas outside parentheses), and the index after the closing ``)``."""
    depth, start, parts = 0, open_paren + 1, []
    for i, c in _code(text, open_paren):
        if c in "()":
            depth += 1 if c == "(" else -1
            if depth == 0:
                return parts + [text[start:i]], i + 1
        elif c == "," and depth == 1:
            parts.append(text[start:i])
            start = i + 1
    raise SourceError("no closing parenthesis")


# A bracket weighs more than any nesting of angle brackets inside it.
_TEMPLATE_DEPTH = {"(": 100, "[": 100, "{": 100, ")": -100, "]": -100, "}": -100, "<": 1, ">": -1}


def _template_end(text: str, i: int) -> int:
    """``text[i]`` is the ``<`` of a template argument list: the index after its ``>``."""
    depth = 0
    for j, c in _code(text, i):
        depth += _TEMPLATE_DEPTH.get(c, 0)
        if c == ">" and depth == 0:
            return j + 1
    raise SourceError("a '<' written against a name, which this tool reads as template arguments, does not close: "
                      "write a comparison with spaces around it (a < b), as clang-format does")


def split_comparison(condition: str) -> tuple[str, str, str] | None:
    """(lhs, operator, rhs) of a check's condition, or None for a unary check.

    A comparison is an ``==``, ``!=``, ``<=``, ``>=``, ``<`` or ``>`` outside brackets; a ``<``
    written against a name (``static_cast<int>``, ``std::vector<double>``) opens template
    arguments, which is how clang-format writes them and how the tests are formatted."""
    found: list[tuple[int, str]] = []
    depth, resume = 0, 0  # resume: after a two- or three-character operator, or template arguments
    for i, c in _code(condition):
        two = condition[i:i + 2]
        if i < resume:
            continue
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif depth == 0 and two in ("&&", "||"):
            raise SourceError(f"'{two}' at the top of a check: put the condition in parentheses")
        elif depth == 0 and c == "?":
            raise SourceError("'?' at the top of a check: put the condition in parentheses")
        elif two in ("<<", ">>", "->") or condition[i:i + 3] == "<=>":
            resume = i + (3 if condition[i:i + 3] == "<=>" else 2)
        elif c == "<" and i > 0 and (condition[i - 1].isalnum() or condition[i - 1] in "_:"):
            resume = _template_end(condition, i)
        elif depth == 0 and two in ("==", "!=", "<=", ">="):
            found.append((i, two))
            resume = i + 2
        elif depth == 0 and c in "<>":
            found.append((i, c))
    if not found:
        return None
    if len(found) > 1:
        raise SourceError(f"{len(found)} comparisons at the top of one check ({', '.join(o for _, o in found)})")
    at, op = found[0]
    lhs, rhs = condition[:at].strip(), condition[at + len(op):].strip()
    if not lhs or not rhs:
        raise SourceError(f"a comparison '{op}' with an empty side")
    return lhs, op, rhs


def _rewrite(name: str, args: list[str]) -> str:
    """The observer's text for one invocation of ``name``."""
    base = name.removeprefix("DOCTEST_")
    kind = base.replace("_UNARY", "").removesuffix("_MESSAGE")
    if base in _CUT or base in ("WARN", "WARN_FALSE") or base.startswith("WARN_"):
        return "static_cast<void>(0)"
    if base in ("FAIL", "FAIL_CHECK"):
        return f"ILLUM_OBSERVE_FAIL({base})"
    if base in _APPROX:
        return f"ILLUM_OBSERVE_VALUE(CHECK, ({args[0].strip()}))"
    if base == "ILLUM_CHECK_THROWS_CONTAINING":
        if len(args) < 3:
            raise SourceError("ILLUM_CHECK_THROWS_CONTAINING needs an expression, a text and a type")
        return f"ILLUM_OBSERVE_THROWS(CHECK_THROWS_CONTAINING, {args[0].strip()}, {','.join(args[2:]).strip()})"
    if base in _THROWS:
        kind_type = ",".join(args[1:]).strip() if kind.endswith("_AS") else _ANY_TYPE
        return f"ILLUM_OBSERVE_THROWS({kind}, {args[0].strip()}, {kind_type})"
    level, _, suffix = base.partition("_")
    if suffix in _BINARY:
        lhs, rhs = args[0].strip(), ",".join(args[1:]).strip()
        if level == "REQUIRE":
            return f"ILLUM_OBSERVE_CHECK(REQUIRE, ({lhs}) {_BINARY[suffix]} ({rhs}))"
        return f"ILLUM_OBSERVE_VALUE(CHECK, ({lhs}))"
    condition = args[0].strip() if base.endswith("_MESSAGE") else ",".join(args).strip()
    if base in _WHOLE:
        if base.startswith(("CHECK_UNARY", "REQUIRE_UNARY")):
            return f"ILLUM_OBSERVE_CHECK({kind}, ({condition}))"
        parts = split_comparison(condition)  # only to refuse what doctest would refuse too
        return f"ILLUM_OBSERVE_CHECK({kind}, {condition if parts else f'({condition})'})"
    parts = split_comparison(condition)
    if parts is None:
        return f"ILLUM_OBSERVE_CHECK({kind}, ({condition}))"
    return f"ILLUM_OBSERVE_VALUE({kind}, ({parts[0]}))"


def rewrite(text: str, origin: str) -> str:
    """The observer's version of one source file (``origin``: the path its records name)."""
    out: list[str] = [f'#line 1 "{origin}"\n']
    copied = resume = 0  # resume: after the name or the macro invocation just read
    for i, _ in _code(text):
        if i < resume or not (match := _IDENTIFIER.match(text, i)):
            continue
        name, resume = match.group(0), match.end()
        before = text[text.rfind("\n", 0, i) + 1:i]  # its line up to it: `x.` or `x->` names a member, not a macro
        if (name.removeprefix("DOCTEST_") not in _NAMES or before.rstrip().endswith((".", "->", "::"))
                or (i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_"))):
            continue
        opening = _OPENING.match(text, resume)
        if not opening or before.lstrip().startswith("#"):  # a preprocessor line (#define CHECK ..., #undef CHECK)
            continue
        line = text.count("\n", 0, i) + 1
        try:
            args, end = _arguments(text, opening.end() - 1)
            replacement = _rewrite(name, args)
        except SourceError as error:
            raise SourceError(f"{origin}:{line}: {name}: {error}") from None
        out.append(text[copied:i])
        out.append(replacement + "\n" * (text.count("\n", i, end) - replacement.count("\n")))
        copied = resume = end
    out.append(text[copied:])
    return "".join(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, type=Path, help="folder for the rewritten files")
    parser.add_argument("files", nargs="+", type=Path)
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    for source in args.files:
        try:
            rewritten = rewrite(source.read_text(encoding="utf-8"), str(source.resolve()))
        except (OSError, UnicodeDecodeError, SourceError) as error:
            print(f"observer_sources: {error}", file=sys.stderr)
            return 1
        target = args.out / source.parent.name / source.name
        target.parent.mkdir(parents=True, exist_ok=True)
        if not target.exists() or target.read_text(encoding="utf-8") != rewritten:
            target.write_text(rewritten, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
