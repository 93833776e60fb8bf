#include "fissure/fracture/simulation.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/exemplar/pattern_stats.hpp"
#include "fissure/fracture/crack_noise.hpp"
#include "crack_path.hpp"
#include "nearest_seed.hpp"
#include "polygon_geometry.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>
#include <queue>

namespace fissure {
namespace {

using detail::position_before;
using Voigt = Eigen::Matrix<double, 6, 1>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

double normal_component(const Voigt& s, const Eigen::Vector3d& d) {
  return d.x() * d.x() * s(0) + d.y() * d.y() * s(1) + d.z() * d.z() * s(2) +
         2.0 * (d.y() * d.z() * s(3) + d.x() * d.z() * s(4) + d.x() * d.y() * s(5));
}

Voigt outer(const Eigen::Vector3d& d) {
  Voigt v;
  v << d.x() * d.x(), d.y() * d.y(), d.z() * d.z(), d.y() * d.z(), d.x() * d.z(), d.x() * d.y();
  return v;
}

// σ restricted to the plane orthogonal to the unit vector n, in an orthonormal basis (u, v) of
// that plane: [[uu, uv], [uv, vv]].
struct PlaneStress {
  Eigen::Vector3d u, v;
  double uu, vv, uv;
  double mid() const { return 0.5 * (uu + vv); }
  double radius() const { return std::sqrt(0.25 * (uu - vv) * (uu - vv) + uv * uv); }
};

PlaneStress plane_stress(const Voigt& s, const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = n.cross(a).normalized();
  const Eigen::Vector3d v = n.cross(u);
  const Eigen::Matrix3d t = voigt_to_tensor(s);
  return {u, v, u.dot(t * u), v.dot(t * v), u.dot(t * v)};
}

// The largest normal stress over directions in the plane orthogonal to n (Algorithm 1's crossing
// time bracket: no direction computed).
double tangent_max(const Voigt& s, const Eigen::Vector3d& n) {
  const PlaneStress p = plane_stress(s, n);
  return p.mid() + p.radius();
}

// That plane's two principal stresses (largest first) and the unit direction of the largest.
struct PlanePrincipal {
  double top, second;
  Eigen::Vector3d direction;
};

PlanePrincipal plane_principal(const Voigt& s, const Eigen::Vector3d& n) {
  const PlaneStress p = plane_stress(s, n);
  // The top eigenvector of [[uu, uv], [uv, vv]] at angle θ from u, tan 2θ = 2uv / (uu − vv).
  const double theta = 0.5 * std::atan2(2.0 * p.uv, p.uu - p.vv);
  return {p.mid() + p.radius(), p.mid() - p.radius(), std::cos(theta) * p.u + std::sin(theta) * p.v};
}

// One heap entry of Algorithm 1's event queue: the earliest time the tet may cross its
// resistance. Ordered by time, then by the larger stress-to-resistance ratio (the paper-gaps
// rule for cracks due at one instant, e.g. at t = 0), then by the tet's centroid (x, then y,
// then z), so the order is the body's, not its numbering's (ElementOrder tests).
struct Event {
  double time;
  double neg_ratio;
  Eigen::Vector3d where;  // the tet's centroid: distinct for distinct tets, whatever their numbering
  int tet;
  bool operator>(const Event& o) const {
    if (time != o.time) return time > o.time;
    if (neg_ratio != o.neg_ratio) return neg_ratio > o.neg_ratio;
    return position_before(o.where, where);
  }
};

// S_k, the crack's implicit function: the paper's noisy plane, or, for a turning crack, the same
// noise on the distance to its traced path (crack_path.hpp).
class CrackField {
public:
  explicit CrackField(CrackSurfaceFunction plane) : m_plane(std::move(plane)) {}
  void follow(detail::CrackPath path) { m_path = std::move(path); }
  double operator()(const Eigen::Vector3d& x) const { return m_path ? (*m_path)(x) + m_plane.noise(x) : m_plane(x); }
  void subtract(double offset) { m_plane.subtract(offset); }

private:
  CrackSurfaceFunction m_plane;
  std::optional<detail::CrackPath> m_path;
};

class Simulation {
public:
  Simulation(const FractureBody& body, const FractureParams& params, const StressField& initial,
             const Eigen::VectorXd& resistance, std::uint64_t seed, const SimulationOptions& options)
      : m_body(body), m_mesh(body.mesh()), m_params(params), m_initial(initial), m_resistance(resistance), m_seed(seed),
        m_options(options), m_propagation(m_mesh) {
    const auto n = static_cast<std::size_t>(m_mesh.tet_count());
    m_stress.resize(n);
    for (std::size_t t = 0; t < n; ++t) m_stress[t] = initial.row(static_cast<Eigen::Index>(t)).transpose();
    m_base_time.assign(n, 0.0);
    m_initiable.assign(n, 1);
    m_cuts_of_tet.resize(n);
    m_node_value.assign(static_cast<std::size_t>(m_mesh.node_count()), 0.0);
    m_node_stamp.assign(static_cast<std::size_t>(m_mesh.node_count()), -1);
    m_flood_stamp.assign(n, -1);
    m_snap = 1e-6 * body.mean_edge_length();
    m_near_crack.assign(n, kFar);
    if (params.crack_turning > 0.0 || params.star_biaxiality < 1.0) {
      // Paths as far as a crack can run (across the body), in steps of an element or of an eighth
      // of r_relax if that is finer, bending no tighter than r_relax/2 (or 1.5 elements, where
      // the mesh is coarser than that: crack_path.hpp), so the path does not depend on the mesh
      // where the mesh resolves it.
      const double h = body.mean_edge_length();
      const auto box = m_mesh.bounding_box();
      m_path.max_length = (box.row(1) - box.row(0)).norm();
      // Never finer than a quarter element: the P1 interpolant cannot show a finer course, and a
      // course traced at r_relax/8 for r_relax = 3 µm (in the fit's prior) had millions of points,
      // each node's value a pass over them (a 1,600-crack trial took 390 s).
      m_path.step = std::max(std::min(h, params.relax_radius / 8.0), h / 4.0);
      m_path.min_radius = std::max(params.relax_radius / 2.0, 1.5 * h);
      m_path.ends_at = [this](int tet) {
        for (const auto& [crack, cut] : m_cuts_of_tet[static_cast<std::size_t>(tet)])
          if (crack != m_path_leaves) return true;
        return false;
      };
      // Simplex noise's gradient is below ~3 per unit frequency (Gustavson's scaling); twice the
      // bound leaves room for the P1 interpolant of a curved surface in a long tet.
      double noise_slope = 0.0;
      for (const NoiseOctave& o : params.noise) noise_slope += o.amplitude * o.frequency * 3.0;
      m_max_slope = 2.0 * (1.0 + noise_slope);
      m_free_distance.assign(n, kInf);
      m_free_normal.assign(n, Eigen::Vector3d::Zero());
    }
    if (params.star_biaxiality < 1.0) {
      // Each boundary node's outward normal (area-weighted over its faces), for a star's kink.
      m_node_surface_normal.assign(static_cast<std::size_t>(m_mesh.node_count()), Eigen::Vector3d::Zero());
      for (const BoundaryFace& f : m_mesh.boundary_faces())
        for (int v : f.nodes) m_node_surface_normal[static_cast<std::size_t>(v)] += f.area * f.normal;
      for (Eigen::Vector3d& nrm : m_node_surface_normal)
        if (nrm.norm() > 0.0) nrm.normalize();
    }
    m_gc = critical_energy_release_rate(params);
    m_flaw = flaw_size(params);
    m_directional = resolve_directional();
    m_next_check = std::max(m_options.stop_check_at, 1);
  }

