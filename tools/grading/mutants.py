"""``tools/grade --mutants``: how many plausible student bugs do the grading tests catch?

    tools/grade --mutants [NN ...] [--sample N] [--seed S] [--jobs J]
                [--report FILE] [--timeout SECONDS] [--list] [--only ID ...]
                [--compare-without GLOB] [--fail-under PERCENT] [--work-dir DIR]

For each named lesson (default: every lesson with exercises) the tool makes
*mutants* of the lesson's exercise units -- the reference file with one small
change a student could plausibly make (``<`` for ``<=``, ``-`` for ``+``, a
constant nudged, ``i`` for ``j``, an ``abs`` dropped, a condition negated, a
loop bound off by one...) -- builds each one, runs the lesson's grading
suite on it and reports it:

* **killed** -- some grading test failed (or the program crashed): the
  suite catches this bug;
* **timed out** -- the suite did not finish in time (an endless loop): also
  caught, a student would not get the marks;
* **survived** -- every grading test passed: a student who made this
  mistake would get full marks for wrong code;
* **did not build** -- the change does not compile (with the project's
  warnings as errors); not a mistake a student could hand in.

score = (killed + timed out) / (killed + timed out + survived), leaving out
the mutants listed as *equivalent* in ``tests/mutants/equivalent.txt``
(changes no test could ever detect, each with a reason).

Only lines a student writes are mutated: a line of the reference unit that
also appears in the unit's stub (``exercises/NN_*/<unit>.cpp``: includes,
signatures, provided helpers) is left alone.

Builds are incremental: each worker keeps a private copy of the source tree
and one configured build tree under ``build/mutants/wK/`` (its layout mirrors
``build/release`` so that ccache, with a ``base_dir``, reuses objects of the
developer's own builds); a mutant rewrites one file and rebuilds only the
lesson's test program. The copy is refreshed from the working tree at every
run, so uncommitted tests count.
"""
from __future__ import annotations

import argparse
import difflib
import hashlib
import os
import queue
import random
import re
import shlex
import shutil
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from . import project

EQUIVALENT_FILE = Path("tests") / "mutants" / "equivalent.txt"
WORK_DIR = Path("build") / "mutants"

# ---------------------------------------------------------------------------
# A small C++ tokenizer: enough to find operators, literals and names outside
# comments, strings and preprocessor lines.

_TOKEN = re.compile(
    r"""
    (?P<comment>//[^\n]*|/\*.*?\*/)
  | (?P<string>"(?:\\.|[^"\\\n])*"|'(?:\\.|[^'\\\n])*')
  | (?P<number>(?:\d[\d']*\.?[\d']*|\.\d[\d']*)(?:[eE][+-]?\d+)?[fFlLuU]*)
  | (?P<ident>[A-Za-z_]\w*)
  | (?P<op><=>|<<=|>>=|->\*|->|::|\+\+|--|<<|>>|<=|>=|==|!=|&&|\|\||\+=|-=|\*=|/=|%=|&=|\|=|\^=|[-+*/%<>=!&|^~?:;,.(){}\[\]\#])
  | (?P<space>\s+)
  | (?P<other>.)
    """,
    re.VERBOSE | re.DOTALL,
)


@dataclass
class Token:
    kind: str
    text: str
    start: int
    end: int
    line: int
    template: bool = False  # an angle bracket of a template argument list


def tokenize(source: str) -> list[Token]:
    tokens: list[Token] = []
    line = 1
    at_line_start = True
    in_preprocessor = False
    for match in _TOKEN.finditer(source):
        kind, text = match.lastgroup or "other", match.group()
        if kind == "space":
            if "\n" in text:
                # A preprocessor line ends at a newline not escaped by a backslash.
                if in_preprocessor and not source[match.start() - 1:match.start()] == "\\":
                    in_preprocessor = False
                at_line_start = True
            line += text.count("\n")
            continue
        if kind == "op" and text == "#" and at_line_start:
            in_preprocessor = True
        at_line_start = False
        if kind != "comment" and not in_preprocessor:
            tokens.append(Token(kind, text, match.start(), match.end(), line))
        line += text.count("\n")
    _mark_templates(tokens)
    return tokens


_TEMPLATE_ARGUMENT_TOKENS = {"::", ",", "*", "&", "<", ">", ">>"}


def _mark_templates(tokens: list[Token]) -> None:
    """Marks ``<`` and ``>`` of template argument lists: a ``<`` after a name
    whose tokens up to a matching ``>`` can only be template arguments."""
    for index, token in enumerate(tokens):
        if token.text != "<" or token.template or index == 0:
            continue
        before = tokens[index - 1]
        if before.kind != "ident":
            continue
        depth, closing = 1, []
        for j in range(index + 1, min(len(tokens), index + 40)):
            t = tokens[j]
            if t.kind in ("ident", "number"):
                continue
            if t.text not in _TEMPLATE_ARGUMENT_TOKENS:
                break
            if t.text == "<":
                depth += 1
            elif t.text in (">", ">>"):
                depth -= 1 if t.text == ">" else 2
                closing.append(t)
                if depth <= 0:
                    token.template = True
                    for c in closing:
                        c.template = True
                    break


def body_tokens(tokens: list[Token]) -> list[bool]:
    """For each token: does it lie inside a function (or class) body, i.e. inside
    braces other than a namespace's?"""
    inside: list[bool] = []
    stack: list[bool] = []  # True for a brace that is a body
    for index, token in enumerate(tokens):
        if token.text == "{":
            back = [t.text for t in tokens[max(0, index - 3):index]]
            is_namespace = "namespace" in back[-2:] or (back[-1:] == ["namespace"])
            is_namespace = is_namespace or (len(back) >= 2 and back[-2] == "namespace")
            stack.append(not is_namespace)
            inside.append(any(stack))
            continue
        if token.text == "}":
            inside.append(any(stack))
            if stack:
                stack.pop()
            continue
        inside.append(any(stack))
    return inside


# ---------------------------------------------------------------------------
# Mutation operators.


