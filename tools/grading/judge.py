"""The judge: a test's verdict from the witness's check records (a trusted build of the reference) and
the observer's (the student's program, every expected side cut away), in the grader's own process, which
never runs student code (docs/grading-defences.md, "How a test is judged"). A test passes when the
observer reached the witness's checks in the same order and each left side satisfies the witness's
comparison; a missing, extra, reordered or wrongly kinded record fails its test and nothing else. What
the student's program says of its own verdict is never read."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from .results import Failure, normal_file

NOT_IMPLEMENTED = "NotImplemented: "
MAX_FAILURES = 10  # failures described for one test


class JudgeError(Exception):
    """The witness's records cannot be judged (the grader's fault, not the student's)."""


@dataclass
class Verdict:
    passed: bool
    failures: list[Failure] = field(default_factory=list)

    @property
    def not_implemented_only(self) -> bool:
        return not self.passed and bool(self.failures) and all(f.not_implemented for f in self.failures)


def _number(value: Any) -> float | int | None:
    """A JSON value as the number it stands for (non-finite doubles are {"double": "nan"})."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return value
    if isinstance(value, dict) and set(value) == {"double"}:
        return {"nan": math.nan, "inf": math.inf, "-inf": -math.inf}.get(value["double"])
    return None


def _equal(a: Any, b: Any) -> bool:
    """C++'s == on the two values as written (numbers compared as the program compares them)."""
    x, y = _number(a), _number(b)
    if x is not None and y is not None:
        return float(x) == float(y) if isinstance(x, float) or isinstance(y, float) else x == y
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_equal(p, q) for p, q in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict) and "pointer" in a and "pointer" in b:
        raise JudgeError("a check compares two pointers: addresses differ between programs")
    return type(a) is type(b) and a == b


def _less(a: Any, b: Any) -> bool:
    x, y = _number(a), _number(b)
    if x is not None and y is not None:
        return float(x) < float(y) if isinstance(x, float) or isinstance(y, float) else x < y
    if isinstance(a, str) and isinstance(b, str):
        return a.encode("utf-8") < b.encode("utf-8")
    if isinstance(a, list) and isinstance(b, list):  # std::vector's and std::array's <
        for p, q in zip(a, b):
            if _less(p, q):
                return True
            if _less(q, p):
                return False
        return len(a) < len(b)
    raise JudgeError(f"values that cannot be ordered: {describe(a)} and {describe(b)}")


def holds(op: str, lhs: Any, rhs: Any) -> bool:
    """Whether ``lhs op rhs`` holds, as the C++ check computes it."""
    if op not in ("==", "!=", "<", "<=", ">", ">="):
        raise JudgeError(f"an unknown comparison {op!r}")
    if isinstance(rhs, dict) and "approx" in rhs:
        if (number := _number(lhs)) is None:
            return False
        # doctest's Approx: |x − v| < ε·(scale + max(|x|, |v|)), in the same double arithmetic
        x, value, epsilon, scale = float(number), float(rhs["approx"]), float(rhs["epsilon"]), float(rhs["scale"])
        equal = abs(x - value) < epsilon * (scale + max(abs(x), abs(value)))
        return {"==": equal, "!=": not equal, "<": x < value and not equal, "<=": x < value or equal,
                ">": x > value and not equal, ">=": x > value or equal}[op]
    if op in ("==", "!="):
        return _equal(lhs, rhs) == (op == "==")
    # a < b and a >= b are decided by a < b; a > b and a <= b by b < a.
    less = _less(lhs, rhs) if op in ("<", ">=") else _less(rhs, lhs)
    return less == (op in ("<", ">"))


def describe(value: Any) -> str:
    """A value as the student reads it: doubles with 17 significant digits."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:.17g}"
    if isinstance(value, str):
        return '"' + value + '"'
    if value is None:
        return "nullopt"
    if isinstance(value, list):
        return "(" + ", ".join(describe(v) for v in value) + ")"
    if isinstance(value, dict):
        if "double" in value:
            return str(value["double"])
        if "approx" in value:
            return (f"Approx( {describe(float(value['approx']))} ) (within a relative {float(value['epsilon']):.3g}"
                    + (f", scale {float(value['scale']):.3g}" if float(value["scale"]) != 1.0 else "") + ")")
        if "text" in value:
            return str(value["text"])
        if "pointer" in value:
            return "a pointer" if value["pointer"] else "nullptr"
        if "contains" in value:
            return f"a message containing {describe(value['contains'])}"
    return str(value)


def first_difference(lhs: Any, rhs: Any) -> str:
    """For two sequences: where they first differ, else ''."""
    if not (isinstance(lhs, list) and isinstance(rhs, list)):
        return ""
    if len(lhs) != len(rhs):
        return f"{len(lhs)} element(s) where {len(rhs)} were expected"
    for index, (p, q) in enumerate(zip(lhs, rhs)):
        if not _equal(p, q):
            inner = first_difference(p, q)
            return f"first difference at [{index}]: " + (inner or f"{describe(p)} where {describe(q)} was expected")
    return ""


def _site(record: dict) -> tuple[str, int]:
    return normal_file(str(record.get("file", ""))), int(record.get("line", 0) or 0)


def _where(record: dict) -> str:
    return "{}:{}".format(*_site(record))


def _threw(lhs: Any) -> str | None:
    """The exception text of an observation whose left side threw, else None."""
    return str(lhs["threw"]) if isinstance(lhs, dict) and set(lhs) == {"threw"} else None


def check_passes(witness: dict, lhs: Any) -> bool:
    """Whether the observed left side passes the witness's check."""
    kind = str(witness.get("kind", ""))
    if _threw(lhs) is not None:
        return False
    if "THROWS" in kind or "NOTHROW" in kind:
        if not (isinstance(lhs, dict) and "threw" in lhs):
            return False
        if kind.endswith("NOTHROW"):
            return not lhs["threw"]
        if kind.endswith("THROWS_CONTAINING"):
            contains = str((witness.get("rhs") or {}).get("contains", ""))
            return bool(lhs.get("as")) and contains in str(lhs.get("message", ""))
        if kind.endswith("THROWS_AS"):
            return bool(lhs.get("as"))
        return bool(lhs["threw"])
    op = witness.get("op")
    if op is None:
        return isinstance(lhs, bool) and lhs != kind.endswith("FALSE")
    return holds(str(op), lhs, witness.get("rhs")) != kind.endswith("FALSE")


