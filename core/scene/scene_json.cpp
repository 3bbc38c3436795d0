#include "scene/scene_json.hpp"

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_generators.hpp"
#include "mesh/tet_mesh_io.hpp"
#include "mesh/tet_mesh_validation.hpp"
#include "mesh/tetrahedralize.hpp"
#include "scene/choice_table.hpp"
#include "scene/parameter_table.hpp"

namespace progsim {
namespace {

using Json = nlohmann::json;

[[noreturn]] void scene_error(const std::string& where, const std::string& what) {
  fail(Status::invalid_scene, where + ": " + what);
}

void expect_object(const Json& j, const std::string& where) {
  if (!j.is_object())
    scene_error(where, "must be a JSON object, got " + std::string(j.type_name()));
}

/// Rejects keys not in `allowed` (catches typos such as "thicknes").
void expect_keys(const Json& j, const std::string& where,
                 std::initializer_list<const char*> allowed) {
  expect_object(j, where);
  for (const auto& item : j.items()) {
    bool known = false;
    std::string list;
    for (const char* key : allowed) {
      known = known || item.key() == key;
      list += std::string(list.empty() ? "" : ", ") + key;
    }
    if (!known) scene_error(where, "unknown key '" + item.key() + "' (allowed: " + list + ")");
  }
}

const Json& require(const Json& j, const char* key, const std::string& where) {
  if (!j.contains(key)) scene_error(where, std::string("missing required field '") + key + "'");
  return j.at(key);
}

double number(const Json& j, const std::string& where) {
  if (!j.is_number()) scene_error(where, "must be a number, got " + std::string(j.type_name()));
  return j.get<double>();
}

double number_or(const Json& j, const char* key, double fallback, const std::string& where) {
  return j.contains(key) ? number(j.at(key), where + "." + key) : fallback;
}

int integer(const Json& j, const std::string& where) {
  if (!j.is_number_integer()) scene_error(where, "must be a whole number");
  return j.get<int>();
}

Vec3 vec3(const Json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) scene_error(where, "must be an array of 3 numbers");
  Vec3 v;
  for (int k = 0; k < 3; ++k) v[k] = number(j[k], where + "[" + std::to_string(k) + "]");
  if (!v.allFinite()) scene_error(where, "must be finite");
  return v;
}

Vec3 vec3_or(const Json& j, const char* key, const Vec3& fallback, const std::string& where) {
  return j.contains(key) ? vec3(j.at(key), where + "." + key) : fallback;
}

/// Reads a table parameter j[name] (default from the table), checks its range.
double parameter(const Json& j, const char* group, const char* name, const std::string& where) {
  const ParameterSpec& spec = find_parameter(group, name);
  const std::string label = where + "." + name;
  const double value = j.contains(name) ? number(j.at(name), label) : spec.default_value;
  check_parameter(spec, value, label);
  return value;
}

/// The most quads a grid or cylinder generator may make (1e8 triangles, about 4 GB of mesh).
constexpr long kMaxGeneratedQuads = 50'000'000;

TriangleMesh generated_mesh(const Json& j, const std::string& where) {
  const std::string kind = j.at("generator").get<std::string>();
  if (kind == "grid") {
    expect_keys(j, where, {"generator", "width", "height", "nx", "ny"});
    const int nx = integer(require(j, "nx", where), where + ".nx");
    const int ny = integer(require(j, "ny", where), where + ".ny");
    const double w = number(require(j, "width", where), where + ".width");
    const double h = number(require(j, "height", where), where + ".height");
    if (nx < 1 || ny < 1 || nx * static_cast<long>(ny) > kMaxGeneratedQuads)
      scene_error(where, "nx and ny must be at least 1 and nx·ny at most 5e7");
    if (!(w > 0.0) || !(h > 0.0)) scene_error(where, "width and height must be positive");
    return make_grid(w, h, nx, ny);
  }
  if (kind == "sphere") {
    expect_keys(j, where, {"generator", "radius", "subdivisions"});
    const double r = number(require(j, "radius", where), where + ".radius");
    const int s = integer(require(j, "subdivisions", where), where + ".subdivisions");
    if (!(r > 0.0) || s < 0 || s > 9)
      scene_error(where, "radius must be > 0, subdivisions in [0, 9]");
    return make_sphere(r, s);
  }
  if (kind == "cylinder") {
    expect_keys(j, where,
                {"generator", "radius", "length", "angle_degrees", "n_around", "n_along"});
    const double r = number(require(j, "radius", where), where + ".radius");
    const double len = number(require(j, "length", where), where + ".length");
    const double deg = number_or(j, "angle_degrees", 360.0, where);
    const int na = integer(require(j, "n_around", where), where + ".n_around");
    const int nl = integer(require(j, "n_along", where), where + ".n_along");
    if (!(r > 0.0) || !(len > 0.0) || !(deg > 0.0 && deg <= 360.0) || na < 3 || nl < 1 ||
        na * static_cast<long>(nl) > kMaxGeneratedQuads)
      scene_error(where,
                  "need radius > 0, length > 0, angle_degrees in (0, 360], n_around ≥ 3, "
                  "n_along ≥ 1 and n_around·n_along at most 5e7");
    return make_cylinder(r, len, deg * kPi / 180.0, na, nl);
  }
  if (kind == "box") {
    expect_keys(j, where, {"generator", "size"});
    const Vec3 size = vec3(require(j, "size", where), where + ".size");
    if (!(size.array() > 0.0).all()) scene_error(where + ".size", "must be positive");
    return make_box(size);
  }
  scene_error(
      where + ".generator",
      "unknown generator '" + kind + "' (known: grid, sphere, cylinder, box; tet_box for solids)");
}

TriangleMesh body_mesh(const Json& j, const std::string& where, const std::string& base_dir) {
  expect_object(j, where);
  if (j.contains("file")) {
    expect_keys(j, where, {"file"});
    std::filesystem::path path = j.at("file").get<std::string>();
    if (path.is_relative()) path = std::filesystem::path(base_dir) / path;
    return read_mesh(path.string());
  }
  if (j.contains("generator")) return generated_mesh(j, where);
  scene_error(where, "needs either 'file' or 'generator'");
}

/// A body's geometry as Body holds it: a surface, or a solid's vertices, boundary and tets.
struct BodyGeometry {
  TriangleMesh mesh;
  Tets tets;
};

/// A solid from its tets, validated (naming `label`) before its boundary is extracted.
BodyGeometry solid_geometry(TetMesh volume, const std::string& label) {
  validate_tet_mesh(volume, label);
  BodyGeometry g;
  g.mesh.faces = tet_boundary_faces(volume);
  g.mesh.vertices = std::move(volume.vertices);
  g.tets = std::move(volume.tets);
  return g;
}

/// {"generator": "tet_box", "size": [x, y, z], "cells": [nx, ny, nz]}: make_tet_box.
TetMesh generated_tets(const Json& j, const std::string& where) {
  expect_keys(j, where, {"generator", "size", "cells"});
  const Vec3 size = vec3(require(j, "size", where), where + ".size");
  if (!(size.array() > 0.0).all()) scene_error(where + ".size", "must be positive");
  const Json& cells = require(j, "cells", where);
  if (!cells.is_array() || cells.size() != 3)
    scene_error(where + ".cells", "must be three whole numbers [nx, ny, nz]");
  int n[3];
  for (int k = 0; k < 3; ++k) {
    if (!cells[k].is_number_integer() || cells[k].get<long>() < 1 || cells[k].get<long>() > 1000)
      scene_error(where + ".cells", "must be three whole numbers in [1, 1000]");
    n[k] = cells[k].get<int>();
  }
  return make_tet_box(size, n[0], n[1], n[2]);
}

/// "tetrahedralize": {"cell_size", "facet_size", "facet_distance", "facet_angle",
/// "cell_radius_edge_ratio", "edge_size", "feature_angle", "time_limit"}, each optional
/// (TetrahedralizeOptions).
TetrahedralizeOptions tetrahedralize_options(const Json& j, const std::string& where) {
  expect_object(j, where);
  expect_keys(j, where,
              {"cell_size", "facet_size", "facet_distance", "facet_angle", "cell_radius_edge_ratio",
               "edge_size", "feature_angle", "time_limit"});
  TetrahedralizeOptions o;
  o.cell_size = number_or(j, "cell_size", o.cell_size, where);
  o.facet_size = number_or(j, "facet_size", o.facet_size, where);
  o.facet_distance = number_or(j, "facet_distance", o.facet_distance, where);
  o.facet_angle = number_or(j, "facet_angle", o.facet_angle, where);
  o.cell_radius_edge_ratio =
      number_or(j, "cell_radius_edge_ratio", o.cell_radius_edge_ratio, where);
  o.edge_size = number_or(j, "edge_size", o.edge_size, where);
  o.feature_angle = number_or(j, "feature_angle", o.feature_angle, where);
  o.time_limit = number_or(j, "time_limit", o.time_limit, where);
  return o;
}

/// The solid a closed surface (a file or generator, `j` without its "tetrahedralize") bounds,
/// filled with tets by CGAL Mesh_3; errors name `where`.
BodyGeometry filled_geometry(const Json& j, const std::string& where, const std::string& base_dir) {
  Json surface = j;
  surface.erase("tetrahedralize");
  const TetrahedralizeOptions options =
      tetrahedralize_options(j.at("tetrahedralize"), where + ".tetrahedralize");
  const TriangleMesh closed = body_mesh(surface, where, base_dir);
  try {
    return solid_geometry(tetrahedralize_surface(closed, options), where);
  } catch (const Error& e) {  // keep the status (invalid_mesh for an open surface), add where
    fail(e.status(), where + ".tetrahedralize: " + e.what());
  }
}

/// A body's "mesh": a tet mesh file (.mesh, .msh, .node/.ele), the tet_box generator or any
/// closed surface with "tetrahedralize" make a solid; any other file or generator a shell
/// (body_mesh).
BodyGeometry body_geometry(const Json& j, const std::string& where, const std::string& base_dir) {
  expect_object(j, where);
  if (j.contains("tetrahedralize")) return filled_geometry(j, where, base_dir);
  if (j.contains("file") && j.at("file").is_string()) {
    std::filesystem::path path = j.at("file").get<std::string>();
    if (path.is_relative()) path = std::filesystem::path(base_dir) / path;
    if (is_tet_mesh_path(path.string())) {
      expect_keys(j, where, {"file"});
      return solid_geometry(read_tet_mesh(path.string()), path.string());
    }
  }
  if (j.value("generator", std::string()) == "tet_box")
    return solid_geometry(generated_tets(j, where), where);
  return {body_mesh(j, where, base_dir), Tets()};
}

void apply_transform(const Json& j, const std::string& where, Positions& p) {
  expect_keys(j, where, {"scale", "rotate", "translate"});
  const double scale = number_or(j, "scale", 1.0, where);
  if (!(scale > 0.0) || !std::isfinite(scale)) scene_error(where + ".scale", "must be positive");
  Mat3 rotation = Mat3::Identity();
  if (j.contains("rotate")) {
    const Json& r = j.at("rotate");
    expect_keys(r, where + ".rotate", {"axis", "degrees"});
    const Vec3 axis = vec3(require(r, "axis", where + ".rotate"), where + ".rotate.axis");
    if (!(axis.norm() > 0.0)) scene_error(where + ".rotate.axis", "must be non-zero");
    const double deg = number(require(r, "degrees", where + ".rotate"), where + ".rotate.degrees");
    rotation = Eigen::AngleAxisd(deg * kPi / 180.0, axis.normalized()).toRotationMatrix();
  }
  const Vec3 shift = vec3_or(j, "translate", Vec3::Zero(), where);
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    p.row(i) = (rotation * (scale * p.row(i).transpose()) + shift).transpose();
}

/// The option j[key] names among `known` (name, value), the first when j has no key;
/// scene_error naming the known ones otherwise.
template <typename Enum>
Enum choice(const Json& j, const std::string& key, const std::string& where,
            std::initializer_list<std::pair<const char*, Enum>> known) {
  const std::string name = j.value(key, std::string(known.begin()->first));
  std::string names;
  for (const auto& [option, value] : known) {
    if (name == option) return value;
    names += (names.empty() ? "" : ", ") + std::string(option);
  }
  scene_error(where + "." + key, "unknown '" + name + "' (known: " + names + ")");
}

/// The named option group.key of the choice table (choices.def) that j[key] gives, the
/// table's default when j has no key; scene_error naming the known ones otherwise.
template <typename Enum>
Enum table_choice(const Json& j, const char* group, const char* key, const std::string& where) {
  const ChoiceSpec& spec = find_choice(group, key);
  if (!j.contains(key)) return static_cast<Enum>(spec.default_index);
  const std::string label = where + "." + key;
  if (!j.at(key).is_string()) scene_error(label, "must be a string, one of the known options");
  return static_cast<Enum>(choice_index(spec, j.at(key).get<std::string>(), label));
}

ShellMaterial material(const Json& j, const std::string& where) {
  expect_keys(j, where,
              {"youngs_modulus", "bending_youngs_modulus", "poisson_ratio", "thickness", "density",
               "friction", "strain_limit", "bending_model", "solid_model"});
  ShellMaterial m;
  m.youngs_modulus = parameter(j, "material", "youngs_modulus", where);
  m.bending_youngs_modulus = parameter(j, "material", "bending_youngs_modulus", where);
  m.poisson_ratio = parameter(j, "material", "poisson_ratio", where);
  m.thickness = parameter(j, "material", "thickness", where);
  m.density = parameter(j, "material", "density", where);
  m.friction = parameter(j, "material", "friction", where);
  m.strain_limit = parameter(j, "material", "strain_limit", where);
  m.bending_model = table_choice<BendingModel>(j, "material", "bending_model", where);
  return m;
}

Body body(const Json& j, const std::string& where, const std::string& base_dir) {
  expect_keys(j, where,
              {"name", "mesh", "transform", "material", "pressure", "pressure_ramp", "velocity"});
  Body b;
  b.name = j.value("name", where);
  BodyGeometry geometry = body_geometry(require(j, "mesh", where), where + ".mesh", base_dir);
  b.mesh = std::move(geometry.mesh);
  b.tets = std::move(geometry.tets);
  if (j.contains("transform"))
    apply_transform(j.at("transform"), where + ".transform", b.mesh.vertices);
  const Json material_json = j.contains("material") ? j.at("material") : Json::object();
  b.material = material(material_json, where + ".material");
  b.solid_model =
      table_choice<SolidModel>(material_json, "material", "solid_model", where + ".material");
  b.pressure = number_or(j, "pressure", 0.0, where);
  b.pressure_ramp = number_or(j, "pressure_ramp", 0.0, where);
  b.velocity = vec3_or(j, "velocity", Vec3::Zero(), where);
  return b;
}

int body_index(const Json& j, const std::vector<Body>& bodies, const std::string& where) {
  if (j.is_number_integer()) return j.get<int>();
  if (j.is_string())
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (bodies[b].name == j.get<std::string>()) return static_cast<int>(b);
  scene_error(where, "names no body (use a body's name or index)");
}

VertexBox vertex_box(const Json& j, const std::string& where) {
  expect_keys(j, where, {"min", "max"});
  return {vec3(require(j, "min", where), where + ".min"),
          vec3(require(j, "max", where), where + ".max")};
}

MotionKeyframe motion_keyframe(const Json& j, const std::string& where) {
  expect_keys(j, where, {"time", "translation", "axis", "angle"});
  MotionKeyframe key;
  key.time = number(require(j, "time", where), where + ".time");
  key.translation = vec3_or(j, "translation", key.translation, where);
  key.axis = vec3_or(j, "axis", key.axis, where);
  key.angle = number_or(j, "angle", key.angle, where);
  return key;  // times, axes: validate_motion()
}

/// A motion's "keyframes" and "interpolation", exclusive with its velocities and axis.
void motion_keyframes(const Json& j, const std::string& where, HandleMotion& m) {
  for (const char* rate : {"velocity", "angular_velocity", "axis"})
    if (j.contains(rate))
      scene_error(where, std::string("give either 'keyframes' or '") + rate + "', not both");
  const Json& keys = j.at("keyframes");
  if (!keys.is_array() || keys.empty())
    scene_error(where + ".keyframes",
                "must be a non-empty array of {\"time\", \"translation\", \"axis\", \"angle\"}");
  for (std::size_t k = 0; k < keys.size(); ++k)
    m.keyframes.push_back(
        motion_keyframe(keys[k], where + ".keyframes[" + std::to_string(k) + "]"));
  m.interpolation = choice<Interpolation>(j, "interpolation", where,
                                          {{"linear", Interpolation::linear},
                                           {"hold", Interpolation::hold},
                                           {"smooth", Interpolation::smooth}});
}

HandleMotion motion(const Json& j, const std::string& where) {
  expect_keys(
      j, where,
      {"velocity", "axis", "center", "angular_velocity", "offset", "keyframes", "interpolation"});
  HandleMotion m;
  if (j.contains("keyframes"))
    motion_keyframes(j, where, m);
  else if (j.contains("interpolation"))
    scene_error(where + ".interpolation", "needs 'keyframes' to interpolate between");
  m.velocity = vec3_or(j, "velocity", Vec3::Zero(), where);
  m.axis = vec3_or(j, "axis", Vec3::UnitZ(), where);
  m.center = vec3_or(j, "center", Vec3::Zero(), where);
  m.angular_velocity = number_or(j, "angular_velocity", 0.0, where);
  m.offset = vec3_or(j, "offset", Vec3::Zero(), where);
  if (!(m.axis.norm() > 0.0)) scene_error(where + ".axis", "must be non-zero");
  m.axis.normalize();
  return m;
}

/// "axes": the letters of the coordinates a handle prescribes, e.g. "xz" (HandleAxis bits); ""
/// only where `allow_none` (a rotation support's free translation).
unsigned handle_axes(const Json& j, const std::string& where, bool allow_none) {
  if (!j.is_string()) scene_error(where, "must be a string of axes such as \"xz\"");
  const std::string letters = j.get<std::string>();
  unsigned axes = 0;
  for (char c : letters) {
    const std::size_t k = std::string("xyz").find(c);
    if (k == std::string::npos || (axes & (1u << k)) != 0)
      scene_error(where, "'" + letters + "' must list each of x, y, z at most once");
    axes |= 1u << k;
  }
  if (axes == 0 && !allow_none)
    scene_error(where, "holds no axis (give e.g. \"xyz\" or \"y\"; \"\" only with \"support\": " +
                           std::string("\"rotation\")"));
  return axes;
}

/// A body and vertices of it, as handles and loads select them.
struct VertexSelection {
  int body = 0;
  std::vector<int> vertices;
  std::optional<VertexBox> region;  ///< set when a box alone selected them
};

/// j's "body" (name or index) and the vertices its "vertices" list and its "box" select.
VertexSelection vertex_selection(const Json& j, const std::vector<Body>& bodies,
                                 const std::string& where) {
  VertexSelection s;
  s.body = body_index(require(j, "body", where), bodies, where + ".body");
  if (s.body < 0 || s.body >= static_cast<int>(bodies.size()))
    scene_error(where + ".body", "index " + std::to_string(s.body) + " does not exist");
  if (j.contains("vertices")) {
    const Json& v = j.at("vertices");
    if (!v.is_array()) scene_error(where + ".vertices", "must be an array of vertex indices");
    for (std::size_t k = 0; k < v.size(); ++k)
      s.vertices.push_back(integer(v[k], where + ".vertices[" + std::to_string(k) + "]"));
  }
  if (j.contains("box")) {
    const VertexBox box = vertex_box(j.at("box"), where + ".box");
    const std::vector<int> boxed = box.select(bodies[s.body].mesh.vertices);
    if (!j.contains("vertices")) s.region = box;
    s.vertices.insert(s.vertices.end(), boxed.begin(), boxed.end());
  }
  if (s.vertices.empty())
    scene_error(where, "selects no vertices (give 'vertices' or a 'box' that contains some)");
  return s;
}

Handle handle(const Json& j, const std::vector<Body>& bodies, const std::string& where) {
  expect_keys(j, where, {"body", "vertices", "box", "motion", "axes", "support"});
  Handle h;
  VertexSelection selection = vertex_selection(j, bodies, where);
  h.body = selection.body;
  h.vertices = std::move(selection.vertices);
  h.region = selection.region;
  if (j.contains("motion")) h.motion = motion(j.at("motion"), where + ".motion");
  h.support = choice<HandleSupport>(
      j, "support", where,
      {{"position", HandleSupport::position}, {"rotation", HandleSupport::rotation}});
  const bool rotation = h.support == HandleSupport::rotation;
  if (rotation) h.axes = 0;  // a rotation support translates freely unless "axes" holds some
  if (j.contains("axes")) h.axes = handle_axes(j.at("axes"), where + ".axes", rotation);
  return h;
}

/// A load: {"body", "vertices"/"box", "force", "distribution", "moment": {"axis", "magnitude"},
/// "normal_force", "ramp"}, with a force, a moment, a normal force or several.
Load load(const Json& j, const std::vector<Body>& bodies, const std::string& where) {
  expect_keys(
      j, where,
      {"body", "vertices", "box", "force", "distribution", "moment", "normal_force", "ramp"});
  if (!j.contains("force") && !j.contains("moment") && !j.contains("normal_force"))
    scene_error(where, "needs a 'force', a 'moment', a 'normal_force' or several");
  Load l;
  VertexSelection selection = vertex_selection(j, bodies, where);
  l.body = selection.body;
  l.vertices = std::move(selection.vertices);
  l.region = selection.region;
  l.force = vec3_or(j, "force", Vec3::Zero(), where);
  l.distribution = choice<LoadDistribution>(j, "distribution", where,
                                            {{"mass", LoadDistribution::mass},
                                             {"area", LoadDistribution::area},
                                             {"per_vertex", LoadDistribution::per_vertex}});
  if (j.contains("moment")) {
    const Json& m = j.at("moment");
    const std::string at = where + ".moment";
    expect_keys(m, at, {"axis", "magnitude"});
    l.moment_axis = vec3(require(m, "axis", at), at + ".axis");
    l.moment = number(require(m, "magnitude", at), at + ".magnitude");
  }
  l.normal_force = number_or(j, "normal_force", 0.0, where);
  l.ramp = number_or(j, "ramp", 0.0, where);
  return l;
}

Obstacle obstacle(const Json& j, const std::string& where, const std::string& base_dir) {
  expect_keys(j, where, {"name", "mesh", "transform", "motion", "friction", "progressive"});
  Obstacle o;
  o.name = j.value("name", where);
  o.mesh = body_mesh(require(j, "mesh", where), where + ".mesh", base_dir);
  if (j.contains("transform"))
    apply_transform(j.at("transform"), where + ".transform", o.mesh.vertices);
  if (j.contains("motion")) o.motion = motion(j.at("motion"), where + ".motion");
  o.friction = parameter(j, "material", "friction", where);
  if (j.contains("progressive")) {
    if (!j.at("progressive").is_boolean())
      scene_error(where + ".progressive", "must be true or false");
    o.progressive = j.at("progressive").get<bool>();
  }
  return o;
}

Ground ground(const Json& j) {
  expect_keys(j, "ground", {"normal", "height", "friction"});
  Ground g;
  g.enabled = true;
  g.normal = vec3_or(j, "normal", g.normal, "ground");
  if (!(g.normal.norm() > 0.0)) scene_error("ground.normal", "must be non-zero");
  g.normal.normalize();
  g.height = number_or(j, "height", 0.0, "ground");
  g.friction = parameter(j, "material", "friction", "ground");
  return g;
}

void contact(const Json& j, Scene& scene) {
  expect_keys(j, "contact", {"dhat", "stiffness", "friction_velocity", "crossing_start"});
  scene.contact.dhat = parameter(j, "contact", "dhat", "contact");
  scene.contact.stiffness = parameter(j, "contact", "stiffness", "contact");
  scene.contact.friction_velocity = parameter(j, "contact", "friction_velocity", "contact");
  scene.contact.crossing_start = parameter(j, "contact", "crossing_start", "contact") != 0.0;
}

void simulation(const Json& j, Scene& scene) {
  const std::string where = "simulation";
  expect_keys(j, where, {"mode", "time_step", "duration", "output_every", "gravity_ramp"});
  scene.mode = table_choice<StepMode>(j, "simulation", "mode", where);
  scene.time_step = parameter(j, "simulation", "time_step", where);
  scene.duration = parameter(j, "simulation", "duration", where);
  scene.output_every = static_cast<int>(parameter(j, "simulation", "output_every", where));
  scene.gravity_ramp = parameter(j, "simulation", "gravity_ramp", where);
}

void solver(const Json& j, Scene& scene) {
  expect_keys(j, "solver",
              {"newton_tolerance", "max_newton_iterations", "max_cg_iterations",
               "line_search_extrapolation"});
  scene.solver.tolerance = parameter(j, "solver", "newton_tolerance", "solver");
  scene.solver.max_iterations =
      static_cast<int>(parameter(j, "solver", "max_newton_iterations", "solver"));
  scene.solver.max_cg_iterations =
      static_cast<int>(parameter(j, "solver", "max_cg_iterations", "solver"));
  scene.solver.extrapolate = parameter(j, "solver", "line_search_extrapolation", "solver") != 0.0;
}

WindKeyframe wind_keyframe(const Json& j, const std::string& where) {
  expect_keys(j, where, {"time", "velocity"});
  return {number(require(j, "time", where), where + ".time"),
          vec3(require(j, "velocity", where), where + ".velocity")};
}

/// The "wind" section: a constant "velocity" or gusts as "keyframes", and the air's coefficients.
WindSettings wind(const Json& j, const Scene& scene) {
  const std::string where = "wind";
  expect_keys(j, where, {"velocity", "keyframes", "density", "drag", "lift"});
  if (!scene.effects.has(Effect::wind))
    scene_error(where, "the scene has a 'wind' section but does not enable the 'wind' effect");
  if (j.contains("velocity") && j.contains("keyframes"))
    scene_error(where, "give either 'velocity' (a steady wind) or 'keyframes' (gusts), not both");
  WindSettings w;
  w.velocity = vec3_or(j, "velocity", w.velocity, where);
  w.density = parameter(j, "wind", "density", where);
  w.drag = parameter(j, "wind", "drag", where);
  w.lift = parameter(j, "wind", "lift", where);
  if (j.contains("keyframes")) {
    const Json& keys = j.at("keyframes");
    if (!keys.is_array() || keys.empty())
      scene_error(where + ".keyframes", "must be a non-empty array of {\"time\", \"velocity\"}");
    for (std::size_t k = 0; k < keys.size(); ++k)
      w.keyframes.push_back(
          wind_keyframe(keys[k], where + ".keyframes[" + std::to_string(k) + "]"));
  }
  return w;
}

/// The "progressive" section: {"coarse_levels": k, "coarsening_ratio": r} or {"levels": [...]}
/// plus the preview and proxy options and "proximal".
ProgressiveSettings progressive(const Json& j) {
  const std::string where = "progressive";
  expect_keys(j, where,
              {"coarse_levels", "coarsening_ratio", "levels", "preview_iterations",
               "preview_tolerance", "prolongation", "proxy_hessian", "proximal", "preview_membrane",
               "prediction", "consistency_weight", "galerkin_refresh"});
  ProgressiveSettings p;
  if (j.contains("coarse_levels"))
    p.coarse_levels = integer(j.at("coarse_levels"), where + ".coarse_levels");
  p.coarsening_ratio = number_or(j, "coarsening_ratio", p.coarsening_ratio, where);
  p.preview_tolerance = parameter(j, "progressive", "preview_tolerance", where);
  p.consistency_weight = parameter(j, "progressive", "consistency_weight", where);
  p.galerkin_refresh = parameter(j, "progressive", "galerkin_refresh", where);
  p.preview_iterations = static_cast<int>(parameter(j, "progressive", "preview_iterations", where));
  if (j.contains("proximal") &&
      j.at("proximal").is_boolean())  // true/false, or 1/0 as a table switch
    p.proximal = j.at("proximal").get<bool>();
  else
    p.proximal = parameter(j, "progressive", "proximal", where) != 0.0;
  p.prolongation = table_choice<ProxyProlongation>(j, "progressive", "prolongation", where);
  p.hessian = table_choice<ProxyHessian>(j, "progressive", "proxy_hessian", where);
  p.preview_membrane = table_choice<MembraneModel>(j, "progressive", "preview_membrane", where);
  p.prediction = table_choice<DynamicsPrediction>(j, "progressive", "prediction", where);
  if (j.contains("levels")) {
    const Json& levels = j.at("levels");
    if (!levels.is_array()) scene_error(where + ".levels", "must be an array of vertex counts");
    for (std::size_t k = 0; k < levels.size(); ++k)
      p.level_vertices.push_back(integer(levels[k], where + ".levels[" + std::to_string(k) + "]"));
  }
  return p;
}

Scene scene_from_json(const Json& root, const std::string& base_dir) {
  expect_keys(root, "scene",
              {"name", "simulation", "gravity", "effects", "solver", "bodies", "handles", "contact",
               "obstacles", "ground", "progressive", "wind", "loads"});
  Scene scene;
  scene.name = root.value("name", std::string("scene"));
  simulation(root.contains("simulation") ? root.at("simulation") : Json::object(), scene);
  solver(root.contains("solver") ? root.at("solver") : Json::object(), scene);
  scene.gravity = vec3_or(root, "gravity", scene.gravity, "scene");
  const Json& effects = require(root, "effects", "scene");
  if (!effects.is_array()) scene_error("effects", "must be an array of effect names");
  for (const Json& e : effects) {
    if (!e.is_string()) scene_error("effects", "must hold effect names (strings)");
    scene.effects.enable(parse_effect(e.get<std::string>()));
  }
  const Json& bodies = require(root, "bodies", "scene");
  if (!bodies.is_array() || bodies.empty()) scene_error("bodies", "must be a non-empty array");
  for (std::size_t b = 0; b < bodies.size(); ++b)
    scene.bodies.push_back(body(bodies[b], "bodies[" + std::to_string(b) + "]", base_dir));
  if (root.contains("handles")) {
    const Json& handles = root.at("handles");
    if (!handles.is_array()) scene_error("handles", "must be an array");
    for (std::size_t h = 0; h < handles.size(); ++h)
      scene.handles.push_back(
          handle(handles[h], scene.bodies, "handles[" + std::to_string(h) + "]"));
  }
  if (root.contains("loads")) {
    const Json& loads = root.at("loads");
    if (!loads.is_array()) scene_error("loads", "must be an array");
    for (std::size_t k = 0; k < loads.size(); ++k)
      scene.loads.push_back(load(loads[k], scene.bodies, "loads[" + std::to_string(k) + "]"));
  }
  contact(root.contains("contact") ? root.at("contact") : Json::object(), scene);
  if (root.contains("progressive")) scene.progressive = progressive(root.at("progressive"));
  if (root.contains("obstacles")) {
    const Json& obstacles = root.at("obstacles");
    if (!obstacles.is_array()) scene_error("obstacles", "must be an array");
    for (std::size_t k = 0; k < obstacles.size(); ++k)
      scene.obstacles.push_back(
          obstacle(obstacles[k], "obstacles[" + std::to_string(k) + "]", base_dir));
  }
  if (root.contains("ground")) scene.ground = ground(root.at("ground"));
  if (root.contains("wind")) scene.wind = wind(root.at("wind"), scene);
  validate_scene(scene);
  return scene;
}

}  // namespace

Scene parse_scene(const std::string& json_text, const std::string& base_dir) {
  Json root;
  try {
    root = Json::parse(json_text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const Json::exception& e) {
    fail(Status::invalid_scene, std::string("scene is not valid JSON: ") + e.what());
  }
  try {
    return scene_from_json(root, base_dir);
  } catch (const Json::exception& e) {  // type errors inside value()/get<>()
    fail(Status::invalid_scene, std::string("scene has a field of the wrong type: ") + e.what());
  }
}

Scene load_scene_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(Status::io_error, "cannot read scene file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  const std::string dir = std::filesystem::absolute(path).parent_path().string();
  return parse_scene(text.str(), dir);
}

}  // namespace progsim
