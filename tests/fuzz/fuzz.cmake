# Fuzz targets (tests/fuzz/fuzz_<name>.cpp): one per scene loader, and the ray structures
# (fuzz_ray_structures: random small scenes traced through every structure against brute force).
#  * ILLUM_FUZZ=ON (preset "fuzz", clang): libFuzzer programs bin/fuzz_<loader>; tools/fuzz runs them.
#  * every build: bin/fuzz_replay_<loader> runs the target once per file, and CTest
#    replays the regression inputs (tests/fuzz/regressions/<loader>/) and the seeds.
file(GLOB fuzz_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/fuzz_*.cpp)
file(GLOB fuzz_json_seeds CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/scenes/*.json
     ${PROJECT_SOURCE_DIR}/tests/badinput/scenes/*.json)
file(GLOB fuzz_obj_seeds CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/scenes/*.obj
     ${PROJECT_SOURCE_DIR}/tests/badinput/scenes/*.obj)
foreach(source IN LISTS fuzz_sources)
  get_filename_component(target ${source} NAME_WE)        # fuzz_sphere_scene
  string(REGEX REPLACE "^fuzz_" "" loader ${target})     # sphere_scene
  if(ILLUM_FUZZ)
    add_executable(${target} ${source})
    target_link_libraries(${target} PRIVATE illum::illum)
    target_link_options(${target} PRIVATE -fsanitize=fuzzer)
  endif()
  if(ILLUM_FUZZ)
    continue()
  endif()
  add_executable(fuzz_replay_${loader} ${source} ${CMAKE_CURRENT_LIST_DIR}/replay_main.cpp)
  target_link_libraries(fuzz_replay_${loader} PRIVATE illum::illum)
  if(ILLUM_BUILD_TESTS)
    file(GLOB regressions CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/regressions/${loader}/*)
    if(loader MATCHES "^obj")  # the OBJ reader's seeds are OBJ files, the others' scenes
      set(fuzz_seeds ${fuzz_obj_seeds})
    else()
      set(fuzz_seeds ${fuzz_json_seeds})
    endif()
    add_test(NAME fuzz_regressions_${loader} COMMAND fuzz_replay_${loader} ${regressions} ${fuzz_seeds})
    set_tests_properties(fuzz_regressions_${loader} PROPERTIES LABELS "fuzz;badinput")
  endif()
endforeach()
