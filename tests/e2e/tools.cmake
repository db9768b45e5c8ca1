# Unit tests of the grading driver's pure parts (tools/grading/), standard library only.
add_test(NAME tools_grade_py COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_grade.py)
set_tests_properties(tools_grade_py PROPERTIES LABELS grading ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# The judge's comparisons and verdicts, and the observer's sources (tools/grading/judge.py,
# observer_sources.py): each verdict worked by hand from doctest's definitions.
add_test(NAME tools_judge_py COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_judge.py)
set_tests_properties(tools_judge_py PROPERTIES LABELS grading ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# The mutant generator of tools/grade --mutants (its smoke run is a .ci/run stage).
add_test(NAME tools_mutants_py COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_mutants.py)
set_tests_properties(tools_mutants_py PROPERTIES LABELS grading ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# Unit tests of tools/figures.py (figures in the lesson texts come from the programs' tables).
add_test(NAME figures_tool COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_figures.py)
set_tests_properties(figures_tool PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# The task tables' source reader (tools/task_tables.py; the tables themselves: CTest task_tables).
add_test(NAME tools_task_tables_py COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_task_tables.py)
set_tests_properties(tools_task_tables_py PROPERTIES LABELS grading ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# tools/check_fresh_debian's argument checks (the run itself needs root, the network and half an hour).
add_test(NAME tools_check_fresh_debian_py
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_check_fresh_debian.py)
set_tests_properties(tools_check_fresh_debian_py PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# tools/bootstrap's arguments (it takes none: a typo is refused before the first step).
add_test(NAME tools_bootstrap_py COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_bootstrap.py)
set_tests_properties(tools_bootstrap_py PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# tools/fuzz's arguments (a wrong one is refused before the fuzz build).
add_test(NAME tools_fuzz_py COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_fuzz.py)
set_tests_properties(tools_fuzz_py PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# tools/check_container's argument checks (the run itself needs a container engine, the network and
# about 25 minutes).
add_test(NAME tools_check_container_py
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_check_container.py)
set_tests_properties(tools_check_container_py PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# One home per helper: no hand-written best-of-N timing, no π typed in, OpenMP only through
# core/threads.hpp, no second copy of a helper that has a home (tests/checks/check_one_home.py).
add_test(NAME one_home COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/checks/check_one_home.py)
set_tests_properties(one_home PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
add_test(NAME tools_check_one_home_py
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_check_one_home.py)
set_tests_properties(tools_check_one_home_py PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# Every "lesson NN, §M" in lib/, exercises/, tests/, lessons/ and slides/ names a section of
# lesson NN's text, the one that teaches the file citing it (tests/checks/check_section_refs.py).
add_test(NAME section_refs COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/checks/check_section_refs.py)
set_tests_properties(section_refs PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
add_test(NAME tools_check_section_refs_py
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_check_section_refs.py)
set_tests_properties(tools_check_section_refs_py PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# Unity builds (CMakeLists.txt, illum_unity_build): no private helper of one file is called bare by a
# later file of the same unit, where overload resolution could pick it (tests/checks/check_unity_units.py).
set(unity_units_required "")
if(ILLUM_UNITY_BUILD)
  set(unity_units_required --require-units)  # a build that makes units must have some to check
endif()
add_test(NAME unity_units COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/checks/check_unity_units.py
                                  --build-dir ${CMAKE_BINARY_DIR} ${unity_units_required})
set_tests_properties(unity_units PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
add_test(NAME tools_check_unity_units_py
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_check_unity_units.py)
set_tests_properties(tools_check_unity_units_py PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# The test programs' own per-test time limit (tests/support/test_main.cpp): the student's test
# command stops an endless loop with a message, and stays out of the grader's way.
add_test(NAME test_watchdog
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/e2e/watchdog_e2e.py --bin ${CMAKE_BINARY_DIR}/bin)
set_tests_properties(test_watchdog PROPERTIES LABELS grading ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# The plot check (tools/gallery/plots.py): gnuplot's own reading of small scripts, broken and whole.
add_test(NAME plots_tool COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_plots.py)
set_tests_properties(plots_tool PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# Every plot the e2e runs drew (test-out/lessonNN/*.gp) joins its lines and shows every point
# inside its frame; CI's tools/figures.py --check does the same for the main job's plots.
add_test(NAME plots COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/checks/check_plots.py
                            --out ${CMAKE_BINARY_DIR}/test-out)
set_tests_properties(plots PROPERTIES FIXTURES_REQUIRED lesson_outputs LABELS tools
                                      ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# Every link and image of the texts resolves in the source tree (a fresh clone has no out/).
add_test(NAME text_links COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/figures.py --links)
set_tests_properties(text_links PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# tools/compare_runs.py (the arm64 stage of tools/check_platforms): tables agree but for timings.
add_test(NAME compare_runs_tool COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_compare_runs.py)
set_tests_properties(compare_runs_tool PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
