#pragma once
/// @file Strain-limit correction of a refined start (PSQ, Zhang et al. 2023, §4.4.5 and
/// Algorithm 2 line 9): safe refinement leaves the new level intersection-free near the prolonged
/// target, but its new vertices can stretch faces far beyond their strain limit. With the
/// coarser level's vertices held (PSQ fixes them, as PCS fixes the even vertices of a
/// subdivision), the new vertices move as little as they can while every face comes under its
/// limit, the contact barrier and CCD keeping the state intersection-free.
#include <memory>
#include <vector>

#include "contact/contact_potential.hpp"
#include "sim/shell_model.hpp"

namespace progsim {

/// What a strain-limit correction did.
struct StrainCorrectionStats {
  int strained_faces = 0;    ///< faces at or beyond their strain limit before it
  int over_limit_faces = 0;  ///< … after it (faces whose vertices are all held stay)
  int newton_iterations = 0;
  double stretch_before = 0.0;  ///< largest σ₁ over the limited faces before (0: no limit)
  double stretch_after = 0.0;   ///< … after
  /// The coarser level's vertices had to move too: with them held, some face could not come
  /// under its limit.
  bool moved_coarse_vertices = false;
};

/// Parameters of the correction's penalty continuation.
struct StrainCorrectionSettings {
  /// Each face is drawn toward t_f = s_f − ŝ/2 (inside the barrier's band, under the limit).
  double target_band_fraction = 0.5;
  double first_stiffness = 1e2;  ///< ρ of the first solve, relative to the proximity
  double growth = 10.0;          ///< ρ grows by this factor while a movable face is over
  double max_stiffness = 1e8;    ///< … up to this
  int max_iterations = 50;       ///< Newton iterations per solve
  /// Newton tolerance (NewtonSettings::tolerance): the faces only need to come under their
  /// limits, not to a tight minimum.
  double tolerance = 1e-4;
};

/// Corrects x (3|V| of `model`, intersection-free) in place so that every face with a vertex
/// not in `fixed` (3|V| DOF mask) comes under its strain limit s_f (ShellMaterial::strain_limit):
/// minimises
///   ½ Σ_i (A_i/Ā) ‖x_i − x_i⁰‖² + ρ Σ_f Ā_f Σ_i (σ_i,f − t_f)₊²  (+ contact barrier)
/// over the free DOFs (A_i the lumped rest area, Ā the mean face area, x⁰ the start), raising ρ
/// tenfold until no face with a free vertex is at or beyond its limit, or a stiffer pull brought
/// no face under it (held vertices or contact keep the rest over; they are counted). `contact`
/// (nullable) is the level's contact barrier with its obstacles placed; pairs already within their
/// offsets are accepted (ContactPotential::fit_offsets) and every step is CCD-bounded, so nothing
/// crosses. Without a strain-limited face, or with none beyond its limit, x is unchanged.
/// @param length the level's length scale (Newton tolerance)
/// @throws Error(invalid_argument) if x or fixed is not 3|V| long.
StrainCorrectionStats correct_strain(const ShellModel& model, const std::vector<bool>& fixed,
                                     std::unique_ptr<ContactPotential> contact, double length,
                                     Vector& x, const StrainCorrectionSettings& settings = {});

}  // namespace progsim
