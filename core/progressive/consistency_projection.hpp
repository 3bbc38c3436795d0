#pragma once
/// @file The geometric consistency of a level with the next coarser one (PD++'s metric, VPD
/// App. C eq. 19): how well the coarser frame captures the finer one's bulk motion.
#include <Eigen/SparseCholesky>

#include "common/types.hpp"
#include "hierarchy/prolongation.hpp"

namespace progsim {

/// Π = (UᵀMU)⁻¹UᵀM, the mass-weighted least-squares projection of a fine state onto the coarse
/// level through the intrinsic part U of the prolongation (the projection VPD App. C builds from
/// U; its formula was lost from our copy, so the choice is ours), and the distance of the result
/// from a coarse state. UᵀMU is factorized once. Coarse vertices no fine vertex depends on (zero
/// columns of U, as a coarse tet level can have) are left out of the projection and the norm.
class ConsistencyProjection {
 public:
  /// `intrinsic` U (n_fine × n_coarse), `fine_masses` M (n_fine), `coarse_masses` (n_coarse) for
  /// the norm. Throws Error(numerical_failure) if UᵀMU is singular.
  ConsistencyProjection(const ProlongationMatrix& intrinsic, const Eigen::VectorXd& fine_masses,
                        Eigen::VectorXd coarse_masses);
  /// ‖Π x_fine − x_coarse‖ mass-weighted RMS over the coarse vertices (m); both as DOFs (3|V|).
  double distance(const Vector& fine, const Vector& coarse) const;

 private:
  Eigen::SparseMatrix<double> weighted_transpose_;             ///< UᵀM (n_coarse × n_fine)
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> normal_;  ///< UᵀMU
  Eigen::VectorXd coarse_masses_;
};

}  // namespace progsim
