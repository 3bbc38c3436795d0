#pragma once
/// @file Material of a volumetric (tetrahedral) solid and the Lamé parameters derived from it.

namespace progsim {

/// The isotropic hyperelastic energy density of a solid (VPD §3.1.3 footnote 1: "St.
/// Venant–Kirchhoff, Neo-Hookean, or co-rotational elasticity").
enum class SolidModel {
  /// ψ = μ/2 (tr FᵀF − 3) − μ ln J + λ/2 (ln J)² (Bonet and Wood 2008, eq. 6.27; IPC's
  /// volumetric default). Infinite for J ≤ 0: it resists inversion by itself.
  neo_hookean,
  /// ψ = μ tr E² + λ/2 (tr E)², E = (FᵀF − I)/2 (Bonet and Wood 2008, eq. 6.11). Softens in
  /// strong compression; the inversion-free line search keeps J > 0.
  stvk,
  /// Fixed corotated: ψ = μ ‖F − R‖² + λ/2 (J − 1)², R the rotation of F's polar decomposition
  /// (Stomakhin et al. 2012, eq. 4).
  corotated,
};

/// Isotropic solid. SI units.
struct SolidMaterial {
  double youngs_modulus = 1e5;  ///< E, Pa
  double poisson_ratio = 0.3;   ///< ν, dimensionless, in (−1, 0.5)
  double density = 1000.0;      ///< ρ, kg/m³
  SolidModel model = SolidModel::neo_hookean;
};

/// Lamé parameters of a 3D isotropic material, Pa.
struct LameParameters {
  double mu;      ///< shear modulus μ = E / (2(1 + ν))
  double lambda;  ///< λ = E ν / ((1 + ν)(1 − 2ν))
};

/// μ and λ of a 3D material (Bonet and Wood 2008, eq. 4.32 with the small-strain limit).
inline LameParameters lame_parameters(const SolidMaterial& m) {
  const double e = m.youngs_modulus, nu = m.poisson_ratio;
  return {e / (2.0 * (1.0 + nu)), e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))};
}

}  // namespace progsim
