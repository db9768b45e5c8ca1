#!/usr/bin/env python3
"""The judge (tools/grading/judge.py) and the observer's sources (tools/grading/observer_sources.py).

Expected verdicts come from doctest's own definitions, worked by hand here: Approx is
|a − v| < ε·(scale + max(|a|, |v|)); a check compares its left side with its right side as C++
does; a test passes only when the observer's checks are the witness's, in order, and each holds.
"""
from __future__ import annotations

import math
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))

from grading.judge import JudgeError, check_passes, describe, first_difference, holds, judge_test  # noqa: E402
from grading.observer_sources import SourceError, rewrite, split_comparison  # noqa: E402


def approx(value: float, epsilon: float = 1.1920928955078125e-05, scale: float = 1.0) -> dict:
    return {"approx": value, "epsilon": epsilon, "scale": scale}


def witness(line: int, kind: str = "CHECK", op: str | None = "==", rhs=None, expr: str = "x == y") -> dict:
    return {"event": "check", "file": "../../tests/01_ray_sphere/grading.cpp", "line": line, "kind": kind,
            "expr": expr, "op": op, "lhs": None, "rhs": rhs, "passed": True, "context": "why"}


def observed(line: int, lhs, kind: str = "CHECK") -> dict:
    return {"event": "check", "file": "/x/tests/01_ray_sphere/grading.cpp", "line": line, "kind": kind, "lhs": lhs}


class ValuesTest(unittest.TestCase):
    def test_approx_is_doctests_relative_formula(self) -> None:
        # ε = 1e-3, v = 100: the bound is 1e-3 · (1 + 100.5) ≈ 0.1015 at a = 100.5 (passes), 0.1012 at
        # a = 100.2 (passes); a = 100.11 is 0.11 away, bound 1e-3 · 101.11 = 0.10111: fails.
        self.assertTrue(holds("==", 100.1, approx(100, 1e-3)))
        self.assertFalse(holds("==", 100.11, approx(100, 1e-3)))
        self.assertTrue(holds("!=", 100.11, approx(100, 1e-3)))
        # Near zero the scale (1) makes it absolute: |1e-9 − 0| < 1e-8 · (1 + 1e-9).
        self.assertTrue(holds("==", 1e-9, approx(0.0, 1e-8)))
        self.assertFalse(holds("==", 1e-7, approx(0.0, 1e-8)))
        # Ordered comparisons with Approx: a < v and not approximately equal.
        self.assertTrue(holds("<", 99.0, approx(100, 1e-3)))
        self.assertFalse(holds("<", 99.95, approx(100, 1e-3)))
        self.assertTrue(holds("<=", 99.95, approx(100, 1e-3)))

    def test_exact_comparisons_and_types(self) -> None:
        self.assertTrue(holds("==", 2, 2))
        self.assertTrue(holds("==", 0.5, 0.5))
        self.assertFalse(holds("==", 0.25000000000000006, 0.25))
        self.assertTrue(holds("==", -0.0, 0.0))  # IEEE: −0 == +0
        self.assertFalse(holds("==", {"double": "nan"}, {"double": "nan"}))  # NaN != NaN
        self.assertTrue(holds("!=", {"double": "nan"}, {"double": "nan"}))
        self.assertTrue(holds("<", 1, 2.5))
        self.assertTrue(holds(">=", [1, 2], [1, 1]))
        self.assertTrue(holds("==", [1.0, 2.0, 3.0], [1, 2, 3]))
        self.assertFalse(holds("==", [1, 2], [1, 2, 3]))
        self.assertTrue(holds("==", None, None))  # nullopt == nullopt
        self.assertFalse(holds("==", 4.0, None))
        self.assertFalse(holds("==", "4", 4))
        self.assertTrue(holds("<", "abc", "abd"))
        with self.assertRaises(JudgeError):
            holds("==", {"pointer": "set"}, {"pointer": "set"})

    def test_values_are_written_in_full(self) -> None:
        self.assertEqual(describe(0.1), "0.10000000000000001")
        self.assertEqual(describe([1, 0.5]), "(1, 0.5)")
        self.assertIn("within a relative 1e-12", describe(approx(4.0, 1e-12)))
        self.assertEqual(first_difference([[0, 0, 1], [1, 0, 1]], [[0, 0, 1], [1, 0, 2]]),
                         "first difference at [1]: first difference at [2]: 1 where 2 was expected")


