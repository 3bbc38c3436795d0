// What a coarse level makes a bent flat sheet cost: the sheet of a bundled scene bent without
// stretching onto cylinders of radius R, each level's vertices placed on the cylinder. Per
// level, the level's own elastics (what a direct coarse solve minimises), PSQ's proxy (the
// finest elastics of the prolonged state, PSQ eq. 2) and the proxy with the tension-field
// membrane ("preview_membrane": "tension_field"); for the finest mesh bent exactly, its
// elastics; and the continuum value k κ² A of a uniformly bent plate (κ = 1/R, D = 2k, the
// normalisation of HingeBending). Membrane energy above the finest mesh's is locking: the
// level cannot bend without stretching. Prints a table, writes CSV.
//
// usage: bench_bent_sheet_energy [scene.json] [csv_path] [R ...]
//        scene: a bundled scene whose first body is a flat, axis-aligned sheet with a
//        "progressive" section (default scenes/psq_cloth_on_sphere.json); R in m (default
//        0.5 0.25 0.16: the 1 m sheet wraps less than a full turn). Only membrane and bending
//        are evaluated.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "energy/tension_field_membrane.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;

namespace {

/// The sheet's plane: the axis along which it bends (u), the normal (n) and its centre.
struct SheetAxes {
  int u = 0, n = 1;
  Vec3 centre = Vec3::Zero();
};

/// The axes of an axis-aligned flat sheet (one bounding-box extent zero); exits otherwise.
SheetAxes sheet_axes(const Positions& rest) {
  const Vec3 lo = rest.colwise().minCoeff(), hi = rest.colwise().maxCoeff();
  const Vec3 extent = hi - lo;
  SheetAxes axes;
  extent.minCoeff(&axes.n);
  if (extent[axes.n] > 1e-9 * extent.maxCoeff()) {
    std::fprintf(stderr, "the scene's first body is not a flat, axis-aligned sheet\n");
    std::exit(2);
  }
  axes.u = (axes.n + 1) % 3;
  axes.centre = 0.5 * (lo + hi);
  return axes;
}

/// The sheet bent onto a cylinder of radius R about an axis across u: arc length along u is
/// kept (u' = R sin(s/R), n' = n − R(1 − cos(s/R)) with s the distance from the centre).
Positions bent(const Positions& rest, const SheetAxes& axes, double radius) {
  Positions out = rest;
  for (Eigen::Index i = 0; i < rest.rows(); ++i) {
    const double s = rest(i, axes.u) - axes.centre[axes.u];
    out(i, axes.u) = axes.centre[axes.u] + radius * std::sin(s / radius);
    out(i, axes.n) = rest(i, axes.n) - radius * (1.0 - std::cos(s / radius));
  }
  return out;
}

/// Σ of the triangle areas (m²).
double total_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vec3 a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
               c = mesh.vertices.row(mesh.faces(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

struct Elastics {
  double membrane = 0.0, bending = 0.0;
};

/// The membrane and bending terms of `problem` at positions x.
Elastics elastics(const Problem& problem, const Positions& x) {
  const Vector dofs = as_dofs(x);
  Elastics e;
  for (const auto& term : problem.terms()) {
    const std::string name = term->name();
    if (name == "membrane") e.membrane = term->value(dofs);
    if (name == "bending") e.bending = term->value(dofs);
  }
  return e;
}

/// The scene with only the shell elastics: no contact, handles, obstacles or gravity.
Scene elastics_only(Scene scene) {
  EffectSet effects;
  effects.enable(Effect::membrane);
  effects.enable(Effect::bending);
  scene.effects = effects;
  scene.handles.clear();
  scene.obstacles.clear();
  scene.ground.enabled = false;
  scene.progressive.proximal = false;
  return scene;
}

int run(int argc, char** argv) {
  const std::string scene_path =
      argc > 1 ? argv[1] : PROGSIM_SOURCE_DIR "/scenes/psq_cloth_on_sphere.json";
  const std::string csv_path = argc > 2 ? argv[2] : "bent_sheet_energy.csv";
  std::vector<double> radii;
  for (int k = 3; k < argc; ++k) radii.push_back(std::stod(argv[k]));
  if (radii.empty()) radii = {0.5, 0.25, 0.16};
  const Scene scene = elastics_only(load_scene_file(scene_path));
  auto hierarchy = std::make_shared<const MeshHierarchy>(build_scene_hierarchy(scene));
  const int finest = static_cast<int>(hierarchy->levels.size()) - 1;
  const SheetAxes axes = sheet_axes(hierarchy->levels[finest].rest.vertices);
  const ShellMaterial& material = scene.bodies[0].material;
  const double area = total_area(hierarchy->levels[finest].rest);
  ProgressiveSimulation psq(scene, hierarchy);
  std::vector<std::unique_ptr<LevelSimulation>> levels;
  for (int l = 0; l <= finest; ++l)
    levels.push_back(std::make_unique<LevelSimulation>(scene, SimulationLevel{hierarchy, l, {}}));
  const Problem& fine_problem = levels[finest]->problem();
  const ShellModel& fine_model = levels[finest]->model();
  const TensionFieldMembrane relaxed(fine_model.rest.vertices, fine_model.rest.faces,
                                     fine_model.face_materials);  // as "preview_membrane" sets it
  std::ofstream csv = bench::open_csv(csv_path);
  csv << "scene,radius,model,level,vertices,membrane_J,bending_J\n";
  std::printf(
      "%s: k κ² A is the continuum bending energy; membrane above the finest mesh's is "
      "locking\n",
      scene.name.c_str());
  std::printf("%7s %-26s %9s %12s %12s\n", "R (m)", "model", "vertices", "membrane J", "bending J");
  for (double radius : radii) {
    auto row = [&](const std::string& model, int level, int vertices, Elastics e) {
      std::printf("%7.3g %-26s %9d %12.4g %12.4g\n", radius, model.c_str(), vertices, e.membrane,
                  e.bending);
      csv << scene.name << ',' << radius << ',' << model << ',' << level << ',' << vertices << ','
          << e.membrane << ',' << e.bending << '\n';
    };
    // Σ_e k θ² ‖ē‖²/(Ā₁+Ā₂) → k κ² A for a uniformly bent sheet (HingeBending).
    row("continuum k κ² A", finest, 0,
        {0.0, hinge_bending_modulus(material) * area / (radius * radius)});
    const Positions exact = bent(hierarchy->levels[finest].rest.vertices, axes, radius);
    row("finest bent exactly", finest, static_cast<int>(exact.rows()),
        elastics(fine_problem, exact));
    for (int l = 0; l < finest; ++l) {
      const Positions x = bent(hierarchy->levels[l].rest.vertices, axes, radius);
      const std::string level = " level " + std::to_string(l);
      row("direct coarse" + level, l, static_cast<int>(x.rows()),
          elastics(levels[l]->problem(), x));
      const Positions prolonged = psq.prolong_to_finest(l, x);
      Elastics proxy = elastics(fine_problem, prolonged);
      row("PSQ proxy" + level, l, static_cast<int>(x.rows()), proxy);
      proxy.membrane = relaxed.value(as_dofs(prolonged));
      row("tension-field proxy" + level, l, static_cast<int>(x.rows()), proxy);
    }
  }
  std::printf("CSV: %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(argc, argv, "bench_bent_sheet_energy [scene.json] [csv_path] [R ...]",
                             run);
}
