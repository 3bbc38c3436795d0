// Prolongation operators on synthetic coarse/fine pairs built without a decimator (a grid rolled
// onto a cylinder, anchors located in the flat grid; two subdivision levels of a sphere,
// anchors by radial projection): rest recovery, the paper's formula with an SVD polar factor as
// an independent reference, rigid equivariance, scaling, Uᵀ restriction, the barycentric
// operator, degenerate deformed faces, argument checks and thread-count independence.
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/parallel.hpp"
#include "hierarchy/barycentric_prolongation.hpp"
#include "hierarchy/hierarchy_test_meshes.hpp"
#include "hierarchy/shell_prolongation.hpp"
#include "mesh/mesh_generators.hpp"
#include "support/energy_checks.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using progsim::test_support::expect_error;
using progsim::test_support::max_row_distance;
using progsim::test_support::random_rotation;

namespace {

using Mat3x2 = Eigen::Matrix<double, 3, 2>;

constexpr double kRollRadius = 0.4;  // the unit grid spans 2.5 rad of the cylinder

/// A coarse mesh, the fine rest positions and each fine vertex's anchor on the coarse mesh.
struct LevelPair {
  std::string name;
  TriangleMesh coarse;
  Positions fine_rest;
  SurfaceAnchors anchors;
};

/// (x, y, 0) ↦ (R sin(x/R), y, R cos(x/R)): a flat x–y mesh rolled onto a cylinder about y.
Positions rolled(const Positions& flat) {
  Positions out(flat.rows(), 3);
  for (Eigen::Index v = 0; v < flat.rows(); ++v) {
    const double angle = flat(v, 0) / kRollRadius;
    out.row(v) << kRollRadius * std::sin(angle), flat(v, 1), kRollRadius * std::cos(angle);
  }
  return out;
}

/// Among the faces of `coarse`, the one where `weights_in(face)` has the largest minimum entry.
template <class WeightsIn>
SurfaceAnchor best_anchor(const Faces& faces, WeightsIn weights_in) {
  SurfaceAnchor best;
  double best_min = -std::numeric_limits<double>::infinity();
  for (int f = 0; f < faces.rows(); ++f) {
    const Vec3 w = weights_in(f);
    if (w.allFinite() && w.minCoeff() > best_min) {
      best_min = w.minCoeff();
      best = {f, w};
    }
  }
  EXPECT_GT(best_min, -1e-12) << "point not covered by the coarse mesh";
  return best;
}

/// Anchors of the points `fine` in the flat (z = 0) mesh `coarse`: 2-D barycentric weights.
SurfaceAnchors planar_anchors(const TriangleMesh& coarse, const Positions& fine) {
  SurfaceAnchors anchors(fine.rows());
  for (Eigen::Index i = 0; i < fine.rows(); ++i)
    anchors[i] = best_anchor(coarse.faces, [&](int f) {
      Eigen::Matrix3d m;  // rows: x, y, 1 of the corners
      for (int k = 0; k < 3; ++k)
        m.col(k) << coarse.vertices(coarse.faces(f, k), 0), coarse.vertices(coarse.faces(f, k), 1),
            1.0;
      return Vec3(m.inverse() * Vec3(fine(i, 0), fine(i, 1), 1.0));
    });
  return anchors;
}

/// Anchors of the points `fine` on `coarse` where the ray from the origin through each point
/// crosses a coarse face: λ = [x₀ x₁ x₂]⁻¹ p, weights λ / Σλ (Σλ > 0 on the ray's side).
SurfaceAnchors radial_anchors(const TriangleMesh& coarse, const Positions& fine) {
  SurfaceAnchors anchors(fine.rows());
  for (Eigen::Index i = 0; i < fine.rows(); ++i)
    anchors[i] = best_anchor(coarse.faces, [&](int f) {
      Mat3 m;
      for (int k = 0; k < 3; ++k) m.col(k) = coarse.vertices.row(coarse.faces(f, k)).transpose();
      const Vec3 lambda = m.inverse() * fine.row(i).transpose();
      return lambda.sum() > 0.0 ? Vec3(lambda / lambda.sum()) : Vec3::Constant(-1.0);
    });
  return anchors;
}

/// make_grid(1, 1, n, n) as coarse, make_grid(1, 1, m, m) as fine, both rolled onto the cylinder.
LevelPair cylinder_pair(int coarse_n, int fine_n) {
  LevelPair pair;
  pair.name = "cylinder " + std::to_string(coarse_n) + "/" + std::to_string(fine_n);
  pair.coarse = make_grid(1.0, 1.0, coarse_n, coarse_n);
  const Positions fine_flat = make_grid(1.0, 1.0, fine_n, fine_n).vertices;
  pair.anchors = planar_anchors(pair.coarse, fine_flat);
  pair.coarse.vertices = rolled(pair.coarse.vertices);
  pair.fine_rest = rolled(fine_flat);
  return pair;
}

LevelPair sphere_pair() {
  LevelPair pair;
  pair.name = "sphere 1/3";
  pair.coarse = make_sphere(1.0, 1);
  pair.fine_rest = make_sphere(1.0, 3).vertices;
  pair.anchors = radial_anchors(pair.coarse, pair.fine_rest);
  return pair;
}

std::vector<LevelPair> level_pairs() {
  return {cylinder_pair(4, 16), sphere_pair()};
}

ShellProlongation shell_of(const LevelPair& pair) {
  return ShellProlongation(pair.coarse.vertices, pair.coarse.faces, pair.anchors, pair.fine_rest);
}

/// U written out from the anchors (n_fine × n_coarse, dense).
Eigen::MatrixXd dense_intrinsic(const LevelPair& pair) {
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(pair.fine_rest.rows(), pair.coarse.num_vertices());
  for (std::size_t i = 0; i < pair.anchors.size(); ++i)
    for (int k = 0; k < 3; ++k)
      u(i, pair.coarse.faces(pair.anchors[i].face, k)) += pair.anchors[i].weights(k);
  return u;
}

Positions times(const Eigen::MatrixXd& u, const Positions& x) {
  return u * x;
}

/// A non-rigid deformation of the rest shape: a shear-bend map plus uniform noise of ±0.03.
Positions deformed(const Positions& rest, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.03, 0.03);
  Positions x(rest.rows(), 3);
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const double px = rest(v, 0), py = rest(v, 1), pz = rest(v, 2);
    x.row(v) << 1.1 * px + 0.2 * py * py + noise(rng), 0.9 * py + 0.1 * pz + noise(rng),
        pz + 0.3 * px * py + noise(rng);
  }
  return x;
}

