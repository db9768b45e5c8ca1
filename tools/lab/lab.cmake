# `illum lab` (docs/lab.md), part of the illum_cli target. It needs cpp-httplib
# (Debian's libcpp-httplib-dev, found through pkg-config, which gives the
# definitions the library was compiled with); without it `illum lab` says how
# to get it and the rest of the build is unchanged. The page and three.js are
# compiled into the binary by embed_assets.py, run at every build (it rewrites
# the generated file only when something changed).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(ILLUM_HTTPLIB QUIET IMPORTED_TARGET GLOBAL cpp-httplib)
endif()
# Debian's cpp-httplib is a compiled library built against GCC's libstdc++: a build with another
# standard library (Clang with libc++, as tools/check_platforms libcxx) compiles against its header
# but cannot link it. So a small server is linked with it first; where that fails the lab is left out
# with the reason (ILLUM_LAB_MISSING, in the configure step, in `illum lab` and in the lab tests) and
# the rest of the build goes on, instead of a link error at the end of the build.
set(ILLUM_LAB_MISSING "")
if(NOT ILLUM_HTTPLIB_FOUND)
  string(CONCAT ILLUM_LAB_MISSING "CMake did not find cpp-httplib. Install it (tools/install-deps, or apt-get "
                "install libcpp-httplib-dev and pkgconf), then configure and build again (cmake --preset "
                "release && cmake --build --preset release --target illum_cli)")
elseif(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_SYSTEM_NAME STREQUAL "Linux")
  # GCC on Linux links libstdc++, the standard library Debian's cpp-httplib is built for: the check
  # below (a compile and link of about 2 s in the first configure) would only pass.
  set(ILLUM_HTTPLIB_LINKS TRUE)
else()
  include(CheckCXXSourceCompiles)
  set(CMAKE_REQUIRED_LIBRARIES PkgConfig::ILLUM_HTTPLIB)
  set(CMAKE_REQUIRED_QUIET ON)
  check_cxx_source_compiles([[
#include <httplib.h>
int main() {
  httplib::Server server;
  server.set_error_handler([](const httplib::Request&, httplib::Response& response) { response.status = 500; });
  return server.is_running() ? 1 : 0;
}]] ILLUM_HTTPLIB_LINKS)
  unset(CMAKE_REQUIRED_LIBRARIES)
  unset(CMAKE_REQUIRED_QUIET)
  if(NOT ILLUM_HTTPLIB_LINKS)
    string(REPLACE ";" " " found "${ILLUM_HTTPLIB_LINK_LIBRARIES}")
    string(CONCAT ILLUM_LAB_MISSING "the cpp-httplib CMake found (${found}) does not link with this compiler "
                  "and standard library (Debian's is compiled for GCC's libstdc++). Build the lab with GCC "
                  "(cmake --preset release && cmake --build --preset release --target illum_cli), or with a "
                  "cpp-httplib built for this standard library")
  endif()
endif()

set_property(GLOBAL PROPERTY ILLUM_LAB_MISSING "${ILLUM_LAB_MISSING}")  # for tests/e2e/lab.cmake

set(ILLUM_LAB_DIR ${CMAKE_CURRENT_SOURCE_DIR}/lab)
target_include_directories(illum_cli PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
if(NOT ILLUM_LAB_MISSING)
  set(lab_generated ${CMAKE_BINARY_DIR}/generated/lab_assets.cpp)
  add_custom_target(illum_lab_assets
    COMMAND ${Python3_EXECUTABLE} ${ILLUM_LAB_DIR}/embed_assets.py --source ${PROJECT_SOURCE_DIR} --out ${lab_generated}
    BYPRODUCTS ${lab_generated}
    COMMENT "Embedding the lab's page and three.js"
    VERBATIM)
  # The lab's sources once, for illum_cli and for the test build against the stubs (tests/e2e/lab.cmake).
  add_library(illum_lab_objects OBJECT ${ILLUM_LAB_DIR}/lab_common.cpp ${ILLUM_LAB_DIR}/lab_trace.cpp
                                       ${ILLUM_LAB_DIR}/lab_radiosity.cpp ${ILLUM_LAB_DIR}/lab_hierarchy.cpp
                                       ${ILLUM_LAB_DIR}/lab_compare.cpp ${ILLUM_LAB_DIR}/lab_reference.cpp ${ILLUM_LAB_DIR}/lab_server.cpp
                                       ${lab_generated})
  add_dependencies(illum_lab_objects illum_lab_assets)
  target_include_directories(illum_lab_objects PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(illum_lab_objects PUBLIC illum_options PkgConfig::ILLUM_HTTPLIB)
  target_sources(illum_cli PRIVATE $<TARGET_OBJECTS:illum_lab_objects>)
  target_link_libraries(illum_cli PRIVATE PkgConfig::ILLUM_HTTPLIB)
  # The lessons whose exercise units this build takes from exercises/ (the lab shows whose code runs).
  set(lab_exercises "")
  foreach(nn IN LISTS ILLUM_UNIT_LESSONS)
    if(ILLUM_UNITS_FROM_${nn} STREQUAL "stubs")
      list(APPEND lab_exercises ${nn})
    endif()
  endforeach()
  string(REPLACE ";" "," lab_exercises "${lab_exercises}")
  set_source_files_properties(${ILLUM_LAB_DIR}/lab_server.cpp PROPERTIES
                              COMPILE_DEFINITIONS "ILLUM_LAB_EXERCISES=\"${lab_exercises}\"")
  # The lab's own code answers requests; the work it asks for (tracing, hemicubes, solvers) is the
  # library's, compiled at -O3.
  illum_cold_code(illum_lab_objects ${ILLUM_LAB_DIR}/lab_common.cpp ${ILLUM_LAB_DIR}/lab_trace.cpp
                  ${ILLUM_LAB_DIR}/lab_radiosity.cpp ${ILLUM_LAB_DIR}/lab_hierarchy.cpp ${ILLUM_LAB_DIR}/lab_compare.cpp
                  ${ILLUM_LAB_DIR}/lab_reference.cpp ${ILLUM_LAB_DIR}/lab_server.cpp)
  # After the definitions above, which keep lab_server.cpp apart. Two files to a unit: Make
  # compiles the lab's objects last, and one unit of all four (each instantiating nlohmann-json)
  # was the build's last 14 s on one core (docs/measurements.md).
  illum_unity_build(illum_lab_objects 2)
else()
  message(STATUS "illum: no lab in this build (`illum lab` will say so): ${ILLUM_LAB_MISSING}")
  target_sources(illum_cli PRIVATE ${ILLUM_LAB_DIR}/lab_unavailable.cpp ${ILLUM_LAB_DIR}/lab_common.cpp)
  set_source_files_properties(${ILLUM_LAB_DIR}/lab_unavailable.cpp PROPERTIES
                              COMPILE_DEFINITIONS "ILLUM_LAB_MISSING=\"${ILLUM_LAB_MISSING}\"")
endif()
