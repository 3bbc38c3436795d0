#pragma once
/// @file Joint flattening of the patch around a collapsing edge (the intrinsic map of PSQ §4.3,
/// after Liu et al. 2021, "Surface multigrid via intrinsic prolongation"): the faces before and
/// after the collapse are mapped onto one convex polygon by a Tutte-style map with mean-value
/// weights (Floater 2003, "Mean value coordinates"), bijective for a convex boundary, so a point
/// of a before face can be re-expressed in an after face.
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// The faces around an edge (a, b) before and after collapsing it (local vertex ids).
struct CollapsePatch {
  std::vector<Vec3> points;                ///< rest positions of the patch vertices before the
                                           ///< collapse (points.size())
  std::vector<std::array<int, 3>> before;  ///< every face incident to a or b, oriented (CCW)
  std::vector<std::array<int, 3>> after;   ///< the faces after the collapse: the vertex `a` is
                                           ///< the merged vertex, `b` no longer appears
  int a = -1, b = -1;                      ///< the collapsing edge's endpoints
  Vec3 merged_point;                       ///< position of the merged vertex after the collapse
};

/// How a patch was flattened.
enum class FlatteningKind {
  /// Projection onto the plane of the patch's area-weighted normal: nearly isometric on the
  /// gently curved patches decimation sees, exact on planar ones, so tracked points move as
  /// little as the geometry does (the role of Liu et al. 2021's conformal flattening).
  projected,
  /// Convex boundary (unit circle by arclength) and mean-value interior (Floater 2003):
  /// bijective for every disk-shaped patch, but distorting.
  convex,
};

/// A joint flattening: uv of every patch vertex before the collapse, and the uv of the merged
/// vertex after it (all other vertices keep their uv).
struct JointFlattening {
  std::vector<Vec2> uv;  ///< (points.size()), before the collapse
  Vec2 merged_uv;        ///< uv of vertex a in the `after` faces
  FlatteningKind kind = FlatteningKind::convex;
};

/// Flattens the before and after faces of `patch` onto one polygon, trying the projected
/// flattening first and the convex one where the projection folds. Returns std::nullopt when
/// neither is valid. Valid means: the before faces' boundary is a single simple loop and the
/// after faces' boundary is that loop with b merged into a; all values finite; every
/// before/after uv triangle has signed area > 1e-12 × the polygon area; both boundary polygons
/// are simple and interior vertices are wound once, so both piecewise-linear maps are
/// bijective. When a and b both lie on the loop, b goes on the chord between its loop
/// neighbours so the polygon is the same before and after; where that folds (a border corner
/// such as an ear), the projected flattening leaves b in place and the collapse cuts the corner
/// off (points there move onto the new border side). The merged vertex takes the uv of a or b
/// when one of them is on the loop, else its own projection (projected) or the mean-value
/// average of its after-face neighbours (convex). Throws Error(invalid_argument) for a face or
/// endpoint id outside [0, points.size()).
std::optional<JointFlattening> flatten_collapse(const CollapsePatch& patch);

/// As flatten_collapse(patch), with only the given kind of flattening.
std::optional<JointFlattening> flatten_collapse(const CollapsePatch& patch, FlatteningKind kind);

/// Point location after a collapse: the point at barycentric weights `w` (3) of the corners of
/// patch.before[before_face] is mapped to uv and located in the after faces. Returns (index into
/// patch.after, barycentric weights (3) of its corners), weights clamped to >= 0 and renormalised
/// to sum 1, choosing the after face that maximises the smallest weight (robust for points on
/// shared edges). `flat` must be a valid flattening of `patch`. Throws Error(invalid_argument)
/// for a before_face out of range, a flattening of another size, or no usable after face.
std::pair<int, Vec3> relocate_point(const CollapsePatch& patch, const JointFlattening& flat,
                                    int before_face, const Vec3& w);

}  // namespace progsim
