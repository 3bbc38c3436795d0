#pragma once
/// @file Material of a thin shell and the moduli derived from it.

namespace progsim {

/// The discrete bending energy of a shell.
enum class BendingModel {
  /// HingeBending: dihedral angles of interior edges (Grinspun et al. 2003, as in C-IPC and the
  /// PSQ seeds). Softer than the plate on right-triangle grids, and more so under refinement.
  hinge,
  /// MidedgeBending: the mid-edge shape operator (Grinspun et al. 2006; Chen et al. 2018) with
  /// each edge's normal the bisector of its faces. Exact on regular grids, stiff on irregular
  /// ones.
  midedge,
  /// FittedMidedgeBending: the same shape operator with each edge's normal fitted to the
  /// curvature of its two faces' neighbourhoods. Converges on irregular meshes too.
  midedge_fitted,
};

/// Isotropic shell material. SI units.
struct ShellMaterial {
  double youngs_modulus = 1e6;  ///< E, Pa
  /// E_b of the bending term alone, Pa (PSQ supplement Table 1: E_mem, E_bend); 0: E.
  double bending_youngs_modulus = 0.0;
  double poisson_ratio = 0.3;  ///< ν, dimensionless, in [0, 0.5)
  double thickness = 1e-3;     ///< t, m
  double density = 200.0;      ///< ρ, kg/m³ (volumetric; areal density is ρ t)
  double friction = 0.0;       ///< Coulomb μ of the surface (contact pairs mix √(μ_a μ_b))
  double strain_limit = 0.0;   ///< s_max > 1: cap on membrane principal stretches; 0: none
  /// one per scene (all bodies agree); the default is choices.def's
  BendingModel bending_model = BendingModel::hinge;
};

/// Shear modulus μ = E / (2(1+ν)).
inline double shear_modulus(const ShellMaterial& m) {
  return m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
}

/// Plane-stress Lamé λ = E ν / (1 − ν²) (membrane, PSQ footnote 1 / C-IPC §4).
inline double plane_stress_lambda(const ShellMaterial& m) {
  const double nu = m.poisson_ratio;
  return m.youngs_modulus * nu / (1.0 - nu * nu);
}

/// Hinge bending modulus k = E_b t³ / (24(1 − ν²)) (DESIGN.md §2, Grinspun et al. 2003), with
/// E_b = bending_youngs_modulus when set, E otherwise.
inline double hinge_bending_modulus(const ShellMaterial& m) {
  const double t = m.thickness;
  const double nu = m.poisson_ratio;
  const double e = m.bending_youngs_modulus > 0.0 ? m.bending_youngs_modulus : m.youngs_modulus;
  return e * t * t * t / (24.0 * (1.0 - nu * nu));
}

}  // namespace progsim
