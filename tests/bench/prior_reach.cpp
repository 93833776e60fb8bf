// prior_reach: what patterns the fit's prior (paper Table 3) can produce, and where the shared
// exemplars sit among them (issue 10, "Expressiveness"; docs/fracture.md, "What the prior reaches").
// scripts/prior-reach.sh runs it and turns its output into the section's tables.
//
//   prior_reach --out runs.jsonl [--images DIR] [--image-size PX] [--draws N] [--seed S]
//               [--tets N] [--tile W,H,T] [--material NAME|FILE] [--age A] [--corners 0|1] [--exemplar NAME=PNG]...
//
// One body, prepared once: the tile meshed by CGAL (as `fissure fracture tile:W,H,T --tets N`
// does), the default supports and load. Physical values from the material (ceramic-tile); the
// five fitted parameters (dσ_e, r_relax, v_relax, R_cvar, l) from table3_priors(), their
// references R_cm (the material's) and √(fragment area). The latter is the exemplar's: its mean
// normalised fragment area times the body's visible area (paper-gaps §2). One prior run has to
// serve every exemplar, so r_relax is drawn up to the largest exemplar scale and each exemplar's
// own prior is the sub-box r_relax ≤ its scale (the report filters the draws by it; uniform
// draws stay uniform on the sub-box).
//
// Runs, each under directional (Eq. 3) and isotropic (Eq. 4) relaxation with the same
// parameters and seed (so the two modes are paired):
//  - the 32 corners of the 5-D box, seed 1 (one resistance field and noise for every corner, so
//    the differences between corners are the parameters'); a PNG of each into --images;
//  - the centre of the box and each parameter alone at its low and high end (seed 1, PNGs);
//  - N uniform draws from the box, draw i with its own seed.
// Each run's visible pattern is measured by compute_pattern_stats (the fit's statistics, on the
// geometry, at the fit's reference resolution) and compared by Eq. 5 with every exemplar given.
// Output: one JSON object per line: "exemplar" records first, then "run" records (schema in
// write_run below). Deterministic: serial, seeded fissure::Rng streams only.

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/exemplar/similarity.hpp"
#include "fissure/fit/fit_prior.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/fracture/pattern_image.hpp"
#include "fissure/fracture/prepared_body.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/simulation.hpp"
#include "fissure/fracture/visible_pattern.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace {
using namespace fissure;

struct Args {
  std::string out;
  std::string images;
  int image_size = 256;
  int draws = 300;
  std::uint64_t seed = 1;
  int tets = 24000;
  std::string tile = "tile:1,1,0.02";
  std::string material = kDefaultMaterialName;
  double age = -1.0;  // < 0: the material's
  bool corners = true;
  std::vector<std::pair<std::string, std::string>> exemplars;  // name, PNG path
};

[[noreturn]] void usage(const std::string& problem) {
  throw InvalidInput(problem +
                     "\nusage: prior_reach --out runs.jsonl [--images DIR] [--image-size PX] [--draws N] [--seed S] "
                     "[--tets N] [--tile tile:W,H,T] [--material NAME|FILE] [--age A] [--corners 0|1] [--exemplar NAME=PNG]...");
}

double parse_count(const std::string& text, const std::string& flag, double lo, double hi) {
  const std::vector<double> v = parse_number_list(text, flag, 1, "a number");
  if (!(v[0] >= lo && v[0] <= hi) || v[0] != std::floor(v[0])) {
    usage(flag + " " + text + " is not an integer in [" + format_number(lo) + ", " + format_number(hi) + "]");
  }
  return v[0];
}

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) usage(flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--out") a.out = value;
    else if (flag == "--images") a.images = value;
    else if (flag == "--image-size") a.image_size = static_cast<int>(parse_count(value, flag, 64, 4096));
    else if (flag == "--draws") a.draws = static_cast<int>(parse_count(value, flag, 0, 1e6));
    else if (flag == "--seed") a.seed = static_cast<std::uint64_t>(parse_count(value, flag, 0, 1e15));
    else if (flag == "--tets") a.tets = static_cast<int>(parse_count(value, flag, 100, 1e7));
    else if (flag == "--tile") a.tile = value;
    else if (flag == "--material") a.material = value;
    else if (flag == "--corners") a.corners = parse_count(value, flag, 0, 1) != 0;
    else if (flag == "--age") a.age = parse_number_list(value, flag, 1, "a number")[0];
    else if (flag == "--exemplar") {
      const auto eq = value.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == value.size()) usage("--exemplar " + value + " is not NAME=PNG");
      a.exemplars.emplace_back(value.substr(0, eq), value.substr(eq + 1));
    } else {
      usage("unknown option " + flag);
    }
  }
  if (a.out.empty()) usage("--out is required");
  return a;
}

