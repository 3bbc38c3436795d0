#pragma once
/// @file Flat test sheets and their isometric wrapping onto a cylinder, for the bending terms'
/// closed-form cylinder energies.
#include <cmath>

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

}  // namespace progsim::test_support
