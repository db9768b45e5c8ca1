"""The mutants of a C++ exercise unit: a small tokenizer (operators, literals and names outside comments,
strings and preprocessor lines) and the mutation operators, each a plausible student slip (`<` for `<=`,
a constant nudged, `i` for `j`, an `abs` dropped, a loop bound off by one, a factor dropped, …), made only
on the lines a student writes (not one of the stub's). `tools/grade --mutants` runs them (mutants.py)."""
from __future__ import annotations

import difflib
import hashlib
import re
from dataclasses import dataclass, field
from pathlib import Path

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
    close: int = -1  # a template argument list's '<': the index of its closing '>' (or '>>')


def tokenize(source: str) -> list[Token]:
    tokens: list[Token] = []
    line, at_line_start, in_preprocessor = 1, True, False
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
    """Marks ``<`` and ``>`` of template argument lists: a ``<`` after a name whose tokens up to a matching ``>``
    can only be template arguments."""
    for index, token in enumerate(tokens):
        if token.text != "<" or token.template or index == 0 or tokens[index - 1].kind != "ident":
            continue
        depth, closing = 1, []
        for j in range(index + 1, min(len(tokens), index + 40)):
            t = tokens[j]
            if t.kind in ("ident", "number"):
                continue
            if t.text not in _TEMPLATE_ARGUMENT_TOKENS:
                break
            depth += {"<": 1, ">": -1, ">>": -2}.get(t.text, 0)
            if t.text in (">", ">>"):
                closing.append(t)
                if depth <= 0:
                    token.template, token.close = True, j
                    for c in closing:
                        c.template = True
                    break


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
    failed_test: str = ""   # the first grading test that failed (a killed mutant)
    source: str = field(default="", repr=False)  # the unit's text the offsets refer to

    @property
    def ident(self) -> str:
        return hashlib.sha1(f"{self.unit}:{self.start}:{self.operator}:{self.replacement}".encode()).hexdigest()[:8]

    def apply(self, source: str | None = None) -> str:
        source = self.source if source is None else source
        return source[:self.start] + self.replacement + source[self.end:]

    def equivalence_key(self) -> str:
        return f"{self.unit.as_posix()}: {code_only(self.source_line)} => {code_only(self.mutated_line)}"

    def diff(self) -> str:
        unit = self.unit.as_posix()
        return "".join(difflib.unified_diff(self.source.splitlines(keepends=True),
                                            self.apply().splitlines(keepends=True), f"a/{unit}", f"b/{unit}", n=1))


def code_only(line: str) -> str:
    """A line without its trailing // comment, so that editing a comment keeps an equivalence entry valid."""
    return re.sub(r"\s*//.*$", "", line).strip()


_RELATIONAL = {"<": "<=", "<=": "<", ">": ">=", ">=": ">", "==": "!=", "!=": "=="}
_ARITHMETIC = {"+": "-", "-": "+", "*": "/", "/": "*", "+=": "-=", "-=": "+=", "*=": "/=", "/=": "*="}
_MIN_MAX = {"min": "max", "max": "min", "fmin": "fmax", "fmax": "fmin"}
_REMOVABLE_CALLS = {"abs", "fabs", "clamp"}
_TYPE_WORDS = {"double", "float", "int", "auto", "const", "char", "void", "bool", "long", "unsigned", "size_t",
               "constexpr", "operator", "return"}
_OPERAND_END = {")", "]"}
_CONTROL = {"if", "while", "for", "return", "switch"}


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
    """Index of the bracket that closes (or opens) the one at tokens[index], or -1."""
    pairs = {"(": ")", "[": "]", ")": "(", "]": "["}
    here, other = tokens[index].text, pairs[tokens[index].text]
    step, depth = (1 if here in "([" else -1), 0
    for j in range(index, len(tokens) if step > 0 else -1, step):
        depth += (tokens[j].text == here) - (tokens[j].text == other)
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


def _operand_after(tokens: list[Token], index: int) -> int:
    """The index of the last token of the operand that starts at tokens[index] (a name with its calls, subscripts
    and members, a number, a parenthesised expression), or -1 when it is not one of those."""
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
            j = after.close
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
        opening = _matching(tokens, index)
        if opening < 0:
            return -1
        name = tokens[opening - 1]  # the called or subscripted name, if there is one
        if (token.text == ")" and (opening == 0 or name.kind != "ident")) or name.text in _TYPE_WORDS | _CONTROL:
            return opening  # a parenthesised expression, a cast, a condition
        j = opening - 1
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
            opening = _matching(tokens, j - 2)
            if opening < 0:
                return -1
            j = opening - 1 if opening >= 1 and tokens[opening - 1].kind == "ident" else opening
        else:
            break
    return j


