// The only translation unit that includes CGAL Mesh_3: it compiles slowly, so it is kept alone.
#include "fissure/mesh/tetrahedralize.hpp"

#include "fissure/base/error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/make_mesh_3.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace fissure {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Surface_mesh<Kernel::Point_3>;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, Polyhedron>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;

// Mean tet volume as a fraction of cell_size³, measured on bulky boxes (0.3 m cube, 0.7K–70K
// tets: 0.22 ± 0.01). Thin plates deviate (the thickness, not the size bound, sets the tets), so
// this is only the first guess; misses are corrected by re-meshing (tests/bench/bench_mesh.cpp).
constexpr double kVolumePerCellSizeCubed = 0.22;
constexpr int kMaxAttempts = 3;

Polyhedron to_polyhedron(const SurfaceMesh& surface) {
  Polyhedron p;
  std::vector<Polyhedron::Vertex_index> v(static_cast<std::size_t>(surface.vertex_count()));
  for (Eigen::Index i = 0; i < surface.vertex_count(); ++i) {
    v[static_cast<std::size_t>(i)] =
        p.add_vertex(Kernel::Point_3(surface.vertices(i, 0), surface.vertices(i, 1), surface.vertices(i, 2)));
  }
  for (Eigen::Index f = 0; f < surface.face_count(); ++f) {
    const auto face = p.add_face(v[surface.faces(f, 0)], v[surface.faces(f, 1)], v[surface.faces(f, 2)]);
    if (face == Polyhedron::null_face()) {
      throw InvalidInput(surface.source_name + ": face " + std::to_string(f) +
                         " cannot be added (non-manifold or inconsistently oriented surface; repair it first)");
    }
  }
  if (!CGAL::is_closed(p)) {
    throw InvalidInput(surface.source_name + ": the surface is open; only closed surfaces bound a volume");
  }
  return p;
}

TetMesh mesh_once(const Polyhedron& polyhedron, const TetrahedralizeOptions& options, double size,
                  const std::string& source) {
  using namespace CGAL::parameters;
  CGAL::get_default_random() = CGAL::Random(options.seed);
  Domain domain(polyhedron);
  domain.detect_features(options.feature_angle_deg);
  const Criteria criteria(edge_size = size, facet_angle = options.facet_angle_deg, facet_size = size,
                          facet_distance = size / 4.0,
                          cell_radius_edge_ratio = options.cell_radius_edge_ratio, cell_size = size);
  const Complex c3t3 = CGAL::make_mesh_3<Complex>(
      domain, criteria, no_lloyd(), no_odt(),
      perturb(time_limit = options.perturb_time_limit_s, sliver_bound = options.sliver_bound_deg),
      exude(time_limit = options.exude_time_limit_s, sliver_bound = options.sliver_bound_deg));

  // Nodes numbered in order of first use by the cells, cells in the complex's order: both are
  // fixed by the (deterministic) triangulation.
  std::unordered_map<Triangulation::Vertex_handle, int> index;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector4i> cells;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    Eigen::Vector4i tet;
    for (int k = 0; k < 4; ++k) {
      const auto vh = c->vertex(k);
      const auto [it, inserted] = index.try_emplace(vh, static_cast<int>(points.size()));
      if (inserted) {
        const auto& p = vh->point();
        points.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
      }
      tet[k] = it->second;
    }
    const Eigen::Vector3d& a = points[tet[0]];
    if ((points[tet[1]] - a).dot((points[tet[2]] - a).cross(points[tet[3]] - a)) < 0.0) std::swap(tet[2], tet[3]);
    cells.push_back(tet);
  }
  if (cells.empty()) throw NumericalFailure(source + ": CGAL produced no tetrahedra");
  // A degenerate tet here is the mesher's fault, not the user's: report it as a numerical failure.
  Eigen::MatrixX3d nodes(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) nodes.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  Eigen::MatrixX4i tets(static_cast<Eigen::Index>(cells.size()), 4);
  for (std::size_t i = 0; i < cells.size(); ++i) tets.row(static_cast<Eigen::Index>(i)) = cells[i].transpose();
  try {
    return TetMesh(std::move(nodes), std::move(tets), source);
  } catch (const InvalidInput& e) {
    throw NumericalFailure(std::string("tetrahedralize produced an invalid mesh: ") + e.what());
  }
}

}  // namespace