@dataclass
class Mutant:
    lesson: str
    unit: Path           # path of the reference unit, relative to the root
    line: int
    operator: str        # short name of the kind of change
    start: int           # byte range of the original text that is replaced
    end: int
    original: str
    replacement: str
    source_line: str = ""   # the line before the change (stripped)
    mutated_line: str = ""  # the line after the change (stripped)
    status: str = ""        # killed / survived / timed out / did not build
    status_without: str = ""  # the same against the suite without the --compare-without files
    seconds: float = 0.0
    failed_test: str = ""   # the first grading test that failed (a killed mutant)
    source: str = field(default="", repr=False)  # the unit's text the offsets refer to

    @property
    def ident(self) -> str:
        digest = hashlib.sha1(f"{self.unit}:{self.start}:{self.operator}:{self.replacement}".encode()).hexdigest()
        return digest[:8]

    def apply(self, source: str | None = None) -> str:
        source = self.source if source is None else source
        return source[:self.start] + self.replacement + source[self.end:]

    def equivalence_key(self) -> str:
        return f"{self.unit.as_posix()}: {_code_only(self.source_line)} => {_code_only(self.mutated_line)}"

    def diff(self) -> str:
        source = self.source
        lines = difflib.unified_diff(source.splitlines(keepends=True), self.apply(source).splitlines(keepends=True),
                                     fromfile=f"a/{self.unit.as_posix()}", tofile=f"b/{self.unit.as_posix()}", n=1)
        return "".join(lines)


def _code_only(line: str) -> str:
    """A line without its trailing // comment, so that editing a comment keeps an equivalence entry valid."""
    return re.sub(r"\s*//.*$", "", line).strip()


_RELATIONAL = {"<": "<=", "<=": "<", ">": ">=", ">=": ">", "==": "!=", "!=": "=="}
_ARITHMETIC = {"+": "-", "-": "+", "*": "/", "/": "*", "+=": "-=", "-=": "+=", "*=": "/=", "/=": "*="}
_MIN_MAX = {"min": "max", "max": "min", "fmin": "fmax", "fmax": "fmin"}
_REMOVABLE_CALLS = {"abs", "fabs", "clamp"}
_TYPE_WORDS = {"double", "float", "int", "auto", "const", "char", "void", "bool", "long", "unsigned", "size_t",
               "constexpr", "operator", "return"}
_OPERAND_END = {")", "]"}


def _is_binary(tokens: list[Token], index: int) -> bool:
    """A + - * / between two operands (not unary, not a pointer declarator)."""
    if index == 0 or index + 1 >= len(tokens):
        return False
    before, after = tokens[index - 1], tokens[index + 1]
    if before.kind == "number" or before.text in _OPERAND_END:
        return after.text not in (")", ",", ";", ">")
    if before.kind != "ident" or before.text in _TYPE_WORDS:
        return False
    if tokens[index].text == "*" and (before.text[:1].isupper() or before.template):
        return False  # `Patch* p`, `std::vector<T>* v`
    return after.text not in (")", ",", ";", ">", "&", "=")


def _matching(tokens: list[Token], index: int) -> int:
    """Index of the bracket closing tokens[index] (a '(' or '['), or -1."""
    opening = tokens[index].text
    closing = {"(": ")", "[": "]"}[opening]
    depth = 0
    for j in range(index, len(tokens)):
        if tokens[j].text == opening:
            depth += 1
        elif tokens[j].text == closing:
            depth -= 1
            if depth == 0:
                return j
    return -1


def _top_level_commas(tokens: list[Token], open_index: int, close_index: int) -> list[int]:
    commas, depth = [], 0
    for j in range(open_index + 1, close_index):
        text = tokens[j].text
        if text in ("(", "[", "{") or (text == "<" and tokens[j].template):
            depth += 1
        elif text in (")", "]", "}") or (text == ">" and tokens[j].template):
            depth -= 1
        elif text == "," and depth == 0:
            commas.append(j)
    return commas


def _matching_back(tokens: list[Token], index: int) -> int:
    """Index of the bracket opening tokens[index] (a ')' or ']'), or -1."""
    closing = tokens[index].text
    opening = {")": "(", "]": "["}[closing]
    depth = 0
    for j in range(index, -1, -1):
        if tokens[j].text == closing:
            depth += 1
        elif tokens[j].text == opening:
            depth -= 1
            if depth == 0:
                return j
    return -1


def _operand_after(tokens: list[Token], index: int) -> int:
    """The index of the last token of the operand that starts at tokens[index]
    (a name with its calls, subscripts and members, a number, a parenthesised
    expression), or -1 when it is not one of those."""
    if index >= len(tokens):
        return -1
    token = tokens[index]
    if token.text == "(":
        return _matching(tokens, index)
    if token.kind == "number":
        return index
    if token.kind != "ident" or token.text in _TYPE_WORDS:
        return -1
    j = index
    while j + 1 < len(tokens):
        after = tokens[j + 1]
        if after.text in ("::", ".", "->") and j + 2 < len(tokens) and tokens[j + 2].kind == "ident":
            j += 2
        elif after.text in ("(", "["):
            close = _matching(tokens, j + 1)
            if close < 0:
                return -1
            j = close
        elif after.text == "<" and after.template:
            depth, k = 0, j + 1
            while k < len(tokens):
                if tokens[k].text == "<" and tokens[k].template:
                    depth += 1
                elif tokens[k].text in (">", ">>") and tokens[k].template:
                    depth -= 1 if tokens[k].text == ">" else 2
                    if depth <= 0:
                        break
                k += 1
            if k >= len(tokens):
                return -1
            j = k
        else:
            break
    return j


def _operand_before(tokens: list[Token], index: int) -> int:
    """The index of the first token of the operand that ends at tokens[index], or -1."""
    if index < 0:
        return -1
    token = tokens[index]
    j = index
    if token.text in (")", "]"):
        j = _matching_back(tokens, index)
        if j < 0:
            return -1
        if token.text == "(" or j == 0 or tokens[j - 1].kind != "ident" or tokens[j - 1].text in _TYPE_WORDS \
                or tokens[j - 1].text in ("if", "while", "for", "return", "switch"):
            if tokens[index].text == ")" and (j == 0 or tokens[j - 1].kind != "ident"
                                              or tokens[j - 1].text in ("if", "while", "for", "return", "switch")):
                return j
        j -= 1  # the called name
        if tokens[j].text in _TYPE_WORDS or tokens[j].text in ("if", "while", "for", "return", "switch"):
            return j + 1
    elif token.kind == "number":
        return index
    elif token.kind != "ident" or token.text in _TYPE_WORDS:
        return -1
    # A member or scope chain: a.b, a->b, ns::f, v[i].x.
    while j >= 2 and tokens[j - 1].text in ("::", ".", "->"):
        before = tokens[j - 2]
        if before.kind == "ident":
            j -= 2
        elif before.text in (")", "]"):
            opening = _matching_back(tokens, j - 2)
            if opening < 0:
                return -1
            j = opening - 1 if opening >= 1 and tokens[opening - 1].kind == "ident" else opening
        else:
            break
    return j


