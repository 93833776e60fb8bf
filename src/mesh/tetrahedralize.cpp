// The only translation unit that includes CGAL Mesh_3: it compiles slowly, so it is kept alone.
#include "fissure/mesh/tetrahedralize.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/memory.hpp"
#include "fissure/base/number_text.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Mesh_3/Sliver_perturber.h>
#include <CGAL/Mesh_3/Slivers_exuder.h>
#include <CGAL/exude_mesh_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/perturb_mesh_3.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <unordered_map>

namespace fissure {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Surface_mesh<Kernel::Point_3>;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, Polyhedron>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_face_graph_triangle_primitive<Polyhedron>>>;

// Mean tet volume as a fraction of cell_size³, measured on bulky boxes (0.3 m cube, 0.7K–70K
// tets: 0.22 ± 0.01). Thin plates deviate (the thickness, not the size bound, sets the tets), so
// this is only the first guess; misses are corrected by re-meshing (tests/bench/bench_mesh.cpp).
constexpr double kVolumePerCellSizeCubed = 0.22;
constexpr int kMaxAttempts = 3;
// Extra attempts, each with a smaller size bound, after a mesh that does not fill its surface.
constexpr int kMaxRefills = 4;
constexpr double kRefillShrink = 0.6;
// Tets per triangulation vertex in the finished mesh (24K-tet tile: 24016 / 4647 = 5.2); turns
// the vertex count CGAL has reached into a fraction of the expected work.
constexpr double kTetsPerVertex = 5.2;
// Peak memory (see tetrahedralize_memory_estimate), measured with tests/bench/peak_rss on
// `fissure mesh tile:1,1,1 --tets N`: 111 MB at 24K tets, 159 MB at 100K, 289 MB at 300K (the
// 1 × 1 × 0.05 m tile at 100K: 164 MB), 104 MB for a 64-tet mesh. The slope is 630–650 bytes per
// tet; 700 keeps a margin, and the fixed part is the process with its libraries.
constexpr double kTetrahedralizeBytesPerTet = 700.0;
constexpr double kTetrahedralizeFixedBytes = 100e6;
// Largest facet distance, in units of the thickness 2V/A. With a quarter of the size bound alone
// the fragments of a torus (2 cm tube) held 98.9 % of its volume at 23K tets (97.3 % at 6K);
// 0.02 of the thickness gives 99.1 % at the same count (0.01: 99.7 % at 4.5× the tets). Flat
// faces are unaffected: they are reproduced exactly whatever the bound.
constexpr double kFacetDistancePerThickness = 0.02;

// Largest size bound, in units of the thickness 2V/A, used for a body: on the 1 × 1 × 0.05 m
// tile a bound of 1.5 × 2V/A still fills the plate and 2 × leaves it hollow (measured, 500 tets
// asked for); 1.25 keeps a margin, and the check after every attempt catches what it misses.
constexpr double kMaxSizePerThickness = 1.25;
// A request whose size bound must shrink to fit the body by more than this many tets (relative
// and absolute part) is refused up front instead of running for minutes on a much larger mesh.
constexpr double kMaxTetsOverTarget = 10.0;
constexpr double kMaxExtraTets = 1e5;

// Watches a running refinement from inside CGAL: the size functors below are called for every
// facet and cell CGAL tests, so they are where the caller's CancelToken is read (and copied into
// CGAL's own stop flag, Mesher_3's `pointer_to_stop_atomic_boolean`) and where progress is
// reported, at most five times per second.
class RefinementWatch {
public:
  RefinementWatch(ProgressSink& sink, const CancelToken* cancel, const Triangulation& triangulation,
                  double expected_vertices, double from, double to)
      : m_sink(sink), m_cancel(cancel), m_triangulation(triangulation), m_expected_vertices(expected_vertices),
        m_from(from), m_to(to), m_last(std::chrono::steady_clock::now()) {}

