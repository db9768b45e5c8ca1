# The lab (`illum lab`, docs/lab.md), label "lab":
#   lab_api       tests/lab/test_lab_api.py: every endpoint answers; /api/trace is `illum trace`'s JSON;
#                 bad requests get 400 (or 403, 404, 405) with a message naming the parameter, never a
#                 crash (a seeded fuzz of query strings too); several clients at once; Ctrl-C (SIGINT)
#                 and SIGTERM stop it cleanly; a busy port and a bad scene are refused; a build on the
#                 stubs answers 501 with the function to write (illum_cli_stubs, below)
#   lab_browser   tests/lab/run_browser_test.py, label "browser" too: the page in headless Chromium (Debian's,
#                 through puppeteer-core): a click on Whitted's glass ball draws the nodes `illum trace
#                 --pixel` writes; 10 shots give the unshot power of the library's progressive solver
#                 (lab_reference, below) and lesson 11's own table; a hemicube row sums to its exact
#                 value; lesson 14's hierarchy: a click draws links, a bad ε refused; the comparison's number; two tabs at once; nothing fetched from elsewhere; and
#                 a mutant student build (illum_cli_mutant, below) beside the reference: the first
#                 differing node and shot; the stubs beside the reference and alone
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
  # A student's build with two plausible mistakes, for the reference beside it (docs/lab.md): lesson
  # 06's evaluate entering glass with η_i/η_t = η instead of 1/η, and lesson 11's shoot with
  # reciprocity upside down (F_ij A_j/A_i for F_ji = F_ij A_i/A_j). Both units are copied from the
  # reference at configure time into the build folder, changed there, and never written to the source tree; where the reference units are
  # absent (a student edition) or the lines changed, the mutant is not made and lab_browser says so.
  set(lab_mutant_missing "")
  set(lab_mutant_units "")
  if(NOT ILLUM_EXERCISES STREQUAL "" OR EXISTS ${PROJECT_SOURCE_DIR}/STUDENT_EDITION)
    set(lab_mutant_missing "this build does not take every unit from the reference (ILLUM_EXERCISES='${ILLUM_EXERCISES}')")
  endif()
  foreach(change IN ITEMS
          "trace/ray_tree.cpp|hit->front_face ? 1.0 / m.index_of_refraction : m.index_of_refraction|hit->front_face ? m.index_of_refraction : 1.0 / m.index_of_refraction"
          "radiosity/radiosity_solvers.cpp|(form_factor_row[j] * area_i / patches[j].area)|(form_factor_row[j] * patches[j].area / area_i)")
    string(REPLACE "|" ";" change "${change}")
    list(GET change 0 unit)
    list(GET change 1 before)
    list(GET change 2 after)
    set(from ${PROJECT_SOURCE_DIR}/lib/illum/${unit})
    if(lab_mutant_missing OR NOT EXISTS ${from})
      set(lab_mutant_missing "${lab_mutant_missing} lib/illum/${unit} is absent;")
      continue()
    endif()
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${from})
    file(READ ${from} text)
    string(FIND "${text}" "${before}" at)
    if(at LESS 0)
      set(lab_mutant_missing "${lab_mutant_missing} lib/illum/${unit} no longer holds '${before}';")
      continue()
    endif()
    string(REPLACE "${before}" "${after}" text "${text}")
    get_filename_component(name ${unit} NAME)
    file(CONFIGURE OUTPUT ${CMAKE_BINARY_DIR}/lab-mutant/${name} CONTENT "${text}" @ONLY)
    list(APPEND lab_mutant_units ${CMAKE_BINARY_DIR}/lab-mutant/${name})
  endforeach()
  set(lab_mutant_arguments "")
  if(NOT lab_mutant_missing)
    # The reference units of every lesson, lessons 06 and 11 compiled again with the mutants in place.
    set(objects $<TARGET_OBJECTS:illum_common>)
    set(sources ${lab_mutant_units})
    foreach(nn IN LISTS ILLUM_UNIT_LESSONS)
      if(nn STREQUAL "06" OR nn STREQUAL "11")
        foreach(unit IN LISTS ILLUM_REFERENCE_UNITS_${nn})
          get_filename_component(name ${unit} NAME)
          if(NOT name STREQUAL "ray_tree.cpp" AND NOT name STREQUAL "radiosity_solvers.cpp")
            list(APPEND sources ${unit})
          endif()
        endforeach()
      else()
        list(APPEND objects $<TARGET_OBJECTS:illum_reference_units_${nn}>)
      endif()
    endforeach()
    add_library(illum_lab_mutant STATIC ${objects} ${sources})
    target_link_libraries(illum_lab_mutant PUBLIC illum_options)
    add_executable(illum_cli_mutant $<TARGET_OBJECTS:illum_cli_objects> $<TARGET_OBJECTS:illum_source_dir>
                                    $<TARGET_OBJECTS:illum_lab_objects>)
    target_link_libraries(illum_cli_mutant PRIVATE illum_lab_mutant PkgConfig::ILLUM_HTTPLIB)
    set(lab_mutant_arguments --illum-mutant $<TARGET_FILE:illum_cli_mutant>)
  else()
    set(lab_mutant_arguments --no-mutant "${lab_mutant_missing}")
  endif()
  find_program(ILLUM_NODE node)
  add_test(NAME lab_browser
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/lab/run_browser_test.py --illum $<TARGET_FILE:illum_cli>
                   --illum-stubs $<TARGET_FILE:illum_cli_stubs> ${lab_mutant_arguments}
                   --reference $<TARGET_FILE:lab_reference> --lesson11 $<TARGET_FILE:lesson11>
                   --work ${CMAKE_BINARY_DIR}/test-out/lab-browser)
  set_tests_properties(lab_browser PROPERTIES LABELS "lab;browser" TIMEOUT 900)
else()
  get_property(lab_missing GLOBAL PROPERTY ILLUM_LAB_MISSING)
  add_test(NAME lab_api COMMAND ${Python3_EXECUTABLE} -c
           "import sys; sys.exit(sys.argv[1])" "this build has no lab: ${lab_missing}")
  set_tests_properties(lab_api PROPERTIES LABELS lab)
endif()
