# The bad-input suite (label badinput): one CTest test per case of
# tests/badinput/cases.txt, run by run_case.py, which checks the exit code,
# the message's words and that the output folder is left unchanged.
set(badinput_dir ${CMAKE_CURRENT_LIST_DIR})
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${badinput_dir}/cases.txt)
set(badinput_sanitized "")
if(ILLUM_SANITIZE)
  set(badinput_sanitized --sanitized)  # run_case.py skips the cases a sanitizer cannot run (ulimit -v)
endif()
file(STRINGS ${badinput_dir}/cases.txt badinput_names REGEX "^\\[.+\\]$")
foreach(line IN LISTS badinput_names)
  string(REGEX REPLACE "^\\[(.+)\\]$" "\\1" name "${line}")
  add_test(NAME badinput.${name}
           COMMAND ${Python3_EXECUTABLE} ${badinput_dir}/run_case.py --cases ${badinput_dir}/cases.txt
                   --case ${name} --bin $<TARGET_FILE_DIR:illum_cli> --scenes ${badinput_dir}/scenes
                   --work ${CMAKE_BINARY_DIR}/badinput/${name} ${badinput_sanitized})
  # 77: the machine cannot set the case up (a full disk needs unshare -m, a read-only folder as root setpriv).
  set_tests_properties(badinput.${name} PROPERTIES LABELS badinput TIMEOUT 180 SKIP_RETURN_CODE 77
                                                   ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
endforeach()
