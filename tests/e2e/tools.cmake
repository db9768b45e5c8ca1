# Unit tests of the grading driver's pure parts (tools/grading/), standard library only.
add_test(NAME tools_grade_py COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_grade.py)
set_tests_properties(tools_grade_py PROPERTIES LABELS grading ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# The mutant generator of tools/grade --mutants (its smoke run is a .ci/run stage).
add_test(NAME tools_mutants_py COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_mutants.py)
set_tests_properties(tools_mutants_py PROPERTIES LABELS grading ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
# Unit tests of tools/figures.py (figures in the lesson texts come from the programs' tables).
add_test(NAME figures_tool COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_figures.py)
set_tests_properties(figures_tool PROPERTIES LABELS tools ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
