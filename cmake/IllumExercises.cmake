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
  set_source_files_properties(${all_stubs} PROPERTIES COMPILE_OPTIONS "-Wno-unused-parameter")

  list(LENGTH selected n_units)
  message(STATUS "illum: ${n_units} exercise unit(s); ILLUM_EXERCISES='${ILLUM_EXERCISES}'")
  set(ILLUM_COMMON_SOURCES ${common} PARENT_SCOPE)
  set(ILLUM_SELECTED_UNITS ${selected} PARENT_SCOPE)
  set(ILLUM_STUB_UNITS ${all_stubs} PARENT_SCOPE)
endfunction()
