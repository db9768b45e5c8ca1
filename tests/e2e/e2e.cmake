# End-to-end tests: every lesson program runs with --quick and its outputs are checked.
foreach(program IN LISTS ILLUM_LESSON_PROGRAMS)
  add_test(NAME e2e_${program}
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/check_outputs.py
                   --run $<TARGET_FILE:${program}> --out ${CMAKE_BINARY_DIR}/test-out/${program})
  set_tests_properties(e2e_${program} PROPERTIES FIXTURES_SETUP lesson_outputs LABELS e2e)
endforeach()
