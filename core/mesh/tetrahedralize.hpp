#pragma once
/// @file Tetrahedralizing the solid bounded by a closed triangle surface with CGAL's Delaunay
/// refinement mesher (CGAL Mesh_3 manual: polyhedral domains with features), the
/// tetrahedralization step of the VPD hierarchy (VPD §3.1.2, where TetWild plays this role).
///
/// The output does not keep the input's vertices: Mesh_3 resamples the surface, so the boundary
/// of the tet mesh interpolates the input surface (its vertices lie on it) within
/// facet_distance, as VPD §3.1.2 allows ("strict boundary preservation is not required").
/// Sharp edges (normals turning by more than feature_angle) and their corners are protected
/// and kept exactly, so a box stays a box: its tet mesh's boundary lies on the box's planes.
#include "mesh/tet_mesh.hpp"
#include "mesh/triangle_mesh.hpp"

namespace progsim {

/// Sizing and quality bounds of the tetrahedralization (the CGAL Mesh_3 criteria). A value of
/// 0 takes the default named in its comment.
struct TetrahedralizeOptions {
  /// Upper bound on the circumradius of every tet, m (a regular tet of circumradius R has
  /// edges 1.63·R). 0: the surface's bounding-box diagonal / 20.
  double cell_size = 0.0;
  /// Upper bound on the radius of the surface Delaunay balls of boundary faces, m. 0: cell_size.
  double facet_size = 0.0;
  /// Upper bound on the distance between a boundary face's circumcentre and the input surface,
  /// m: how far the boundary may depart from the input. 0: cell_size / 10.
  double facet_distance = 0.0;
  /// Lower bound on the angles of boundary faces, degrees, in (0, 30] (Mesh_3 terminates for
  /// bounds up to 30°).
  double facet_angle = 25.0;
  /// Upper bound on circumradius / shortest edge of every tet, at least 2 (Mesh_3 terminates
  /// from 2 on). It does not bound slivers; sliver perturbation then removes most.
  double cell_radius_edge_ratio = 3.0;
  /// Upper bound on the length of the segments of protected sharp edges, m. 0: cell_size.
  double edge_size = 0.0;
  /// An input edge whose two face normals differ by more than this angle (degrees, in
  /// [0, 180]) is a sharp feature, protected with its end corners; 180: none.
  double feature_angle = 60.0;
  /// Seed of Mesh_3's random generator: equal inputs and options give identical meshes.
  unsigned seed = 0;
  /// Wall-clock budget of one Mesh_3 run, s (> 0): Mesh_3's facet refinement can cycle without
  /// end on some surfaces (measured: a decimated level of CGAL's elephant with feature_angle 180
  /// ran for 10 min without finishing); it is stopped then.
  double time_limit = 300.0;
};

/// Fills the solid bounded by `closed_surface` with tets (CGAL make_mesh_3 on a
/// Polyhedral_mesh_domain_with_features_3, manifold surface complex, with sliver perturbation;
/// without exudation, which is not deterministic in CGAL 5.5), keeping the cells of the complex,
/// vertices numbered in order of first use and tets positively oriented (tet_mesh.hpp).
/// Deterministic for a given input and options. The number of tets grows like (size / cell_size)³.
/// Throws Error(invalid_mesh) naming the problem if the surface fails validate_mesh, is not
/// closed (an edge on one face only) or intersects itself; Error(invalid_argument) for an
/// option out of range, or sizes too fine for memory (cell_size below the bounding-box diagonal
/// / 215, i.e. about 10⁷ tets; facet and edge sizes below 10⁻³ of it; facet_distance below 10⁻⁶);
/// Error(invalid_mesh) if the result fails validate_tet_mesh (then a smaller cell_size or
/// facet_distance usually helps); Error(internal) if CGAL fails (Mesh_3 asserts "a facet is not
/// in conflict with its refinement point" on surfaces with edges of about 10⁻⁸ of their size,
/// whatever the seed: measured on a decimated level of CGAL's elephant); Error(numerical_failure)
/// if Mesh_3 exceeds time_limit or refines past 2·10⁶ vertices. Nothing is written to disk
/// (Mesh_3's own debug dumps are switched off).
TetMesh tetrahedralize_surface(const TriangleMesh& closed_surface,
                               const TetrahedralizeOptions& options = {});

}  // namespace progsim
