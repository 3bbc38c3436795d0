#pragma once
/// @file What every benchmark's main needs: errors (a bad argument, a scene or CSV file that
/// cannot be opened) end the program with a message, the usage and exit status 2.
#include <cstdio>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>

namespace progsim::bench {

/// `body(argc, argv)`'s exit status; on an exception, prints "error: …" and `usage` to stderr
/// and returns 2.
template <class Body>
int guarded_main(int argc, char** argv, const char* usage, Body body) {
  try {
    return body(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\nusage: %s\n", e.what(), usage);
    return 2;
  }
}

/// The CSV file at `path`, opened for writing before the (long) measurement starts; throws
/// std::runtime_error naming the path when it cannot be.
inline std::ofstream open_csv(const std::string& path) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write CSV file " + path);
  return csv;
}

}  // namespace progsim::bench