class CheckTest(unittest.TestCase):
    def test_unary_and_false_checks(self) -> None:
        self.assertTrue(check_passes(witness(1, "CHECK", None), True))
        self.assertFalse(check_passes(witness(1, "CHECK", None), False))
        self.assertTrue(check_passes(witness(1, "CHECK_FALSE", None), False))
        self.assertTrue(check_passes(witness(1, "CHECK_FALSE", "==", 3), 4))  # CHECK_FALSE(x == 3), x = 4
        self.assertFalse(check_passes(witness(1, "CHECK", None), 1))  # a number is not a unary observation

    def test_throws_family(self) -> None:
        threw_as = {"threw": True, "as": True, "message": "radius must be positive"}
        other = {"threw": True, "as": False, "message": "NotImplemented: Sphere::Sphere"}
        none = {"threw": False, "as": False, "message": ""}
        self.assertTrue(check_passes(witness(1, "CHECK_THROWS_AS", None), threw_as))
        self.assertFalse(check_passes(witness(1, "CHECK_THROWS_AS", None), other))
        self.assertTrue(check_passes(witness(1, "CHECK_THROWS", None), other))
        self.assertFalse(check_passes(witness(1, "CHECK_NOTHROW", None), other))
        self.assertTrue(check_passes(witness(1, "CHECK_NOTHROW", None), none))
        contains = witness(1, "CHECK_THROWS_CONTAINING", None, {"contains": "positive"})
        self.assertTrue(check_passes(contains, threw_as))
        self.assertFalse(check_passes(contains, dict(threw_as, message="bad radius")))
        self.assertFalse(check_passes(witness(1), {"threw": "NotImplemented: f"}))


class TestVerdictTest(unittest.TestCase):
    def checks(self) -> list[dict]:
        return [witness(10, "REQUIRE", "==", 2), witness(11, rhs=approx(9.0)), witness(12, rhs=approx(11.0))]

    def test_right_values_pass_and_a_wrong_one_fails_with_both_sides(self) -> None:
        good = [observed(10, 2, "REQUIRE"), observed(11, 9.0), observed(12, 11.0)]
        self.assertTrue(judge_test(self.checks(), good).passed)
        bad = [observed(10, 2, "REQUIRE"), observed(11, 8.5), observed(12, 11.0)]
        verdict = judge_test(self.checks(), bad)
        self.assertFalse(verdict.passed)
        self.assertIn("got:      8.5", verdict.failures[0].message)
        self.assertIn("expected: == Approx( 9 )", verdict.failures[0].message)

    def test_missing_extra_reordered_and_renamed_records_fail(self) -> None:
        right = [observed(10, 2, "REQUIRE"), observed(11, 9.0), observed(12, 11.0)]
        for case, records in {"missing": right[:2], "extra": right + [observed(13, 1.0)],
                              "reordered": [right[0], right[2], right[1]],
                              "renamed": [right[0], observed(11, 9.0, "CHECK_FALSE"), right[2]],
                              "none": [],
                              "forged booleans": [observed(10, True, "REQUIRE"), observed(11, True),
                                                  observed(12, True)]}.items():
            with self.subTest(case):
                self.assertFalse(judge_test(self.checks(), records).passed)

    def test_a_failed_require_stops_the_test(self) -> None:
        verdict = judge_test(self.checks(), [observed(10, 1, "REQUIRE"), observed(11, 8.0)])
        self.assertEqual(len(verdict.failures), 1)

    def test_not_implemented_is_recognised(self) -> None:
        stub = judge_test(self.checks(), [], stopped="NotImplemented: sphere_roots_notes — write it")
        self.assertTrue(stub.not_implemented_only)
        threw = judge_test(self.checks(), [observed(10, {"threw": "NotImplemented: f — hint"}, "REQUIRE")])
        self.assertTrue(threw.not_implemented_only)
        crash = judge_test(self.checks(), [observed(10, 2, "REQUIRE")], stopped="killed by SIGSEGV")
        self.assertFalse(crash.passed)
        self.assertFalse(crash.not_implemented_only)
        self.assertIn("SIGSEGV", crash.failures[0].message)

    def test_an_exception_after_the_last_check_fails(self) -> None:
        right = [observed(10, 2, "REQUIRE"), observed(11, 9.0), observed(12, 11.0)]
        self.assertFalse(judge_test(self.checks(), right, stopped="std::runtime_error: late").passed)

    def test_hidden_tests_keep_their_explanations_to_themselves(self) -> None:
        verdict = judge_test(self.checks(), [observed(10, 3, "REQUIRE")], hidden=True)
        self.assertEqual(verdict.failures[0].context, "")

    def test_a_witness_that_failed_or_made_no_check_is_the_graders_fault(self) -> None:
        with self.assertRaises(JudgeError):
            judge_test([], [])
        with self.assertRaises(JudgeError):
            judge_test([dict(witness(1), passed=False)], [observed(1, 1)])