  FractureResult run() {
    FractureResult result;
    double now = m_options.fixed_time_step > 0.0 ? run_fixed_steps(result) : run_events(result);
    result.simulated_age = result.crack_limit_reached || m_stopped ? now : m_params.age;
    result.stopped_early = m_stopped;
    result.cracks = std::move(m_cracks);
    if (m_options.label_fragments) {
      result.fragments =
          label_fragments(m_mesh, result.cracks, static_cast<int>(result.cracks.size()), &result.partial_cracks);
    }
    if (m_options.progress) m_options.progress->report("simulate", 1.0);
    return result;
  }

private:
  // Whether stop_check asks to stop now (called once the crack count reaches the next check).
  bool stop_requested() {
    if (!m_options.stop_check || m_stopped || static_cast<int>(m_cracks.size()) < m_next_check) return m_stopped;
    const int next = m_options.stop_check(m_cracks);
    if (next <= 0) m_stopped = true;
    else m_next_check = std::max(next, static_cast<int>(m_cracks.size()) + 1);
    return m_stopped;
  }

  void after_crack(double now) {
    if ((m_cracks.size() & 63u) == 0) {
      if (m_options.cancel) m_options.cancel->throw_if_cancelled();
      if (m_options.progress) m_options.progress->report("simulate", m_params.age > 0.0 ? now / m_params.age : 1.0);
    }
  }

  // Algorithm 1 as printed: t = 0, Δt, 2Δt, … < age (and a last test at age itself); at each t
  // every element over its resistance cracks, the largest ratio first, re-tested after each
  // crack's relaxation.
  double run_fixed_steps(FractureResult& result) {
    const double step = m_options.fixed_time_step;
    double now = 0.0;
    for (long long i = 0;; ++i) {
      now = std::min(static_cast<double>(i) * step, m_params.age);
      for (;;) {
        int best = -1;
        double best_ratio = 1.0;
        for (int t = 0; t < m_mesh.tet_count(); ++t) {
          if (!m_initiable[static_cast<std::size_t>(t)]) continue;
          const double r = ratio(t, now);
          if (r >= best_ratio && (best < 0 || r > best_ratio || before(t, best))) {
            best = t;
            best_ratio = r;
          }
        }
        if (best < 0) break;
        if (static_cast<int>(m_cracks.size()) >= m_options.max_cracks) {
          result.crack_limit_reached = true;
          return now;
        }
        open_crack(best, now);
        after_crack(now);
        if (stop_requested()) return now;
      }
      if (now >= m_params.age) break;
    }
    return now;
  }

  double run_events(FractureResult& result) {
    const double age = m_params.age;
    // The queue starts from lower bounds of the crossing times, (R − λ_max)/rate (λ_max grows
    // at most at `rate`), from one vectorised λ_max pass: an early entry is re-checked when
    // popped like a stale one, so only the tets that come up pay for the exact crossing time.
    Eigen::VectorXd lambda;
    max_principal_of(m_initial, lambda);
    std::vector<Event> entries;
    entries.reserve(static_cast<std::size_t>(m_mesh.tet_count()));
    const double rate = m_params.stress_rate;
    for (int t = 0; t < m_mesh.tet_count(); ++t) {
      const double r = m_resistance(t);
      const double bound = lambda(t) >= r ? 0.0 : (rate > 0.0 ? (r - lambda(t)) / rate : kInf);
      if (bound <= age) entries.push_back({bound, -lambda(t) / r, m_mesh.centroid(t), t});
    }
    std::priority_queue<Event, std::vector<Event>, std::greater<>> queue(std::greater<>{}, std::move(entries));
    double now = 0.0;
    while (!queue.empty()) {
      const Event e = queue.top();
      if (e.time > age) break;
      queue.pop();
      if (!m_initiable[static_cast<std::size_t>(e.tet)]) continue;
      // The entry may be stale: relaxation since it was pushed can only have delayed it.
      const double when = crossing_time(e.tet, e.time);
      if (when > e.time) {
        if (when <= age) queue.push({when, -ratio(e.tet, when), m_mesh.centroid(e.tet), e.tet});
        continue;
      }
      if (static_cast<int>(m_cracks.size()) >= m_options.max_cracks) {
        result.crack_limit_reached = true;
        break;
      }
      now = e.time;
      open_crack(e.tet, now);
      after_crack(now);
      if (stop_requested()) break;
    }
    return now;
  }

  // Ties between tets at one instant with one ratio: the lower centroid (x, then y, then z)
  // first, so the choice is the body's, not the numbering's.
  bool before(int a, int b) const { return position_before(m_mesh.centroid(a), m_mesh.centroid(b)); }

  bool resolve_directional() const {
    switch (m_params.relaxation) {
      case RelaxationChoice::Directional: return true;
      case RelaxationChoice::Isotropic: return false;
      case RelaxationChoice::FromExemplar: {
        const double angle = m_options.exemplar_mean_junction_angle_deg;
        if (!std::isfinite(angle)) {
          throw InvalidInput("relaxation 'from-exemplar' needs an exemplar's mean junction angle; choose 'directional' "
                             "or 'isotropic', or fit the material to an exemplar");
        }
        return relaxation_mode_for(angle) == RelaxationMode::Directional;
      }
    }
    return true;
  }

  // σ_e at time t ≥ its base time: the stored stress plus the in-plane increase since.
  Voigt stress_at(int tet, double t) const {
    const auto e = static_cast<std::size_t>(tet);
    const double dt = t - m_base_time[e];
    if (dt == 0.0 || m_params.stress_rate == 0.0) return m_stress[e];
    return m_stress[e] + (dt * m_params.stress_rate) * m_body.tangent_projectors().row(tet).transpose();
  }

  double ratio(int tet, double t) const {
    return max_principal_stress(stress_at(tet, t)) / m_resistance(tet);
  }

