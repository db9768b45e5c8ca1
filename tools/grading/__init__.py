"""The grading driver of illum (`tools/grade`, docs/grading.md), standard library only, so that it runs on
a fresh Gradescope image and on a student's machine alike. From the pure modules to those that run things:
results (the reporter's records), reports (score table, results.json, JUnit, exit code), project (where
lessons live), judge and observer_sources (verdicts formed outside the student's process), build (CMake, and
blaming a failed build on the student's files), suspicious (exercise files reaching outside the computation),
sandbox and sandbox_init (the student's code run apart), runner (a suite run and its records), integrity and
alone (the grading tests against the reference and the stubs), edition (the student edition), autograder
(Gradescope's zip), gradebook and batch (`--batch`), mutants (`--mutants`), driver (the command line)."""