  std::atomic<bool>* stop_flag() { return &m_stop; }
  void poll() {
    if (m_cancel && m_cancel->cancelled()) m_stop.store(true, std::memory_order_release);
    if (++m_calls % 1024 != 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - m_last < std::chrono::milliseconds(200)) return;
    m_last = now;
    const double done = std::min(0.95, static_cast<double>(m_triangulation.number_of_vertices()) / m_expected_vertices);
    m_sink.report("tetrahedralize", m_from + (m_to - m_from) * done);
  }

private:
  ProgressSink& m_sink;
  const CancelToken* m_cancel;
  const Triangulation& m_triangulation;
  double m_expected_vertices, m_from, m_to;
  std::atomic<bool> m_stop{false};
  std::uint64_t m_calls = 0;
  std::chrono::steady_clock::time_point m_last;
};

// A uniform size bound that lets the watch run each time CGAL asks for it.
struct WatchedSize {
  double size;
  RefinementWatch* watch;
  template <typename Index>
  double operator()(const Kernel::Point_3&, int, const Index&) const {
    watch->poll();
    return size;
  }
};

Polyhedron to_polyhedron(const SurfaceMesh& surface, double scale) {
  Polyhedron p;
  std::vector<Polyhedron::Vertex_index> v(static_cast<std::size_t>(surface.vertex_count()));
  for (Eigen::Index i = 0; i < surface.vertex_count(); ++i) {
    v[static_cast<std::size_t>(i)] = p.add_vertex(
        Kernel::Point_3(scale * surface.vertices(i, 0), scale * surface.vertices(i, 1), scale * surface.vertices(i, 2)));
  }
  for (Eigen::Index f = 0; f < surface.face_count(); ++f) {
    const auto face = p.add_face(v[surface.faces(f, 0)], v[surface.faces(f, 1)], v[surface.faces(f, 2)]);
    if (face == Polyhedron::null_face()) {
      throw InvalidInput(surface.source_name + ": face " + std::to_string(f + 1) +
                         " cannot be added (non-manifold or inconsistently oriented surface; repair it first)");
    }
  }
  if (!CGAL::is_closed(p)) {
    throw InvalidInput(surface.source_name + ": the surface is open; only closed surfaces bound a volume");
  }
  return p;
}

// One Delaunay refinement: CGAL's domain and the complex it fills, kept together because sliver
// removal needs both.
struct Refinement {
  explicit Refinement(const Polyhedron& polyhedron) : domain(polyhedron) {}
  Domain domain;
  Complex c3t3;
};

// Refinement alone at size bound `size` on the scaled `polyhedron` (no sliver removal: an attempt
// judged by its tet count is refined only, and only the accepted one is optimised, see
// remove_slivers). Returns null when `cancel` stopped it.
std::unique_ptr<Refinement> refine(const Polyhedron& polyhedron, const TetrahedralizeOptions& options, double size,
                                   double distance_bound, double expected_tets, ProgressSink& sink, const CancelToken* cancel, double from,
                                   double to) {
  using namespace CGAL::parameters;
  CGAL::get_default_random() = CGAL::Random(options.seed);
  auto r = std::make_unique<Refinement>(polyhedron);
  r->domain.detect_features(options.feature_angle_deg);
  const double expected_vertices = std::max(1.0, expected_tets / kTetsPerVertex);
  RefinementWatch watch(sink, cancel, r->c3t3.triangulation(), expected_vertices, from, to);
  const WatchedSize sized{size, &watch};
  const Criteria criteria(edge_size = size, facet_angle = options.facet_angle_deg, facet_size = sized,
                          facet_distance = distance_bound,
                          cell_radius_edge_ratio = options.cell_radius_edge_ratio, cell_size = sized);
  CGAL::make_mesh_3_bp(r->c3t3, r->domain, criteria, no_lloyd(), no_odt(), no_perturb(), no_exude(),
                       mesh_3_options(pointer_to_stop_atomic_boolean = watch.stop_flag()));
  if (cancel && cancel->cancelled()) return nullptr;
  return r;
}

// Reads the caller's CancelToken inside sliver removal. CGAL 5.5's perturber and exuder read no
// stop flag (the free functions perturb_mesh_3 / exude_mesh_3 stop only at their time limits,
// 10 s each by default), but both classes call a visitor after every vertex perturbed
// (end_of_perturbation_iteration), every sliver bound finished (bound_reached) and every cell
// pumped (after_cell_pumped). On a cancel the watch makes the running pass's own time limit
// expire, so the pass leaves through its own TIME_LIMIT_REACHED exit at its next step and the
// complex, discarded afterwards, stays valid. Not covered: the O(tets) queue builds between
// steps (one per sliver bound, and the exuder's first), which CGAL runs without a visitor. The
// watch only reads, so an uncancelled run computes what the free functions compute (test:
// Tetrahedralize.SliverRemovalWatchKeepsTheMesh). It also reports progress, at most five times
// per second.
class SliverWatch {
public:
  SliverWatch(const CancelToken* cancel, std::function<void()> expire, std::function<void(double)> report)
      : m_cancel(cancel), m_expire(std::move(expire)), m_report(std::move(report)) {}

