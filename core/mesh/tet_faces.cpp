#include "mesh/tet_faces.hpp"

#include <algorithm>
#include <tuple>

namespace progsim {

std::array<int, 3> oriented_face(const Tets& tets, int t, int local) {
  const int* corner = kTetFaceCorners[local];
  return {tets(t, corner[0]), tets(t, corner[1]), tets(t, corner[2])};
}

bool same_orientation(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  for (int shift = 0; shift < 3; ++shift)
    if (a[0] == b[shift] && a[1] == b[(shift + 1) % 3] && a[2] == b[(shift + 2) % 3]) return true;
  return false;
}

std::vector<TetFace> sorted_tet_faces(const Tets& tets) {
  std::vector<TetFace> faces;
  faces.reserve(4 * static_cast<std::size_t>(tets.rows()));
  for (int t = 0; t < tets.rows(); ++t) {
    for (int local = 0; local < 4; ++local) {
      std::array<int, 3> key = oriented_face(tets, t, local);
      std::sort(key.begin(), key.end());
      faces.push_back({key, t, local});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const TetFace& a, const TetFace& b) {
    return std::tie(a.key, a.tet, a.local) < std::tie(b.key, b.tet, b.local);
  });
  return faces;
}

Faces boundary_faces(const std::vector<TetFace>& faces, const Tets& tets,
                     std::vector<int>* face_tet) {
  std::vector<std::array<int, 3>> once;
  for_each_face(faces, [&](std::size_t first, std::size_t count) {
    if (count != 1) return;
    once.push_back(oriented_face(tets, faces[first].tet, faces[first].local));
    if (face_tet) face_tet->push_back(faces[first].tet);
  });
  Faces result(static_cast<Eigen::Index>(once.size()), 3);
  for (std::size_t f = 0; f < once.size(); ++f)
    for (int k = 0; k < 3; ++k) result(static_cast<Eigen::Index>(f), k) = once[f][k];
  return result;
}

}  // namespace progsim