def _simple_argument(tokens: list[Token], first: int, last: int) -> bool:
    """An argument a student could write in the neighbour's place: a name, a member, a subscript, a number."""
    if last < first or last - first > 8:
        return False
    return all(t.kind in ("ident", "number") or t.text in (".", "->", "::", "[", "]") for t in tokens[first:last + 1])


def _is_float_literal(text: str) -> bool:
    return any(c in text for c in ".eE") and not text.lower().startswith("0x")


def _nudged_constants(text: str) -> list[str]:
    """0 <-> 1 and 2 -> 1 on integer and floating literals."""
    core = text.rstrip("fFlLuU")
    suffix = text[len(core):]
    try:
        value = float(core.replace("'", ""))
    except ValueError:
        return []
    is_float = _is_float_literal(core)
    targets = {0.0: [1.0], 1.0: [0.0], 2.0: [1.0]}.get(value, [])
    return [("1.0" if t == 1.0 else "0.0") + suffix if is_float else str(int(t)) + suffix for t in targets]


def generate(lesson: str, unit: Path, source: str, stub_lines: set[str]) -> list[Mutant]:
    """Every mutant of one exercise unit (in source order)."""
    tokens = tokenize(source)
    in_body = body_tokens(tokens)
    line_starts = [0] + [m.end() for m in re.finditer(r"\n", source)]

    def line_text(number: int) -> str:
        start = line_starts[number - 1]
        end = source.find("\n", start)
        return source[start:end if end >= 0 else len(source)]

    mutable_lines = {n for n in range(1, len(line_starts) + 1) if line_text(n).strip() not in stub_lines}
    mutants: list[Mutant] = []

    def add(operator: str, start: int, end: int, replacement: str, line: int) -> None:
        if line not in mutable_lines:
            return
        m = Mutant(lesson, unit, line, operator, start, end, source[start:end], replacement, source=source)
        mutated = m.apply(source)
        first = line_starts[line - 1]
        m.source_line = line_text(line).strip()
        # The mutated line: same start, end at the next newline of the mutated text.
        end_of_line = mutated.find("\n", first)
        m.mutated_line = mutated[first:end_of_line if end_of_line >= 0 else len(mutated)].strip()
        mutants.append(m)

    # Index names used alone in a subscript, for the i <-> j swap.
    subscript_names = [tokens[k + 1].text for k in range(len(tokens) - 2)
                       if tokens[k].text == "[" and tokens[k + 1].kind == "ident" and tokens[k + 2].text == "]"]

    for index, token in enumerate(tokens):
        if not in_body[index]:
            continue
        text = token.text
        if token.kind == "op" and text in _RELATIONAL and not token.template:
            add("relational", token.start, token.end, _RELATIONAL[text], token.line)
        elif token.kind == "op" and text in _ARITHMETIC and (text.endswith("=") or _is_binary(tokens, index)):
            add("arithmetic", token.start, token.end, _ARITHMETIC[text], token.line)
        elif token.kind == "op" and text == "-" and index + 1 < len(tokens) and not _is_binary(tokens, index):
            # A unary minus: drop it (a sign flipped).
            after = tokens[index + 1]
            if after.kind in ("ident", "number") or after.text == "(":
                add("sign", token.start, after.start, "", token.line)
        elif token.kind == "number":
            for replacement in _nudged_constants(text):
                add("constant", token.start, token.end, replacement, token.line)
        elif token.kind == "ident" and text in _MIN_MAX and index + 1 < len(tokens) and tokens[index + 1].text == "(":
            add("min/max", token.start, token.end, _MIN_MAX[text], token.line)
        elif token.kind == "ident" and text in _REMOVABLE_CALLS and index + 1 < len(tokens) \
                and tokens[index + 1].text == "(":
            close = _matching(tokens, index + 1)
            if close < 0:
                continue
            commas = _top_level_commas(tokens, index + 1, close)
            first_end = tokens[commas[0]].start if commas else tokens[close].start
            start = tokens[index - 2].start if index >= 2 and tokens[index - 1].text == "::" else token.start
            inner = source[tokens[index + 1].end:first_end].strip()
            if inner:
                add("abs/clamp removed", start, tokens[close].end, f"({inner})", token.line)
        elif token.kind == "ident" and text in ("if", "while") and index + 1 < len(tokens) \
                and tokens[index + 1].text == "(":
            close = _matching(tokens, index + 1)
            if close > 0:
                condition = source[tokens[index + 1].end:tokens[close].start]
                add("condition negated", tokens[index + 1].start, tokens[close].end, f"(!({condition}))", token.line)
        elif token.kind == "ident" and text == "for" and index + 1 < len(tokens) and tokens[index + 1].text == "(":
            close = _matching(tokens, index + 1)
            semis = [j for j in range(index + 2, close) if tokens[j].text == ";"]
            if close > 0 and len(semis) == 2 and semis[1] > semis[0] + 1:
                # `i < n` -> `i < n - 1`: the loop stops one early.
                condition = tokens[semis[0] + 1:semis[1]]
                ops = [t for t in condition if t.text in ("<", "<=", "!=") and not t.template]
                # Only a plain `i < bound`: in `i < n && more` the "bound" would swallow the rest.
                compound = any(t.text in ("&&", "||", "?", ",") for t in condition)
                if len(ops) == 1 and not compound:
                    bound_end = tokens[semis[1] - 1].end
                    bound = source[ops[0].end:bound_end]
                    add("loop bound", ops[0].end, bound_end, f"{bound} - 1", token.line)
                downward = [t for t in condition if t.text in (">", ">=") and not t.template]
                if len(downward) == 1 and not ops and not compound:
                    # `i >= 0` -> `i >= 0 + 1`: a loop that counts down stops one early.
                    bound_end = tokens[semis[1] - 1].end
                    bound = source[downward[0].end:bound_end]
                    add("loop bound", downward[0].end, bound_end, f"{bound} + 1", token.line)
                # The start shifted: `i = first` -> `i = first + 1` (a literal start is nudged as a constant).
                init = tokens[index + 2:semis[0]]
                assign = [k for k, t in enumerate(init) if t.text == "="]
                if len(assign) == 1 and assign[0] + 1 < len(init) and not any(t.text == "," for t in init):
                    start_tokens = init[assign[0] + 1:]
                    if not (len(start_tokens) == 1 and start_tokens[0].kind == "number"):
                        first = source[start_tokens[0].start:start_tokens[-1].end]
                        add("loop bound", start_tokens[0].start, start_tokens[-1].end, f"{first} + 1", token.line)
        elif token.kind == "ident" and text in subscript_names and index >= 1 and tokens[index - 1].text == "[" \
                and index + 1 < len(tokens) and tokens[index + 1].text == "]":
            partner = _index_partner(text, subscript_names)
            # Only a name in scope nearby (declared or used in the last few lines) would compile.
            nearby = {t.text for t in tokens[max(0, index - 80):index] if t.kind == "ident" and t.line >= token.line - 6}
            if partner and partner in nearby:
                add("index swap", token.start, token.end, partner, token.line)
        # The operators of the slips a mutation run of the classic kinds missed (issue 28):
        if token.kind == "op" and text in ("*", "/") and _is_binary(tokens, index):
            # A factor or a division dropped: `a * b` -> `a` and `b`, `a / b` -> `a`.
            right = _operand_after(tokens, index + 1)
            if right > index and (right + 1 >= len(tokens) or tokens[right + 1].text not in ("(", "[")):
                name = "factor dropped" if text == "*" else "division dropped"
                add(name, tokens[index - 1].end, tokens[right].end, "", token.line)
            left = _operand_before(tokens, index - 1)
            if text == "*" and 0 <= left < index and (left == 0 or tokens[left - 1].text not in (".", "->", "::")):
                add("factor dropped", tokens[left].start, tokens[index + 1].start, "", token.line)
        if token.kind == "ident" and text in _MIN_MAX and index + 1 < len(tokens) and tokens[index + 1].text == "(" \
                and not (index >= 1 and tokens[index - 1].text in (".", "->")):
            # A clamp dropped: max(0.0, x) -> x (either argument kept alone).
            close = _matching(tokens, index + 1)
            commas = _top_level_commas(tokens, index + 1, close) if close > 0 else []
            if close > 0 and len(commas) == 1 and tokens[index + 2].text != "{":
                start = tokens[index - 2].start if index >= 2 and tokens[index - 1].text == "::" else token.start
                if index >= 4 and tokens[index - 1].text == "::" and tokens[index - 3].text == "::":
                    start = tokens[index - 4].start
                for first, last in ((index + 2, commas[0] - 1), (commas[0] + 1, close - 1)):
                    kept = source[tokens[first].start:tokens[last].end].strip()
                    if kept:
                        add("clamp dropped", start, tokens[close].end, f"({kept})", token.line)
        if token.kind == "op" and text == "(" and index >= 1 and tokens[index - 1].kind == "ident" \
                and tokens[index - 1].text not in ("if", "while", "for", "switch", "return", "sizeof") \
                and tokens[index - 1].text not in _TYPE_WORDS:
            # An argument replaced by its neighbour: f(a, b) -> f(a, a) and f(b, b).
            close = _matching(tokens, index)
            commas = _top_level_commas(tokens, index, close) if close > 0 else []
            if close > 0 and commas:
                bounds = [index + 1, *(c + 1 for c in commas)]
                ends = [*(c - 1 for c in commas), close - 1]
                arguments = list(zip(bounds, ends))
                for (a_first, a_last), (b_first, b_last) in zip(arguments, arguments[1:]):
                    if not (_simple_argument(tokens, a_first, a_last) and _simple_argument(tokens, b_first, b_last)):
                        continue
                    a_text = source[tokens[a_first].start:tokens[a_last].end]
                    b_text = source[tokens[b_first].start:tokens[b_last].end]
                    if a_text == b_text:
                        continue
                    add("argument neighbour", tokens[a_first].start, tokens[a_last].end, b_text, token.line)
                    add("argument neighbour", tokens[b_first].start, tokens[b_last].end, a_text, token.line)
        if token.kind == "ident" and text == "double" and not (index >= 1 and tokens[index - 1].text == "long"):
            # Float arithmetic where the reference computes in double: a local or a cast.
            after = tokens[index + 1] if index + 1 < len(tokens) else None
            declares = after is not None and after.kind == "ident" and index + 2 < len(tokens) \
                and tokens[index + 2].text in ("=", "{", "(", ";", ",", "[")
            casts = after is not None and after.text == ">" and index >= 2 and tokens[index - 1].text == "<" \
                and tokens[index - 2].text == "static_cast"
            if declares or casts:
                add("float for double", token.start, token.end, "float", token.line)
        if token.kind == "op" and text == "(" and index >= 1 and tokens[index - 1].kind == "ident":
            # f(i, j) -> f(j, i): two plain index names swapped in a call.
            close = _matching(tokens, index)
            if close == index + 4 and tokens[index + 2].text == "," and tokens[index + 1].kind == "ident" \
                    and tokens[index + 3].kind == "ident" and tokens[index + 1].text in subscript_names + ["i", "j"] \
                    and tokens[index + 3].text in subscript_names + ["i", "j"] \
                    and tokens[index + 1].text != tokens[index + 3].text:
                a, b = tokens[index + 1], tokens[index + 3]
                add("index swap", a.start, b.end, f"{b.text}, {a.text}", token.line)
    # One mutant per resulting program: `a * pi * b` loses pi as ' * pi' or as 'pi * ', the same text.
    unique: dict[tuple[int, str], Mutant] = {}
    for m in sorted(mutants, key=lambda m: (m.start, m.operator)):
        unique.setdefault((m.line, m.mutated_line), m)
    return sorted(unique.values(), key=lambda m: (m.start, m.operator))