  // The first time ≥ t at which λ_max(σ_e) ≥ R_e, or +∞. λ_max(σ + τ·rate·P) is non-decreasing
  // (P ⪰ 0) and convex in τ, bracketed by τ_lo = (R − λ)/rate (λ_max grows at most at `rate`) and
  // τ_hi = (R − μ)/rate with μ the largest in-plane normal stress (which grows at exactly `rate`).
  // Safeguarded Newton; the time returned always satisfies the test, evaluated exactly as the
  // caller will evaluate it, so a popped event is never re-queued for round-off.
  double crossing_time(int tet, double t) const {
    const double r = m_resistance(tet);
    const MaxPrincipal now = max_principal_with_direction(stress_at(tet, t));
    if (now.value >= r) return t;
    const double rate = m_params.stress_rate;
    if (rate <= 0.0) return kInf;
    const Eigen::Vector3d normal = m_body.surface_normals().row(tet).transpose();
    double lo = t + (r - now.value) / rate;
    double hi = t + (r - tangent_max(stress_at(tet, t), normal)) / rate;
    if (!(hi < kInf)) return kInf;
    if (max_principal_stress(stress_at(tet, lo)) >= r) return lo;
    // Newton from the upper end: on a convex increasing function it decreases monotonically to
    // the root and stays on the side where the test holds.
    double x = hi;
    for (int it = 0; it < 60; ++it) {
      const MaxPrincipal m = max_principal_with_direction(stress_at(tet, x));
      if (m.value < r) {  // round-off crossed the root: bisect the bracket instead
        lo = x;
        x = 0.5 * (lo + hi);
        continue;
      }
      hi = x;
      const Eigen::Vector3d& d = m.direction;
      const double slope = rate * (1.0 - std::pow(d.dot(normal), 2));
      double next = slope > 0.0 ? x - (m.value - r) / slope : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (hi - lo <= 1e-13 * std::max(1.0, std::abs(hi)) || m.value - r <= 1e-13 * r) break;
      x = next;
    }
    return hi;
  }

  double node_value(int crack, const CrackField& surface, int node) {
    const auto v = static_cast<std::size_t>(node);
    if (m_node_stamp[v] != crack) {
      double s = surface(m_mesh.nodes().row(node).transpose());
      // No node exactly on a crack: zero-area pieces would follow (paper-gaps §3).
      if (std::abs(s) < m_snap) s = s < 0.0 ? -m_snap : m_snap;
      m_node_value[v] = s;
      m_node_stamp[v] = crack;
    }
    return m_node_value[v];
  }

  CrackCut make_cut(int crack, const CrackField& surface, int tet) {
    CrackCut cut;
    cut.tet = tet;
    for (int i = 0; i < 4; ++i) cut.node_values[static_cast<std::size_t>(i)] = node_value(crack, surface, m_mesh.tets()(tet, i));
    return cut;
  }

  Eigen::Matrix<double, 4, 3> tet_nodes(int tet) const {
    Eigen::Matrix<double, 4, 3> p;
    for (int i = 0; i < 4; ++i) p.row(i) = m_mesh.nodes().row(m_mesh.tets()(tet, i));
    return p;
  }

  bool changes_sign(const CrackCut& cut) const {
    bool pos = false, neg = false;
    for (double v : cut.node_values) (v > 0.0 ? pos : neg) = true;
    return pos && neg;
  }

  // Star cracks (docs/fracture.md): under in-plane tension nearly equal in every direction no
  // direction is preferred, and a crack opens as three arms 120° apart (a Y) where one crack
  // would leave a straight line. The arms: a kinked crack whose two arms leave the origin 120°
  // apart, both 120° from the third, a crack of its own that runs from the kink. The third arm
  // runs along the single crack's course, across the max principal direction, to one side or the
  // other by (seed, crack).
  struct StarArms {
    Eigen::Vector3d minus_normal, plus_normal;  // the kinked crack's arms (CrackPath's kink)
    Eigen::Vector3d third;                      // the third arm's direction along the surface
    Eigen::Vector3d up;
    Eigen::Vector3d kink = Eigen::Vector3d::Zero();  // where the arms meet, a node (kinked_field)
    int start = -1;                                  // the tet the kinked crack floods from
  };

  // Each cut's polygon (clipped at junctions) and unit normal, for the relaxation.
  struct CrackPolygons {
    std::vector<std::vector<Eigen::Vector3d>> polygons;
    std::vector<Eigen::Vector3d> normals;
  };

  // Algorithm 1's crack at `origin`: one crack, or, where the stress there is biaxial enough, a
  // three-armed star (star_arms). A star is one event: its two cracks flood the stress of the
  // moment they open, and relax it together after.
  void open_crack(int origin, double t) {
    const int k = static_cast<int>(m_cracks.size());
    const Voigt stress = stress_at(origin, t);
    const MaxPrincipal principal = max_principal_with_direction(stress);
    CrackSurface crack;
    crack.id = k;
    crack.time = t;
    crack.origin_tet = origin;
    crack.origin = m_mesh.centroid(origin);
    crack.normal = opening_direction(stress, principal, k);
    crack.opening_stress = principal.value;
    crack.noise_seed = noise_seed(k);
    std::optional<StarArms> star = star_arms(origin, stress, crack.normal, k);
    std::optional<CrackField> kinked;
    if (star) kinked = kinked_field(crack, *star, t);
    if (!kinked) star.reset();  // no node to kink at: one crack
    CrackField surface = kinked ? std::move(*kinked) : single_field(crack, t);
    // A star floods from a tet around its kink, which the opening tet may not be; the opening
    // tet's flaw is spent either way.
    m_initiable[static_cast<std::size_t>(origin)] = 0;
    if (star) {
      crack.origin_tet = star->start;
      crack.origin = m_mesh.centroid(star->start);
    }
    const int start = crack.origin_tet;
    const CrackPolygons first = flood(std::move(crack), surface, start, t);
    record_crack_hops(k);
    std::optional<CrackPolygons> third;
    if (star && k + 1 < m_options.max_cracks) third = open_third_arm(k, *star, t);
    relax(k, first, t);
    if (third) relax(k + 1, *third, t);
  }

  // The paper's noisy plane through the origin's centroid with the crack's normal, or, for a
  // turning crack, the noise on the distance to its traced course; its P1 interpolant made to
  // vanish at the centroid (the mean of the origin's node values), so the opening element is
  // always cut, however large the noise.
  CrackField single_field(const CrackSurface& crack, double t) const {
    CrackField surface(CrackSurfaceFunction(crack.origin, crack.normal, m_params.noise, crack.noise_seed));
    if (m_params.crack_turning > 0.0) {
      surface.follow(detail::CrackPath(m_mesh, m_body.surface_normals(), crack.origin_tet, crack.origin, crack.normal,
                                       m_path, turn_for(t, false)));
    }
    double mean = 0.0;
    for (int i = 0; i < 4; ++i) mean += surface(m_mesh.nodes().row(m_mesh.tets()(crack.origin_tet, i)).transpose());
    surface.subtract(0.25 * mean);
    return surface;
  }

