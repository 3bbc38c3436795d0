#include "common/file_output.hpp"

#include <filesystem>
#include <fstream>

#include "common/error.hpp"

namespace progsim {

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& put) {
  const std::string partial = path + ".partial";
  std::ofstream out(partial, std::ios::binary | std::ios::trunc);
  if (!out) fail(Status::io_error, path + ": cannot open the file for writing");
  std::error_code error;
  try {
    put(out);
  } catch (...) {
    out.close();
    std::filesystem::remove(partial, error);
    throw;
  }
  out.close();
  if (out) std::filesystem::rename(partial, path, error);
  if (!out || error) {
    std::filesystem::remove(partial, error);
    fail(Status::io_error, path + ": cannot write the file");
  }
}

}  // namespace progsim