def _index_partner(name: str, names: list[str]) -> str:
    """The index a student could confuse with `name`: i <-> j, k <-> l, else the
    most used other single-name subscript of the file."""
    pairs = {"i": "j", "j": "i", "k": "l", "l": "k", "u": "v", "v": "u", "a": "b", "b": "a"}
    if name in pairs and pairs[name] in names:
        return pairs[name]
    others = [n for n in names if n != name and len(n) <= 2]
    if not others:
        return ""
    return max(sorted(set(others)), key=others.count)


# ---------------------------------------------------------------------------
# The lessons' units and the equivalent-mutant list.


def lesson_units(root: Path, lesson: str) -> list[tuple[Path, Path]]:
    """(reference unit, stub) pairs of one lesson, relative to root."""
    units = []
    lib = root / "lib"
    for stub in sorted((root / "exercises").glob(f"{lesson}_*/*.cpp")):
        found = sorted(lib.rglob(stub.name))
        if found:
            units.append((found[0].relative_to(root), stub.relative_to(root)))
    return units


def all_mutants(root: Path, lesson: str) -> list[Mutant]:
    mutants = []
    for unit, stub in lesson_units(root, lesson):
        stub_lines = {line.strip() for line in (root / stub).read_text(encoding="utf-8").splitlines()}
        stub_lines.discard("")
        source = (root / unit).read_text(encoding="utf-8")
        mutants += generate(lesson, unit, source, stub_lines)
    return mutants


