#include "mesh/tetrahedralize.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_3/Dump_c3t3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/make_mesh_3.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "common/error.hpp"
#include "mesh/intersection_check.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/tet_mesh_validation.hpp"

namespace progsim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, SurfaceMesh>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation, Domain::Corner_index,
                                                        Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;

}  // namespace
}  // namespace progsim

namespace CGAL {
/// Mesh_3 writes its whole complex into the working directory ("dump-bug.mesh" and
/// ".binary.cgal", megabytes) before raising some errors (Refine_facets_3's "already inserted on
/// surface", Protect_edges_sizing_field): a library must not write into its caller's folder. The
/// error still reaches tetrahedralize_surface as a Failure_exception. Both values of the
/// streamability flag are specialised, so this holds whichever CGAL computes for the complex.
template <>
struct Dump_c3t3<progsim::Complex, true> {
  void dump_c3t3(const progsim::Complex&, const std::string&) const {}
};
template <>
struct Dump_c3t3<progsim::Complex, false> {
  void dump_c3t3(const progsim::Complex&, const std::string&) const {}
};
}  // namespace CGAL

namespace progsim {
namespace {

constexpr const char* kLabel = "tetrahedralize";

/// The options with every default resolved against the surface's size.
TetrahedralizeOptions resolved_options(TetrahedralizeOptions o, const TriangleMesh& surface) {
  if (o.cell_size == 0.0) o.cell_size = bounding_box_diagonal(surface.vertices) / 20.0;
  if (o.facet_size == 0.0) o.facet_size = o.cell_size;
  if (o.facet_distance == 0.0) o.facet_distance = o.cell_size / 10.0;
  if (o.edge_size == 0.0) o.edge_size = o.cell_size;
  return o;
}

void require(bool ok, const std::string& what, double value) {
  if (!ok)
    fail(Status::invalid_argument,
         std::string(kLabel) + ": " + what + " (got " + std::to_string(value) + ")");
}

/// Sizes below these fractions of the surface's bounding-box diagonal are refused: Mesh_3 would
/// build about (diagonal / cell_size)³ tets (10⁷ at the bound) and (diagonal / facet_size)²
/// boundary faces, running for hours or out of memory rather than failing.
constexpr double kMinCellFraction = 1.0 / 215.0;
constexpr double kMinFacetFraction = 1e-3;
constexpr double kMinDistanceFraction = 1e-6;
/// Mesh_3 stops refining at this many vertices (about 10⁷ tets, the cell-size bound's count).
constexpr std::size_t kMaxVertices = 2000000;

/// Throws Error(invalid_argument) if `value` (m) is below `fraction` of `diagonal`.
void require_not_below(double value, double fraction, double diagonal, const char* name) {
  if (value < fraction * diagonal)
    fail(Status::invalid_argument,
         std::string(kLabel) + ": " + name + " = " + std::to_string(value) +
             " is too fine for a surface of bounding-box diagonal " + std::to_string(diagonal) +
             " (at least " + std::to_string(fraction * diagonal) +
             ": finer would build more tets than fit in memory)");
}

void check_options(const TetrahedralizeOptions& o, double diagonal) {
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  require(positive(o.cell_size), "cell_size must be positive and finite", o.cell_size);
  require(positive(o.facet_size), "facet_size must be positive and finite", o.facet_size);
  require(positive(o.facet_distance), "facet_distance must be positive and finite",
          o.facet_distance);
  require(positive(o.edge_size), "edge_size must be positive and finite", o.edge_size);
  require(o.facet_angle > 0.0 && o.facet_angle <= 30.0, "facet_angle must lie in (0, 30] degrees",
          o.facet_angle);
  require(o.cell_radius_edge_ratio >= 2.0 && std::isfinite(o.cell_radius_edge_ratio),
          "cell_radius_edge_ratio must be at least 2", o.cell_radius_edge_ratio);
  require(o.feature_angle >= 0.0 && o.feature_angle <= 180.0,
          "feature_angle must lie in [0, 180] degrees", o.feature_angle);
  require(o.time_limit > 0.0 && !std::isnan(o.time_limit), "time_limit must be positive",
          o.time_limit);
  require_not_below(o.cell_size, kMinCellFraction, diagonal, "cell_size");
  require_not_below(o.facet_size, kMinFacetFraction, diagonal, "facet_size");
  require_not_below(o.edge_size, kMinFacetFraction, diagonal, "edge_size");
  require_not_below(o.facet_distance, kMinDistanceFraction, diagonal, "facet_distance");
}

/// A valid manifold that is closed (every edge on two faces) and free of self-intersections:
/// the surface of a solid, which Mesh_3's inside test (ray parity) needs.
void check_closed_surface(const TriangleMesh& surface) {
  validate_mesh(surface, kLabel);
  const MeshTopology topology = build_topology(surface.faces, surface.num_vertices());
  for (std::size_t e = 0; e < topology.edges.size(); ++e)
    if (topology.edge_on_boundary[e])
      fail(Status::invalid_mesh, std::string(kLabel) + ": the surface is not closed: edge (" +
                                     std::to_string(topology.edges[e][0]) + ", " +
                                     std::to_string(topology.edges[e][1]) +
                                     ") lies on one face only");
  const std::vector<FacePair> crossing = intersecting_faces(surface.vertices, surface.faces, 1);
  if (!crossing.empty())
    fail(Status::invalid_mesh, std::string(kLabel) + ": the surface intersects itself: faces " +
                                   std::to_string(crossing[0].a) + " and " +
                                   std::to_string(crossing[0].b) + " cross");
}

SurfaceMesh to_surface_mesh(const TriangleMesh& mesh) {
  SurfaceMesh sm;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    sm.add_vertex(Kernel::Point_3(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2)));
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (sm.add_face(SurfaceMesh::Vertex_index(mesh.faces(f, 0)),
                    SurfaceMesh::Vertex_index(mesh.faces(f, 1)),
                    SurfaceMesh::Vertex_index(mesh.faces(f, 2))) == SurfaceMesh::null_face())
      fail(Status::invalid_mesh,
           std::string(kLabel) + ": CGAL's Surface_mesh cannot insert face " + std::to_string(f));
  return sm;
}

/// Delaunay refinement of the domain to the criteria, then sliver perturbation (CGAL Mesh_3
/// manual, make_mesh_3), keeping the surface complex manifold. No exudation: CGAL 5.5's exuder
/// breaks ties by cell address (a Double_map over facets), and its output changed from one
/// process to the next (1 run in 15 on a sphere); the perturber orders by vertex ids.
Complex mesh_domain(const SurfaceMesh& sm, const TetrahedralizeOptions& o,
                    CGAL::Mesh_error_code* error, std::atomic<bool>* stop) {
  CGAL::Random random(o.seed);  // Mesh_3's only random source here: the initial points
  Domain domain(sm, &random);
  // Protect sharp edges and corners so that flat faces and edges stay exact (Mesh_3 manual).
  if (o.feature_angle < 180.0) domain.detect_features(o.feature_angle);
  namespace p = CGAL::parameters;
  const Criteria criteria(p::edge_size = o.edge_size, p::facet_angle = o.facet_angle,
                          p::facet_size = o.facet_size, p::facet_distance = o.facet_distance,
                          p::cell_radius_edge_ratio = o.cell_radius_edge_ratio,
                          p::cell_size = o.cell_size);
  return CGAL::make_mesh_3<Complex>(domain, criteria, p::manifold(), p::perturb(), p::no_exude(),
                                    p::mesh_3_options(p::maximal_number_of_vertices = kMaxVertices,
                                                      p::pointer_to_error_code = error,
                                                      p::pointer_to_stop_atomic_boolean = stop));
}

/// Sets a flag once `seconds` have passed, unless destroyed first: Mesh_3's stop flag, which its
/// refinement loops check between steps.
class Deadline {
 public:
  Deadline(double seconds, std::atomic<bool>& flag)
      : watcher_([this, seconds, &flag] {
          std::unique_lock<std::mutex> lock(mutex_);
          if (!done_.wait_for(lock, std::chrono::duration<double>(seconds),
                              [this] { return over_; }))
            flag.store(true, std::memory_order_release);
        }) {}
  Deadline(const Deadline&) = delete;
  Deadline& operator=(const Deadline&) = delete;
  ~Deadline() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      over_ = true;
    }
    done_.notify_one();
    watcher_.join();
  }

 private:
  std::mutex mutex_;
  std::condition_variable done_;
  bool over_ = false;
  std::thread watcher_;  // last: started once the members it uses exist
};

