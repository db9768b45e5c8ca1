# Every dependency comes from Debian 12's packages. A missing one stops
# configuration with the name of the package that provides it.

function(illum_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR "illum needs ${what}; install it with:  sudo apt-get install ${package}\n"
                        "(or run tools/install-deps, which installs everything illum needs)")
  endif()
endfunction()

find_package(glm CONFIG QUIET)
illum_require(glm_FOUND "GLM (vector maths)" libglm-dev)

find_path(ILLUM_STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb)
illum_require(ILLUM_STB_INCLUDE_DIR "stb_image_write (PNG and HDR output)" libstb-dev)
add_library(illum::stb INTERFACE IMPORTED)
target_include_directories(illum::stb INTERFACE ${ILLUM_STB_INCLUDE_DIR})

find_package(CLI11 CONFIG QUIET)
illum_require(CLI11_FOUND "CLI11 (command lines)" libcli11-dev)

find_package(nlohmann_json 3 CONFIG QUIET)
illum_require(nlohmann_json_FOUND "nlohmann-json (scene files and reports)" nlohmann-json3-dev)

# OpenMP is optional (ILLUM_OPENMP): without it every `#pragma omp` is ignored and
# core/threads.hpp answers "one thread"; the programs give the same results, on one core.
string(TOUPPER "${ILLUM_OPENMP}" illum_openmp)
set(ILLUM_OPENMP_FOUND OFF)
if(illum_openmp STREQUAL "ON" OR illum_openmp STREQUAL "AUTO")
  find_package(OpenMP QUIET)
  if(OpenMP_CXX_FOUND)
    set(ILLUM_OPENMP_FOUND ON)
  elseif(illum_openmp STREQUAL "ON")
    illum_require(OpenMP_CXX_FOUND "OpenMP (parallel loops; or configure with -DILLUM_OPENMP=OFF)"
                  "g++ (libgomp1), or libomp-dev for clang")
  else()
    message(STATUS "illum: this compiler has no OpenMP: every loop runs on one thread "
                   "(GCC: libgomp; Clang: libomp, e.g. `brew install libomp` and -DOpenMP_ROOT=$(brew --prefix libomp))")
  endif()
elseif(NOT illum_openmp STREQUAL "OFF")
  message(FATAL_ERROR "ILLUM_OPENMP is '${ILLUM_OPENMP}'; it must be AUTO, ON or OFF")
endif()
message(STATUS "illum: OpenMP ${ILLUM_OPENMP_FOUND} (ILLUM_OPENMP=${ILLUM_OPENMP})")

find_package(Python3 COMPONENTS Interpreter QUIET)
illum_require(Python3_FOUND "Python 3 (grading driver and main job)" python3)

if(ILLUM_BUILD_TESTS)
  find_package(doctest CONFIG QUIET)
  illum_require(doctest_FOUND "doctest (the test framework)" doctest-dev)
endif()

if(ILLUM_BUILD_BENCH)
  find_package(benchmark CONFIG QUIET)
  illum_require(benchmark_FOUND "Google Benchmark" libbenchmark-dev)
endif()
