#pragma once
/// @file Basic array types shared by every part of progsim.
#include <Eigen/Core>

namespace progsim {

/// Vertex positions, one row per vertex: (|V| × 3), row-major, metres.
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// Triangle vertex indices, one row per face: (|F| × 3), row-major.
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// Tetrahedron vertex indices, one row per tet: (|T| × 4), row-major.
using Tets = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;
/// Stacked degrees of freedom (x0 y0 z0 x1 ...): (3|V|).
using Vector = Eigen::VectorXd;
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

/// View a (|V| × 3) row-major position array as a flat DOF vector (3|V|), no copy.
inline Eigen::Map<const Vector> as_dofs(const Positions& p) {
  return Eigen::Map<const Vector>(p.data(), p.size());
}

/// View a flat DOF vector (3|V|) as a (|V| × 3) position array, no copy.
inline Eigen::Map<const Positions> as_positions(const Vector& x) {
  return Eigen::Map<const Positions>(x.data(), x.size() / 3, 3);
}

/// True when two arrays have the same shape and entries. Eigen's == asserts on a shape
/// mismatch (and reads out of bounds under NDEBUG), so compare shapes first.
template <class A, class B>
bool same_array(const Eigen::DenseBase<A>& a, const Eigen::DenseBase<B>& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a.derived() == b.derived());
}

}  // namespace progsim
