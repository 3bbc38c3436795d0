#pragma once
/// @file The energy both mid-edge bending models share: per face, a constant quadratic form in
/// three edge quantities, E_f = ½ (s − s̄)ᵀ Q_f (s − s̄); the models differ in how s is measured.
#include <vector>

#include "common/types.hpp"
#include "energy/stencil_term.hpp"

namespace progsim {

/// A StencilTerm<K> of one element per face whose energy is ½ (s − s̄)ᵀ Q (s − s̄) with Q
/// constant and PSD (Grinspun et al. 2006's shape operator in Chen et al. 2018's energy, see
/// midedge::face_stiffness). A derived class measures s (edge_values()) and fills faces_.
template <int K>
class EdgeQuadraticBending : public StencilTerm<K> {
 public:
  using typename StencilTerm<K>::LocalVector;
  using typename StencilTerm<K>::LocalMatrix;
  using typename StencilTerm<K>::Stencil;

  const char* name() const override { return "bending"; }

  /// The rest values s̄ (m) of face f's three edge quantities s_i (0 on boundary edges).
  const Vec3& rest_edge_values(int f) const { return faces_[f].rest_values; }

  /// With `on`, the projected Hessian is the Gauss–Newton Jᵀ Q J (J = ∇s): PSD by itself, equal
  /// to the exact Hessian at rest, and free of the second derivatives of s and of an
  /// eigen-decomposition, but without the geometric stiffness of bent faces (as
  /// HingeProjection::gauss_newton; for dynamic steps, whose inertia keeps the Newton matrix
  /// positive definite). Off (the default): the per-element eigenvalue clamp.
  void set_gauss_newton(bool on) { gauss_newton_ = on; }

 protected:
  EdgeQuadraticBending(std::vector<Stencil> stencils, int num_vertices)
      : StencilTerm<K>(std::move(stencils), num_vertices) {}

  /// The face's constant form.
  struct FaceForm {
    Mat3 stiffness;    ///< Q_f (J/m²)
    Vec3 rest_values;  ///< s̄ (m)
  };

  /// s (m) of face e at xe, optionally with ∇s_i (3K) and ∇²s_i (3K × 3K) per edge.
  virtual Vec3 edge_values(int e, const LocalVector& xe, LocalVector* gradients,
                           LocalMatrix* hessians) const = 0;

  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;
  void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

  std::vector<FaceForm> faces_;

 private:
  bool gauss_newton_ = false;
};

extern template class EdgeQuadraticBending<6>;
extern template class EdgeQuadraticBending<12>;

}  // namespace progsim
