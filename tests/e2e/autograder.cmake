# Gradescope's autograder, checked where it will run (docs/grading.md, "Gradescope"):
#   compat_ubuntu2204  the grading code fits Ubuntu 22.04 (doctest 2.4.8, nlohmann-json 3.10.5,
#                      GCC 11, CMake 3.22, Python 3.10), Gradescope's default image;
#   autograder_e2e     packs the autograder, unpacks it into a temporary /autograder, runs
#                      setup.sh and run_autograder on seven submissions, checks each results.json;
#   grading_attacks    hostile submissions (tests/attacks/, one per attack class of the threat
#                      model in docs/grading-defences.md) through setup.sh and run_autograder: each must
#                      get its honest score and achieve nothing else (needs root: skipped without);
#   batch_e2e          tools/grade --batch on a class of seven submissions and a roster: grades.csv
#                      and the Canvas file checked row by row.
# Both need the reference solutions (not the student edition); the end-to-end test builds its
# own Release tree, so it runs once, in the plain build, not again under the sanitizers.
add_test(NAME compat_ubuntu2204 COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/checks/check_compat.py
                                        --compiler ${CMAKE_CXX_COMPILER})
set_tests_properties(compat_ubuntu2204 PROPERTIES LABELS "grading;autograder")

if(NOT ILLUM_SANITIZE AND NOT EXISTS ${PROJECT_SOURCE_DIR}/STUDENT_EDITION)
  add_test(NAME autograder_e2e
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/e2e/autograder_e2e.py
                   --work-dir ${CMAKE_BINARY_DIR}/autograder-e2e)
  set_tests_properties(autograder_e2e PROPERTIES LABELS "grading;autograder" TIMEOUT 1800
                       ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
  add_test(NAME grading_attacks
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/e2e/attacks_e2e.py
                   --work-dir ${CMAKE_BINARY_DIR}/grading-attacks)
  set_tests_properties(grading_attacks PROPERTIES LABELS "grading;autograder;attacks" TIMEOUT 1800
                       SKIP_RETURN_CODE 77 ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
  add_test(NAME batch_e2e
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/e2e/batch_e2e.py
                   --work-dir ${CMAKE_BINARY_DIR}/batch-e2e)
  set_tests_properties(batch_e2e PROPERTIES LABELS "grading;autograder" TIMEOUT 1800
                       ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
endif()