std::vector<std::string> TetrahedralizeOptions::problems() const {
  std::vector<std::string> out;
  if (target_tets < 10 || target_tets > 50'000'000) out.push_back("target_tets " + std::to_string(target_tets) + " is outside [10, 5e7]");
  if (!(count_tolerance > 0.0 && count_tolerance < 1.0)) out.push_back("count_tolerance must be in (0, 1)");
  if (!(facet_angle_deg > 0.0 && facet_angle_deg <= 30.0)) out.push_back("facet_angle_deg must be in (0, 30] (CGAL termination)");
  if (!(cell_radius_edge_ratio >= 2.0)) out.push_back("cell_radius_edge_ratio must be >= 2 (CGAL termination)");
  if (!(feature_angle_deg > 0.0 && feature_angle_deg < 180.0)) out.push_back("feature_angle_deg must be in (0, 180)");
  if (!(sliver_bound_deg >= 0.0 && sliver_bound_deg < 70.0)) out.push_back("sliver_bound_deg must be in [0, 70)");
  if (!(perturb_time_limit_s >= 0.0) || !(exude_time_limit_s >= 0.0)) out.push_back("time limits must be >= 0");
  if (!(refuse_below_dihedral_deg >= 0.0)) out.push_back("refuse_below_dihedral_deg must be >= 0");
  return out;
}

void TetrahedralizeOptions::validate() const { throw_if_problems("tetrahedralize", problems()); }

TetMesh tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options,
                       TetrahedralizeReport* report, ProgressSink* progress, const CancelToken* cancel) {
  options.validate();
  const std::string source = surface.source_name.empty() ? std::string("surface") : surface.source_name;
  if (surface.face_count() < 4) throw InvalidInput(source + ": the surface has fewer than 4 faces");
  if (!surface.vertices.allFinite()) throw InvalidInput(source + ": a vertex has a non-finite coordinate");
  const double volume = signed_volume(surface);
  if (!(volume > 0.0)) {
    throw InvalidInput(source + ": the surface encloses no positive volume (open or inside out?)");
  }
  const Polyhedron polyhedron = to_polyhedron(surface);
  NullProgress null_progress;
  ProgressSink& sink = progress ? *progress : null_progress;

  TetrahedralizeReport local;
  TetrahedralizeReport& r = report ? *report : local;
  r = TetrahedralizeReport{};
  // Tet count N(h) ~ h^-p: p = 3 in bulk, less in plates a few elements thick. The first miss
  // is corrected with p = 3, later ones with p fitted on the last two attempts (secant in log-log).
  double cell_size = std::cbrt(volume / (kVolumePerCellSizeCubed * options.target_tets));
  double previous_size = 0.0, previous_count = 0.0;
  TetMesh mesh;
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
    if (cancel) cancel->throw_if_cancelled();
    sink.report("tetrahedralize", static_cast<double>(attempt) / kMaxAttempts);
    mesh = mesh_once(polyhedron, options, cell_size, source);
    r.attempts = attempt + 1;
    r.cell_size = cell_size;
    const double count = mesh.tet_count();
    if (std::abs(count / options.target_tets - 1.0) <= options.count_tolerance) break;
    double p = 3.0;
    if (previous_count > 0.0 && previous_count != count) {
      p = std::clamp(-std::log(count / previous_count) / std::log(cell_size / previous_size), 1.0, 4.0);
    }
    previous_size = cell_size;
    previous_count = count;
    cell_size *= std::pow(count / options.target_tets, 1.0 / p);
  }
  sink.report("tetrahedralize", 1.0);
  if (cancel) cancel->throw_if_cancelled();

  r.quality = mesh.quality();
  if (r.quality.min_dihedral_deg < options.refuse_below_dihedral_deg) {
    throw NumericalFailure(source + ": the mesh has a sliver (tet " + std::to_string(r.quality.worst_dihedral_tet) +
                           ", min dihedral " + std::to_string(r.quality.min_dihedral_deg) + " deg) after sliver removal");
  }
  if (r.quality.min_dihedral_deg < 5.0) {
    r.warnings.push_back("min dihedral angle " + std::to_string(r.quality.min_dihedral_deg) +
                         " deg is below 5 deg: stresses in that tet are unreliable");
  }
  const double ratio = static_cast<double>(mesh.tet_count()) / options.target_tets;
  if (std::abs(ratio - 1.0) > options.count_tolerance) {
    r.warnings.push_back(std::to_string(mesh.tet_count()) + " tets instead of the " +
                         std::to_string(options.target_tets) + " asked for");
  }
  return mesh;
}

}  // namespace fissure
