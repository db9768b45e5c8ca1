"""The grading driver of illum (``tools/grade``).

Modules, from the pure to the ones that run things:

* ``results``   what a test program reported, parsed from the ``illum-grade``
                reporter's JSON lines;
* ``reports``   score table, Gradescope ``results.json``, JUnit XML, exit code;
* ``project``   where lessons, exercises and tests live in a source tree;
* ``build``     configuring and building a grading tree with CMake;
* ``runner``    running a test program's ``lessonNN`` suite;
* ``integrity`` the check that grading tests pass on the reference and fail
                on the stubs;
* ``edition``   the student edition (no reference units, no hidden tests);
* ``autograder`` the Gradescope autograder zip and the submission installer;
* ``driver``    the command line.

Only the Python 3 standard library is used, so that the driver runs on a
fresh Gradescope image and on a student's machine alike.
"""
