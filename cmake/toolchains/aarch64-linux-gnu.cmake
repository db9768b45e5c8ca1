# Cross-compiling illum for Linux on arm64 with Debian's GCC (g++-aarch64-linux-gnu),
# running the test programs under qemu-user (qemu-aarch64); CI's stage "arm64".
#
#   cmake -S . -B build/arm64 --toolchain cmake/toolchains/aarch64-linux-gnu.cmake
#   cmake --build build/arm64 --target tests_lesson01 …
#   ctest --test-dir build/arm64 -R '^tests_lesson0[1-6]$'
#
# The header-only libraries (GLM, CLI11, nlohmann-json, doctest, stb) are the host's own
# Debian packages, which hold no machine code; libraries with machine code are looked up
# in the arm64 sysroot only, so the x86-64 cpp-httplib is not found (`illum lab` then says
# it is unavailable; the lab is not part of this build's tests).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)

set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)  # python3, ccache, gnuplot: the host's
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
# pkg-config (cpp-httplib) answers for arm64 only.
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig)
