#include "mesh/mesh_generators.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "mesh/mesh_topology.hpp"

namespace progsim {
namespace {

/// Throws Error(invalid_argument, "<requirement> (got a, b, ...)").
[[noreturn]] void reject_arguments(const std::string& requirement,
                                   std::initializer_list<double> got) {
  std::ostringstream message;
  message << requirement << " (got ";
  const char* separator = "";
  for (const double x : got) message << std::exchange(separator, ", ") << x;
  message << ')';
  fail(Status::invalid_argument, message.str());
}

/// Triangles of an nu × nv quad grid whose vertex (i, j) has index j * columns + i; with
/// `wrap`, column nu is column 0 (columns == nu), otherwise columns == nu + 1. Quads are
/// split along alternating diagonals; triangles are counter-clockwise in (i, j).
Faces quad_grid_faces(int nu, int nv, bool wrap) {
  const int columns = wrap ? nu : nu + 1;
  const auto index = [&](int i, int j) { return j * columns + i % columns; };
  Faces faces(2 * nu * nv, 3);
  int f = 0;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      if ((i + j) % 2 == 0) {
        faces.row(f++) << a, b, c;
        faces.row(f++) << a, c, d;
      } else {
        faces.row(f++) << a, b, d;
        faces.row(f++) << b, c, d;
      }
    }
  }
  return faces;
}

/// The regular icosahedron with unit circumradius, faces oriented outwards. Its vertices
/// are the cyclic permutations of (0, ±1, ±φ), scaled; its faces are the vertex triples that
/// are pairwise one edge apart, which avoids a hand-typed face table.
TriangleMesh make_icosahedron() {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh mesh;
  mesh.vertices.resize(12, 3);
  int v = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double s1 : {-1.0, 1.0}) {
      for (const double s2 : {-phi, phi}) {
        Vec3 p = Vec3::Zero();
        p[(axis + 1) % 3] = s1;
        p[(axis + 2) % 3] = s2;
        mesh.vertices.row(v++) = p.normalized().transpose();
      }
    }
  }
  const double edge = 2.0 / std::sqrt(1.0 + phi * phi);  // on the unit sphere
  const auto adjacent = [&](int a, int b) {
    return std::abs((mesh.vertices.row(a) - mesh.vertices.row(b)).norm() - edge) < 1e-9;
  };
  mesh.faces.resize(20, 3);
  int f = 0;
  for (int a = 0; a < 12; ++a) {
    for (int b = a + 1; b < 12; ++b) {
      for (int c = b + 1; c < 12; ++c) {
        if (!adjacent(a, b) || !adjacent(b, c) || !adjacent(c, a)) continue;
        const Vec3 pa = mesh.vertices.row(a), pb = mesh.vertices.row(b), pc = mesh.vertices.row(c);
        const bool outward = (pb - pa).cross(pc - pa).dot(pa) > 0.0;
        mesh.faces.row(f++) << a, outward ? b : c, outward ? c : b;
      }
    }
  }
  return mesh;
}

/// Splits every triangle of a unit-sphere mesh into four at its edge midpoints, projected
/// back onto the unit sphere. Vertex |V| + e is the midpoint of edge e.
TriangleMesh subdivide_on_unit_sphere(const TriangleMesh& mesh) {
  const std::vector<std::array<int, 2>> edges =
      build_topology(mesh.faces, mesh.num_vertices()).edges;
  const int n = mesh.num_vertices();
  TriangleMesh fine;
  fine.vertices.resize(n + static_cast<int>(edges.size()), 3);
  fine.vertices.topRows(n) = mesh.vertices;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Vec3 mid = mesh.vertices.row(edges[e][0]) + mesh.vertices.row(edges[e][1]);
    fine.vertices.row(n + e) = mid.normalized().transpose();
  }
  const auto midpoint = [&](int a, int b) {
    const std::array<int, 2> key{std::min(a, b), std::max(a, b)};
    return n + static_cast<int>(std::lower_bound(edges.begin(), edges.end(), key) - edges.begin());
  };
  fine.faces.resize(4 * mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    fine.faces.row(4 * f) << a, ab, ca;
    fine.faces.row(4 * f + 1) << ab, b, bc;
    fine.faces.row(4 * f + 2) << ca, bc, c;
    fine.faces.row(4 * f + 3) << ab, bc, ca;
  }
  return fine;
}

}  // namespace

TriangleMesh make_grid(double width, double height, int nx, int ny) {
  if (!(width > 0.0) || !(height > 0.0) || nx < 1 || ny < 1)
    reject_arguments("make_grid: need width, height > 0 and nx, ny >= 1",
                     {width, height, double(nx), double(ny)});
  TriangleMesh mesh;
  mesh.vertices.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      mesh.vertices.row(j * (nx + 1) + i) << width * (static_cast<double>(i) / nx),
          height * (static_cast<double>(j) / ny), 0.0;
  mesh.faces = quad_grid_faces(nx, ny, false);
  return mesh;
}

TriangleMesh make_sphere(double radius, int subdivisions) {
  if (!(radius > 0.0) || subdivisions < 0 || subdivisions > 12)
    reject_arguments("make_sphere: need radius > 0 and subdivisions in [0, 12]",
                     {radius, double(subdivisions)});
  TriangleMesh mesh = make_icosahedron();
  for (int s = 0; s < subdivisions; ++s) mesh = subdivide_on_unit_sphere(mesh);
  mesh.vertices *= radius;
  return mesh;
}

TriangleMesh make_cylinder(double radius, double length, double angle, int n_around, int n_along) {
  // 2π up to rounding (e.g. 360 · π / 180) closes the tube.
  const bool closed = std::abs(angle - kTwoPi) <= 1e-12 * kTwoPi;
  if (!(radius > 0.0) || !(length > 0.0) || !(angle > 0.0) || (angle > kTwoPi && !closed) ||
      n_along < 1 || n_around < (closed ? 3 : 1))
    reject_arguments(
        "make_cylinder: need radius, length > 0, angle in (0, 2π], n_along >= 1 "
        "and n_around >= 1 (3 for a full tube)",
        {radius, length, angle, double(n_around), double(n_along)});
  const int columns = closed ? n_around : n_around + 1;
  TriangleMesh mesh;
  mesh.vertices.resize(columns * (n_along + 1), 3);
  for (int j = 0; j <= n_along; ++j) {
    for (int i = 0; i < columns; ++i) {
      const double theta = angle * (static_cast<double>(i) / n_around);
      mesh.vertices.row(j * columns + i) << radius * std::sin(theta),
          length * (static_cast<double>(j) / n_along), radius * std::cos(theta);
    }
  }
  mesh.faces = quad_grid_faces(n_around, n_along, closed);
  return mesh;
}

TriangleMesh make_box(const Vec3& size) {
  if (!(size.array() > 0.0).all() || !size.allFinite())
    reject_arguments("make_box: every size component must be positive",
                     {size.x(), size.y(), size.z()});
  TriangleMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int v = 0; v < 8; ++v)  // bit k of v selects the upper side along axis k
    for (int k = 0; k < 3; ++k) mesh.vertices(v, k) = ((v >> k) & 1 ? 0.5 : -0.5) * size[k];
  mesh.faces.resize(12, 3);
  mesh.faces << 0, 2, 3, 0, 3, 1,  // z = −
      4, 5, 7, 4, 7, 6,            // z = +
      0, 1, 5, 0, 5, 4,            // y = −
      2, 6, 7, 2, 7, 3,            // y = +
      0, 4, 6, 0, 6, 2,            // x = −
      1, 3, 7, 1, 7, 5;            // x = +
  return mesh;
}

}  // namespace progsim
