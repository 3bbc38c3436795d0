#pragma once
/// @file Flat test sheets and their isometric wrapping onto a cylinder, for the bending terms'
/// closed-form cylinder energies.
#include <cmath>
#include <random>

#include "mesh/mesh_generators.hpp"
#include "mesh/triangle_mesh.hpp"

namespace progsim::test_support {

/// The flat sheet's vertices (z = 0) wrapped isometrically onto a cylinder of radius r whose
/// axis makes the angle alpha (rad) with the sheet's y axis: positions only (3|V|).
inline Vector rolled(const TriangleMesh& flat, double r, double alpha) {
  Vector x(3 * flat.num_vertices());
  const double c = std::cos(alpha), s = std::sin(alpha);
  for (int v = 0; v < flat.num_vertices(); ++v) {
    const double u = c * flat.vertices(v, 0) - s * flat.vertices(v, 1);  // across the axis
    const double w = s * flat.vertices(v, 0) + c * flat.vertices(v, 1);  // along the axis
    x.segment<3>(3 * v) << r * std::sin(u / r), w, r * (1.0 - std::cos(u / r));
  }
  return x;
}

/// About a unit square of rows of equilateral triangles (edge a = 1/n, odd rows shifted by
/// a/2), in the x–y plane, normal +z.
inline TriangleMesh equilateral_sheet(int n) {
  const double a = 1.0 / n, row = a * std::sqrt(3.0) / 2.0;
  const int rows = static_cast<int>(1.0 / row);
  TriangleMesh sheet;
  sheet.vertices.resize((n + 1) * (rows + 1), 3);
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= n; ++i)
      sheet.vertices.row(j * (n + 1) + i) << (i + 0.5 * (j % 2)) * a, j * row, 0.0;
  sheet.faces.resize(2 * n * rows, 3);
  int f = 0;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < n; ++i) {
      const int v00 = j * (n + 1) + i, v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
      if (j % 2 == 0) {
        sheet.faces.row(f++) << v00, v10, v01;
        sheet.faces.row(f++) << v10, v11, v01;
      } else {
        sheet.faces.row(f++) << v00, v10, v11;
        sheet.faces.row(f++) << v00, v11, v01;
      }
    }
  return sheet;
}

/// make_grid's sheet (width × height, nx × ny quads) with every quad split along the same
/// diagonal instead of alternating ones.
inline TriangleMesh one_diagonal_grid(double width, double height, int nx, int ny) {
  TriangleMesh mesh = make_grid(width, height, nx, ny);
  int f = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int v00 = j * (nx + 1) + i, v10 = v00 + 1, v01 = v00 + nx + 1, v11 = v01 + 1;
      mesh.faces.row(f++) << v00, v10, v11;
      mesh.faces.row(f++) << v00, v11, v01;
    }
  return mesh;
}

/// make_grid's sheet with its interior vertices from column `first_column` on moved in-plane by
/// up to `jitter` of a cell (a fixed seed): an irregular mesh of the same outline.
inline TriangleMesh jittered_grid(double width, double height, int nx, int ny, double jitter,
                                  int first_column = 1) {
  TriangleMesh mesh = make_grid(width, height, nx, ny);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> noise(-jitter, jitter);
  for (int j = 1; j < ny; ++j)
    for (int i = first_column; i < nx; ++i) {
      const int v = j * (nx + 1) + i;
      mesh.vertices(v, 0) += noise(rng) * width / nx;
      mesh.vertices(v, 1) += noise(rng) * height / ny;
    }
  return mesh;
}

}  // namespace progsim::test_support
