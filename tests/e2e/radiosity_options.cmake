# Lessons 09 and 11 refuse bad option values with a message naming the
# option, a non-zero exit and no output folder (CTest label badinput).
if(CMAKE_SCRIPT_MODE_FILE)
  file(REMOVE_RECURSE ${OUT})
  separate_arguments(args UNIX_COMMAND "${ARGS}")
  execute_process(COMMAND ${PROGRAM} ${args} --out ${OUT} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(status EQUAL 0)
    message(FATAL_ERROR "${PROGRAM} accepted ${ARGS}")
  endif()
  string(FIND "${err}${out}" "${EXPECT}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the error for ${ARGS} does not mention '${EXPECT}':\n${err}${out}")
  endif()
  if(EXISTS ${OUT})
    message(FATAL_ERROR "${PROGRAM} wrote ${OUT} although ${ARGS} was refused")
  endif()
  return()
endif()

set(cases
    "lesson11|--hemicube-resolution 7|--hemicube-resolution"
    "lesson11|--hemicube-resolution 4|--hemicube-resolution"
    "lesson11|--unshot 0|--unshot"
    "lesson11|--unshot 2|--unshot"
    "lesson11|--patches 0|--patches"
    "lesson11|--patch-edge -5|--patch-edge"
    "lesson11|--solvers jacobo|--solvers"
    "lesson09|--tolerance 0|--tolerance"
    "lesson09|--tolerance 1e-20|--tolerance"
    "lesson09|--cube-n 0|--cube-n")
set(k 0)
foreach(case IN LISTS cases)
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 program)
  list(GET parts 1 args)
  list(GET parts 2 expect)
  math(EXPR k "${k} + 1")
  add_test(NAME badinput_${program}_option_${k}
           COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${program}> "-DARGS=${args}" "-DEXPECT=${expect}"
                   -DOUT=${CMAKE_BINARY_DIR}/test-out/${program}-bad-option-${k} -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(badinput_${program}_option_${k} PROPERTIES LABELS badinput)
endforeach()
