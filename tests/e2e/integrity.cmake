# Grading integrity, tested rather than assumed (docs/architecture.md, "Exercises and grading"):
# every grading test passes on the reference and fails with NotImplemented on the stubs.
# tools/grade --check-integrity runs each tests_lessonNN / tests_lessonNN_stubs pair;
# the hidden tests get a stubs twin here so that they are held to the same rule.
if(TARGET tests_hidden AND NOT TARGET tests_hidden_stubs)
  get_target_property(illum_hidden_sources tests_hidden SOURCES)
  add_executable(tests_hidden_stubs ${illum_hidden_sources})
  target_link_libraries(tests_hidden_stubs PRIVATE illum_stubs doctest::doctest)
  target_include_directories(tests_hidden_stubs PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})  # support/*.hpp
  illum_use_checks(tests_hidden_stubs)
endif()

# Only a reference build can be checked: with ILLUM_EXERCISES set, tests_lessonNN runs
# on a student's code, and the student edition has no reference units at all.
if(ILLUM_EXERCISES STREQUAL "" AND NOT EXISTS ${PROJECT_SOURCE_DIR}/STUDENT_EDITION)
  add_test(NAME grading_integrity
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/grade --check-integrity
                   --build-dir ${CMAKE_BINARY_DIR})
  set_tests_properties(grading_integrity PROPERTIES LABELS grading)
endif()

# Which tests grade which task: every grading test carries a task tag, every exercise README's
# table and build commands are current, and on the stubs each test first stops in a function of
# a task it names (tools/task_tables.py; docs/grading-reference.md, "Task tables").
if(ILLUM_EXERCISES STREQUAL "" AND NOT EXISTS ${PROJECT_SOURCE_DIR}/STUDENT_EDITION)
  add_test(NAME task_tables
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/task_tables.py --check
                   --build-dir ${CMAKE_BINARY_DIR})
  set_tests_properties(task_tables PROPERTIES LABELS grading ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
endif()
