#include "mesh/tet_generators.hpp"

#include <array>
#include <sstream>
#include <utility>

#include "common/error.hpp"

namespace progsim {
namespace {

/// The orders in which a Kuhn tet's path from corner (0,0,0) to (1,1,1) steps along the axes;
/// the last three are odd permutations, whose tets come out negatively oriented.
constexpr int kAxisOrders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                   {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};

void check_box_arguments(const Vec3& size, int nx, int ny, int nz) {
  const bool size_ok = size.allFinite() && (size.array() > 0.0).all();
  if (size_ok && nx >= 1 && ny >= 1 && nz >= 1) return;
  std::ostringstream s;
  s << "make_tet_box: size (" << size.transpose() << ") must be positive and finite and the cell "
    << "counts (" << nx << ", " << ny << ", " << nz << ") at least 1";
  fail(Status::invalid_argument, s.str());
}

/// Index of grid vertex (i, j, k) of a box with nx × ny cells per layer.
int grid_index(const std::array<int, 3>& p, int nx, int ny) {
  return (p[2] * (ny + 1) + p[1]) * (nx + 1) + p[0];
}

/// Writes the 6 tets of the cube whose least corner is `least` as rows 6c .. 6c + 5.
void add_cube_tets(Tets& tets, int c, const std::array<int, 3>& least, int nx, int ny) {
  for (int order = 0; order < 6; ++order) {
    const int t = 6 * c + order;
    std::array<int, 3> corner = least;
    tets(t, 0) = grid_index(corner, nx, ny);
    for (int step = 0; step < 3; ++step) {
      ++corner[kAxisOrders[order][step]];
      tets(t, step + 1) = grid_index(corner, nx, ny);
    }
    if (order >= 3) std::swap(tets(t, 2), tets(t, 3));  // odd order: make the volume positive
  }
}

}  // namespace

TetMesh make_tet_box(const Vec3& size, int nx, int ny, int nz) {
  check_box_arguments(size, nx, ny, nz);
  TetMesh mesh;
  mesh.vertices.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.vertices.row(grid_index({i, j, k}, nx, ny)) =
            Vec3(i * size.x() / nx, j * size.y() / ny, k * size.z() / nz) - size / 2.0;
  mesh.tets.resize(6 * nx * ny * nz, 4);
  int cube = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) add_cube_tets(mesh.tets, cube++, {i, j, k}, nx, ny);
  return mesh;
}

}  // namespace progsim