/// Every row p of x mapped to q p + c.
Positions moved(const Positions& x, const Mat3& q, const Vec3& c) {
  return (x * q.transpose()).rowwise() + c.transpose();
}

/// a_i(x) = n γ + R(F) t written out as in PSQ §4.3 and footnote 2, with R from a thin SVD.
Vec3 reference_offset(const LevelPair& pair, Eigen::Index i, const Positions& coarse) {
  const SurfaceAnchor& anchor = pair.anchors[i];
  Mat3 rest, now;  // corners as columns
  for (int k = 0; k < 3; ++k) {
    rest.col(k) = pair.coarse.vertices.row(pair.coarse.faces(anchor.face, k)).transpose();
    now.col(k) = coarse.row(pair.coarse.faces(anchor.face, k)).transpose();
  }
  const Vec3 e1 = rest.col(1) - rest.col(0), e2 = rest.col(2) - rest.col(0);
  const Vec3 n_rest = e1.cross(e2).normalized(), e_rest = e1.normalized();
  const Vec3 d_rest = pair.fine_rest.row(i).transpose() - rest * anchor.weights;
  const double gamma = n_rest.dot(d_rest);
  const Vec2 t(e_rest.dot(d_rest), n_rest.cross(e_rest).dot(d_rest));
  Mat2 b_rest;
  b_rest << e1.norm(), e1.dot(e2) / e1.norm(), 0.0, e1.cross(e2).norm() / e1.norm();
  Mat3x2 d;
  d << now.col(1) - now.col(0), now.col(2) - now.col(0);
  const Mat3x2 f = d * b_rest.inverse();
  // Fixed-size JacobiSVD has no thin U: take the first two columns of the full one.
  const Eigen::JacobiSVD<Mat3x2> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Mat3x2 r = svd.matrixU().leftCols<2>() * svd.matrixV().transpose();
  const Vec3 n = d.col(0).cross(d.col(1)).normalized();
  return n * gamma + r * t;
}

