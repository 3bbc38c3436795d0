#pragma once
/// @file Procedural tet meshes for scenes, tests and benchmarks.
#include "mesh/tet_mesh.hpp"

namespace progsim {

/// A solid axis-aligned box centred at the origin with edge lengths size (m), split into
/// nx × ny × nz cubes (cuboids) and each cube into 6 tets around its diagonal from the corner
/// of least to the corner of greatest coordinates (Kuhn–Freudenthal subdivision, conforming
/// across cubes). Vertex (i, j, k) has index (k·(ny+1) + j)·(nx+1) + i and sits at
/// (i·size.x/nx, j·size.y/ny, k·size.z/nz) − size/2. (nx+1)(ny+1)(nz+1) vertices, 6·nx·ny·nz
/// tets, all positively oriented (tet_mesh.hpp). Throws Error(Status::invalid_argument) unless
/// every size component is positive and finite and nx, ny, nz ≥ 1.
TetMesh make_tet_box(const Vec3& size, int nx, int ny, int nz);

}  // namespace progsim