@dataclass
class Equivalents:
    reasons: dict[str, str] = field(default_factory=dict)  # key -> reason
    problems: list[str] = field(default_factory=list)

    def reason(self, mutant: Mutant) -> str | None:
        return self.reasons.get(mutant.equivalence_key())


def read_equivalents(path: Path) -> Equivalents:
    """``file: original line => mutated line  -- reason``, one a line; # comments."""
    result = Equivalents()
    if not path.exists():
        return result
    for number, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        key, sep, reason = line.rpartition(" -- ")
        if not sep or " => " not in key or ": " not in key or not reason.strip():
            result.problems.append(f"{path}:{number}: expected 'file: original => mutated -- reason'")
            continue
        unit, _, lines = key.partition(": ")
        original, _, mutated = lines.partition(" => ")
        result.reasons[f"{unit.strip()}: {_code_only(original)} => {_code_only(mutated)}"] = reason.strip()
    return result


# ---------------------------------------------------------------------------
# Student bugs written by hand (tests/mutants/student_bugs/*.bug): realistic
# mistakes the generator does not make (a count in the wrong place, a loop
# that reads what it writes, a fixed epsilon), run like mutants.

BUGS_FOLDER = Path("tests") / "mutants" / "student_bugs"


@dataclass
class BugFile:
    path: Path
    lesson: str = ""
    unit: Path = Path()
    title: str = ""
    caught_by: str = ""  # the test the bug's author expects to fail first (for the reader; not enforced)
    edits: list[tuple[str, str]] = field(default_factory=list)  # (find, replace), each found exactly once


def read_bug(path: Path) -> BugFile:
    """A ``.bug`` file: ``key: value`` lines (lesson, unit, title, caught-by; # comments), then one or
    more ``--- find`` / ``+++ replace`` pairs, each followed by its lines verbatim."""
    bug = BugFile(path)
    mode, find, replace = "header", [], []
    for raw in path.read_text(encoding="utf-8").splitlines():
        if raw == "--- find":
            if mode == "replace":
                bug.edits.append(("\n".join(find), "\n".join(replace)))
            mode, find, replace = "find", [], []
            continue
        if raw == "+++ replace":
            if mode != "find":
                raise ValueError(f"{path}: '+++ replace' without a '--- find' before it")
            mode = "replace"
            continue
        if mode == "header":
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            key, sep, value = line.partition(":")
            if not sep:
                raise ValueError(f"{path}: expected 'key: value', got {line!r}")
            key, value = key.strip(), value.strip()
            if key == "lesson":
                bug.lesson = value
            elif key == "unit":
                bug.unit = Path(value)
            elif key == "title":
                bug.title = value
            elif key == "caught-by":
                bug.caught_by = value
            else:
                raise ValueError(f"{path}: unknown key {key!r} (lesson, unit, title, caught-by)")
        elif mode == "find":
            find.append(raw)
        else:
            replace.append(raw)
    if mode == "replace":
        bug.edits.append(("\n".join(find), "\n".join(replace)))
    if not (bug.lesson and str(bug.unit) != "." and bug.title and bug.edits):
        raise ValueError(f"{path}: needs lesson, unit, title and at least one --- find / +++ replace pair")
    return bug


def bug_mutant(root: Path, bug: BugFile) -> Mutant:
    """The bug as a mutant of its unit: the whole file replaced by the edited one."""
    source = (root / bug.unit).read_text(encoding="utf-8")
    edited = source
    for find, replace in bug.edits:
        count = edited.count(find)
        if count != 1:
            raise ValueError(f"{bug.path.name}: the text to find occurs {count} times in {bug.unit} "
                             f"(expected once):\n{find}")
        edited = edited.replace(find, replace)
    first = next(i for i, (a, b) in enumerate(zip(source, edited + "\0")) if a != b)
    line = source.count("\n", 0, first) + 1
    return Mutant(bug.lesson, bug.unit, line, f"student bug {bug.path.stem}", 0, len(source), source, edited,
                  source_line=bug.title, mutated_line=bug.caught_by, source=source)


def read_bugs(root: Path, folder: Path) -> tuple[list[tuple[BugFile, Mutant]], list[str]]:
    """Every bug of ``folder`` with its mutant, and the problems of the files that could not be read."""
    found, problems = [], []
    for path in sorted(folder.glob("*.bug")):
        try:
            bug = read_bug(path)
            found.append((bug, bug_mutant(root, bug)))
        except (ValueError, OSError) as error:
            problems.append(str(error))
    return found, problems


# ---------------------------------------------------------------------------
# Workers: a private source copy and build tree each.

_COPY_IGNORE = {"build", ".git", "node_modules", "out", "__pycache__"}


def sync_tree(source: Path, destination: Path) -> None:
    """Mirrors the source tree into destination, rewriting only files whose
    content changed (unchanged files keep their time stamps: no rebuild)."""
    seen: set[Path] = set()
    for folder, dirs, files in os.walk(source):
        here = Path(folder)
        relative = here.relative_to(source)
        dirs[:] = [d for d in dirs if not (relative == Path(".") and d in _COPY_IGNORE) and d != "__pycache__"]
        (destination / relative).mkdir(parents=True, exist_ok=True)
        seen.add(destination / relative)
        for name in files:
            if relative == Path(".") and name in _COPY_IGNORE:
                continue  # e.g. a node_modules symlink
            src, dst = here / name, destination / relative / name
            seen.add(dst)
            if src.is_symlink():  # copied as a link, never followed (it may point anywhere, or nowhere)
                target = os.readlink(src)
                if not dst.is_symlink() or os.readlink(dst) != target:
                    if dst.exists() or dst.is_symlink():
                        dst.unlink()
                    os.symlink(target, dst)
                continue
            if dst.is_symlink():
                dst.unlink()
            data = src.read_bytes()
            if not dst.exists() or dst.read_bytes() != data:
                dst.write_bytes(data)
                shutil.copymode(src, dst)
    for folder, dirs, files in os.walk(destination, topdown=False):
        here = Path(folder)
        if here == destination / "build" or destination / "build" in here.parents:
            continue
        for name in files:
            if here / name not in seen:
                (here / name).unlink()
        if here not in seen and here != destination:
            shutil.rmtree(here, ignore_errors=True)