  // Sliver_perturber's visitor: `bound` rises by the criterion's unit up to the sliver bound.
  void bound_reached(double) { poll(); }
  void end_of_perturbation_iteration(std::size_t) { poll(); }
  // Slivers_exuder's visitor: the cells still queued.
  void after_cell_pumped(std::size_t) { poll(); }

private:
  void poll() {
    if (m_cancel && !m_expired && m_cancel->cancelled()) {
      m_expired = true;
      m_expire();
    }
    if (++m_calls % 64 != 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - m_last < std::chrono::milliseconds(200)) return;
    m_last = now;
    m_report(std::chrono::duration<double>(now - m_start).count());
  }

  const CancelToken* m_cancel;
  std::function<void()> m_expire;
  std::function<void(double)> m_report;  // seconds since the pass began
  bool m_expired = false;
  std::uint64_t m_calls = 0;
  std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now(), m_last = m_start;
};

using SliverCriterion = CGAL::Mesh_3::Min_dihedral_angle_criterion<Triangulation>;
using Perturber = CGAL::Mesh_3::Sliver_perturber<Complex, Domain, SliverCriterion, SliverWatch>;
using Exuder = CGAL::Mesh_3::Slivers_exuder<Complex, SliverCriterion, SliverWatch>;

// Sliver removal, each pass bounded by its time limit, and by `cancel` within a step (see
// SliverWatch). CGAL's generator is reseeded so the result depends only on the accepted
// refinement, not on the attempts before it. Without a token, CGAL's own free functions run:
// they are the reference the watched passes are tested against. A cancelled run leaves the
// complex half optimised: the caller checks the token and discards it.
void remove_slivers(Refinement& r, const TetrahedralizeOptions& options, ProgressSink& sink, const CancelToken* cancel,
                    double from, double to) {
  using namespace CGAL::parameters;
  CGAL::get_default_random() = CGAL::Random(options.seed);
  sink.report("tetrahedralize", from);
  const double middle = from + 0.5 * (to - from);
  if (!cancel) {
    CGAL::perturb_mesh_3(r.c3t3, r.domain, time_limit = options.perturb_time_limit_s,
                         sliver_bound = options.sliver_bound_deg);
    sink.report("tetrahedralize", middle);
    CGAL::exude_mesh_3(r.c3t3, time_limit = options.exude_time_limit_s, sliver_bound = options.sliver_bound_deg);
    sink.report("tetrahedralize", to);
    return;
  }
  // Progress within a pass: the share of its time limit used, which is its worst case (0.95
  // at most, the pass may end any time); without a limit, nothing within the pass.
  const auto reporter = [&sink](double lo, double hi, double limit) {
    return [&sink, lo, hi, limit](double seconds) {
      if (limit > 0.0) sink.report("tetrahedralize", lo + (hi - lo) * std::min(0.95, seconds / limit));
    };
  };
  // What perturb_mesh_3 (CGAL/perturb_mesh_3.h, perturb_mesh_3_impl) does, with the watch.
  {
    const SliverCriterion criterion(options.sliver_bound_deg, r.c3t3.triangulation());
    Perturber perturber(r.c3t3, r.domain, criterion);
    for (auto* perturbation : CGAL::default_perturbation_vector(r.c3t3, r.domain, criterion)) {
      perturber.add_perturbation(perturbation);  // the perturber owns it
    }
    perturber.set_time_limit(options.perturb_time_limit_s);
    perturber(SliverWatch(
        cancel, [&perturber] { perturber.set_time_limit(std::numeric_limits<double>::min()); },
        reporter(from, middle, options.perturb_time_limit_s)));
  }
  if (cancel->cancelled()) return;
  sink.report("tetrahedralize", middle);
  // What exude_mesh_3 (CGAL/exude_mesh_3.h, exude_mesh_3_impl) does, with the watch.
  {
    const SliverCriterion criterion(options.sliver_bound_deg, r.c3t3.triangulation());
    Exuder exuder(r.c3t3, criterion);
    exuder.set_time_limit(options.exude_time_limit_s);
    exuder(SliverWatch(
        cancel, [&exuder] { exuder.set_time_limit(std::numeric_limits<double>::min()); },
        reporter(middle, to, options.exude_time_limit_s)));
  }
  if (!cancel->cancelled()) sink.report("tetrahedralize", to);
}

// A cell of (nearly) zero volume with a facet on the complex's boundary. Sliver removal leaves
// such cells where four boundary vertices are cocircular on a flat face (a 12-triangle box
// centred on the origin, meshed at 3000 tets, kept one: all four corners on its top face).
// All its facets lie in one plane, so dropping it exposes the facets behind it, which cover the
// same part of that plane: the volume and the boundary are unchanged. A flat cell inside the
// body is not dropped (its neighbours on either side would not share faces); TetMesh refuses it.
template <class Cell>
bool is_flat_boundary_cell(const Complex& c3t3, const Cell& c) {
  std::array<Eigen::Vector3d, 4> p;
  for (int k = 0; k < 4; ++k) {
    const auto& q = c->vertex(k)->point();
    p[static_cast<std::size_t>(k)] = Eigen::Vector3d(CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z()));
  }
  const double volume = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0;
  double longest = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) longest = std::max(longest, (p[static_cast<std::size_t>(i)] - p[static_cast<std::size_t>(j)]).norm());
  // TetMesh's zero-volume test (kZeroVolume in tet_mesh.cpp), which would refuse the cell.
  if (std::abs(volume) > 1e-12 * longest * longest * longest) return false;
  for (int k = 0; k < 4; ++k)
    if (!c3t3.is_in_complex(c->neighbor(k))) return true;
  return false;
}

