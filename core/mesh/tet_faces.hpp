#pragma once
/// @file Internal to core/mesh: the triangle faces of all tets, grouped by vertex set.
/// Shared by tet mesh validation and boundary extraction so that both see the same faces.
#include <array>
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// The corners (0..3) of face `local` of a tet, the face opposite corner `local`, in the order
/// whose right-hand normal points out of a positively oriented tet (see tet_mesh.hpp).
inline constexpr int kTetFaceCorners[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

/// Face `local` of tet `tet`: its three vertices with their outward order.
struct TetFace {
  std::array<int, 3> key;  ///< the vertex indices, sorted
  int tet;                 ///< the tet this face belongs to
  int local;               ///< 0..3, the tet's vertex opposite the face
};

/// The vertices of face `local` of tet `t` in outward order (for a positively oriented tet).
std::array<int, 3> oriented_face(const Tets& tets, int t, int local);

/// True if two faces with the same vertex set list them in the same cyclic order.
bool same_orientation(const std::array<int, 3>& a, const std::array<int, 3>& b);

/// All 4|T| faces, sorted by key and then by tet. Precondition: no tet repeats a vertex.
std::vector<TetFace> sorted_tet_faces(const Tets& tets);

/// The faces that occur once in `faces` (sorted_tet_faces of `tets`), each in its tet's outward
/// order, in sorted key order: the boundary surface of a valid tet mesh. Nullable `face_tet`
/// receives the tet each boundary face belongs to.
Faces boundary_faces(const std::vector<TetFace>& faces, const Tets& tets,
                     std::vector<int>* face_tet = nullptr);

/// Calls fn(first, count) for each run of `count` faces with one vertex set, in sorted order;
/// `first` indexes `faces`.
template <class Fn>
void for_each_face(const std::vector<TetFace>& faces, Fn&& fn) {
  for (std::size_t first = 0; first < faces.size();) {
    std::size_t end = first + 1;
    while (end < faces.size() && faces[end].key == faces[first].key) ++end;
    fn(first, end - first);
    first = end;
  }
}

}  // namespace progsim