class ObserverSourcesTest(unittest.TestCase):
    def test_the_right_side_is_cut(self) -> None:
        self.assertEqual(split_comparison("r.s_near == doctest::Approx(9.0).epsilon(1e-12)"),
                         ("r.s_near", "==", "doctest::Approx(9.0).epsilon(1e-12)"))
        self.assertEqual(split_comparison("static_cast<int>(hits.size()) >= std::vector<int>{1, 2}.size()"),
                         ("static_cast<int>(hits.size())", ">=", "std::vector<int>{1, 2}.size()"))
        self.assertEqual(split_comparison("a < b"), ("a", "<", "b"))
        self.assertEqual(split_comparison("(x << 2) == y"), ("(x << 2)", "==", "y"))
        self.assertEqual(split_comparison("p->next == \"a == b\""), ("p->next", "==", "\"a == b\""))
        self.assertIsNone(split_comparison("hit.has_value()"))
        self.assertIsNone(split_comparison("(a == b && c)"))
        for refused in ("a == b && c", "a < b == c", "a ? b : c", " == b"):
            with self.subTest(refused), self.assertRaises(SourceError):
                split_comparison(refused)

    def test_a_file_keeps_its_lines_and_loses_every_expected_side(self) -> None:
        source = ('// CHECK(x == 1) in a comment stays\n'
                  'CHECK_MESSAGE(t ==\n    doctest::Approx(4.25).epsilon(1e-12), "why " << 7);\n'
                  'REQUIRE(n == 2);\n'
                  'INFO("expected 4.25");\n'
                  'CHECK_FALSE(inside(p, poly));\n'
                  'ILLUM_CHECK_APPROX(a.s, 6.5, 1e-15);\n'
                  'ILLUM_CHECK_THROWS_CONTAINING(f(), "radius", std::invalid_argument);\n'
                  'CHECK_THROWS_AS(Sphere(c, -1.0), std::invalid_argument);\n'
                  'text.CHECK(3 == 4);\n')
        out = rewrite(source, "/t/tests/01_ray_sphere/grading.cpp")
        self.assertEqual(out.count("\n"), source.count("\n") + 1)  # the #line directive
        self.assertTrue(out.startswith('#line 1 "/t/tests/01_ray_sphere/grading.cpp"\n'))
        for secret in ("4.25", "6.5", "radius", "why", "7);"):
            self.assertNotIn(secret, out, secret)
        self.assertIn("ILLUM_OBSERVE_VALUE(CHECK, (t))", out)
        self.assertIn("ILLUM_OBSERVE_CHECK(REQUIRE, n == 2)", out)
        self.assertIn("ILLUM_OBSERVE_CHECK(CHECK_FALSE, (inside(p, poly)))", out)
        self.assertIn("ILLUM_OBSERVE_THROWS(CHECK_THROWS_CONTAINING, f(), std::invalid_argument)", out)
        self.assertIn("// CHECK(x == 1) in a comment stays", out)
        self.assertIn("text.CHECK(3 == 4)", out)  # a member, not the macro
        self.assertEqual(out.splitlines()[4], "ILLUM_OBSERVE_CHECK(REQUIRE, n == 2);")  # line 3 of the source

    def test_a_check_it_cannot_split_stops_the_build(self) -> None:
        with self.assertRaises(SourceError) as caught:
            rewrite("\n\nCHECK(a == b || c);\n", "/t/x.cpp")
        self.assertIn("/t/x.cpp:3", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
