# End-to-end tests: every lesson program runs with --quick and its outputs are checked.
foreach(program IN LISTS ILLUM_LESSON_PROGRAMS)
  add_test(NAME e2e_${program}
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/checks/check_outputs.py
                   --run $<TARGET_FILE:${program}> --out ${CMAKE_BINARY_DIR}/test-out/${program})
  set_tests_properties(e2e_${program} PROPERTIES FIXTURES_SETUP lesson_outputs LABELS e2e)
endforeach()

# The command line refuses a bad scene with one clear line and writes nothing.
add_test(NAME e2e_illum_render_bad_scene
         COMMAND ${CMAKE_COMMAND} -DILLUM=$<TARGET_FILE:illum_cli> -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/e2e/bad_radius.json
                 -DOUT=${CMAKE_BINARY_DIR}/test-out/illum-bad -P ${CMAKE_CURRENT_SOURCE_DIR}/e2e/expect_refusal.cmake)
# The bad scene input of lesson 06's scene format: an unknown material, a missing OBJ file.
add_test(NAME e2e_illum_render_unknown_material
         COMMAND ${CMAKE_COMMAND} -DILLUM=$<TARGET_FILE:illum_cli> -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/e2e/bad_material.json
                 "-DEXPECT=bad_material.json;primitives[0].material;\"glas\";did you mean 'glass'"
                 -DOUT=${CMAKE_BINARY_DIR}/test-out/illum-bad-material -P ${CMAKE_CURRENT_SOURCE_DIR}/e2e/expect_refusal.cmake)
add_test(NAME e2e_illum_render_missing_obj
         COMMAND ${CMAKE_COMMAND} -DILLUM=$<TARGET_FILE:illum_cli> -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/e2e/missing_obj.json
                 "-DEXPECT=missing_obj.json;primitives[0].obj;no_such_bunny.obj;cannot open the OBJ file"
                 -DOUT=${CMAKE_BINARY_DIR}/test-out/illum-missing-obj -P ${CMAKE_CURRENT_SOURCE_DIR}/e2e/expect_refusal.cmake)
add_test(NAME e2e_illum_render COMMAND illum_cli render spheres --quick --out ${CMAKE_BINARY_DIR}/test-out/illum-render)

# The ray-tree inspector of the command line: one pixel's tree as JSON, Graphviz and overlay.
add_test(NAME e2e_illum_trace
         COMMAND ${CMAKE_COMMAND} -DILLUM=$<TARGET_FILE:illum_cli> -DOUT=${CMAKE_BINARY_DIR}/test-out/illum-trace
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/e2e/expect_trace.cmake)

# A glass cube with faces on x = 0, y = 0 and z = 0, on a floor at z = 0: render and trace finish,
# with at most three shadow rays per shadow test (the walk through the glass used to run forever).
add_test(NAME e2e_illum_glass_cube_on_coordinate_planes
         COMMAND ${CMAKE_COMMAND} -DILLUM=$<TARGET_FILE:illum_cli> -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/e2e/glass_cube_z0.json
                 -DOUT=${CMAKE_BINARY_DIR}/test-out/illum-glass-cube -P ${CMAKE_CURRENT_SOURCE_DIR}/e2e/expect_glass_cube.cmake)
set_tests_properties(e2e_illum_glass_cube_on_coordinate_planes PROPERTIES LABELS e2e TIMEOUT 120)

# Every lesson says how many cores its timings use (--timed-cores: the main job runs the "one"
# programs side by side), writes nothing when asked, and a "one" wrote no table on more threads.
add_test(NAME e2e_timed_cores
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/e2e/timed_cores_e2e.py
                 --bin $<TARGET_FILE_DIR:lesson01> --out ${CMAKE_BINARY_DIR}/test-out)
set_tests_properties(e2e_timed_cores PROPERTIES FIXTURES_REQUIRED lesson_outputs LABELS e2e)
