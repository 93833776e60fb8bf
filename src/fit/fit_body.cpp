#include "fissure/fit/fit_body.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/parallel.hpp"
#include "fissure/fem/load.hpp"
#include "fissure/mesh/tetrahedralize.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

std::vector<std::string> FitBodyOptions::problems() const {
  std::vector<std::string> out;
  const auto positive = [&](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) out.push_back(std::string(name) + " " + format_number(v) + " is not positive");
  };
  positive(long_side, "the fit body's long side");
  positive(thickness, "the fit body's thickness");
  if (tile) {
    positive(tile->width, "the fit body's width");
    positive(tile->height, "the fit body's height");
    positive(tile->thickness, "the fit body's thickness");
  }
  if (tets < 0 || tets > 2000000) out.push_back("the fit body's tet count " + std::to_string(tets) + " is outside [0, 2000000]");
  if (tets_per_fragment < 1) out.push_back("tets per fragment " + std::to_string(tets_per_fragment) + " is below 1");
  if (min_tets < 100 || max_tets < min_tets) {
    out.push_back("the fit body's tet range [" + std::to_string(min_tets) + ", " + std::to_string(max_tets) + "] is empty or below 100");
  }
  if (load_grid < 1 || load_grid > 32) out.push_back("the load grid " + std::to_string(load_grid) + " is outside [1, 32]");
  if (!(load_inset >= 0.0 && load_inset < 0.5)) out.push_back("the load inset " + format_number(load_inset) + " is outside [0, 0.5)");
  return out;
}

FitBodyPlan plan_fit_body(int fragments, double aspect, const FitBodyOptions& options) {
  const auto list = options.problems();
  if (!list.empty()) throw InvalidInput(list.front());
  FitBodyPlan plan;
  if (options.tile) {
    plan.tile = *options.tile;
  } else {
    if (!(aspect > 0.0) || !std::isfinite(aspect)) throw InvalidInput("the exemplar's aspect ratio " + format_number(aspect) + " is not positive");
    plan.tile.width = aspect >= 1.0 ? options.long_side : options.long_side * aspect;
    plan.tile.height = aspect >= 1.0 ? options.long_side / aspect : options.long_side;
    plan.tile.thickness = options.thickness;
  }
  if (options.tets > 0) {
    plan.tets = plan.wanted_tets = options.tets;
    return plan;
  }
  const double wanted = static_cast<double>(std::max(fragments, 1)) * options.tets_per_fragment;
  plan.wanted_tets = static_cast<int>(std::min(wanted, 1e9));
  plan.tets = std::clamp(plan.wanted_tets, options.min_tets, options.max_tets);
  plan.capped = plan.wanted_tets > options.max_tets;
  if (plan.capped) {
    plan.note = "the exemplar's " + std::to_string(fragments) + " fragments want " + std::to_string(plan.wanted_tets) +
                " tets (" + std::to_string(options.tets_per_fragment) + " per fragment); the fit body is capped at " +
                std::to_string(options.max_tets) + ", so the finest fragments are under-resolved";
  }
  return plan;
}

FitBody::FitBody(const FitBodyPlan& plan, const FitBodyOptions& options, const ElasticMaterial& material, int threads,
                 ProgressSink* progress, const CancelToken* cancel)
    : m_plan(plan) {
  TetrahedralizeOptions mesh_options;
  mesh_options.target_tets = plan.tets;
  auto mesh = std::make_shared<TetMesh>(
      tetrahedralize(make_tile_surface(plan.tile), mesh_options, nullptr, progress, cancel));
  if (cancel) cancel->throw_if_cancelled();
  m_prepared = std::make_unique<PreparedBody>(mesh, material, FractureScenario{}, threads);
  m_box = m_prepared->mesh().bounding_box();
  const int g = options.load_grid;
  const Eigen::Vector3d up = m_prepared->scenario().up;
  for (int k = 0; k < g * g; ++k) m_positions.push_back(grid_load_position(*mesh, Eigen::Vector3d::UnitZ(), g, options.load_inset, k));
  const std::size_t tets = static_cast<std::size_t>(mesh->tet_count());
  m_unit_fields.assign(m_positions.size() * tets * 6, 0.0f);
  // Each position's field is independent; the factor and the recovery operator are shared
  // read-only (PreparedBody is immutable).
  parallel_for_dynamic(m_positions.size(), threads, [&](std::size_t k) {
    if (cancel) cancel->throw_if_cancelled();
    const LoadSpec load = patch_load(*mesh, up, m_positions[k], 1.0, m_prepared->scenario().patch_radius);
    const StressField field = m_prepared->stress_of_forces(assemble_load(*mesh, load));
    float* out = m_unit_fields.data() + k * tets * 6;
    for (std::size_t t = 0; t < tets; ++t)
      for (int c = 0; c < 6; ++c) out[t * 6 + static_cast<std::size_t>(c)] = static_cast<float>(field(static_cast<Eigen::Index>(t), c));
    if (progress) progress->report("tabulate loads", static_cast<double>(k + 1) / static_cast<double>(m_positions.size()));
  });
}

Eigen::Vector2d FitBody::load_fraction(int k) const {
  const Eigen::Vector3d& p = load_position(k);
  return {(p.x() - m_box(0, 0)) / (m_box(1, 0) - m_box(0, 0)), (p.y() - m_box(0, 1)) / (m_box(1, 1) - m_box(0, 1))};
}

void FitBody::initial_stress(int k, double force, StressField& out) const {
  const std::size_t tets = static_cast<std::size_t>(mesh().tet_count());
  out.resize(static_cast<Eigen::Index>(tets), 6);
  const float* in = m_unit_fields.data() + static_cast<std::size_t>(k) * tets * 6;
  for (std::size_t t = 0; t < tets; ++t)
    for (int c = 0; c < 6; ++c) out(static_cast<Eigen::Index>(t), c) = force * static_cast<double>(in[t * 6 + static_cast<std::size_t>(c)]);
}

}  // namespace fissure
