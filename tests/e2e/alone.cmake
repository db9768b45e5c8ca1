# Each lesson stands alone (docs/grading-reference.md, "Each lesson stands alone"): for every lesson NN
# with exercise units, its grading tests and its program are linked against a library in
# which lesson NN's units are the reference, so are those of the lessons its
# exercises/NN_*/depends.txt declares, and every other lesson's units are stubs.
# tools/grade --check-alone runs them: every test of suite lessonNN must pass and
# `lessonNN --quick` must finish; that is what a student handed out lesson NN alone has.
# Only the objects already compiled for illum and illum_stubs are reused: each lesson costs
# two or three links, no compilation.
if(NOT ILLUM_EXERCISES STREQUAL "" OR EXISTS ${PROJECT_SOURCE_DIR}/STUDENT_EDITION)
  return()  # needs every reference unit
endif()

# A library of the common objects, the reference units of lesson `nn` and of `with`, the stubs of the rest.
function(illum_alone_library name nn with)
  set(objects $<TARGET_OBJECTS:illum_common>)
  foreach(mm IN LISTS ILLUM_UNIT_LESSONS)
    if(mm STREQUAL nn OR mm IN_LIST with)
      list(APPEND objects $<TARGET_OBJECTS:illum_reference_units_${mm}>)
    else()
      list(APPEND objects $<TARGET_OBJECTS:illum_stub_units_${mm}>)
    endif()
  endforeach()
  add_library(${name} STATIC ${objects})
  target_link_libraries(${name} PUBLIC illum_options)
endfunction()

foreach(nn IN LISTS ILLUM_UNIT_LESSONS)
  if(NOT TARGET illum_reference_units_${nn})
    continue()
  endif()
  illum_lesson_dependencies(${nn} depends)
  illum_alone_library(illum_alone_${nn} ${nn} "${depends}")
  if(TARGET tests_lesson${nn}_objects)
    add_executable(tests_lesson${nn}_alone $<TARGET_OBJECTS:tests_lesson${nn}_objects>
                                           $<TARGET_OBJECTS:illum_test_support>)
    target_link_libraries(tests_lesson${nn}_alone PRIVATE illum_alone_${nn} doctest::doctest)
  endif()
  if(TARGET lesson${nn}_objects)
    set(library illum_alone_${nn})
    if(NOT "${depends_program}" STREQUAL "${depends}")
      set(library illum_alone_${nn}_program)
      illum_alone_library(${library} ${nn} "${depends_program}")
    endif()
    add_executable(lesson${nn}_alone $<TARGET_OBJECTS:lesson${nn}_objects>
                                     $<TARGET_OBJECTS:illum_lesson_support>)
    target_link_libraries(lesson${nn}_alone PRIVATE ${library})
  endif()
endforeach()

add_test(NAME grading_alone
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/grade --check-alone
                 --build-dir ${CMAKE_BINARY_DIR})
set_tests_properties(grading_alone PROPERTIES LABELS grading)