def _simple_argument(tokens: list[Token], first: int, last: int) -> bool:
    """An argument a student could write in the neighbour's place: a name, a member, a subscript, a number."""
    return first <= last <= first + 8 and all(t.kind in ("ident", "number") or t.text in (".", "->", "::", "[", "]")
                                              for t in tokens[first:last + 1])


def generate(lesson: str, unit: Path, source: str, stub_lines: set[str]) -> list[Mutant]:
    """Every mutant of one exercise unit (in source order)."""
    return _Generator(lesson, unit, source, stub_lines).run()


class _Generator:
    """The mutants of one unit: each operator a method that looks at one token of a function body."""

    def __init__(self, lesson: str, unit: Path, source: str, stub_lines: set[str]):
        self.lesson, self.unit, self.source = lesson, unit, source
        self.tokens = tokenize(source)
        self.line_starts = [0] + [m.end() for m in re.finditer(r"\n", source)]
        self.lines = source.split("\n")
        self.mutable = {n for n, text in enumerate(self.lines, start=1) if text.strip() not in stub_lines}
        self.mutants: list[Mutant] = []
        # Index names used alone in a subscript, for the i <-> j swap.
        t = self.tokens
        self.subscripts = [t[k + 1].text for k in range(len(t) - 2)
                           if t[k].text == "[" and t[k + 1].kind == "ident" and t[k + 2].text == "]"]

    def add(self, operator: str, start: int, end: int, replacement: str, line: int) -> None:
        """A mutant, unless its line is one of the stub's (a student does not write it)."""
        if line not in self.mutable:
            return
        m = Mutant(self.lesson, self.unit, line, operator, start, end, self.source[start:end], replacement,
                   source_line=self.lines[line - 1].strip(), source=self.source)
        m.mutated_line = m.apply()[self.line_starts[line - 1]:].split("\n", 1)[0].strip()
        self.mutants.append(m)

    def text(self, first: int, last: int) -> str:
        return self.source[self.tokens[first].start:self.tokens[last].end]

    def call_at(self, index: int, names) -> int:
        """The index of the ')' closing `name(` (-1 if none) when tokens[index] is one of `names` followed by
        '(', else -2."""
        t = self.tokens
        if t[index].kind != "ident" or t[index].text not in names or index + 1 >= len(t) or t[index + 1].text != "(":
            return -2
        return _matching(t, index + 1)

    def run(self) -> list[Mutant]:
        """The operators on every token inside a function (or class) body: inside braces other than a namespace's."""
        braces: list[bool] = []  # True for a brace that is a body
        for index, token in enumerate(self.tokens):
            if token.text == "{":  # a namespace's brace follows `namespace` or `namespace name`
                braces.append("namespace" not in [t.text for t in self.tokens[max(0, index - 2):index]])
            if any(braces):
                for operator in (self.classic, self.dropped_factor, self.dropped_clamp, self.argument_neighbour,
                                 self.float_for_double, self.swapped_arguments):
                    operator(index, token)
            if token.text == "}" and braces:
                braces.pop()
        # One mutant per resulting program: `a * pi * b` loses pi as ' * pi' or as 'pi * ', the same text.
        unique: dict[tuple[int, str], Mutant] = {}
        for m in sorted(self.mutants, key=lambda m: (m.start, m.operator)):
            unique.setdefault((m.line, m.mutated_line), m)
        return sorted(unique.values(), key=lambda m: (m.start, m.operator))

    def classic(self, index: int, token: Token) -> None:
        """The classic slips: a relation, an operator, a sign, a constant, min for max, an abs or clamp
        removed, a condition negated, a loop bound off by one, an index swapped."""
        t, text = self.tokens, token.text
        if token.kind == "op" and text in _RELATIONAL and not token.template:
            self.add("relational", token.start, token.end, _RELATIONAL[text], token.line)
        elif token.kind == "op" and text in _ARITHMETIC and (text.endswith("=") or _is_binary(t, index)):
            self.add("arithmetic", token.start, token.end, _ARITHMETIC[text], token.line)
        elif token.kind == "op" and text == "-" and index + 1 < len(t) and not _is_binary(t, index):
            if t[index + 1].kind in ("ident", "number") or t[index + 1].text == "(":  # a unary minus dropped
                self.add("sign", token.start, t[index + 1].start, "", token.line)
        elif token.kind == "number":  # 0 <-> 1 and 2 -> 1, on integer and floating literals
            core = text.rstrip("fFlLuU")
            try:
                target = {0.0: 1, 1.0: 0, 2.0: 1}.get(float(core.replace("'", "")))
            except ValueError:
                return
            if target is not None:
                point = ".0" if any(c in core for c in ".eE") and not core.lower().startswith("0x") else ""
                self.add("constant", token.start, token.end, f"{target}{point}{text[len(core):]}", token.line)
        elif self.call_at(index, _MIN_MAX) >= -1:
            self.add("min/max", token.start, token.end, _MIN_MAX[text], token.line)
        elif (close := self.call_at(index, _REMOVABLE_CALLS)) >= -1:
            if close < 0:
                return
            commas = _top_level_commas(t, index + 1, close)
            first_end = t[commas[0]].start if commas else t[close].start
            start = t[index - 2].start if index >= 2 and t[index - 1].text == "::" else token.start
            if inner := self.source[t[index + 1].end:first_end].strip():
                self.add("abs/clamp removed", start, t[close].end, f"({inner})", token.line)
        elif (close := self.call_at(index, ("if", "while"))) >= -1:
            if close <= 0:
                return
            condition = self.source[t[index + 1].end:t[close].start]
            self.add("condition negated", t[index + 1].start, t[close].end, f"(!({condition}))", token.line)
        elif token.kind == "ident" and text == "for" and index + 1 < len(t) and t[index + 1].text == "(":
            self.loop_bounds(index, token)
        elif token.kind == "ident" and text in self.subscripts and index >= 1 and t[index - 1].text == "[" \
                and index + 1 < len(t) and t[index + 1].text == "]":
            partner = _index_partner(text, self.subscripts)
            # Only a name in scope nearby (declared or used in the last few lines) would compile.
            nearby = {k.text for k in t[max(0, index - 80):index] if k.kind == "ident" and k.line >= token.line - 6}
            if partner and partner in nearby:
                self.add("index swap", token.start, token.end, partner, token.line)

    def loop_bounds(self, index: int, token: Token) -> None:
        """`i < n` -> `i < n - 1`, `i >= 0` -> `i >= 0 + 1`, `i = first` -> `i = first + 1`: one early or late."""
        t = self.tokens
        close = _matching(t, index + 1)
        semis = [j for j in range(index + 2, close) if t[j].text == ";"]
        if close <= 0 or len(semis) != 2 or semis[1] <= semis[0] + 1:
            return
        condition = t[semis[0] + 1:semis[1]]
        # Only a plain `i < bound`: in `i < n && more` the "bound" would swallow the rest.
        compound = any(k.text in ("&&", "||", "?", ",") for k in condition)
        upward = [k for k in condition if k.text in ("<", "<=", "!=") and not k.template]
        downward = [k for k in condition if k.text in (">", ">=") and not k.template]
        bound_end = t[semis[1] - 1].end
        if len(upward) == 1 and not compound:
            self.add("loop bound", upward[0].end, bound_end, f"{self.source[upward[0].end:bound_end]} - 1", token.line)
        if len(downward) == 1 and not upward and not compound:
            self.add("loop bound", downward[0].end, bound_end, f"{self.source[downward[0].end:bound_end]} + 1",
                     token.line)
        init = t[index + 2:semis[0]]  # a literal start is nudged as a constant
        assign = [k for k, tok in enumerate(init) if tok.text == "="]
        if len(assign) == 1 and assign[0] + 1 < len(init) and not any(tok.text == "," for tok in init):
            start = init[assign[0] + 1:]
            if not (len(start) == 1 and start[0].kind == "number"):
                first = self.source[start[0].start:start[-1].end]
                self.add("loop bound", start[0].start, start[-1].end, f"{first} + 1", token.line)

    # The operators of the slips a mutation run of the classic kinds missed (issue 28):

    def dropped_factor(self, index: int, token: Token) -> None:
        """`a * b` -> `a` and `b`, `a / b` -> `a`."""
        t = self.tokens
        if token.kind != "op" or token.text not in ("*", "/") or not _is_binary(t, index):
            return
        right = _operand_after(t, index + 1)
        if right > index and (right + 1 >= len(t) or t[right + 1].text not in ("(", "[")):
            self.add("factor dropped" if token.text == "*" else "division dropped", t[index - 1].end, t[right].end,
                     "", token.line)
        left = _operand_before(t, index - 1)
        if token.text == "*" and 0 <= left < index and (left == 0 or t[left - 1].text not in (".", "->", "::")):
            self.add("factor dropped", t[left].start, t[index + 1].start, "", token.line)

    def dropped_clamp(self, index: int, token: Token) -> None:
        """`max(0.0, x)` -> `x` (either argument kept alone)."""
        t = self.tokens
        close = self.call_at(index, _MIN_MAX)
        if close <= 0 or (index >= 1 and t[index - 1].text in (".", "->")):
            return
        commas = _top_level_commas(t, index + 1, close)
        if len(commas) != 1 or t[index + 2].text == "{":
            return
        start = t[index - 2].start if index >= 2 and t[index - 1].text == "::" else token.start
        if index >= 4 and t[index - 1].text == "::" and t[index - 3].text == "::":
            start = t[index - 4].start
        for first, last in ((index + 2, commas[0] - 1), (commas[0] + 1, close - 1)):
            if kept := self.text(first, last).strip():
                self.add("clamp dropped", start, t[close].end, f"({kept})", token.line)

    def argument_neighbour(self, index: int, token: Token) -> None:
        """An argument replaced by its neighbour: f(a, b) -> f(a, a) and f(b, b)."""
        t = self.tokens
        if token.text != "(" or token.kind != "op" or index < 1 or t[index - 1].kind != "ident" \
                or t[index - 1].text in _CONTROL | _TYPE_WORDS | {"sizeof"}:
            return
        close = _matching(t, index)
        commas = _top_level_commas(t, index, close) if close > 0 else []
        if not commas:
            return
        arguments = list(zip([index + 1, *(c + 1 for c in commas)], [*(c - 1 for c in commas), close - 1]))
        for (a_first, a_last), (b_first, b_last) in zip(arguments, arguments[1:]):
            if not (_simple_argument(t, a_first, a_last) and _simple_argument(t, b_first, b_last)):
                continue
            a_text, b_text = self.text(a_first, a_last), self.text(b_first, b_last)
            if a_text != b_text:
                self.add("argument neighbour", t[a_first].start, t[a_last].end, b_text, token.line)
                self.add("argument neighbour", t[b_first].start, t[b_last].end, a_text, token.line)

    def float_for_double(self, index: int, token: Token) -> None:
        """Float arithmetic where the reference computes in double: a local or a cast."""
        t = self.tokens
        if token.kind != "ident" or token.text != "double" or (index >= 1 and t[index - 1].text == "long"):
            return
        after = t[index + 1] if index + 1 < len(t) else None
        declares = after is not None and after.kind == "ident" and index + 2 < len(t) \
            and t[index + 2].text in ("=", "{", "(", ";", ",", "[")
        casts = after is not None and after.text == ">" and index >= 2 and t[index - 1].text == "<" \
            and t[index - 2].text == "static_cast"
        if declares or casts:
            self.add("float for double", token.start, token.end, "float", token.line)

    def swapped_arguments(self, index: int, token: Token) -> None:
        """f(i, j) -> f(j, i): two plain index names swapped in a call."""
        t = self.tokens
        if token.kind != "op" or token.text != "(" or index < 1 or t[index - 1].kind != "ident" \
                or _matching(t, index) != index + 4 or t[index + 2].text != ",":
            return
        a, b, names = t[index + 1], t[index + 3], self.subscripts + ["i", "j"]
        if a.kind == b.kind == "ident" and a.text in names and b.text in names and a.text != b.text:
            self.add("index swap", a.start, b.end, f"{b.text}, {a.text}", token.line)


def _index_partner(name: str, names: list[str]) -> str:
    """The index a student could confuse with `name`: i <-> j, k <-> l, else the most used other single-name
    subscript of the file."""
    pairs = {"i": "j", "j": "i", "k": "l", "l": "k", "u": "v", "v": "u", "a": "b", "b": "a"}
    if name in pairs and pairs[name] in names:
        return pairs[name]
    others = [n for n in names if n != name and len(n) <= 2]
    return max(sorted(set(others)), key=others.count, default="")