  // A star's kinked crack, its kink at a node of the opening tet on the surface the star runs
  // along (boundary normal within 45° of up), the nearest to the centroid that works; its
  // function made to vanish there. At a node the P1 interpolant bends with the crack: the traces
  // leave the node along the arms, exactly where the arms are straight, so the face sees a Y
  // down to the junction. A kink inside a tet is one plane there, across the third arm: a T
  // within half an element of the junction, which is where its directions are measured
  // (8–16 mm) on any mesh coarser than that (docs/fracture.md, "Star cracks"). The flood starts
  // in the first tet around the node (face neighbours, breadth first from the opening tet) that
  // the crack cuts clearly, by more than a thousandth of an element. Sets star.kink and
  // star.start; std::nullopt when no node qualifies (an opening tet off the surface).
  std::optional<CrackField> kinked_field(const CrackSurface& crack, StarArms& star, double t) const {
    const int origin = crack.origin_tet;
    const double clear = 1e-3 * m_body.mean_edge_length();
    std::array<int, 4> order{0, 1, 2, 3};
    const auto node = [&](int tet, int i) {
      return Eigen::Vector3d(m_mesh.nodes().row(m_mesh.tets()(tet, i)).transpose());
    };
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const double da = (node(origin, a) - crack.origin).squaredNorm(), db = (node(origin, b) - crack.origin).squaredNorm();
      return da != db ? da < db : a < b;
    });
    for (int i : order) {
      const int v = m_mesh.tets()(origin, i);
      if (!(m_node_surface_normal[static_cast<std::size_t>(v)].dot(star.up) >= std::sqrt(0.5))) continue;
      const Eigen::Vector3d kink = node(origin, i);
      CrackField surface(CrackSurfaceFunction(kink, crack.normal, m_params.noise, crack.noise_seed));
      surface.follow(detail::CrackPath(m_mesh, m_body.surface_normals(), origin, kink, star.minus_normal,
                                       star.plus_normal, m_path, turn_for(t, true)));
      surface.subtract(surface(kink));
      // The tets around node v, breadth first through faces from the opening tet.
      std::vector<int> around{origin};
      for (std::size_t q = 0; q < around.size() && q < 256; ++q) {
        const int tet = around[q];
        bool pos = false, neg = false;
        for (int j = 0; j < 4; ++j) {
          const double value = surface(node(tet, j));
          pos = pos || value > clear;
          neg = neg || value < -clear;
        }
        if (pos && neg) {
          star.kink = kink;
          star.start = tet;
          return surface;
        }
        for (int f = 0; f < 4; ++f) {
          const int u = m_mesh.neighbours()(tet, f);
          if (u < 0 || std::find(around.begin(), around.end(), u) != around.end()) continue;
          for (int j = 0; j < 4; ++j)
            if (m_mesh.tets()(u, j) == v) around.push_back(u);
        }
      }
    }
    return std::nullopt;
  }

  std::uint64_t noise_seed(int k) const {
    return Rng::derive(m_seed, "crack_noise", static_cast<std::uint64_t>(k)).next_u64();
  }

  // A star's arms turn only while closing in on an earlier crack within r_relax (to meet it
  // square). In the open, arms 120° apart turn toward the same principal direction, and so do
  // two arms leaving an earlier crack: they converged into teardrop loops, because the
  // relaxation that keeps real arms apart comes only after the path is traced. (Letting them turn
  // also beyond r_relax from the kink made the Ts no squarer: 24.7° off 90° against 24.0°,
  // FracturePhysics.)
  detail::CrackPath::Turn turn_for(double t, bool star_arm) const {
    return [this, t, star_arm](int from, int tet, const Eigen::Vector3d& normal, const Eigen::Vector3d& up,
                               double step) {
      if (star_arm && !(m_free_distance[static_cast<std::size_t>(tet)] < m_free_distance[static_cast<std::size_t>(from)]))
        return normal;
      return turn_heading(normal, tet, up, step, t);
    };
  }

  std::optional<StarArms> star_arms(int origin, const Voigt& stress, const Eigen::Vector3d& normal, int k) const {
    if (!(m_params.star_biaxiality < 1.0)) return std::nullopt;
    const Eigen::Vector3d up = m_body.surface_normals().row(origin).transpose();
    const PlanePrincipal p = plane_principal(stress, up);
    if (!(p.top > 0.0) || !(p.second >= m_params.star_biaxiality * p.top)) return std::nullopt;
    Eigen::Vector3d along = normal.cross(up);
    // A crack opening near parallel to the surface (at a side wall) delaminates: no surface star.
    if (along.norm() < 0.5) return std::nullopt;
    along.normalize();
    if (Rng::derive(m_seed, "star_side", static_cast<std::uint64_t>(k)).uniform(0.0, 1.0) < 0.5) along = -along;
    // v turned by θ about up (v ⊥ up).
    const auto turned = [&](const Eigen::Vector3d& v, double theta) {
      return Eigen::Vector3d(std::cos(theta) * v + std::sin(theta) * up.cross(v));
    };
    const Eigen::Vector3d minus_arm = turned(along, 2.0 * kPi / 3.0), plus_arm = turned(along, -2.0 * kPi / 3.0);
    // Normals on one side of the path, up × the direction of travel (in along the minus arm,
    // out along the plus arm): CrackPath's convention.
    return StarArms{minus_arm.cross(up), up.cross(plus_arm), along, up, Eigen::Vector3d::Zero(), -1};
  }

