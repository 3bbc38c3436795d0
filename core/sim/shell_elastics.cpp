#include "sim/shell_elastics.hpp"

#include "energy/fitted_midedge_bending.hpp"
#include "energy/gravity.hpp"
#include "energy/hinge_bending.hpp"
#include "energy/midedge_bending.hpp"
#include "energy/neo_hookean_membrane.hpp"
#include "energy/pressure.hpp"
#include "energy/tension_field_membrane.hpp"
#include "energy/tet_elastics.hpp"

namespace progsim {
namespace {

/// Faces of body b, renumbered into the merged model.
Faces body_faces(const ShellModel& model, int b) {
  return model.rest.faces.middleRows(model.face_offset[b],
                                     model.face_offset[b + 1] - model.face_offset[b]);
}

/// The faces that are shells, with their materials and hinges: in a scene that mixes shells
/// and solids, the solids' boundary faces carry no membrane or bending (they are no shell), so
/// those terms leave them out rather than evaluate them at zero thickness.
struct ShellSurface {
  Faces faces;
  std::vector<ShellMaterial> materials;
  std::vector<Hinge> hinges;
};

/// What the shell terms are built on: the model's own faces, or those of a ShellSurface.
struct SurfaceView {
  const Faces& faces;
  const std::vector<ShellMaterial>& materials;
  const std::vector<Hinge>& hinges;
};

/// The shell bodies' faces of a `model` with solids, whose bodies are those of `scene`.
ShellSurface shell_surface(const Scene& scene, const ShellModel& model) {
  ShellSurface out;
  Eigen::Index rows = 0;
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b)
    if (!is_solid(scene.bodies[b])) rows += model.face_offset[b + 1] - model.face_offset[b];
  out.faces.resize(rows, 3);
  rows = 0;
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
    if (is_solid(scene.bodies[b])) continue;
    const Faces faces = body_faces(model, b);
    out.faces.middleRows(rows, faces.rows()) = faces;
    rows += faces.rows();
    out.materials.insert(out.materials.end(), model.face_materials.begin() + model.face_offset[b],
                         model.face_materials.begin() + model.face_offset[b + 1]);
  }
  out.hinges = build_topology(out.faces, model.rest.num_vertices()).hinges;
  return out;
}

/// The membrane term of `surface` under the given model.
std::unique_ptr<EnergyTerm> membrane_term(const Positions& rest, const SurfaceView& surface,
                                          MembraneModel membrane) {
  if (membrane == MembraneModel::tension_field)
    return std::make_unique<TensionFieldMembrane>(rest, surface.faces, surface.materials);
  return std::make_unique<NeoHookeanMembrane>(rest, surface.faces, surface.materials);
}

/// The bending term of `surface`, of the model its materials select (validate_scene() makes all
/// shells agree).
std::unique_ptr<EnergyTerm> bending_term(const Positions& rest, const SurfaceView& surface) {
  const BendingModel chosen =
      surface.materials.empty() ? BendingModel::hinge : surface.materials.front().bending_model;
  if (chosen == BendingModel::midedge)
    return std::make_unique<MidedgeBending>(rest, surface.faces, surface.hinges, surface.materials);
  if (chosen == BendingModel::midedge_fitted)
    return std::make_unique<FittedMidedgeBending>(rest, surface.faces, surface.hinges,
                                                  surface.materials);
  return std::make_unique<HingeBending>(rest, surface.faces, surface.hinges, surface.materials);
}

}  // namespace

ShellElastics make_shell_elastics(const Scene& scene, const ShellModel& model, bool with_gravity,
                                  MembraneModel membrane) {
  ShellElastics out;
  const EffectSet& fx = scene.effects;
  const Positions& rest = model.rest.vertices;
  // Only a model with solids needs its shell faces gathered; otherwise the terms take its own.
  const bool gather =
      model.tets.rows() > 0 && (fx.has(Effect::membrane) || fx.has(Effect::bending));
  const ShellSurface shells = gather ? shell_surface(scene, model) : ShellSurface{};
  const SurfaceView surface =
      gather ? SurfaceView{shells.faces, shells.materials, shells.hinges}
             : SurfaceView{model.rest.faces, model.face_materials, model.topology.hinges};
  if (fx.has(Effect::membrane)) out.terms.push_back(membrane_term(rest, surface, membrane));
  if (fx.has(Effect::bending)) {
    out.terms.push_back(bending_term(rest, surface));
    auto* hinge = dynamic_cast<HingeBending*>(out.terms.back().get());
    // In a dynamic step the inertia M/h² keeps the Newton matrix positive definite, so hinges
    // take the Gauss–Newton block 2c ∇θ∇θᵀ instead of the clamped exact one (HingeProjection;
    // issue 33 §4). Measured: a 3721-vertex cloth dropped on a sphere (bench_contact_breakdown,
    // 50 steps) 117.7 s → 96.5 s with 836 → 820 Newton iterations; the bundled cloth_on_sphere
    // 37.9 s → 34.4 s (1093 → 1114). Quasistatic solves keep the clamp: there the dropped
    // curvature term is the only stiffness a bent, unloaded shell has.
    if (hinge && scene.mode == StepMode::dynamic)
      hinge->set_projection(HingeProjection::gauss_newton);
    if (scene.mode == StepMode::dynamic) {  // the mid-edge models' Jᵀ Q J likewise
      if (auto* midedge = dynamic_cast<EdgeQuadraticBending<6>*>(out.terms.back().get()))
        midedge->set_gauss_newton(true);
      if (auto* fitted = dynamic_cast<EdgeQuadraticBending<12>*>(out.terms.back().get()))
        fitted->set_gauss_newton(true);
    }
  }
  if (fx.has(Effect::elasticity))  // VPD §3.1.3: the volumetric bodies' own elastics
    out.terms.push_back(std::make_unique<TetElastics>(rest, model.tets, model.tet_materials));
  if (with_gravity && fx.has(Effect::gravity)) {
    auto gravity = std::make_unique<Gravity>(model.vertex_masses, scene.gravity);
    out.gravity = gravity.get();
    out.terms.push_back(std::move(gravity));
  }
  if (fx.has(Effect::pressure)) {
    for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
      if (scene.bodies[b].pressure == 0.0) continue;
      auto term = std::make_unique<Pressure>(rest, body_faces(model, b), 0.0);
      out.pressures.emplace_back(term.get(), b);
      out.terms.push_back(std::move(term));
    }
  }
  return out;
}

}  // namespace progsim
