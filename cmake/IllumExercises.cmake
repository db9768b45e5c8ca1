# Exercise units.
#
# An exercise unit is one source file of lib/illum/<area>/ that a lesson asks
# students to write. Its twin lives in exercises/NN_topic/ under the same file
# name, with the same signatures and bodies that throw illum::NotImplemented.
# ILLUM_EXERCISES picks the lessons whose twins replace the reference units:
#   ""      every unit from lib/ (the reference solution)
#   "01;03" lessons 01 and 03 from exercises/, the rest from lib/
#   "all"   every unit from exercises/
# In the student edition the reference twins are absent, so every unit
# comes from exercises/ whatever ILLUM_EXERCISES says.

function(illum_collect_sources)
  set(src ${CMAKE_CURRENT_SOURCE_DIR})
  file(GLOB_RECURSE lib_sources CONFIGURE_DEPENDS ${src}/lib/illum/*.cpp)

  # File names in lib/ are unique, so a stub names its reference by file name alone.
  set(seen "")
  set(lessons_with_units "")
  foreach(file IN LISTS lib_sources)
    get_filename_component(name ${file} NAME)
    if(name IN_LIST seen)
      message(FATAL_ERROR "Two files in lib/illum are named ${name}; exercise twins are matched by file name")
    endif()
    list(APPEND seen ${name})
  endforeach()

  string(REPLACE "," ";" chosen "${ILLUM_EXERCISES}")
  file(GLOB stubs CONFIGURE_DEPENDS ${src}/exercises/[0-9][0-9]_*/*.cpp)
  set(common ${lib_sources})
  set(selected "")
  set(all_stubs "")
  set(lessons_seen "")
  foreach(stub IN LISTS stubs)
    get_filename_component(name ${stub} NAME)
    get_filename_component(dir ${stub} DIRECTORY)
    get_filename_component(dir ${dir} NAME)
    string(SUBSTRING ${dir} 0 2 nn)
    list(APPEND lessons_seen ${nn})
    list(APPEND all_stubs ${stub})
    set(reference "")
    foreach(file IN LISTS lib_sources)
      get_filename_component(lib_name ${file} NAME)
      if(lib_name STREQUAL name)
        set(reference ${file})
      endif()
    endforeach()
    if(reference)
      list(REMOVE_ITEM common ${reference})
    endif()
    # Per lesson, for the "alone" check (tests/e2e/alone.cmake): its reference units and its stubs.
    if(NOT nn IN_LIST lessons_with_units)
      list(APPEND lessons_with_units ${nn})
      set(units_${nn} "")
      set(stubs_${nn} "")
      set(missing_${nn} FALSE)
    endif()
    list(APPEND stubs_${nn} ${stub})
    if(reference)
      list(APPEND units_${nn} ${reference})
    else()
      set(missing_${nn} TRUE)
    endif()
    if(NOT reference OR "all" IN_LIST chosen OR nn IN_LIST chosen)
      list(APPEND selected ${stub})
    else()
      list(APPEND selected ${reference})
    endif()
  endforeach()

  foreach(nn IN LISTS chosen)
    if(NOT nn STREQUAL "all" AND NOT nn IN_LIST lessons_seen)
      message(FATAL_ERROR "ILLUM_EXERCISES names lesson '${nn}', which has no exercise units in exercises/")
    endif()
  endforeach()

  # A stub's parameters are unused until the student writes the body.
  if(MSVC)
    set_source_files_properties(${all_stubs} PROPERTIES COMPILE_OPTIONS "/wd4100")
  else()
    set_source_files_properties(${all_stubs} PROPERTIES COMPILE_OPTIONS "-Wno-unused-parameter")
  endif()

  list(LENGTH selected n_units)
  message(STATUS "illum: ${n_units} exercise unit(s); ILLUM_EXERCISES='${ILLUM_EXERCISES}'")
  # A student's first build: say how long it takes before it starts, once (the tree not yet built).
  if(ILLUM_EXERCISES AND NOT EXISTS ${CMAKE_BINARY_DIR}/libillum.a)
    list(LENGTH lib_sources n_library)
    if(CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache" OR ILLUM_CCACHE_PROGRAM)
      set(reuse "ccache is installed, so objects compiled before, in any tree of these sources, are reused")
    else()
      set(reuse "without ccache every object is compiled once")
    endif()
    message(STATUS "illum: the first build compiles the whole library (${n_library} files) with the lessons' "
                   "programs and tests: about a minute for one lesson's tests and program, three for every target, on two "
                   "cores (43-49 s and 155 s with nothing cached, 2026-12-04; about twice that on a slower machine; "
                   "${reuse}). "
                   "After that, a change to one exercise file recompiles that file and relinks: seconds.")
  endif()
  set(ILLUM_COMMON_SOURCES ${common} PARENT_SCOPE)
  set(ILLUM_SELECTED_UNITS ${selected} PARENT_SCOPE)
  set(ILLUM_STUB_UNITS ${all_stubs} PARENT_SCOPE)
  # ILLUM_UNIT_LESSONS: lessons with exercise units; ILLUM_REFERENCE_UNITS_<NN> (empty when a
  # reference is absent, as in the student edition) and ILLUM_STUB_UNITS_<NN>.
  set(ILLUM_UNIT_LESSONS ${lessons_with_units} PARENT_SCOPE)
  foreach(nn IN LISTS lessons_with_units)
    if(missing_${nn})
      set(ILLUM_REFERENCE_UNITS_${nn} "" PARENT_SCOPE)
    else()
      set(ILLUM_REFERENCE_UNITS_${nn} ${units_${nn}} PARENT_SCOPE)
    endif()
    set(ILLUM_STUB_UNITS_${nn} ${stubs_${nn}} PARENT_SCOPE)
    if(missing_${nn} OR "all" IN_LIST chosen OR nn IN_LIST chosen)
      set(ILLUM_UNITS_FROM_${nn} stubs PARENT_SCOPE)
    else()
      set(ILLUM_UNITS_FROM_${nn} reference PARENT_SCOPE)
    endif()
  endforeach()
endfunction()

# The lessons whose units lesson NN needs, read from exercises/NN_*/depends.txt: one
# line per lesson, "MM" (its grading tests and its program need lesson MM's units) or
# "MM program" (only its program does); "#" starts a comment. The student edition ships
# lesson MM as working reference code unless MM is handed out too, and the "alone" check
# (tests/e2e/alone.cmake) links lesson MM's reference units. <out>: the lessons the
# grading tests need; <out>_program: the lessons the program needs.
function(illum_lesson_dependencies nn out)
  file(GLOB files ${PROJECT_SOURCE_DIR}/exercises/${nn}_*/depends.txt)
  set(grading "")
  set(program "")
  foreach(file IN LISTS files)
    file(STRINGS ${file} lines ENCODING UTF-8)
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "#.*" "" line "${line}")
      string(STRIP "${line}" line)
      if(line MATCHES "^([0-9][0-9])$")
        list(APPEND grading ${CMAKE_MATCH_1})
        list(APPEND program ${CMAKE_MATCH_1})
      elseif(line MATCHES "^([0-9][0-9])[ \t]+program$")
        list(APPEND program ${CMAKE_MATCH_1})
      elseif(NOT line STREQUAL "")
        message(FATAL_ERROR "${file}: '${line}' is neither \"NN\" nor \"NN program\"")
      endif()
    endforeach()
  endforeach()
  set(${out} ${grading} PARENT_SCOPE)
  set(${out}_program ${program} PARENT_SCOPE)
endfunction()
