"""The grading driver of illum (``tools/grade``).

Modules, from the pure to the ones that run things:

* ``results``   what a test program reported, parsed from the ``illum-grade``
                reporter's JSON lines;
* ``reports``   score table, Gradescope ``results.json``, JUnit XML, exit code;
* ``project``   where lessons, exercises and tests live in a source tree;
* ``build``     configuring and building a grading tree with CMake (and blaming
                a failed compile or link on the student's files that cause it);
* ``sandbox``   running a student's code apart: an unprivileged user, a pid
                namespace or process group, resource limits (``sandbox_init``
                is the first process of each run);
* ``suspicious`` the checks that flag an exercise file reaching outside the
                computation (its text, its object file);
* ``runner``    running a test program's ``lessonNN`` suite, its records over
                a pipe, checked for order and duplicates;
* ``integrity`` the check that grading tests pass on the reference and fail
                on the stubs;
* ``edition``   the student edition (no reference units, no hidden tests);
* ``autograder`` the Gradescope autograder zip, its setup and the submission
                installer;
* ``batch``     ``tools/grade --batch``: a folder of submissions, grades.csv;
* ``driver``    the command line.

Only the Python 3 standard library is used, so that the driver runs on a
fresh Gradescope image and on a student's machine alike.
"""