def _failure(witness: dict, message: str, hidden: bool, not_implemented: bool = False,
             exception: str = "") -> Failure:
    file, line = _site(witness)
    return Failure(kind="judged", message=message, file=file, line=line,
                   context="" if hidden else str(witness.get("context", "") or ""),
                   exception=exception, not_implemented=not_implemented,
                   expression=str(witness.get("expr", "") or ""))


def _explain(witness: dict, lhs: Any) -> str:
    """Why an observed value fails the witness's check, in the student's words."""
    kind, expr = str(witness.get("kind", "CHECK")), str(witness.get("expr", ""))
    head = f"{kind}( {expr} ) failed"
    if isinstance(lhs, dict) and "threw" in lhs and ("THROWS" in kind or "NOTHROW" in kind):
        if kind.endswith("NOTHROW"):
            return f"{head}: it threw {lhs.get('message', '')}"
        if not lhs["threw"]:
            return f"{head}: it did not throw at all"
        if not lhs.get("as"):
            return f"{head}: it threw a different exception: {lhs.get('message', '')}"
        return f"{head}: it threw {lhs.get('message', '')}, expected {describe(witness.get('rhs'))}"
    op = witness.get("op")
    if op is None:
        return f"{head}: it is {describe(lhs)}"
    text = f"{head}\n  got:      {describe(lhs)}\n  expected: {op} {describe(witness.get('rhs'))}"
    difference = first_difference(lhs, witness.get("rhs"))
    return text + (f"\n  {difference}" if difference else "")


def judge_test(witness: list[dict], observed: list[dict], stopped: str = "", hidden: bool = False) -> Verdict:
    """The verdict of one test. ``witness``: the trusted run's check records of the test, in order (every one
    passed there); ``observed``: the observer's, in order; ``stopped``: why the observer's run of the test
    ended early ('' when it ended normally): an exception that left the test (its text), a crash, a time-out."""
    if not witness:
        raise JudgeError("the reference's run of this test made no check")
    failures: list[Failure] = []
    for index, expected in enumerate(witness):
        if expected.get("passed") is not True:
            raise JudgeError(f"the reference fails its own check at {_where(expected)}")
        if index >= len(observed):
            failures.append(_stopped_before(expected, stopped, hidden))
            break
        got = observed[index]
        threw = _threw(got.get("lhs"))
        if threw is not None and _site(got) != _site(expected):
            # An exception in another check's expression, before this check ran (a helper with checks
            # of its own, called inside a check): the test stopped there for the student.
            failures.append(_stopped_before(expected, threw, hidden))
            break
        if _site(got) != _site(expected) or got.get("kind") != expected.get("kind"):
            failures.append(_failure(expected, f"the test took another path than the reference's run: its next check "
                                     f"is this one, your run's was {got.get('kind')} at {_where(got)} (a REQUIRE, a "
                                     "loop or a branch that depends on your results)", hidden))
            break
        lhs = got.get("lhs")
        if check_passes(expected, lhs):
            continue
        if threw is not None:
            message, text = threw, f"{expected.get('kind')}( {expected.get('expr', '')} ) threw: {threw}"
        else:
            message = str(lhs.get("message", "")) if isinstance(lhs, dict) and lhs.get("threw") is True else ""
            text = _explain(expected, lhs)
        failures.append(_failure(expected, text, hidden, message.startswith(NOT_IMPLEMENTED), message))
        if str(expected.get("kind", "")).startswith("REQUIRE") or len(failures) >= MAX_FAILURES:
            break  # the test stops at a failed REQUIRE, in the reference's terms too
    else:
        if len(observed) > len(witness):
            extra = observed[len(witness)]
            failures.append(Failure("judged", f"your run made {len(observed) - len(witness)} more check(s) than the "
                                              f"reference's, the first at {_where(extra)}", *_site(extra)))
        elif stopped:
            failures.append(Failure("judged", f"after its last check the test did not end normally: {stopped}",
                                    not_implemented=stopped.startswith(NOT_IMPLEMENTED), exception=stopped))
    return Verdict(passed=not failures, failures=failures)


def _stopped_before(expected: dict, stopped: str, hidden: bool) -> Failure:
    if stopped.startswith(NOT_IMPLEMENTED):
        return _failure(expected, f"not implemented yet: {stopped}", hidden, True, stopped)
    why = stopped or "the test ended without reaching it"
    return _failure(expected, f"your run stopped before this check: {why}", hidden, exception=stopped)
