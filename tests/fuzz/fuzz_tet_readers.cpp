// libFuzzer target: feeds arbitrary bytes to the tet mesh readers. The first byte picks the
// format: 0 → a .mesh file (Medit), 1 → a .msh file (Gmsh), 2 → a .node file holding the first
// half of the rest and an .ele file holding the second half (TetGen). A mesh that reads is
// validated, and a valid one has its boundary extracted. Every call must return or throw
// progsim::Error, never crash, leak, hang or trip a sanitizer.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "common/error.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_mesh_io.hpp"
#include "mesh/tet_mesh_validation.hpp"

namespace {

/// Writes `size` bytes to `path`.
void put_file(const std::string& path, const uint8_t* data, std::size_t size) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), size);
}

void read_validate_extract(const std::string& path) {
  try {
    const progsim::TetMesh mesh = progsim::read_tet_mesh(path);
    progsim::validate_tet_mesh(mesh, path);
    progsim::extract_tet_boundary(mesh);
  } catch (const progsim::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1 || size > 16384) return 0;
  static const char* const extensions[3] = {".mesh", ".msh", ".node"};
  const int format = data[0] % 3;
  const std::string stem = "/tmp/progsim_fuzz_tet_" + std::to_string(::getpid());
  const std::string path = stem + extensions[format];
  const std::size_t rest = size - 1, half = format == 2 ? rest / 2 : rest;
  put_file(path, data + 1, half);
  if (format == 2) put_file(stem + ".ele", data + 1 + half, rest - half);
  read_validate_extract(path);
  std::remove(path.c_str());
  if (format == 2) std::remove((stem + ".ele").c_str());
  return 0;
}
