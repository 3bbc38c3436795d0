#pragma once
/// @file Work of a uniform pressure on a surface (enclosed-volume potential).
#include <array>
#include <vector>

#include "energy/stencil_term.hpp"

namespace progsim {

/// E(x) = −p V(x), the potential of a uniform pressure p acting on the enclosed volume
///   V(x) = Σ_f (1/6) (x_a − o)·((x_b − o) × (x_c − o))   (divergence theorem),
/// one element per face (a, b, c). Its gradient is −p times the area-weighted vertex normals
/// (∂V/∂x_a = Σ_f (1/6)(x_b − o) × (x_c − o)).
///
/// For a closed, outward-oriented surface V is the enclosed volume and does not depend on the
/// reference point o. For an open surface V is the volume of the cone from o, which is the
/// right potential (up to a constant) when the surface's boundary is held fixed; o is the
/// centroid of the rest vertices.
///
/// Hessian: exact, symmetric and indefinite. Summed per edge, it has only off-diagonal blocks:
/// an edge a → b of face (a, b, c) whose neighbour across the edge is (b, a, d) contributes
/// ∂²E/∂x_a∂x_b = (p/6) [x_c − x_d]× (x_d → o on a boundary edge). The per-face blocks about o,
/// (p/6)[x_c − o]×, would sum to the same matrix but are each as large as p times the body's
/// radius; hessian_values() therefore writes, into each face's slots, half of each of its edges'
/// blocks, and its PSD projection is the exact eigenvalue clamp of every edge's 6×6 matrix
/// [[0, K], [Kᵀ, 0]], K = (p/6)[v]×: ½ [[|K| P, K], [Kᵀ, |K| P]], |K| = |p| ‖v‖/6, P = I − v̂v̂ᵀ.
/// That keeps the projected Hessian as small as the exact one and translation invariant.
class Pressure : public StencilTerm<3> {
 public:
  /// @param rest rest positions (|V| × 3), m (sets |V| and o)
  /// @param faces the surface's triangles (|F| × 3), indices into rest; outward-oriented
  /// @param pressure p, Pa (positive inflates)
  /// @throws Error(invalid_mesh) if faces is a closed surface with negative rest volume
  ///         (oriented inwards) or an index is out of range.
  Pressure(const Positions& rest, const Faces& faces, double pressure = 0.0);

  const char* name() const override { return "pressure"; }
  /// Per face, half of the edge-paired blocks of each of its edges (see the class comment).
  void hessian_values(const Vector& x, bool project_psd, double* values) const override;

  /// Sets p (Pa).
  void set_pressure(double pressure) { pressure_ = pressure; }
  /// p (Pa).
  double pressure() const { return pressure_; }
  /// V(x) (m³) at stacked positions x (3|V|).
  double volume(const Vector& x) const;
  /// True if every edge of the surface has exactly two faces, with opposite orientations.
  bool closed() const { return closed_; }

 protected:
  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  /// The face's own Hessian about o (what the edge pairing redistributes); exact in sum.
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

 private:
  /// Signed volume (1/6) a·(b × c) of the tetrahedron (o, x_a, x_b, x_c), m³.
  double element_volume(const LocalVector& xe) const;

  double pressure_;
  Vec3 origin_;  ///< o: centroid of the rest surface vertices
  bool closed_ = false;
  /// Per face and edge k (corner k → k+1): the vertex opposite that edge in the neighbouring
  /// face, or −1 for a boundary (or non-manifold) edge.
  std::vector<std::array<int, 3>> across_;
};

}  // namespace progsim