// The four statistics the prior is summarised by, plus two cheap ones, from one PatternStats.
// NaN where a statistic is undefined (no degree-3 junction, fewer than two fragments or cracks),
// written as null: an unbroken tile has no T fraction, and 0 would be a value.
struct Summary {
  int fragments = 0;
  double t_fraction = std::numeric_limits<double>::quiet_NaN();
  double mean_angle_deg = std::numeric_limits<double>::quiet_NaN();
  double std_log_area = std::numeric_limits<double>::quiet_NaN();
  double junction_density = 0.0;
  double std_log_length = std::numeric_limits<double>::quiet_NaN();
  int t = 0, y = 0, x = 0, ends = 0;
};

double std_log10(const std::vector<double>& values) {
  if (values.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  double mean = 0.0;
  for (double v : values) mean += std::log10(v);
  mean /= static_cast<double>(values.size());
  double ss = 0.0;
  for (double v : values) ss += (std::log10(v) - mean) * (std::log10(v) - mean);
  return std::sqrt(ss / static_cast<double>(values.size()));  // population: the pattern is the population
}

Summary summarise(const PatternStats& s) {
  Summary m;
  m.fragments = s.fragment_count;
  if (s.t_count + s.y_count > 0) {
    m.t_fraction = static_cast<double>(s.t_count) / (s.t_count + s.y_count);  // among degree-3, as exemplar-table.sh
  }
  if (s.junction_count > 0) m.mean_angle_deg = s.mean_junction_angle_deg;
  m.std_log_area = std_log10(s.fragment_areas);
  m.junction_density = s.junction_density;
  m.std_log_length = std_log10(s.crack_lengths);
  m.t = s.t_count;
  m.y = s.y_count;
  m.x = s.x_count;
  m.ends = s.end_count;
  return m;
}

nlohmann::ordered_json number_or_null(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; }

nlohmann::ordered_json to_json(const Summary& m) {
  return {{"fragments", m.fragments},
          {"t_fraction", number_or_null(m.t_fraction)},
          {"mean_junction_angle_deg", number_or_null(m.mean_angle_deg)},
          {"std_log10_area", number_or_null(m.std_log_area)},
          {"junction_density", m.junction_density},
          {"std_log10_length", number_or_null(m.std_log_length)},
          {"t", m.t},
          {"y", m.y},
          {"x", m.x},
          {"free_ends", m.ends}};
}

struct Exemplar {
  std::string name;
  PatternStats stats;
  double fragment_scale = 0.0;  ///< √(mean normalised fragment area × body's visible area), m
};

// One box of the five fitted parameters, in table3_priors() order, in absolute units.
// The fit's box (fit_prior.hpp) plus the corners this report draws.
struct PriorBox : fissure::PriorBox {
  std::array<double, 5> corner_lo{};  // lo, or just above it where the range excludes lo
};

PriorBox prior_box(const FractureParams& base, double fragment_scale) {
  PriorBox box;
  static_cast<fissure::PriorBox&>(box) = make_prior_box(base, fragment_scale);
  const auto& table = fracture_parameter_table();
  for (std::size_t k = 0; k < 5; ++k) {
    // r_relax's range excludes 0: its low corner is 1 % of the box, far below an element size
    // (≈ 1.5 cm at 24K tets on the 1 m tile), where relaxation and the per-path energy decay
    // act as at 0.
    const ParameterInfo& info = table[box.row[k]];
    box.corner_lo[k] = (info.min_exclusive && box.lo[k] <= info.min) ? box.lo[k] + 0.01 * (box.hi[k] - box.lo[k])
                                                                     : box.lo[k];
  }
  return box;
}

struct Body {
  std::unique_ptr<PreparedBody> prepared;
  double visible_area = 0.0;
};

class Runner {
public:
  Runner(const Args& args, const FractureParams& base, const Body& body, const std::vector<Exemplar>& exemplars)
      : m_args(args), m_base(base), m_body(body), m_exemplars(exemplars) {}

  // Runs `values` (absolute, table3_priors order) under both relaxation modes; returns the lines.
  void run(const std::string& kind, int index, const std::array<double, 5>& values, const PriorBox& box,
           std::uint64_t seed, const std::string& image_stem, std::string& out) {
    FractureParams p = m_base;
    for (std::size_t k = 0; k < 5; ++k) parameter_value(p, box.row[k]) = values[k];
    const StressField initial = m_body.prepared->initial_stress(p);
    const Eigen::VectorXd resistance = draw_resistance(m_body.prepared->mesh().centroids(), p, seed);
    for (RelaxationChoice mode : {RelaxationChoice::Directional, RelaxationChoice::Isotropic}) {
      p.relaxation = mode;
      const auto start = std::chrono::steady_clock::now();
      const FractureResult result = simulate_fracture(m_body.prepared->fracture_body(), p, initial, resistance, seed);
      const VisiblePattern visible = extract_visible_pattern(m_body.prepared->mesh(), result.cracks,
                                                             static_cast<int>(result.cracks.size()),
                                                             m_body.prepared->scenario().up);
      if (!visible.has_visible_face) throw InvalidInput("prior_reach: the body has no visible face: " + visible.empty_reason);
      PatternStats stats = compute_pattern_stats(visible.graph, visible.stats_options);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

      nlohmann::ordered_json line = {{"record", "run"}, {"kind", kind}, {"index", index}, {"mode", to_string(mode)},
                                     {"seed", seed}};
      nlohmann::ordered_json params, fractions;
      for (std::size_t k = 0; k < 5; ++k) {
        const char* name = table3_priors()[k].name;
        params[name] = values[k];
        fractions[name] = box.hi[k] > box.lo[k] ? (values[k] - box.lo[k]) / (box.hi[k] - box.lo[k]) : 0.0;
      }
      line["params"] = params;
      line["box_fraction"] = fractions;
      line["stats"] = to_json(summarise(stats));
      line["fracture"] = {{"cracks", result.cracks.size()},
                          {"partial_cracks", result.partial_cracks.size()},
                          {"fragments_3d", result.fragments.count},
                          {"seconds", seconds}};
      // The total (weights 3, 1, 1) and its unweighted EMD terms, so the report can say which
      // statistic keeps a draw from an exemplar.
      nlohmann::ordered_json eq5, terms;
      for (const Exemplar& e : m_exemplars) {
        const Similarity d = pattern_similarity(stats, e.stats);
        eq5[e.name] = d.total;
        terms[e.name] = {d.fragment, d.crack, d.junction};
      }
      line["eq5"] = eq5;
      line["eq5_terms"] = terms;
      if (!image_stem.empty() && !m_args.images.empty()) {
        PatternImageOptions image;
        image.long_side_px = m_args.image_size;
        // Thinner than the fit's 3 px at 1024: at 256 px a 3 px line would fill the dense corners.
        image.line_width_px = 1.5;
        const std::string file = image_stem + "-" + to_string(mode) + ".png";
        write_pattern_image(std::filesystem::path(m_args.images) / file, render_pattern_image(visible, image));
        line["image"] = file;
      }
      out += line.dump() + "\n";
      std::fprintf(stderr, "prior_reach: %s %d %s: %zu cracks, %d fragments, %.2f s\n", kind.c_str(), index,
                   to_string(mode), result.cracks.size(), stats.fragment_count, seconds);
    }
  }

private:
  const Args& m_args;
  const FractureParams& m_base;
  const Body& m_body;
  const std::vector<Exemplar>& m_exemplars;
};

int run(const Args& args) {
  const FractureMaterial material = load_material(find_material(args.material));
  FractureParams base = material.params;
  // Age is an input the user sets, not a fitted parameter; only dσ_e·age reaches the stress map,
  // so a different age rescales dσ_e's prior. Overridable to show what another age would reach.
  if (args.age >= 0.0) base.age = args.age;
  base.validate();

  // The body, once: as `fissure fracture tile:W,H,T --tets N` meshes and prepares it.
  const TileSpec tile = parse_tile_spec(args.tile);
  TetrahedralizeOptions mesh_options;
  mesh_options.target_tets = args.tets;
  auto mesh = std::make_shared<const TetMesh>(tetrahedralize(make_tile_surface(tile), mesh_options));
  Body body;
  body.prepared = std::make_unique<PreparedBody>(mesh, base.elastic(), FractureScenario{});
  body.visible_area = extract_visible_pattern(*mesh, {}, 0, body.prepared->scenario().up).graph.total_area;

  std::string out;
  std::vector<Exemplar> exemplars;
  double largest_scale = 0.0;
  for (const auto& [name, path] : args.exemplars) {
    Exemplar e;
    e.name = name;
    e.stats = analyze_exemplar(path).stats;
    if (e.stats.fragment_areas.empty()) throw InvalidInput("prior_reach: exemplar " + path + " has no fragment");
    double mean_area = 0.0;
    for (double a : e.stats.fragment_areas) mean_area += a;
    mean_area /= static_cast<double>(e.stats.fragment_areas.size());
    e.fragment_scale = std::sqrt(mean_area * body.visible_area);
    largest_scale = std::max(largest_scale, e.fragment_scale);
    nlohmann::ordered_json line = {{"record", "exemplar"},
                                   {"name", name},
                                   {"path", path},
                                   {"fragment_scale_m", e.fragment_scale},
                                   {"relaxation_mode", to_string(e.stats.relaxation_mode)},
                                   {"stats", to_json(summarise(e.stats))}};
    out += line.dump() + "\n";
    exemplars.push_back(std::move(e));
  }
  // Without exemplars, the scale of the material's own r_relax: the box then holds the default.
  const double fragment_scale = largest_scale > 0.0 ? largest_scale : base.relax_radius;
  const PriorBox box = prior_box(base, fragment_scale);
  nlohmann::ordered_json header = {{"record", "body"},
                                   {"tile", args.tile},
                                   {"tets", mesh->tet_count()},
                                   {"visible_area_m2", body.visible_area},
                                   {"material", material.name},
                                   {"age", base.age},
                                   {"fragment_scale_m", fragment_scale},
                                   {"draws", args.draws},
                                   {"seed", args.seed}};
  for (std::size_t k = 0; k < 5; ++k) {
    header["prior"][table3_priors()[k].name] = {box.lo[k], box.hi[k], box.corner_lo[k]};
  }
  out.insert(0, header.dump() + "\n");

  Runner runner(args, base, body, exemplars);
  // Corners: bit k set = parameter k (table3_priors order) at its high end.
  for (int c = 0; c < (args.corners ? 32 : 0); ++c) {
    std::array<double, 5> v{};
    std::string bits;
    for (std::size_t k = 0; k < 5; ++k) {
      const bool high = (c >> k) & 1;
      v[k] = high ? box.hi[k] : box.corner_lo[k];
      bits += high ? 'H' : 'L';
    }
    runner.run("corner", c, v, box, 1, "prior-" + bits, out);
  }
  // One parameter at a time: the centre of the box, then each parameter at its low and high end
  // with the others at the centre (seed 1). The corners mostly show the two extremes of dσ_e
  // (unbroken, or driven far past R_cm); these show what each parameter does on its own.
  const char* const kSymbols[] = {"dse", "rrelax", "vrelax", "rcvar", "l"};
  for (int a = 0; a < (args.corners ? 11 : 0); ++a) {
    std::array<double, 5> v{};
    for (std::size_t k = 0; k < 5; ++k) v[k] = 0.5 * (box.lo[k] + box.hi[k]);
    std::string stem = "prior-mid";
    if (a > 0) {
      const std::size_t k = static_cast<std::size_t>((a - 1) / 2);
      const bool high = (a - 1) % 2 == 1;
      v[k] = high ? box.hi[k] : box.corner_lo[k];
      stem += std::string("-") + kSymbols[k] + (high ? "-high" : "-low");
    }
    runner.run("axis", a, v, box, 1, stem, out);
  }
  for (int i = 0; i < args.draws; ++i) {
    Rng rng = Rng::derive(args.seed, "prior_draw", static_cast<std::uint64_t>(i));
    std::array<double, 5> v{};
    // (lo, hi]: 1 − u lies in (0, 1], so r_relax, whose range excludes 0, is never 0.
    for (std::size_t k = 0; k < 5; ++k) v[k] = box.lo[k] + (box.hi[k] - box.lo[k]) * (1.0 - rng.uniform());
    runner.run("draw", i, v, box, rng.next_u64(), "", out);
  }
  write_file_atomically(args.out, out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse_args(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "prior_reach: " << e.what() << '\n';
    return 1;
  }
}