  // The star's third arm, crack k + 1: through the kinked crack's kink o along `star.third`
  // (its noise made to vanish at o, so it meets the kink there), opened in the first tet along
  // the arm, within a few elements of o, that no crack cuts and its own surface does; it floods
  // from there both ways, back to the kink, where it ends on the kinked crack (a T by the flood's
  // rules, a Y by its angles), and out. std::nullopt when no tet qualifies (a mesh too coarse for
  // the arm to leave the kink): the star stays a kinked crack.
  std::optional<CrackPolygons> open_third_arm(int k, const StarArms& star, double t) {
    const CrackSurface& kinked = m_cracks[static_cast<std::size_t>(k)];
    const Eigen::Vector3d o = star.kink;
    CrackSurface crack;
    crack.id = k + 1;
    crack.time = t;
    crack.normal = star.up.cross(star.third);
    crack.noise_seed = noise_seed(k + 1);
    CrackField surface(CrackSurfaceFunction(o, crack.normal, m_params.noise, crack.noise_seed));
    // Its path does not end in the kinked crack's tets it starts among.
    m_path_leaves = k;
    surface.follow(detail::CrackPath(m_mesh, m_body.surface_normals(), kinked.origin_tet, o, crack.normal, crack.normal,
                                     m_path, turn_for(t, true)));
    m_path_leaves = -1;
    surface.subtract(surface(o));
    const double h = m_body.mean_edge_length();
    int tet = kinked.origin_tet;
    for (int i = 1; i <= 8; ++i) {
      tet = detail::locate_tet(m_mesh, tet, o + (0.5 * h * i) * star.third);
      if (tet < 0) return std::nullopt;
      if (!m_cuts_of_tet[static_cast<std::size_t>(tet)].empty()) continue;
      CrackCut cut = make_cut(k + 1, surface, tet);
      if (!changes_sign(cut)) continue;
      crack.origin_tet = tet;
      crack.origin = m_mesh.centroid(tet);
      crack.opening_stress = max_principal_stress(stress_at(tet, t));
      crack.branch_of = k;
      return flood(std::move(crack), surface, tet, t);
    }
    return std::nullopt;
  }

  // Floods `crack` (id, time, origin tet and normal set) from tet `origin`, which `surface` cuts,
  // through the tets it crosses, and adds it to the cracks.
  CrackPolygons flood(CrackSurface crack, const CrackField& surface, int origin, double t) {
    const int k = crack.id;

    // Flood (paper-gaps §3): breadth first through the faces the surface crosses, with an
    // energy budget carried along each path (docs/fracture.md): each tet adds A_e (G_e − G_c),
    // where G_e = π a σ_n² / E is Griffith's release rate for a crack of size a = max(√(A/π),
    // a_f) under the normal stress σ_n across it, and the budget a path carries decays as
    // exp(−ℓ/r_relax) over the distance ℓ it travels; a tet that would drive its path's budget
    // below zero is not entered. One budget for the whole crack (paper-gaps' reading) let energy
    // released in one place carry the crack anywhere: a crack opened in tension ran 0.7 m through
    // unstressed material, and cracks opened at a tile's side walls delaminated it. Energy
    // released at the front drives it only within the distance over which a crack redistributes
    // stress, r_relax.
    std::vector<CrackCut>& cuts = crack.cuts;
    // A frontier entry: a tet of E_c, its path's budget, and how many tets in a row the flood has
    // entered on it without paying (to close a junction: see below).
    struct Front {
      int tet;
      int cut;  // index in cuts
      int free_steps;
      double budget;  // energy carried along the path to this tet, J
    };
    std::deque<Front> frontier;
    // Each cut's polygon (clipped at a junction) as the flood measured it, kept for the crack's
    // area and the relaxation.
    CrackPolygons out;
    double area = 0.0;
    auto release = [&](int tet, const std::vector<Eigen::Vector3d>& polygon) {
      const Eigen::Vector3d av = detail::polygon_area_vector(polygon);
      const double a_e = 0.5 * av.norm();
      if (a_e <= 0.0) return std::pair{0.0, 0.0};
      const double sn = std::max(0.0, normal_component(stress_at(tet, t), av / av.norm()));
      const double size = std::max(std::sqrt(area / kPi), m_flaw);
      return std::pair{a_e * (kPi * size * sn * sn / m_params.youngs_modulus - m_gc), a_e};
    };
    {
      CrackCut first = make_cut(k, surface, origin);
      out.polygons.push_back(crack_polygon(tet_nodes(origin), first));
      const auto [gain, a_e] = release(origin, out.polygons.back());
      area = a_e;
      cuts.push_back(first);
      m_flood_stamp[static_cast<std::size_t>(origin)] = k;
      frontier.push_back({origin, 0, 0, std::max(0.0, gain)});
    }
    const bool on_path = m_max_slope < kInf;  // a turning crack or a star's arm may follow a path
    std::vector<int> stopped_on;
    while (!frontier.empty()) {
      const Front front = frontier.front();
      frontier.pop_front();
      const int tet = front.tet;
      // In a T-junction tet the crack exists on its arrival side of the earlier crack only; it
      // goes on through the faces its trace crosses on that side, to close the junction there.
      const CrackCut clipped = cuts[static_cast<std::size_t>(front.cut)];
      const CrackCut* clip = clipped.clipped_by >= 0 ? &cut_of(clipped.clipped_by, tet) : nullptr;
      for (int f = 0; f < 4; ++f) {
        const int u = m_mesh.neighbours()(tet, f);
        if (u < 0 || m_flood_stamp[static_cast<std::size_t>(u)] == k) continue;
        // Only through faces the surface crosses: the face's three nodes change sign.
        const auto& face = TetMesh::kLocalFaces[static_cast<std::size_t>(f)];
        bool pos = false, neg = false;
        for (int i : face) (node_value(k, surface, m_mesh.tets()(tet, i)) > 0.0 ? pos : neg) = true;
        if (!(pos && neg)) continue;
        // From a T tet, on through any face where part of the trace lies on the arrival side: the
        // middle of the trace alone missed faces the clipping crack crosses, and left the
        // junction open on the visible face (demo tile: 100 of 136 free ends).
        if (clip && !trace_reaches_side(tet, f, k, surface, *clip, clipped.clip_side)) continue;
        CrackCut cut = make_cut(k, surface, u);
        if (on_path && too_steep(u, cut)) continue;
        const auto nodes_u = tet_nodes(u);
        const auto& earlier = m_cuts_of_tet[static_cast<std::size_t>(u)];
        const CrackCut* u_clip = nullptr;
        std::vector<Eigen::Vector3d> polygon;  // this crack's polygon in u, clipped at a T
        if (!earlier.empty()) {
          // Crack meets crack: end on the side it arrived from (the side holding the middle of
          // its trace on the shared face) of the crack it runs into first. Where several earlier
          // cracks cut u (a corner), that is the one leaving the least of its polygon on the
          // arrival side: clipping by the earliest one left gaps before a nearer crack (on the
          // demo tile, interior free ends on the visible face 160 → 136).
          double least = kInf;
          for (const auto& [i, i_cut] : earlier) {
            const CrackCut& other = m_cracks[static_cast<std::size_t>(i)].cuts[static_cast<std::size_t>(i_cut)];
            CrackCut trial = cut;
            trial.clipped_by = i;
            // Going on along the crack it already ends on, it stays on the same side of it (the
            // P1 values of that crack are shared across the face).
            trial.clip_side =
                clip && i == clipped.clipped_by ? clipped.clip_side : arrival_side(tet, f, u, k, surface, other);
            auto trial_polygon = crack_polygon(nodes_u, trial, &other);
            const double remaining = detail::polygon_area(trial_polygon);
            if (remaining < least) {
              least = remaining;
              cut.clipped_by = i;
              cut.clip_side = trial.clip_side;
              u_clip = &other;
              polygon = std::move(trial_polygon);
            }
          }
        }
        if (!u_clip) polygon = crack_polygon(nodes_u, cut);
        const auto [gain, a_e] = release(u, polygon);
        // Arrest here when u would take the path's budget below zero (another path may still
        // reach u), unless the tip is closing a junction: entering a tet of the crack it runs
        // into, or closing in on an earlier crack a few element sizes away (the earlier crack's
        // free surface concentrates stress at an approaching tip; a crack that stops just short
        // of another reads as a gap in the drawing, not a T). Such unpaid steps end kJoinHops
        // tets after the last paid one: the gaps they close are the mesh's, an element or two
        // wide, and without the cap a crack with no energy ran on along every crack it met
        // (tangent cracks opened at a tile's side walls delaminated it through T tets).
        const int near_u = m_near_crack[static_cast<std::size_t>(u)];
        const bool closing_in = u_clip || (near_u <= kJoinHops && near_u < m_near_crack[static_cast<std::size_t>(tet)]);
        const double carried =
            front.budget * std::exp(-(m_mesh.centroid(u) - m_mesh.centroid(tet)).norm() / m_params.relax_radius);
        const double path_budget = carried + gain;
        const bool paid = path_budget >= 0.0;
        if (!paid && !(closing_in && front.free_steps < kJoinHops)) continue;
        area += a_e;
        m_flood_stamp[static_cast<std::size_t>(u)] = k;
        cuts.push_back(cut);
        out.polygons.push_back(std::move(polygon));
        if (u_clip) stopped_on.push_back(cut.clipped_by);
        frontier.push_back(
            {u, static_cast<int>(cuts.size()) - 1, paid ? 0 : front.free_steps + 1, paid ? path_budget : 0.0});
      }
    }
    std::sort(stopped_on.begin(), stopped_on.end());
    stopped_on.erase(std::unique(stopped_on.begin(), stopped_on.end()), stopped_on.end());
    crack.stopped_on = std::move(stopped_on);

    out.normals.resize(cuts.size());
    double total_area = 0.0;
    for (std::size_t i = 0; i < cuts.size(); ++i) {
      const Eigen::Vector3d av = detail::polygon_area_vector(out.polygons[i]);
      out.normals[i] = av.norm() > 0.0 ? Eigen::Vector3d(av.normalized()) : crack.normal;
      total_area += 0.5 * av.norm();
    }
    crack.area = total_area;
    for (std::size_t i = 0; i < cuts.size(); ++i) {
      const auto tet = static_cast<std::size_t>(cuts[i].tet);
      m_initiable[tet] = 0;
      m_cuts_of_tet[tet].emplace_back(k, static_cast<int>(i));
    }
    m_cracks.push_back(std::move(crack));
    return out;
  }

