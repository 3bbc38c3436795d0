#pragma once
/// @file Tet mesh validation: rejects volume meshes the simulator cannot use, naming the first
/// offending element.
#include <string>

#include "mesh/tet_mesh.hpp"

namespace progsim {

/// Checks, in this order: at least one tet; finite coordinates; indices in range; no tet
/// repeating a vertex; every tet positively oriented (tet_mesh.hpp) with a volume above
/// 1e-14 times the cube of the bounding-box diagonal ("inverted" if its signed volume is below
/// minus that, "degenerate" otherwise); no two tets on the same four vertices; every triangle
/// face shared by at most two tets, which traverse it in opposite orientations; a boundary
/// (the faces of one tet only) that is a closed 2-manifold: every boundary edge on exactly two
/// boundary faces, and the boundary faces around each boundary vertex forming one fan (no
/// bow-tie vertex); no unreferenced vertex.
/// Throws Error(Status::invalid_mesh, "<label>: tet 12 ...") naming the first problem.
/// @param label names the mesh in messages (usually its file name).
void validate_tet_mesh(const TetMesh& mesh, const std::string& label);

}  // namespace progsim
