#pragma once
/// @file Writing a file so that a failure never leaves a half-written one in its place.
#include <functional>
#include <ostream>
#include <string>

namespace progsim {

/// Opens `path` + ".partial" (binary, truncated), lets `put` write the contents, and renames
/// the partial file over `path`: a failed write leaves an older file at `path` intact.
/// Throws Error(Status::io_error) naming `path` if the file cannot be opened, written or moved
/// into place; an exception from `put` propagates. Either way the partial file is removed.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& put);

}  // namespace progsim