  const CrackCut& cut_of(int crack, int tet) const {
    for (const auto& [j, index] : m_cuts_of_tet[static_cast<std::size_t>(tet)]) {
      if (j == crack) return m_cracks[static_cast<std::size_t>(j)].cuts[static_cast<std::size_t>(index)];
    }
    throw NumericalFailure("fracture simulation: crack " + std::to_string(crack) + " does not cut " + m_mesh.tet_label(tet));
  }

  // Whether crack k's trace on local face f of `tet` has a point on side `side` (±1) of crack
  // `other`'s P1 interpolant in `tet` (≥ 0 kept, crack_polygon's rule): its end points on the
  // face's edges are enough, the interpolant being linear along the trace.
  bool trace_reaches_side(int tet, int f, int k, const CrackField& surface, const CrackCut& other, int side) {
    const auto& face = TetMesh::kLocalFaces[static_cast<std::size_t>(f)];
    for (int a = 0; a < 3; ++a) {
      const int la = face[static_cast<std::size_t>(a)], lb = face[static_cast<std::size_t>((a + 1) % 3)];
      const double va = node_value(k, surface, m_mesh.tets()(tet, la)), vb = node_value(k, surface, m_mesh.tets()(tet, lb));
      if ((va > 0.0) == (vb > 0.0)) continue;
      const double s = va / (va - vb);
      const double h = (1.0 - s) * other.node_values[static_cast<std::size_t>(la)] + s * other.node_values[static_cast<std::size_t>(lb)];
      if (side * h >= 0.0) return true;
    }
    return false;
  }

  // The crack's normal: the max principal direction, except where the largest principal stress
  // is repeated (equi-biaxial tension, e.g. uniform in-plane shrinkage with no resistance
  // spread): any direction in that eigenspace is one, and the eigensolver's choice is the same
  // fixed axis every time, which filled a tile with parallel cracks (mean junction angle 10°).
  // There the direction is drawn in the plane of the two top eigenvectors from (seed, crack).
  Eigen::Vector3d opening_direction(const Voigt& stress, const MaxPrincipal& principal, int k) const {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(voigt_to_tensor(stress));
    const Eigen::Vector3d& values = eigen.eigenvalues();  // ascending
    const double scale = std::max(std::abs(values(2)), std::abs(values(1)));
    // Equal to round-off: a stress built from equal parts differs in its last bits only.
    if (!(values(2) - values(1) <= 1e-9 * scale)) return principal.direction;
    const double angle = Rng::derive(m_seed, "crack_direction", static_cast<std::uint64_t>(k)).uniform(0.0, kPi);
    return (std::cos(angle) * eigen.eigenvectors().col(2) + std::sin(angle) * eigen.eigenvectors().col(1)).normalized();
  }

  // The middle of crack k's trace on local face f of `tet` (the mean of its points on the face's
  // edges), or the tet's centroid when the face is not crossed.
  Eigen::Vector3d trace_middle(int tet, int f, int k, const CrackField& surface) {
    const auto& face = TetMesh::kLocalFaces[static_cast<std::size_t>(f)];
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (int a = 0; a < 3; ++a) {
      const int na = m_mesh.tets()(tet, face[static_cast<std::size_t>(a)]);
      const int nb = m_mesh.tets()(tet, face[static_cast<std::size_t>((a + 1) % 3)]);
      const double va = node_value(k, surface, na), vb = node_value(k, surface, nb);
      if ((va > 0.0) == (vb > 0.0)) continue;
      const double s = va / (va - vb);
      sum += m_mesh.nodes().row(na).transpose() + s * (m_mesh.nodes().row(nb) - m_mesh.nodes().row(na)).transpose();
      ++count;
    }
    return count ? Eigen::Vector3d(sum / count) : m_mesh.centroid(tet);
  }

