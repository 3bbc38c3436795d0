# Sourced by the build scripts: compile through ccache where it is installed, so that the
# Python wheel's CMake build (pip, the same sources and flags as build/release) reuses the
# release build's objects. CMake reads these when it first configures a build folder.
# ccache keys on the compiler's name as well: left alone, CMake picks c++ for build/release
# while scikit-build-core picks Python's g++, and no object is shared. So both get cc/c++
# unless the caller names a compiler (the sanitizer build names clang).
if command -v ccache >/dev/null 2>&1; then
  export CMAKE_C_COMPILER_LAUNCHER=${CMAKE_C_COMPILER_LAUNCHER:-ccache}
  export CMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER:-ccache}
  export CC=${CC:-cc} CXX=${CXX:-c++}
fi
