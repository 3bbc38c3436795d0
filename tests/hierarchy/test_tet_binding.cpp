// Binding a fine tet mesh to a coarse one that overlaps it without conforming (VPD §3.3): exact
// reproduction of affine maps, negative weights outside, and no binding across a slit that
// Euclidean nearest-tet binding would cross (PD-VPD-NOTES risk 6: two prongs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "hierarchy/tet_binding.hpp"
#include "hierarchy/tet_prolongation.hpp"
#include "mesh/tet_generators.hpp"
#include "mesh/tet_mesh_validation.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;

namespace {

/// A box of nx × ny × nz unit cells whose grid lines are moved to xs, ys, zs (increasing), with
/// the cells for which `removed(i, j)` holds taken out and unused vertices dropped.
template <class Removed>
TetMesh grid_solid(const std::vector<double>& xs, const std::vector<double>& ys,
                   const std::vector<double>& zs, Removed removed) {
  const int nx = static_cast<int>(xs.size()) - 1, ny = static_cast<int>(ys.size()) - 1,
            nz = static_cast<int>(zs.size()) - 1;
  const TetMesh box = make_tet_box(Vec3(nx, ny, nz), nx, ny, nz);
  // Unit cells centred at the origin: vertex coordinate + n/2 is its grid index.
  const auto index = [](double c, int n) { return static_cast<int>(std::lround(c + 0.5 * n)); };
  std::vector<int> kept;
  for (int t = 0; t < box.num_tets(); ++t) {
    Vec3 centroid = Vec3::Zero();
    for (int k = 0; k < 4; ++k) centroid += box.vertices.row(box.tets(t, k)).transpose() / 4.0;
    const int i = static_cast<int>(std::floor(centroid.x() + 0.5 * nx));
    const int j = static_cast<int>(std::floor(centroid.y() + 0.5 * ny));
    if (!removed(i, j)) kept.push_back(t);
  }
  std::vector<int> new_index(box.num_vertices(), -1);
  TetMesh out;
  out.tets.resize(static_cast<Eigen::Index>(kept.size()), 4);
  int count = 0;
  for (std::size_t r = 0; r < kept.size(); ++r)
    for (int k = 0; k < 4; ++k) {
      int& v = new_index[box.tets(kept[r], k)];
      if (v < 0) v = count++;
      out.tets(static_cast<Eigen::Index>(r), k) = v;
    }
  out.vertices.resize(count, 3);
  for (int v = 0; v < box.num_vertices(); ++v)
    if (new_index[v] >= 0)
      out.vertices.row(new_index[v]) << xs[index(box.vertices(v, 0), nx)],
          ys[index(box.vertices(v, 1), ny)], zs[index(box.vertices(v, 2), nz)];
  return out;
}

std::vector<double> linspace(double a, double b, int cells) {
  std::vector<double> out(cells + 1);
  for (int i = 0; i <= cells; ++i) out[i] = a + (b - a) * i / cells;
  return out;
}

/// Fine U: prongs x ∈ [−1.5, −0.5] and [−0.45, 1.5] above y = 0, a slit between them.
TetMesh fine_u() {
  std::vector<double> xs = linspace(-1.5, -0.5, 4);
  const std::vector<double> right = linspace(-0.45, 1.5, 7);
  xs.insert(xs.end(), right.begin(), right.end());
  return grid_solid(xs, linspace(-1.0, 1.0, 8), linspace(0.0, 0.5, 2),
                    [](int i, int j) { return i == 4 && j >= 4; });
}

/// Coarse U: prong A thinner (x ≤ −0.6), prong B wider (x ≥ −0.43) than the fine one's.
TetMesh coarse_u() {
  return grid_solid({-1.5, -0.6, -0.43, 1.5}, {-1.0, 0.0, 1.0}, {0.0, 0.5},
                    [](int i, int j) { return i == 1 && j == 1; });
}

double box_distance(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return (p.cwiseMax(lo).cwiseMin(hi) - p).norm();
}

}  // namespace

TEST(TetBinding, BindsEveryVertexOfAConformingCopyToItself) {
  const TetMesh mesh = make_tet_box(Vec3(1.0, 2.0, 0.5), 2, 3, 2);
  const std::vector<TetBinding> b = bind_to_tets(mesh, mesh);
  const ProlongationMatrix w = tet_prolongation_matrix(b, mesh);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    EXPECT_EQ(b[v].kind, BindingKind::inside);
    EXPECT_NEAR(w.coeff(v, v), 1.0, 1e-12);
  }
  EXPECT_LT(
      (Eigen::MatrixXd(w) - Eigen::MatrixXd::Identity(w.rows(), w.cols())).cwiseAbs().maxCoeff(),
      1e-12);
}