TEST(ShellProlongation, RecoversTheRestShape) {
  for (const LevelPair& pair : level_pairs()) {
    SCOPED_TRACE(pair.name);
    const ShellProlongation p = shell_of(pair);
    ASSERT_EQ(p.fine_vertices(), pair.fine_rest.rows());
    ASSERT_EQ(p.coarse_vertices(), pair.coarse.num_vertices());
    const Positions fine = p(pair.coarse.vertices);
    EXPECT_LE(max_row_distance(fine, pair.fine_rest),
              1e-12 * bounding_box_diagonal(pair.fine_rest));
    // The offsets carry real detail: the barycentric operator alone misses the rest shape.
    const Positions anchors_only = times(dense_intrinsic(pair), pair.coarse.vertices);
    EXPECT_GT(max_row_distance(anchors_only, pair.fine_rest), 1e-2);
  }
}

TEST(ShellProlongation, MatchesThePaperFormulaWithAnSvdPolarFactor) {
  for (const LevelPair& pair : level_pairs()) {
    SCOPED_TRACE(pair.name);
    const ShellProlongation p = shell_of(pair);
    const Positions x = deformed(pair.coarse.vertices, 7);
    Positions offsets(p.fine_vertices(), 3);
    p.offsets(x, offsets);
    Positions expected(p.fine_vertices(), 3);
    for (Eigen::Index i = 0; i < expected.rows(); ++i)
      expected.row(i) = reference_offset(pair, i, x).transpose();
    EXPECT_LE(max_row_distance(offsets, expected), 1e-12);
    expected += times(dense_intrinsic(pair), x);
    EXPECT_LE(max_row_distance(p(x), expected), 1e-12);
  }
}

TEST(ShellProlongation, IsEquivariantUnderRigidMotions) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> shift(-2.0, 2.0);
  for (const LevelPair& pair : level_pairs()) {
    SCOPED_TRACE(pair.name);
    const ShellProlongation p = shell_of(pair);
    const Positions x = deformed(pair.coarse.vertices, 3);
    const Positions fine = p(x);
    for (int trial = 0; trial < 5; ++trial) {
      const Mat3 q = random_rotation(rng);
      const Vec3 c(shift(rng), shift(rng), shift(rng));
      EXPECT_LE(max_row_distance(p(moved(x, q, c)), moved(fine, q, c)), 1e-10) << "trial " << trial;
    }
  }
}

TEST(ShellProlongation, ScalingScalesTheAnchorsButOnlyRotatesTheOffsets) {
  for (const LevelPair& pair : level_pairs()) {
    SCOPED_TRACE(pair.name);
    const ShellProlongation p = shell_of(pair);
    const Eigen::MatrixXd u = dense_intrinsic(pair);
    const Positions rest_offsets = pair.fine_rest - times(u, pair.coarse.vertices);
    const Positions x = deformed(pair.coarse.vertices, 5);
    Positions offsets(p.fine_vertices(), 3), scaled_offsets(p.fine_vertices(), 3);
    p.offsets(x, offsets);
    // |a_i(x)| = |d̄_i|: the offsets are rotated copies of the rest offsets, at any state.
    EXPECT_LE((offsets.rowwise().norm() - rest_offsets.rowwise().norm()).cwiseAbs().maxCoeff(),
              1e-12);
    for (const double s : {0.25, 3.0}) {
      SCOPED_TRACE(s);
      p.offsets(s * x, scaled_offsets);
      EXPECT_LE(max_row_distance(scaled_offsets, offsets), 1e-12);
      EXPECT_LE(max_row_distance(p(s * x) - scaled_offsets, s * times(u, x)), 1e-12 * s);
      p.offsets(s * pair.coarse.vertices, scaled_offsets);
      EXPECT_LE(max_row_distance(scaled_offsets, rest_offsets), 1e-12);
    }
  }
}

