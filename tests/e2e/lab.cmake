# The lab (`illum lab`, docs/lab.md), label "lab":
#   lab_api       tests/lab/test_lab_api.py: every endpoint answers; /api/trace is `illum trace`'s JSON;
#                 bad requests get 400 (or 403, 404, 405) with a message naming the parameter, never a
#                 crash (a seeded fuzz of query strings too); several clients at once; Ctrl-C (SIGINT)
#                 and SIGTERM stop it cleanly; a busy port and a bad scene are refused; a build on the
#                 stubs answers 501 with the function to write (illum_cli_stubs, below)
#   lab_browser   tests/lab/lab_browser.mjs, label "browser" too: the page in headless Chromium (Debian's,
#                 through puppeteer-core): a click on Whitted's glass ball draws the nodes `illum trace
#                 --pixel` writes; 10 shots give the unshot power of the library's progressive solver
#                 (lab_reference, below) and lesson 11's own table; a hemicube row sums to its exact
#                 value; the comparison's number; two tabs at once; nothing fetched from elsewhere
# Without a cpp-httplib this build can link (tools/lab/lab.cmake, ILLUM_LAB_MISSING) the lab tests fail
# with the reason and the advice: they never pass by skipping.
if(TARGET illum_lab_objects)
  add_executable(lab_reference ${CMAKE_CURRENT_SOURCE_DIR}/e2e/lab_reference.cpp)
  target_link_libraries(lab_reference PRIVATE illum::illum)
  # The same `illum` linked against every exercise stub: what a student edition runs before any code is written.
  add_executable(illum_cli_stubs $<TARGET_OBJECTS:illum_cli_objects> $<TARGET_OBJECTS:illum_source_dir>
                                 $<TARGET_OBJECTS:illum_lab_objects>)
  target_link_libraries(illum_cli_stubs PRIVATE illum_stubs PkgConfig::ILLUM_HTTPLIB)
  add_test(NAME lab_api
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/lab/test_lab_api.py --illum $<TARGET_FILE:illum_cli>
                   --illum-stubs $<TARGET_FILE:illum_cli_stubs> --work ${CMAKE_BINARY_DIR}/test-out/lab-api)
  set_tests_properties(lab_api PROPERTIES LABELS lab TIMEOUT 600)
  find_program(ILLUM_NODE node)
  add_test(NAME lab_browser
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/lab/run_browser_test.py --illum $<TARGET_FILE:illum_cli>
                   --reference $<TARGET_FILE:lab_reference> --lesson11 $<TARGET_FILE:lesson11>
                   --work ${CMAKE_BINARY_DIR}/test-out/lab-browser)
  set_tests_properties(lab_browser PROPERTIES LABELS "lab;browser" TIMEOUT 600)
else()
  get_property(lab_missing GLOBAL PROPERTY ILLUM_LAB_MISSING)
  add_test(NAME lab_api COMMAND ${Python3_EXECUTABLE} -c
           "import sys; sys.exit(sys.argv[1])" "this build has no lab: ${lab_missing}")
  set_tests_properties(lab_api PROPERTIES LABELS lab)
endif()