TEST(TetProlongation, ReproducesAffineMapsWithNegativeWeightsOutsideTheCoarseMesh) {
  const TetMesh fine = make_tet_box(Vec3(1.0, 1.0, 1.0), 5, 5, 5);
  TetMesh coarse = make_tet_box(Vec3(1.0, 1.0, 1.0), 2, 2, 2);
  coarse.vertices *= 0.9;  // fine boundary vertices lie outside the coarse mesh
  validate_tet_mesh(coarse, "coarse");
  const std::vector<TetBinding> b = bind_to_tets(coarse, fine);
  const ProlongationMatrix w = tet_prolongation_matrix(b, coarse);
  int outside = 0;
  for (const TetBinding& binding : b) outside += binding.kind != BindingKind::inside;
  EXPECT_EQ(outside, 6 * 6 * 6 - 4 * 4 * 4);  // the nodes on the box's faces, at ±0.5 > 0.45
  double min_weight = 0.0, max_weight = 0.0;
  for (int k = 0; k < w.outerSize(); ++k)
    for (ProlongationMatrix::InnerIterator it(w, k); it; ++it) {
      min_weight = std::min(min_weight, it.value());
      max_weight = std::max(max_weight, it.value());
    }
  EXPECT_LT(min_weight, -0.01);  // extrapolation happened
  EXPECT_LT(max_weight, 2.0);    // and stayed bounded
  const Eigen::VectorXd row_sums = w * Eigen::VectorXd::Ones(w.cols());
  EXPECT_LT((row_sums.array() - 1.0).abs().maxCoeff(), 1e-12);
  const Mat3 a = (Mat3() << 1.2, 0.3, -0.1, 0.0, 0.8, 0.4, 0.2, -0.5, 1.1).finished();
  const Vec3 shift(0.3, -2.0, 5.0);
  const Positions moved_coarse = (coarse.vertices * a.transpose()).rowwise() + shift.transpose();
  const Positions expected = (fine.vertices * a.transpose()).rowwise() + shift.transpose();
  EXPECT_LT((Positions(w * moved_coarse) - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(TetBinding, NeverBindsAcrossASlitThatNearestTetBindingWouldCross) {
  const TetMesh fine = fine_u(), coarse = coarse_u();
  validate_tet_mesh(fine, "fine U");
  validate_tet_mesh(coarse, "coarse U");
  // The trap is set: a fine vertex on prong A's slit face is nearer to coarse prong B than to A.
  const Vec3 on_face(-0.5, 0.5, 0.25);
  ASSERT_LT(box_distance(on_face, Vec3(-0.43, 0.0, 0.0), Vec3(1.5, 1.0, 0.5)),
            box_distance(on_face, Vec3(-1.5, 0.0, 0.0), Vec3(-0.6, 1.0, 0.5)));
  const std::vector<TetBinding> b = bind_to_tets(coarse, fine);
  const ProlongationMatrix w = tet_prolongation_matrix(b, coarse);
  // Move coarse prong B's top vertices (x ≥ −0.43, y = 1) up: fine prong A must stay still.
  Positions moved = coarse.vertices;
  for (int v = 0; v < coarse.num_vertices(); ++v)
    if (coarse.vertices(v, 0) >= -0.43 && coarse.vertices(v, 1) == 1.0) moved(v, 1) += 0.5;
  const Positions fine_moved = w * moved;
  int prong_a = 0, by_ray = 0;
  for (int v = 0; v < fine.num_vertices(); ++v) {
    if (fine.vertices(v, 0) > -0.5 || fine.vertices(v, 1) <= 0.0) continue;
    ++prong_a;
    by_ray += b[v].kind == BindingKind::ray;
    EXPECT_LT((fine_moved.row(v) - fine.vertices.row(v)).norm(), 1e-12) << "fine vertex " << v;
  }
  EXPECT_GT(prong_a, 20);
  EXPECT_GT(by_ray, 0);  // the slit face's vertices were bound by rays, not containment
}

TEST(TetBinding, AVertexAnUlpOutsideACoarseFaceBindsInsideTheTetBehindIt) {
  // A mesher (CGAL Mesh_3's perturbation) can leave a boundary vertex an ulp off a plane both
  // levels share: it must bind inside, not by ray to a neighbouring tet with negative weights.
  const TetMesh coarse = make_tet_box(Vec3(1.0, 1.0, 1.0), 2, 2, 2);
  TetMesh fine = make_tet_box(Vec3(1.0, 1.0, 1.0), 3, 3, 3);
  int moved = 0;
  for (int v = 0; v < fine.num_vertices(); ++v)
    if (fine.vertices(v, 1) == -0.5) {
      fine.vertices(v, 1) = std::nextafter(-0.5, -1.0);  // an ulp below the face y = −0.5
      ++moved;
    }
  ASSERT_GT(moved, 0);
  const std::vector<TetBinding> b = bind_to_tets(coarse, fine);
  for (int v = 0; v < fine.num_vertices(); ++v) {
    EXPECT_EQ(b[v].kind, BindingKind::inside) << "fine vertex " << v;
    EXPECT_GT(b[v].weights.minCoeff(), -1e-9) << "fine vertex " << v;
  }
}