class Workspace:
    """One worker's copy of the tree (``build/mutants/wK``) and its build tree."""

    def __init__(self, root: Path, base: Path, number: int):
        self.root = root
        self.src = base / f"w{number}"
        # Same depth as build/release, so ccache's base_dir makes paths identical.
        self.build = self.src / "build" / "release"
        self.number = number
        self.current: Path | None = None  # the unit rewritten now, if any

    def prepare(self, echo) -> tuple[bool, str]:
        sync_tree(self.root, self.src)
        command = ["cmake", "-S", str(self.src), "-B", str(self.build), "-DCMAKE_BUILD_TYPE=Release",
                   "-DILLUM_BUILD_TESTS=ON", "-DILLUM_WERROR=ON", "-DILLUM_EXERCISES=", "-DILLUM_HIDDEN_TESTS="]
        if shutil.which("ccache"):
            command.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
        return done.returncode == 0, done.stdout

    def build_targets(self, targets: list[str], timeout: float, jobs: int = 1) -> tuple[bool, str]:
        command = ["cmake", "--build", str(self.build), "-j", str(jobs), "--target", *targets]
        try:
            done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                  errors="replace", timeout=timeout)
        except subprocess.TimeoutExpired:
            return False, f"the build did not finish within {timeout:g} s"
        return done.returncode == 0, done.stdout

    def write_unit(self, unit: Path, text: str) -> None:
        # One mutant at a time: a worker that moves on to another unit puts the
        # previous one back first, or every later mutant would also carry the
        # last mutation of that unit (and be killed by it, not by its own).
        if self.current is not None and self.current != unit:
            self.restore()
        path = self.src / unit
        path.write_text(text, encoding="utf-8")
        self.current = unit

    def restore(self) -> None:
        if self.current is not None:
            original = (self.root / self.current).read_bytes()
            (self.src / self.current).write_bytes(original)
            self.current = None


def lesson_targets(root: Path, lesson: str) -> list[str]:
    targets = [f"tests_lesson{lesson}"]
    # The hidden program only when it holds this lesson's suite: linking it costs as much as the lesson's own.
    if any(f'"lesson{lesson}"' in path.read_text(encoding="utf-8", errors="replace")
           for path in project.hidden_sources(root)):
        targets.append("tests_hidden")
    return targets


_TEST_CASE_LINE = re.compile(r"^TEST CASE:\s+(.*)$", re.M)


def run_grading(workspace: Workspace, lesson: str, timeout: float, extra: tuple[str, ...] = ()) -> tuple[str, str]:
    """('killed' | 'survived' | 'timed out', first failing test) for the built tree.

    A mutant only needs one failing test to be killed, so the suite runs with
    doctest's --abort-after=1: a wrong program stops at its first failed
    assertion instead of failing thousands of them (which can take minutes),
    and a time-out then really means a program that does not finish."""
    bin_dir = workspace.build / "bin"
    programs = [bin_dir / f"tests_lesson{lesson}"]
    if "tests_hidden" in lesson_targets(workspace.root, lesson):
        programs.append(bin_dir / "tests_hidden")
    for program in programs:
        command = [str(program), f"-ts=lesson{lesson}", "--abort-after=1", "--no-version", "--no-colors", *extra]
        try:
            # One process: a mutant that crashes a test is killed there; the tests after it need not run.
            done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                  text=True, errors="replace", timeout=timeout,
                                  env=dict(os.environ, ILLUM_TEST_ONE_PROCESS="1"))
        except subprocess.TimeoutExpired:
            return "timed out", ""
        if done.returncode == 124 and "(an endless loop?)" in done.stdout:
            return "timed out", ""  # the test program's own per-test limit (tests/support/test_main.cpp)
        if done.returncode != 0:
            found = _TEST_CASE_LINE.search(done.stdout)
            if found:
                return "killed", found.group(1).strip()
            return "killed", f"{program.name} exited with status {done.returncode}"
        if not extra and ("test cases:" not in done.stdout or re.search(r"test cases:\s+0 \|", done.stdout)):
            return "killed", f"{program.name} ran no lesson{lesson} test"
    return "survived", ""


# ---------------------------------------------------------------------------
# The run.