  // Crack paths (docs/fracture.md): the heading of a crack entering `to` from `from`. Its part
  // along the surface (orthogonal to the nearest surface normal n_s) turns toward p, the top
  // principal direction of the stress in the tangent plane, by the fraction w = 1 − exp(−a·ℓ/ℓ_t)
  // of the way: ℓ the step (centroid to centroid), ℓ_t = r_relax·(1 − β)/β the turning length
  // (β = crack_turning; β = 1 turns at once), and a = (λ₁ − max(λ₂, 0))/R_e ∈ [0, 1] how much
  // more one direction pulls than the other, against the element's resistance: in equi-biaxial
  // tension p means nothing and the crack runs straight, and in a relaxed region a weak stress
  // cannot swing it around. Per length, not per element, so a finer mesh turns a crack as much.
  // Turning only along the surface keeps a crack across the surface: surface tension opens
  // cracks there, and a crack turned parallel to it would delaminate the body.
  Eigen::Vector3d turn_heading(const Eigen::Vector3d& heading, int to, const Eigen::Vector3d& n_s, double step,
                               double t) const {
    const PlanePrincipal top = plane_principal(turning_stress(to, t), n_s);
    const double a = std::clamp((top.top - std::max(top.second, 0.0)) / m_resistance(to), 0.0, 1.0);
    const Eigen::Vector3d along = heading - heading.dot(n_s) * n_s;
    if (!(a > 0.0) || along.norm() < 1e-6) return heading;
    const double beta = m_params.crack_turning;
    double w = 1.0;
    if (beta < 1.0) {
      w = 1.0 - std::exp(-a * step * beta / (m_params.relax_radius * (1.0 - beta)));
    }
    const Eigen::Vector3d p = top.direction.dot(along) < 0.0 ? Eigen::Vector3d(-top.direction) : top.direction;
    const Eigen::Vector3d target = p * along.norm() + heading.dot(n_s) * n_s;
    const Eigen::Vector3d turned = heading + w * (target - heading);
    const double norm = turned.norm();
    return norm > 1e-12 ? Eigen::Vector3d(turned / norm) : heading;
  }

  // Whether the P1 interpolant of `cut` in `tet` is steeper than a turning crack's field can be:
  // the path distance has slope 1 and the noise octaves add at most Σ A_i·f_i·|∇simplex|, so a
  // slope several times that is the jump of D across a bend's medial axis (crack_path.hpp), not
  // a crack; the flood does not enter there.
  bool too_steep(int tet, const CrackCut& cut) const {
    const auto p = tet_nodes(tet);
    Eigen::Matrix3d a;
    for (int i = 0; i < 3; ++i) a.row(i) = p.row(i + 1) - p.row(0);
    const auto& v = cut.node_values;
    const Eigen::Vector3d g = a.partialPivLu().solve(Eigen::Vector3d(v[1] - v[0], v[2] - v[0], v[3] - v[0]));
    return !(g.norm() <= m_max_slope);
  }

  // The stress a turning tip in `tet` answers to: the stress map, except that in directional mode
  // the normal stress across the nearest earlier crack within r_relax is released in full, by the
  // kernel φ (Eq. 2), instead of by at most v_relax: that crack's faces carry no traction, so a tip
  // closing in on it turns to meet it square, as cracks in tiles, glazes and mud do (a T near
  // 90°). The map itself keeps Eq. 3's partial release, which sets when elements crack.
  Voigt turning_stress(int tet, double t) const {
    Voigt s = stress_at(tet, t);
    const auto e = static_cast<std::size_t>(tet);
    if (!m_directional || !(m_free_distance[e] < kInf)) return s;
    const double phi = relaxation_kernel(m_free_distance[e], m_params.relax_radius);
    const Eigen::Vector3d& d = m_free_normal[e];
    s -= phi * std::max(0.0, normal_component(s, d)) * outer(d);
    return s;
  }

  // ±1: the sign of crack `other`'s P1 interpolant (in tet u) at the middle of crack k's trace on
  // the face through which k arrives from `from` (its local face f).
  int arrival_side(int from, int f, int u, int k, const CrackField& surface, const CrackCut& other) {
    const Eigen::Vector3d mid = trace_middle(from, f, k, surface);
    // Barycentric coordinates of `mid` in u give the P1 value of `other` there.
    const auto p = tet_nodes(u);
    Eigen::Matrix3d a;
    a.col(0) = (p.row(1) - p.row(0)).transpose();
    a.col(1) = (p.row(2) - p.row(0)).transpose();
    a.col(2) = (p.row(3) - p.row(0)).transpose();
    const Eigen::Vector3d b = a.partialPivLu().solve(mid - p.row(0).transpose());
    const double value = (1.0 - b.sum()) * other.node_values[0] + b(0) * other.node_values[1] +
                         b(1) * other.node_values[2] + b(2) * other.node_values[3];
    return value >= 0.0 ? 1 : -1;
  }

  // Eqs. 2–4 around the new crack, in every tet within r_relax of its polygons (distances
  // through the body, by nearest-polygon propagation). Tensile-only clamp (paper-gaps §4,
  // reading b): at most the tensile normal stress along d is removed, so λ_max never rises.
  void relax(int k, const CrackPolygons& crack, double t) {
    const auto& polygons = crack.polygons;
    const auto& normals = crack.normals;
    const double radius = m_params.relax_radius, rate = m_params.relax_rate;
    const bool turning = m_params.crack_turning > 0.0;
    if ((rate <= 0.0 && !turning) || radius <= 0.0) return;
    const auto& cuts = m_cracks[static_cast<std::size_t>(k)].cuts;
    std::vector<std::pair<int, int>> seeds;
    seeds.reserve(cuts.size());
    for (std::size_t i = 0; i < cuts.size(); ++i) seeds.emplace_back(cuts[i].tet, static_cast<int>(i));
    m_propagation.run(
        seeds,
        [&](int tet, int i) {
          return detail::polygon_distance(m_mesh.centroid(tet), polygons[static_cast<std::size_t>(i)],
                                          normals[static_cast<std::size_t>(i)]);
        },
        radius);
    for (int tet : m_propagation.reached()) {
      const double distance = m_propagation.distance_of(tet);
      const double phi = relaxation_kernel(distance, radius);
      if (phi <= 0.0) continue;
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      if (m_directional || turning) {
        // d: orthogonal to the nearest surface normal and to the crack's path along the
        // surface, i.e. the crack normal projected on the tangent plane (paper §5.2).
        const Eigen::Vector3d n_s = m_body.surface_normals().row(tet).transpose();
        const Eigen::Vector3d& c = normals[static_cast<std::size_t>(m_propagation.seed_of(tet))];
        d = c - c.dot(n_s) * n_s;
        d = d.norm() > 0.1 ? Eigen::Vector3d(d.normalized()) : c;  // a crack parallel to the surface
      }
      const auto e = static_cast<std::size_t>(tet);
      if (turning && distance < m_free_distance[e]) {
        m_free_distance[e] = distance;
        m_free_normal[e] = d;
      }
      if (rate <= 0.0) continue;
      m_stress[e] = relax_element_stress(stress_at(tet, t), rate * phi, m_directional, d);
      m_base_time[e] = t;
    }
  }

