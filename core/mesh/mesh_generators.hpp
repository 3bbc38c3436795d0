#pragma once
/// @file Procedural meshes for scenes, tests and benchmarks.
#include "mesh/triangle_mesh.hpp"

namespace progsim {

/// A flat rectangle in the x–y plane, corner at the origin, size width × height (m),
/// nx × ny quads, each split into two triangles along alternating diagonals; normal +z.
/// (nx+1)(ny+1) vertices, vertex (i, j) at index j*(nx+1)+i, at (i·width/nx, j·height/ny, 0);
/// 2·nx·ny faces. Throws Error(Status::invalid_argument) unless width, height > 0, nx, ny ≥ 1.
TriangleMesh make_grid(double width, double height, int nx, int ny);

/// A closed sphere of the given radius centred at the origin: icosahedron subdivided
/// `subdivisions` times and projected onto the sphere; outward normals.
/// 10·4^s + 2 vertices (the first 12 are the icosahedron's), 20·4^s faces.
/// Throws Error(Status::invalid_argument) unless radius > 0 and 0 ≤ subdivisions ≤ 12.
TriangleMesh make_sphere(double radius, int subdivisions);

/// An open cylindrical patch around the y axis: radius r, length along y, spanning
/// `angle` radians around the axis (2π for a full tube), n_around × n_along quads;
/// outward normals. For angle < 2π the patch has a boundary.
/// Vertex (i, j) sits at (r sin θᵢ, j·length/n_along, r cos θᵢ) with θᵢ = i·angle/n_around,
/// index j·c + i, where c = n_around + 1 columns for a patch; for angle = 2π (up to rounding)
/// the seam is welded and c = n_around. 2·n_around·n_along faces, alternating diagonals.
/// Throws Error(Status::invalid_argument) unless radius, length > 0, 0 < angle ≤ 2π,
/// n_along ≥ 1 and n_around ≥ 1 (≥ 3 for a full tube).
TriangleMesh make_cylinder(double radius, double length, double angle, int n_around, int n_along);

/// A closed axis-aligned box centred at the origin with edge lengths size (m): 8 vertices,
/// 12 faces (two per side), outward normals, sharp edges. Throws Error(invalid_argument)
/// unless every size component is positive and finite.
TriangleMesh make_box(const Vec3& size);

}  // namespace progsim