@dataclass
class LessonReport:
    lesson: str
    generated: int = 0          # every mutant of the lesson
    equivalent: int = 0         # of them listed as equivalent
    mutants: list[Mutant] = field(default_factory=list)  # the ones run
    seconds: float = 0.0
    baseline_seconds: float = 0.0
    problem: str = ""

    def count(self, status: str, without: bool = False) -> int:
        return sum(1 for m in self.mutants if (m.status_without if without else m.status) == status)

    def detected(self, without: bool = False) -> int:
        return self.count("killed", without) + self.count("timed out", without)

    def scored(self, without: bool = False) -> int:
        return self.detected(without) + self.count("survived", without)

    def score_of(self, without: bool = False) -> float | None:
        scored = self.scored(without)
        return 100.0 * self.detected(without) / scored if scored else None

    @property
    def score(self) -> float | None:
        return self.score_of()


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="tools/grade --mutants",
        description="Mutation report: build small plausible bugs of the lessons' exercise units and count how "
                    "many the grading tests catch (see docs/grading.md).")
    parser.add_argument("--mutants", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("lessons", nargs="*", metavar="NN", help="lessons (default: every lesson with exercises)")
    parser.add_argument("--sample", type=int, metavar="N",
                        help="a seeded random sample of N mutants per lesson (those listed as equivalent are then "
                             "left out of it)")
    parser.add_argument("--seed", type=int, default=1, metavar="S", help="seed of --sample (default 1)")
    parser.add_argument("--jobs", "-j", type=int, default=max(1, (os.cpu_count() or 2) // 2), metavar="J",
                        help="parallel workers, each with its own build tree (default: half the cores)")
    parser.add_argument("--report", type=Path, metavar="FILE", help="write the Markdown report here")
    parser.add_argument("--timeout", type=float, metavar="SECONDS",
                        help="seconds per suite run (default: 10 × the unmutated run, at least 20)")
    parser.add_argument("--list", action="store_true", help="list the mutants (after --sample) and stop")
    parser.add_argument("--only", action="append", default=[], metavar="ID",
                        help="run only the mutant with this id (from --list or a report); repeatable")
    parser.add_argument("--compare-without", metavar="GLOB",
                        help="also score every mutant against the suite without the test files matching GLOB "
                             "(doctest --source-file-exclude), e.g. to show what new tests add")
    parser.add_argument("--work-dir", type=Path, metavar="DIR", help=f"workers' trees (default {WORK_DIR})")
    parser.add_argument("--fail-under", type=float, metavar="PERCENT",
                        help="exit 1 if a lesson scores below PERCENT")
    parser.add_argument("--bugs", nargs="?", const=str(BUGS_FOLDER), metavar="DIR",
                        help="run the hand-written student bugs of DIR (default tests/mutants/student_bugs, "
                             "*.bug files) instead of generated mutants")
    args = parser.parse_args(argv)
    try:
        args.lessons = sorted(set(project.normalize_lesson(text) for text in args.lessons))
    except ValueError as error:
        parser.error(str(error))
    if args.sample is not None and args.sample < 1:
        parser.error("--sample N needs N ≥ 1")
    if args.jobs < 1:
        parser.error("--jobs J needs J ≥ 1")
    return args


def choose(root: Path, args: argparse.Namespace, equivalents: Equivalents) -> list[LessonReport]:
    exercises = project.exercise_lessons(root)
    unknown = [nn for nn in args.lessons if nn not in exercises]
    if unknown:  # a wrong command: exit status 2, as every tools/grade command
        print(f"tools/grade --mutants: lesson(s) {', '.join(unknown)} have no exercise units; "
              f"lessons with exercises: {', '.join(exercises)}", file=sys.stderr)
        raise SystemExit(2)
    reports = []
    if getattr(args, "bugs", None):
        bugs, problems = read_bugs(root, root / args.bugs if not Path(args.bugs).is_absolute() else Path(args.bugs))
        for problem in problems:
            print(f"tools/grade --mutants --bugs: {problem}", file=sys.stderr)
        if problems:
            raise SystemExit(2)
        for lesson in args.lessons or exercises:
            report = LessonReport(lesson)
            report.mutants = [m for bug, m in bugs if bug.lesson == lesson]
            report.generated = len(report.mutants)
            if args.only:
                report.mutants = [m for m in report.mutants if m.ident in args.only]
            if report.generated:
                reports.append(report)
        return reports
    for lesson in args.lessons or exercises:
        report = LessonReport(lesson)
        every = all_mutants(root, lesson)
        report.generated = len(every)
        report.equivalent = sum(1 for m in every if equivalents.reason(m) is not None)
        chosen = every
        if args.sample is not None and args.sample < len(every):
            # Drawn from every mutant, equivalent or not, so that listing an equivalent
            # mutant later leaves the rest of a seed's sample as it was (fair before/after runs).
            rng = random.Random(f"{args.seed}:{lesson}")
            chosen = sorted(rng.sample(every, args.sample), key=lambda m: (str(m.unit), m.start))
        report.mutants = [m for m in chosen if equivalents.reason(m) is None]
        if args.only:
            report.mutants = [m for m in report.mutants if m.ident in args.only]
        reports.append(report)
    return reports


class Progress:
    def __init__(self, total: int):
        self.total, self.done, self.start = total, 0, time.monotonic()
        self.lock = threading.Lock()

    def report(self, mutant: Mutant) -> None:
        with self.lock:
            self.done += 1
            elapsed = time.monotonic() - self.start
            left = elapsed / self.done * (self.total - self.done)
            what = (f"{mutant.source_line}" if mutant.operator.startswith("student bug") else
                    f"{mutant.original!r} -> {mutant.replacement!r}")
            print(f"[{self.done}/{self.total} {elapsed:5.0f} s, ~{left:4.0f} s left] {mutant.status:13} "
                  f"{mutant.unit.name}:{mutant.line} {mutant.operator}: {what}"
                  + (f"  ({mutant.failed_test})" if mutant.failed_test else ""),
                  file=sys.stderr, flush=True)


def run_lesson(report: LessonReport, workspaces: list[Workspace], timeout_arg: float | None,
               compare_without: str | None = None) -> None:
    root = workspaces[0].root
    start = time.monotonic()
    targets = lesson_targets(root, report.lesson)
    # Baseline: each worker builds the unmutated tree; the suite must pass on it.
    # The first build of a tree compiles the whole library: share the cores among the workers.
    build_jobs = max(1, (os.cpu_count() or 1) // len(workspaces))
    for workspace in workspaces:
        workspace.restore()
        ok, output = workspace.build_targets(targets, timeout=3600, jobs=build_jobs)
        if not ok:
            report.problem = f"the unmutated tree does not build in {workspace.build}:\n{output[-3000:]}"
            return
    t0 = time.monotonic()
    status, failed = run_grading(workspaces[0], report.lesson, timeout=timeout_arg or 600)
    report.baseline_seconds = time.monotonic() - t0
    if status != "survived":
        report.problem = f"the grading suite does not pass on the reference ({status}: {failed}); fix that first"
        return
    timeout = timeout_arg or max(20.0, 10 * report.baseline_seconds)
    progress = Progress(len(report.mutants))
    # Mutants of one unit go to one worker in turn, so it rewrites the file in place.
    work: queue.Queue[Mutant] = queue.Queue()
    for mutant in sorted(report.mutants, key=lambda m: (str(m.unit), m.start)):
        work.put(mutant)

    def worker(workspace: Workspace) -> None:
        while True:
            try:
                mutant = work.get_nowait()
            except queue.Empty:
                break
            t = time.monotonic()
            workspace.write_unit(mutant.unit, mutant.apply())
            ok, _ = workspace.build_targets(targets, timeout=max(300.0, timeout))
            if not ok:
                mutant.status = "did not build"
            else:
                mutant.status, mutant.failed_test = run_grading(workspace, report.lesson, timeout)
                mutant.status_without = mutant.status
                if compare_without and mutant.status != "survived":
                    # Fewer tests cannot kill what the whole suite lets through: run only if it matters.
                    mutant.status_without, _ = run_grading(workspace, report.lesson, timeout,
                                                           (f"--source-file-exclude={compare_without}",))
            if mutant.status == "did not build":
                mutant.status_without = mutant.status
            mutant.seconds = time.monotonic() - t
            progress.report(mutant)
        workspace.restore()

    threads = [threading.Thread(target=worker, args=(w,)) for w in workspaces]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    # Leave every tree built from the unmutated sources.
    for workspace in workspaces:
        workspace.restore()
    report.seconds = time.monotonic() - start


def summary_table(reports: list[LessonReport], compare_without: str | None = None) -> str:
    extra = f" score without `{compare_without}` |" if compare_without else ""
    lines = ["| lesson | mutants (equivalent) | run | killed | timed out | survived | did not build | score |"
             + extra + " time |",
             "|---|---|---|---|---|---|---|---|" + ("---|" if compare_without else "") + "---|"]

    def percent(value: float | None) -> str:
        return "n/a" if value is None else f"**{value:.1f}%**"

    for r in reports:
        score = "error" if r.problem else percent(r.score)
        row = (f"| {r.lesson} | {r.generated} ({r.equivalent}) | {len(r.mutants)} | {r.count('killed')} | "
               f"{r.count('timed out')} | {r.count('survived')} | {r.count('did not build')} | {score} |")
        if compare_without:
            before = r.score_of(without=True)
            row += (" n/a |" if before is None or r.problem else
                    f" {before:.1f}% ({r.count('survived', True)} survived) |")
        lines.append(row + f" {r.seconds:.0f} s |")
    return "\n".join(lines)


def markdown_report(reports: list[LessonReport], root: Path, command: str, compare_without: str | None = None) -> str:
    parts = [
        "# Grading power: the mutation report",
        "",
        "Produced by `tools/grade --mutants` (docs/grading-reference.md explains how to read it). Regenerate with:",
        "",
        "```sh",
        command,
        "```",
        "",
        "A *mutant* is a reference exercise unit with one plausible student mistake. **score** = "
        "(killed + timed out) / (killed + timed out + survived): the share of those mistakes the lesson's "
        "grading suite catches. Mutants listed in `tests/mutants/equivalent.txt` (no test could detect them) "
        "are left out; *did not build* mutants do not compile and are not scored. *time* is the whole "
        "lesson's run on this machine (two cores, shared).",
        "",
        summary_table(reports, compare_without),
        "",
    ]
    if compare_without:
        parts[-1:-1] = ["", f"*score without `{compare_without}`*: the same mutants against the suite without "
                        f"the test files matching `{compare_without}` (what the score was before those tests)."]
    for r in reports:
        parts.append(f"## Lesson {r.lesson}")
        parts.append("")
        if r.problem:
            parts += ["Not run: " + r.problem.splitlines()[0], ""]
            continue
        parts.append(f"{len(r.mutants)} mutant(s) run of {r.generated} ({r.equivalent} equivalent left out); "
                     f"unmutated suite {r.baseline_seconds:.1f} s.")
        parts.append("")
        survivors = [m for m in r.mutants if m.status == "survived"]
        if not survivors:
            parts += ["No survivor.", ""]
        for m in survivors:
            parts += [f"- survived: `{m.unit.as_posix()}:{m.line}` ({m.operator}, id `{m.ident}`)", "", "  ```diff"]
            parts += ["  " + line for line in m.diff().rstrip("\n").splitlines()]
            parts += ["  ```", ""]
    return "\n".join(parts).rstrip("\n") + "\n"


def bugs_report(reports: list[LessonReport], command: str) -> str:
    """Markdown: every hand-written student bug, whether the grading suite catches it, and by which test."""
    lines = ["# Student bugs: does the grading suite catch them?", "",
             "Produced by `tools/grade --mutants --bugs` (docs/grading.md). Regenerate with:", "", "```sh",
             command, "```", "",
             "Each bug is a mistake written by hand into a copy of a reference exercise unit "
             "(`tests/mutants/student_bugs/*.bug`), built and graded like a mutant.", "",
             "| lesson | bug | what the student did | status | first test that fails |", "|---|---|---|---|---|"]
    for r in reports:
        for m in r.mutants:
            name = m.operator.removeprefix("student bug ")
            test = m.failed_test.replace("|", "\\|") or "—"
            title = m.source_line.replace("|", "\\|")
            lines.append(f"| {r.lesson} | `{name}` | {title} | {m.status} | {test} |")
    caught = sum(r.detected() for r in reports)
    scored = sum(r.scored() for r in reports)
    lines += ["", f"Caught: {caught} of {scored}" + (f" ({100.0 * caught / scored:.0f}%)." if scored else "."), ""]
    return "\n".join(lines)


def main(argv: list[str]) -> int:
    args = parse_arguments(argv)
    root = project.ROOT
    if project.is_student_edition(root):
        print("tools/grade --mutants: mutants are made from the reference solutions, which the student edition "
              "does not have", file=sys.stderr)
        return 2
    equivalents = read_equivalents(root / EQUIVALENT_FILE)
    for problem in equivalents.problems:
        print(f"tools/grade --mutants: {problem}", file=sys.stderr)
    if equivalents.problems:
        return 2
    reports = choose(root, args, equivalents)
    if args.list and args.bugs:
        for r in reports:
            for m in r.mutants:
                print(f"{m.ident} lesson{r.lesson} {m.operator.removeprefix('student bug ')} "
                      f"{m.unit.as_posix()}:{m.line}: {m.source_line}")
        return 0
    if args.list:
        for r in reports:
            for m in r.mutants:
                print(f"{m.ident} lesson{r.lesson} {m.unit.as_posix()}:{m.line} {m.operator}: "
                      f"{m.source_line}  =>  {m.mutated_line}")
        return 0
    base = (args.work_dir or root / WORK_DIR).resolve()
    jobs = max(1, min(args.jobs, max(len(r.mutants) for r in reports) if reports else 1))
    workspaces = [Workspace(root, base, k) for k in range(jobs)]
    for workspace in workspaces:
        print(f"tools/grade --mutants: preparing {workspace.src}", file=sys.stderr, flush=True)
        ok, output = workspace.prepare(echo=False)
        if not ok:
            print(output[-4000:], file=sys.stderr)
            print(f"tools/grade --mutants: could not configure {workspace.build}", file=sys.stderr)
            return 2
    for report in reports:
        print(f"tools/grade --mutants: lesson {report.lesson}: {len(report.mutants)} mutant(s) of "
              f"{report.generated}, {jobs} worker(s)", file=sys.stderr, flush=True)
        run_lesson(report, workspaces, args.timeout, args.compare_without)
        if report.problem:
            print(f"tools/grade --mutants: lesson {report.lesson}: {report.problem}", file=sys.stderr)
    command = "tools/grade " + shlex.join(argv if "--mutants" in argv else ["--mutants", *argv])
    if args.bugs:
        text = bugs_report(reports, command)
        print(text)
    else:
        print(summary_table(reports, args.compare_without))
        for r in reports:
            for m in (m for m in r.mutants if m.status == "survived"):
                print(f"survived: {m.ident} {m.unit.as_posix()}:{m.line} {m.operator}: {m.source_line}  =>  "
                      f"{m.mutated_line}")
        text = markdown_report(reports, root, command, args.compare_without)
    if args.report:
        args.report.parent.mkdir(parents=True, exist_ok=True)
        args.report.write_text(text, encoding="utf-8")
        print(f"wrote {args.report}", file=sys.stderr)
    if any(r.problem for r in reports):
        return 2
    if args.fail_under is not None and any(r.score is not None and r.score < args.fail_under for r in reports):
        return 1
    return 0