// The complex's cells as a TetMesh, nodes multiplied by `unscale` (a power of two, so exactly).
// Nodes are numbered in order of first use by the cells, cells in the complex's order: both are
// fixed by the (deterministic) triangulation.
TetMesh to_tet_mesh(const Complex& c3t3, double unscale, const std::string& source) {
  std::unordered_map<Triangulation::Vertex_handle, int> index;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector4i> cells;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    if (is_flat_boundary_cell(c3t3, c)) continue;
    Eigen::Vector4i tet;
    for (int k = 0; k < 4; ++k) {
      const auto vh = c->vertex(k);
      const auto [it, inserted] = index.try_emplace(vh, static_cast<int>(points.size()));
      if (inserted) {
        const auto& p = vh->point();
        points.emplace_back(unscale * CGAL::to_double(p.x()), unscale * CGAL::to_double(p.y()),
                            unscale * CGAL::to_double(p.z()));
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

// Why `mesh` does not fill the surface (`tree` holds it multiplied by `scale`), or "" when it does. The
// boundary nodes CGAL makes are intersections with the input triangles, so they lie on the input
// surface up to double round-off; `on_surface` (1e-9 of the diagonal) is far above that and far
// below any real gap. The boundary is then a triangulation inscribed in the input: where a facet
// lies in one input triangle's plane it reproduces it exactly, and only facets that cut across an
// unprotected input edge (a curved region) may deviate, by at most the facet-distance criterion
// `facet_distance`. So the volume may differ by Σ area·facet_distance over those facets, and the
// boundary area may exceed the input's only by round-off there and elsewhere by the same
// facets' slope (≤ 5 %: facet-distance a quarter of the size bound keeps them within 15° of the
// surface, 1/cos 15° = 1.035). A hollow mesh fails both: its cavity walls add area that is on no
// input triangle.
std::string fill_problem(const TetMesh& mesh, const AabbTree& tree, double scale, double volume, double area,
                         const Eigen::AlignedBox3d& box, double facet_distance) {
  const auto distance = [&](const Eigen::Vector3d& p) {
    return std::sqrt(tree.squared_distance(Kernel::Point_3(scale * p.x(), scale * p.y(), scale * p.z()))) / scale;
  };
  const double on_surface = 1e-9 * box.diagonal().norm();
  // Nodes: CGAL's sliver perturbation moves boundary vertices and projects them back onto the
  // surface by a few Newton steps, not exactly: the default 16 cm bowl at 24K tets had a node
  // 1.6e-8 m (1e-7 of the diagonal) off it, and was refused. 1e-6 of the diagonal is still far
  // below a real gap (a hollow mesh's cavity walls lie an element size, ≳ 1e-3, off).
  const double node_on_surface = 1e-6 * box.diagonal().norm();
  double mesh_area = 0.0, curved_area = 0.0, farthest_node = 0.0;
  int farthest = -1;
  std::vector<char> seen(static_cast<std::size_t>(mesh.node_count()), 0);
  for (const BoundaryFace& f : mesh.boundary_faces()) {
    mesh_area += f.area;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int v : f.nodes) {
      const Eigen::Vector3d p = mesh.nodes().row(v).transpose();
      centroid += p / 3.0;
      if (seen[static_cast<std::size_t>(v)]) continue;
      seen[static_cast<std::size_t>(v)] = 1;
      const double d = distance(p);
      if (d > farthest_node) {
        farthest_node = d;
        farthest = v;
      }
    }
    if (distance(centroid) > on_surface) curved_area += f.area;
  }
  const auto figures = [&](double value, double expected, const char* unit) {
    return format_number(value) + " " + unit + " instead of " + format_number(expected) + " " + unit + " (" +
           format_number(100.0 * (value / expected - 1.0), 3) + " %)";
  };
  if (farthest_node > node_on_surface) {
    return "boundary " + mesh.node_label(farthest) + " lies " + format_number(farthest_node) +
           " m off the surface";
  }
  const double mesh_volume = mesh.total_volume();
  // Round-off of summing the tet volumes: below 1e-9 relative up to 5e7 tets.
  const double volume_tolerance = 1e-9 * volume + curved_area * facet_distance;
  if (std::abs(mesh_volume - volume) > volume_tolerance) {
    return "the mesh holds " + figures(mesh_volume, volume, "m^3") + " of volume (tolerance " +
           format_number(100.0 * volume_tolerance / volume, 3) + " %)";
  }
  if (mesh_area > area * (1.0 + 1e-9) + 0.05 * curved_area) {
    return "the mesh boundary has " + figures(mesh_area, area, "m^2") + " of area (inner walls: it is hollow)";
  }
  Eigen::AlignedBox3d mesh_box;
  for (Eigen::Index i = 0; i < mesh.node_count(); ++i) mesh_box.extend(mesh.nodes().row(i).transpose());
  const double box_tolerance = on_surface + facet_distance;
  if ((mesh_box.min() - box.min()).cwiseAbs().maxCoeff() > box_tolerance ||
      (mesh_box.max() - box.max()).cwiseAbs().maxCoeff() > box_tolerance) {
    return "the mesh's bounding box differs from the surface's by " +
           format_number(std::max((mesh_box.min() - box.min()).cwiseAbs().maxCoeff(),
                                  (mesh_box.max() - box.max()).cwiseAbs().maxCoeff())) + " m";
  }
  return "";
}

}  // namespace

std::vector<std::string> TetrahedralizeOptions::problems() const {
  std::vector<std::string> out;
  if (target_tets < 10 || target_tets > 50'000'000) {
    out.push_back("target_tets " + format_number(target_tets) + " is outside [10, 5e7]");
  }
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

double tetrahedralize_memory_estimate(int target_tets) {
  return kTetrahedralizeBytesPerTet * target_tets + kTetrahedralizeFixedBytes;
}

std::int64_t tetrahedralize_version() {
  // Bump kAlgorithm when a change to this file (criteria, attempts, sliver passes, node order)
  // changes the mesh some surface gets: cached meshes of the old code then stop matching.
  constexpr std::int64_t kAlgorithm = 1;
  return kAlgorithm * 100000000000LL + static_cast<std::int64_t>(CGAL_VERSION_NR);
}

TetMesh tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options,
                       TetrahedralizeReport* report, ProgressSink* progress, const CancelToken* cancel) {
  options.validate();
  const std::string source = surface.source_name.empty() ? std::string("surface") : surface.source_name;
  require_memory(tetrahedralize_memory_estimate(options.target_tets), options.memory_limit_bytes,
                 "tetrahedralize: " + format_number(options.target_tets) + " tets");
  if (surface.face_count() < 4) throw InvalidInput(source + ": the surface has fewer than 4 faces");
  if (!surface.vertices.allFinite()) throw InvalidInput(source + ": a vertex has a non-finite coordinate");
  const double volume = signed_volume(surface);
  if (!(volume > 0.0)) {
    throw InvalidInput(source + ": the surface encloses no positive volume (open or inside out?)");
  }
  // Mesh a copy scaled by a power of two (exact both ways) to a diagonal in [1, 2): CGAL's
  // predicates are exact, but some of Mesh_3's tolerances are absolute, so a 1 µm body and a
  // 1 km one are meshed alike.
  const Eigen::Vector3d lo = surface.vertices.colwise().minCoeff(), hi = surface.vertices.colwise().maxCoeff();
  const double scale = std::ldexp(1.0, -std::ilogb((hi - lo).norm()));
  const double unscale = 1.0 / scale;
  const Polyhedron polyhedron = to_polyhedron(surface, scale);
  AabbTree tree(faces(polyhedron).first, faces(polyhedron).second, polyhedron);
  tree.accelerate_distance_queries();
  const double area = surface_area(surface);
  const Eigen::AlignedBox3d box(lo, hi);
  NullProgress null_progress;
  ProgressSink& sink = progress ? *progress : null_progress;

  TetrahedralizeReport local;
  TetrahedralizeReport& r = report ? *report : local;
  r = TetrahedralizeReport{};
  // Tet count N(h) ~ h^-p: p = 3 in bulk, less in plates a few elements thick. The first miss
  // is corrected with p = 3, later ones with p fitted on the last two attempts (secant in log-log).
  double cell_size = std::cbrt(volume / (kVolumePerCellSizeCubed * options.target_tets));
  // Size bound the body can hold: a Delaunay cell bigger than the body's thickness has its
  // circumcentre outside a plate and is dropped, which leaves the mesh hollow (a 1 × 1 × 0.05 m
  // tile at 500 tets kept 0.018 of its 0.05 m³). 2V/A is the thickness of a plate (a cube of side
  // a gives a/3).
  const double thickness = 2.0 * volume / area;
  double size_limit = kMaxSizePerThickness * thickness;
  // How far a boundary facet may sit from a curved surface: a quarter of the size bound, and at
  // most kFacetDistancePerThickness of the thickness, so a thin curved wall keeps its volume
  // (the facets' deficit is about area × distance, a fraction 2·distance/thickness of it).
  const auto facet_distance = [&](double size) { return std::min(size / 4.0, kFacetDistancePerThickness * thickness); };
  if (cell_size > size_limit) {
    const double needed = volume / (kVolumePerCellSizeCubed * size_limit * size_limit * size_limit);
    if (needed > kMaxTetsOverTarget * options.target_tets + kMaxExtraTets) {
      throw InvalidInput(source + ": " + format_number(options.target_tets) + " tets would be about " +
                         format_number(cell_size, 3) + " m across, too coarse for a body " + format_number(thickness, 3) +
                         " m thick (2V/A), which they would leave hollow; it needs a size bound of at most " +
                         format_number(size_limit, 3) + " m, at least about " + format_number(needed, 2) +
                         " tets: ask for that many");
    }
    cell_size = size_limit;
  }
  double previous_size = 0.0, previous_count = 0.0;
  TetMesh mesh;
  int count_attempts = 0, refills = 0;
  std::string problem;
  // A mesh that does not fill the surface: re-mesh with a smaller bound, which means more tets,
  // never more than kMaxTetsOverTarget times the request (plus kMaxExtraTets) nor more than
  // memory allows. Returns false when it gives up (`problem` then says why).
  const auto shrink_for_refill = [&]() {
    const double next = kRefillShrink * cell_size;
    const double next_tets = volume / (kVolumePerCellSizeCubed * next * next * next);
    if (refills++ == kMaxRefills) return false;
    if (next_tets > kMaxTetsOverTarget * options.target_tets + kMaxExtraTets) {
      problem += "; a finer bound would need about " + format_number(next_tets, 2) + " tets, more than " +
                 format_number(kMaxTetsOverTarget) + " times the " + format_number(options.target_tets) +
                 " asked for (ask for more)";
      return false;
    }
    require_memory(tetrahedralize_memory_estimate(static_cast<int>(next_tets)), options.memory_limit_bytes,
                   "tetrahedralize: re-meshing " + source + " with " + format_number(next_tets, 3) + " tets");
    size_limit = next;
    cell_size = next;
    previous_count = 0.0;
    return true;
  };
  for (int attempt = 0;; ++attempt) {
    if (cancel) cancel->throw_if_cancelled();
    const double from = 1.0 - std::ldexp(1.0, -attempt), to = 1.0 - std::ldexp(1.0, -attempt - 1);
    const double optimise_from = from + 0.8 * (to - from);
    sink.report("tetrahedralize", from);
    const double expected = volume / (kVolumePerCellSizeCubed * cell_size * cell_size * cell_size);
    // Refine only, and judge the attempt by its count and fill: sliver removal, which costs up
    // to several times the refinement on thin plates (docs/architecture.md), moves or drops only
    // a few percent of the tets and is spent on the accepted refinement alone.
    std::unique_ptr<Refinement> refinement = refine(polyhedron, options, scale * cell_size, scale * facet_distance(cell_size),
                                                    expected, sink, cancel, from, optimise_from);
    if (cancel) cancel->throw_if_cancelled();
    r.attempts = attempt + 1;
    r.cell_size = cell_size;
    // The refined complex may still hold a flat tet that sliver removal would remove (seen on a
    // 0.05 m thick curved shell): TetMesh refuses it, and such an attempt is judged by its count
    // alone. Whatever is accepted is checked after sliver removal below.
    try {
      problem = fill_problem(to_tet_mesh(refinement->c3t3, unscale, source), tree, scale, volume, area, box,
                             facet_distance(cell_size));
    } catch (const NumericalFailure&) {
      problem.clear();
    }
    if (!problem.empty()) {
      if (!shrink_for_refill()) break;
      continue;
    }
    const double count = static_cast<double>(refinement->c3t3.number_of_cells_in_complex());
    bool accept = std::abs(count / options.target_tets - 1.0) <= options.count_tolerance ||
                  ++count_attempts == kMaxAttempts;
    if (!accept) {
      double p = 3.0;
      if (previous_count > 0.0 && previous_count != count) {
        p = std::clamp(-std::log(count / previous_count) / std::log(cell_size / previous_size), 1.0, 4.0);
      }
      const double next = std::min(size_limit, cell_size * std::pow(count / options.target_tets, 1.0 / p));
      // Too many tets at the largest bound the body holds: a coarser mesh would be hollow.
      accept = next == cell_size;
      if (!accept) {
        previous_size = cell_size;
        previous_count = count;
        cell_size = next;
        continue;
      }
    }
    remove_slivers(*refinement, options, sink, cancel, optimise_from, to);
    if (cancel) cancel->throw_if_cancelled();
    mesh = to_tet_mesh(refinement->c3t3, unscale, source);
    // Perturbation moves boundary nodes along the surface and exudation changes which cells are
    // kept: the optimised mesh is checked again.
    problem = fill_problem(mesh, tree, scale, volume, area, box, facet_distance(cell_size));
    if (problem.empty() || !shrink_for_refill()) break;
  }
  if (!problem.empty()) {
    throw NumericalFailure(source + ": after " + format_number(r.attempts) + " attempts (last size bound " +
                           format_number(r.cell_size, 3) + " m) " + problem);
  }
  sink.report("tetrahedralize", 1.0);

  r.quality = mesh.quality();
  if (r.quality.min_dihedral_deg < options.refuse_below_dihedral_deg) {
    throw NumericalFailure(source + ": the mesh has a sliver (" + mesh.tet_label(r.quality.worst_dihedral_tet) +
                           ", min dihedral " + format_number(r.quality.min_dihedral_deg, 3) +
                           " deg) after sliver removal; more tets (a finer mesh) usually avoids it");
  }
  if (r.quality.min_dihedral_deg < 5.0) {
    r.warnings.push_back("min dihedral angle " + format_number(r.quality.min_dihedral_deg, 3) +
                         " deg is below 5 deg: stresses in that tet are unreliable");
  }
  const double ratio = static_cast<double>(mesh.tet_count()) / options.target_tets;
  if (std::abs(ratio - 1.0) > options.count_tolerance) {
    r.warnings.push_back(format_number(mesh.tet_count()) + " tets instead of the " + format_number(options.target_tets) +
                         " asked for");
  }
  return mesh;
}

}  // namespace fissure
