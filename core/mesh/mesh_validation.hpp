#pragma once
/// @file Mesh validation: rejects meshes the simulator cannot use, naming the first
/// offending element.
#include <string>

#include "mesh/triangle_mesh.hpp"

namespace progsim {

/// Checks, in this order: at least one face; finite coordinates; indices in range;
/// no face repeating a vertex; no degenerate (zero- or near-zero-area) face; no edge
/// shared by more than two faces (non-manifold) or traversed twice in the same direction
/// (inconsistent orientation); no non-manifold vertex (bow-tie); no unreferenced vertex.
/// Throws Error(Status::invalid_mesh, "<label>: face 12 ...") naming the first problem.
/// @param label names the mesh in messages (usually its file name).
void validate_mesh(const TriangleMesh& mesh, const std::string& label);

}  // namespace progsim
