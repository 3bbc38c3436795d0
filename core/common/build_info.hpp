#pragma once
/// @file Version and build configuration, for `progsim info` and bug reports.
#include <string>

namespace progsim {

/// The library version, "MAJOR.MINOR.PATCH".
const char* version_string();

/// Multi-line description: version, compiler, build type, OpenMP threads, and the versions of
/// Eigen, CHOLMOD and CGAL the library was built with.
std::string build_info();

}  // namespace progsim