TEST(ShellProlongation, RestrictsGradientsWithTheTransposedIntrinsicMatrix) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (const LevelPair& pair : level_pairs()) {
    SCOPED_TRACE(pair.name);
    const ShellProlongation p = shell_of(pair);
    const Eigen::MatrixXd u = dense_intrinsic(pair);
    EXPECT_LE((Eigen::MatrixXd(p.intrinsic()) - u).cwiseAbs().maxCoeff(), 0.0);
    Positions g(p.fine_vertices(), 3);
    for (Eigen::Index k = 0; k < g.size(); ++k) g.data()[k] = value(rng);
    const Positions expected = u.transpose() * g;
    EXPECT_LE(max_row_distance(p.restrict_gradient(g), expected), 1e-13);
  }
}

TEST(ShellProlongation, DegenerateDeformedFacesFallBackToTheAnchor) {
  const LevelPair pair = cylinder_pair(4, 16);
  const ShellProlongation p = shell_of(pair);
  const Eigen::MatrixXd u = dense_intrinsic(pair);
  Positions x = deformed(pair.coarse.vertices, 9);
  // Face 0's third corner moved onto its first: exactly zero area, no normal.
  x.row(pair.coarse.faces(0, 2)) = x.row(pair.coarse.faces(0, 0));
  Positions offsets(p.fine_vertices(), 3);
  p.offsets(x, offsets);
  const Positions fine = p(x);
  ASSERT_TRUE(fine.allFinite());
  const Positions anchors_only = times(u, x);
  int on_face_0 = 0;
  for (std::size_t i = 0; i < pair.anchors.size(); ++i)
    if (pair.anchors[i].face == 0) {
      ++on_face_0;
      EXPECT_EQ(offsets.row(i).norm(), 0.0) << "fine vertex " << i;
      EXPECT_LE((fine.row(i) - anchors_only.row(i)).norm(), 1e-14) << "fine vertex " << i;
    }
  EXPECT_GT(on_face_0, 0);
  // Every coarse vertex at one point: every offset falls back, nothing becomes NaN.
  p.offsets(Positions::Ones(p.coarse_vertices(), 3), offsets);
  EXPECT_EQ(offsets.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ShellProlongation, SliverFacesKeepOrthonormalFrames) {
  for (const LevelPair& pair : level_pairs()) {
    SCOPED_TRACE(pair.name);
    const ShellProlongation p = shell_of(pair);
    const Positions rest_offsets =
        pair.fine_rest - times(dense_intrinsic(pair), pair.coarse.vertices);
    for (const double thickness : {1e-9, 1e-13}) {
      SCOPED_TRACE(thickness);
      // Face 0's third corner moved to `thickness` off the line of its first edge.
      Positions x = deformed(pair.coarse.vertices, 13);
      const Vec3 x0 = x.row(pair.coarse.faces(0, 0)), x1 = x.row(pair.coarse.faces(0, 1));
      const Vec3 off_line = (x1 - x0).cross(Vec3(0.3, -0.5, 0.8)).normalized();
      x.row(pair.coarse.faces(0, 2)) = (0.3 * x0 + 0.7 * x1 + thickness * off_line).transpose();
      Positions offsets(p.fine_vertices(), 3);
      p.offsets(x, offsets);
      // |a_i| = |d̄_i| holds only if the frame stayed orthonormal.
      EXPECT_LE((offsets.rowwise().norm() - rest_offsets.rowwise().norm()).cwiseAbs().maxCoeff(),
                1e-13);
      // Still the paper's offset, to the conditioning of the polar factor (~ε / thickness).
      for (std::size_t i = 0; i < pair.anchors.size(); ++i) {
        if (pair.anchors[i].face != 0) continue;
        EXPECT_LE((offsets.row(i).transpose() - reference_offset(pair, i, x)).norm(),
                  1e-15 / thickness)
            << "fine vertex " << i;
      }
    }
  }
}

TEST(BarycentricProlongation, IsTheIntrinsicMatrix) {
  for (const LevelPair& pair : level_pairs()) {
    SCOPED_TRACE(pair.name);
    const BarycentricProlongation p(pair.coarse.faces, pair.coarse.num_vertices(), pair.anchors);
    const Eigen::MatrixXd u = dense_intrinsic(pair);
    ASSERT_EQ(p.fine_vertices(), pair.fine_rest.rows());
    ASSERT_EQ(p.coarse_vertices(), pair.coarse.num_vertices());
    EXPECT_LE((Eigen::MatrixXd(p.intrinsic()) - u).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LE((u.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-12);
    EXPECT_LE(p.intrinsic().nonZeros(), 3 * p.fine_vertices());
    const Positions x = deformed(pair.coarse.vertices, 1);
    EXPECT_LE(max_row_distance(p(x), times(u, x)), 1e-14);
    Positions offsets = Positions::Constant(p.fine_vertices(), 3, 7.0);
    p.offsets(x, offsets);
    EXPECT_EQ(offsets.cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(Prolongation, RejectsBadAnchors) {
  const LevelPair pair = cylinder_pair(2, 4);
  const int faces = pair.coarse.num_faces();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 third = Vec3::Constant(1.0 / 3.0);
  for (const bool shell : {false, true}) {
    SCOPED_TRACE(shell ? "shell" : "barycentric");
    // Constructs the operator with fine vertex 5 anchored at (face, weights).
    const auto construct = [&](int face, const Vec3& weights) {
      SurfaceAnchors anchors = pair.anchors;
      anchors[5] = {face, weights};
      return [&pair, shell, anchors] {
        if (shell)
          ShellProlongation(pair.coarse.vertices, pair.coarse.faces, anchors, pair.fine_rest);
        else
          BarycentricProlongation(pair.coarse.faces, pair.coarse.num_vertices(), anchors);
      };
    };
    expect_error(construct(faces, third), Status::invalid_argument,
                 {"fine vertex 5: anchor face " + std::to_string(faces) + " out of range"});
    expect_error(construct(-1, third), Status::invalid_argument,
                 {"fine vertex 5: anchor face -1 out of range"});
    expect_error(construct(0, Vec3(nan, 0.5, 0.5)), Status::invalid_argument,
                 {"fine vertex 5: anchor weights (nan, 0.5, 0.5) are not finite"});
    expect_error(construct(0, Vec3(-0.1, 0.6, 0.5)), Status::invalid_argument,
                 {"fine vertex 5: anchor weights (-0.1, 0.6, 0.5) have a negative entry"});
    expect_error(construct(0, Vec3(0.2, 0.6, 0.5)), Status::invalid_argument,
                 {"fine vertex 5: anchor weights (0.2, 0.6, 0.5) do not sum to 1"});
  }
}

TEST(ShellProlongation, RejectsBadMeshes) {
  const LevelPair pair = cylinder_pair(2, 4);
  const TriangleMesh& c = pair.coarse;
  SurfaceAnchors too_few = pair.anchors;
  too_few.pop_back();
  expect_error([&] { ShellProlongation(c.vertices, c.faces, too_few, pair.fine_rest); },
               Status::invalid_argument, {"24 anchors for 25 fine vertices"});
  Faces out_of_range = c.faces;
  out_of_range(3, 1) = c.num_vertices();
  expect_error([&] { ShellProlongation(c.vertices, out_of_range, pair.anchors, pair.fine_rest); },
               Status::invalid_mesh, {"coarse face 3 has vertex index 9 out of range"});
  Faces with_degenerate(c.num_faces() + 1, 3);
  with_degenerate << c.faces, 0, 1, 1;
  expect_error(
      [&] { ShellProlongation(c.vertices, with_degenerate, pair.anchors, pair.fine_rest); },
      Status::invalid_mesh, {"rest face 8 is degenerate"});
  Positions nan_rest = pair.fine_rest;
  nan_rest(3, 2) = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { ShellProlongation(c.vertices, c.faces, pair.anchors, nan_rest); },
               Status::invalid_argument, {"fine rest vertex 3 is not finite"});
}

TEST(Prolongation, RejectsWrongShapes) {
  const LevelPair pair = cylinder_pair(2, 4);
  const ShellProlongation shell = shell_of(pair);
  const BarycentricProlongation barycentric(pair.coarse.faces, pair.coarse.num_vertices(),
                                            pair.anchors);
  for (const Prolongation* p :
       {static_cast<const Prolongation*>(&shell), static_cast<const Prolongation*>(&barycentric)}) {
    const Positions coarse = pair.coarse.vertices, too_many(10, 3);
    Positions fine(25, 3), short_fine(24, 3);
    expect_error([&] { p->apply(too_many, fine); }, Status::invalid_argument,
                 {"apply: coarse positions have 10 rows, expected 9"});
    expect_error([&] { p->apply(coarse, short_fine); }, Status::invalid_argument,
                 {"apply: output has 24 rows, expected 25"});
    expect_error([&] { p->offsets(coarse, short_fine); }, Status::invalid_argument,
                 {"offsets: output has 24 rows, expected 25"});
    expect_error([&] { p->restrict_gradient(short_fine); }, Status::invalid_argument,
                 {"restrict_gradient got 24 rows for 25 fine vertices"});
  }
  // Equal vertex counts (every fine vertex on a coarse corner): in-place use is refused.
  SurfaceAnchors corners(pair.coarse.num_vertices());
  for (int f = 0; f < pair.coarse.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) corners[pair.coarse.faces(f, k)] = {f, Vec3::Unit(k)};
  const BarycentricProlongation identity(pair.coarse.faces, pair.coarse.num_vertices(), corners);
  Positions x = pair.coarse.vertices;
  EXPECT_EQ(identity(x), x);
  expect_error([&] { identity.apply(x, x); }, Status::invalid_argument, {"aliases the input"});
}

TEST(Prolongation, ResultsAreBitwiseIndependentOfTheThreadCount) {
  const LevelPair pair = cylinder_pair(4, 64);
  ASSERT_GE(pair.fine_rest.rows(), kMinParallelItems) << "the loops would not fork";
  const ShellProlongation shell = shell_of(pair);
  const BarycentricProlongation barycentric(pair.coarse.faces, pair.coarse.num_vertices(),
                                            pair.anchors);
  const Positions x = deformed(pair.coarse.vertices, 21);
  const int threads = omp_get_max_threads();
  for (const Prolongation* p :
       {static_cast<const Prolongation*>(&shell), static_cast<const Prolongation*>(&barycentric)}) {
    Positions serial(p->fine_vertices(), 3), parallel(p->fine_vertices(), 3);
    Positions serial_offsets(p->fine_vertices(), 3), parallel_offsets(p->fine_vertices(), 3);
    omp_set_num_threads(1);
    p->apply(x, serial);
    p->offsets(x, serial_offsets);
    omp_set_num_threads(2);
    p->apply(x, parallel);
    p->offsets(x, parallel_offsets);
    EXPECT_TRUE((serial.array() == parallel.array()).all());
    EXPECT_TRUE((serial_offsets.array() == parallel_offsets.array()).all());
  }
  omp_set_num_threads(threads);
}

}  // namespace