  // Tet hops from every tet within kJoinHops of the new crack to it, kept as the minimum over
  // all cracks so far (for the join rule of the flood). Hops through face adjacency, not
  // distances: a hop is about one element size, and a breadth-first pass over the few tets around
  // a crack costs a fraction of the polygon distances relaxation needs.
  void record_crack_hops(int k) {
    const auto& cuts = m_cracks[static_cast<std::size_t>(k)].cuts;
    m_hop_frontier.clear();
    for (const CrackCut& c : cuts) {
      m_near_crack[static_cast<std::size_t>(c.tet)] = 0;
      m_hop_frontier.push_back(c.tet);
    }
    for (int hop = 1; hop <= kJoinHops && !m_hop_frontier.empty(); ++hop) {
      m_hop_next.clear();
      for (int tet : m_hop_frontier) {
        for (int f = 0; f < 4; ++f) {
          const int u = m_mesh.neighbours()(tet, f);
          if (u < 0 || m_near_crack[static_cast<std::size_t>(u)] <= hop) continue;
          m_near_crack[static_cast<std::size_t>(u)] = static_cast<std::uint8_t>(hop);
          m_hop_next.push_back(u);
        }
      }
      std::swap(m_hop_frontier, m_hop_next);
    }
  }

  const FractureBody& m_body;
  const TetMesh& m_mesh;
  const FractureParams& m_params;
  const StressField& m_initial;
  const Eigen::VectorXd& m_resistance;
  std::uint64_t m_seed;
  SimulationOptions m_options;
  detail::NearestSeedPropagation m_propagation;
  std::vector<Voigt> m_stress;
  std::vector<double> m_base_time;
  std::vector<char> m_initiable;
  std::vector<std::vector<std::pair<int, int>>> m_cuts_of_tet;  // (crack, index of its cut)
  std::vector<double> m_node_value;
  std::vector<int> m_node_stamp;
  std::vector<int> m_flood_stamp;
  // Tet hops to the nearest earlier crack, up to kJoinHops (kFar beyond).
  std::vector<std::uint8_t> m_near_crack;
  // With crack turning: the distance to the nearest earlier crack within r_relax (∞ beyond) and
  // the relaxation direction d of its nearest polygon (turning_stress).
  std::vector<double> m_free_distance;
  std::vector<Eigen::Vector3d> m_free_normal;
  // With star cracks: each boundary node's outward normal (zero inside).
  std::vector<Eigen::Vector3d> m_node_surface_normal;
  std::vector<int> m_hop_frontier, m_hop_next;
  // A tip this many tets from an earlier crack, and closing in, runs on to it whatever its budget.
  static constexpr int kJoinHops = 3;
  static constexpr std::uint8_t kFar = 255;
  std::vector<CrackSurface> m_cracks;
  double m_snap = 0.0, m_gc = 0.0, m_flaw = 0.0;
  detail::CrackPath::Options m_path;
  int m_path_leaves = -1;  // a crack whose tets do not end the path being traced (a star's third arm)
  double m_max_slope = kInf;
  bool m_directional = true;
  bool m_stopped = false;  ///< stop_check asked to stop
  int m_next_check = 0;    ///< the crack count of stop_check's next call

};

void check_inputs(const FractureBody& body, const FractureParams& params, const StressField& initial,
                  const Eigen::VectorXd& resistance, const SimulationOptions& options) {
  params.validate();
  const TetMesh& mesh = body.mesh();
  if (initial.rows() != mesh.tet_count()) {
    throw InvalidInput("fracture simulation: the initial stress has " + std::to_string(initial.rows()) +
                       " rows for " + std::to_string(mesh.tet_count()) + " tets");
  }
  if (resistance.size() != mesh.tet_count()) {
    throw InvalidInput("fracture simulation: " + std::to_string(resistance.size()) + " resistances for " +
                       std::to_string(mesh.tet_count()) + " tets");
  }
  for (int t = 0; t < mesh.tet_count(); ++t) {
    if (!initial.row(t).allFinite()) throw InvalidInput("fracture simulation: the initial stress of " + mesh.tet_label(t) + " is not finite");
    const double r = resistance(t);
    if (!(r > 0.0) || !std::isfinite(r)) {
      throw InvalidInput("fracture simulation: the resistance of " + mesh.tet_label(t) + " is " + format_number(r) +
                         " Pa; it must be positive and finite");
    }
  }
  if (options.max_cracks < 0) throw InvalidInput("fracture simulation: max_cracks is negative");
  if (!(options.fixed_time_step >= 0.0) || !std::isfinite(options.fixed_time_step)) {
    throw InvalidInput("fracture simulation: fixed_time_step " + format_number(options.fixed_time_step) +
                       " must be a finite number ≥ 0");
  }
}

}  // namespace

double relaxation_kernel(double distance, double radius) {
  if (!(radius > 0.0) || !(std::abs(distance) < radius)) return 0.0;
  // (d/r)², not d²/r²: for r below ~1e-154 (the table admits any r > 0) r² underflows to 0 and
  // d²/r² is 0/0 = NaN at d = 0, which the relaxation would spread into every stress it touches.
  const double u = distance / radius;
  const double q = 1.0 - u * u;
  return q * q * q;
}

Eigen::Matrix<double, 6, 1> relax_element_stress(const Eigen::Matrix<double, 6, 1>& stress, double amount,
                                                 bool directional, const Eigen::Vector3d& direction) {
  Voigt s = stress;
  if (directional) {
    s -= std::min(amount, std::max(0.0, normal_component(s, direction))) * outer(direction);
  } else {
    s.head<3>().array() -= std::min(amount, std::max(0.0, max_principal_stress(s)));
  }
  return s;
}

double critical_energy_release_rate(const FractureParams& params) {
  return params.fracture_toughness * params.fracture_toughness / params.youngs_modulus;
}

double flaw_size(const FractureParams& params) {
  const double k = params.fracture_toughness / params.resistance_mean;
  return k * k / kPi;
}

FractureResult simulate_fracture(const FractureBody& body, const FractureParams& params, const StressField& initial_stress,
                                 const Eigen::VectorXd& resistance, std::uint64_t seed,
                                 const SimulationOptions& options) {
  check_inputs(body, params, initial_stress, resistance, options);
  Simulation simulation(body, params, initial_stress, resistance, seed, options);
  return simulation.run();
}

}  // namespace fissure
