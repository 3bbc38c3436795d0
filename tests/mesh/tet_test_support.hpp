#pragma once
/// @file Helpers shared by the tet mesh tests: data files, hand-built meshes, a scratch folder.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "mesh/tet_mesh.hpp"

namespace progsim::tet_test {

/// The path of tests/data/tet/`name`.
inline std::string tet_data(const std::string& name) {
  return (std::filesystem::path(PROGSIM_TEST_DATA_DIR) / "tet" / name).string();
}

/// The unit tet: corners at the origin and at e_x, e_y, e_z, positively oriented (volume 1/6).
inline TetMesh unit_tet() {
  TetMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.tets.resize(1, 4);
  mesh.tets << 0, 1, 2, 3;
  return mesh;
}

/// The unit cube of tests/data/tet/cube5.mesh, 0-based: vertex x + 2y + 4z at (x, y, z), four
/// corner tets and the central regular tet (1, 2, 4, 7).
inline TetMesh cube5() {
  TetMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int v = 0; v < 8; ++v) mesh.vertices.row(v) << v % 2, v / 2 % 2, v / 4;
  mesh.tets.resize(5, 4);
  mesh.tets << 0, 1, 2, 4, 3, 2, 1, 7, 5, 1, 4, 7, 6, 4, 2, 7, 1, 2, 4, 7;
  return mesh;
}

/// A scratch folder per test, removed afterwards.
class TetScratch : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("progsim_tet_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// The path of `name` in the scratch folder.
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// Writes `text` to `name` in the scratch folder and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return path(name);
  }

  std::filesystem::path dir_;
};

}  // namespace progsim::tet_test