/// One Mesh_3 run within the time limit. Throws Error(numerical_failure) if it was stopped.
Complex mesh_within_limits(const SurfaceMesh& sm, const TetrahedralizeOptions& o) {
  std::atomic<bool> stop{false};
  CGAL::Mesh_error_code error = CGAL::CGAL_MESH_3_NO_ERROR;
  Complex c3t3;
  {
    const Deadline deadline(o.time_limit, stop);
    c3t3 = mesh_domain(sm, o, &error, &stop);
  }
  if (error == CGAL::CGAL_MESH_3_STOPPED)
    fail(Status::numerical_failure, std::string(kLabel) + ": CGAL Mesh_3 did not finish within " +
                                        std::to_string(o.time_limit) +
                                        " s (time_limit); its refinement may cycle on this "
                                        "surface: try feature_angle below 180 or other sizes");
  if (error == CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED)
    fail(Status::numerical_failure, std::string(kLabel) + ": CGAL Mesh_3 refined past " +
                                        std::to_string(kMaxVertices) +
                                        " vertices; try larger sizes");
  return c3t3;
}

/// The cells of the complex as a tet mesh: vertices numbered by first use, so that unused
/// triangulation vertices (outside the solid) drop out; tets flipped to positive orientation.
TetMesh to_tet_mesh(const Complex& c3t3) {
  std::map<Triangulation::Vertex_handle, int> index;  // lookup only: numbering is by first use
  std::vector<Vec3> points;
  std::vector<Eigen::Vector4i> tets;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    Eigen::Vector4i tet;
    for (int k = 0; k < 4; ++k) {
      const auto [it, added] = index.emplace(c->vertex(k), static_cast<int>(points.size()));
      if (added) {
        const auto& p = c->vertex(k)->point().point();
        points.emplace_back(p.x(), p.y(), p.z());
      }
      tet[k] = it->second;
    }
    tets.push_back(tet);
  }
  TetMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v)
    mesh.vertices.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  mesh.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t t = 0; t < tets.size(); ++t)
    mesh.tets.row(static_cast<Eigen::Index>(t)) = tets[t].transpose();
  const Eigen::VectorXd volumes = tet_signed_volumes(mesh.vertices, mesh.tets);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (volumes[t] < 0.0) std::swap(mesh.tets(t, 2), mesh.tets(t, 3));
  return mesh;
}

}  // namespace

TetMesh tetrahedralize_surface(const TriangleMesh& closed_surface,
                               const TetrahedralizeOptions& options) {
  check_closed_surface(closed_surface);
  const TetrahedralizeOptions o = resolved_options(options, closed_surface);
  check_options(o, bounding_box_diagonal(closed_surface.vertices));
  TetMesh mesh;
  try {
    mesh = to_tet_mesh(mesh_within_limits(to_surface_mesh(closed_surface), o));
  } catch (const CGAL::Failure_exception& e) {
    fail(Status::internal, std::string(kLabel) + ": CGAL Mesh_3 failed: " + e.message());
  }
  validate_tet_mesh(mesh, std::string(kLabel) + " (CGAL Mesh_3 output; try a smaller cell_size)");
  return mesh;
}

}  // namespace progsim
