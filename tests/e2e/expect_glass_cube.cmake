# The hard case of a glass cube with faces on the coordinate planes x = 0, y = 0, z = 0, standing
# on a floor at z = 0 (glass_cube_z0.json): `illum render` and `illum trace` finish and write their
# files, and the render's counts show at most three shadow rays per shadow test (one light: the
# first ray, and one after each of the at most two faces of a convex cube it crosses). Rays that
# met the face they leave at s = 0 made the shadow walk through the glass run forever.
# (A hang is caught by the test's TIMEOUT; what is asserted is the count.)
file(REMOVE_RECURSE ${OUT}-render ${OUT}-trace)
execute_process(COMMAND ${ILLUM} render ${SCENE} --quick --out ${OUT}-render RESULT_VARIABLE status
                ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "illum render of the glass cube failed (${status}):\n${err}")
endif()
foreach(file manifest.json render.png counts.txt)
  if(NOT EXISTS ${OUT}-render/${file})
    message(FATAL_ERROR "illum render did not write ${file}")
  endif()
endforeach()
file(READ ${OUT}-render/counts.txt counts)
string(REGEX MATCH "rays: primary ([0-9]+), shadow ([0-9]+), reflection ([0-9]+), refraction ([0-9]+)" line
       "${counts}")
if(NOT line)
  message(FATAL_ERROR "counts.txt has no ray counts:\n${counts}")
endif()
set(primary ${CMAKE_MATCH_1})
set(shadow ${CMAKE_MATCH_2})
set(reflection ${CMAKE_MATCH_3})
set(refraction ${CMAKE_MATCH_4})
math(EXPR tests_allowed "3 * (${primary} + ${reflection} + ${refraction})")
if(shadow GREATER tests_allowed OR refraction EQUAL 0 OR shadow EQUAL 0)
  message(FATAL_ERROR "the glass cube's render cast ${shadow} shadow rays for ${primary} primary, ${reflection} "
                      "reflected and ${refraction} refracted rays: at most ${tests_allowed} expected, and some "
                      "refracted and shadow rays")
endif()

execute_process(COMMAND ${ILLUM} trace ${SCENE} --quick --pixel 48 36 --out ${OUT}-trace RESULT_VARIABLE status
                ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "illum trace of the glass cube failed (${status}):\n${err}")
endif()
foreach(file manifest.json render.png ray_tree.json ray_tree.dot)
  if(NOT EXISTS ${OUT}-trace/${file})
    message(FATAL_ERROR "illum trace did not write ${file}")
  endif()
endforeach()
string(REGEX MATCH "primary ([0-9]+), shadow ([0-9]+), reflection ([0-9]+), refraction ([0-9]+)" line "${err}")
math(EXPR tests_allowed "3 * (${CMAKE_MATCH_1} + ${CMAKE_MATCH_3} + ${CMAKE_MATCH_4})")
if(NOT line OR CMAKE_MATCH_2 GREATER tests_allowed)
  message(FATAL_ERROR "the traced pixel's tree: ${err}")
endif()
message(STATUS "illum render and trace of the glass cube: ${shadow} shadow rays for "
               "${primary} + ${reflection} + ${refraction} rays; the pixel's tree: ${line}")
