#pragma once
/// The body every trial of a fit fractures (paper §6.2: "a rectangular tile geometry,
/// proportioned similar to the exemplar"): a tile with the exemplar's aspect ratio, its long side
/// 1 m and 2 cm thick unless told otherwise, meshed once, resting on its rim (the default
/// supports), struck on its top face by the default patch at a position each trial draws.
///
/// The static fields are tabulated (performance.md §4.2, measured there against modal and direct
/// solves): the recovered σ⁰ of a unit patch load at each of G × G positions on the top face
/// (a grid over its inner part), stored in single precision. A trial's σ⁰ is then the drawn
/// position's field times l·m·g: exact for that position, no solve. The paper's uniform law on
/// the load position becomes a uniform law on the grid's G² positions.
///
/// Resolution follows the exemplar: a pattern of F fragments needs enough elements per fragment
/// to be reproducible, so the tet count is `tets_per_fragment`·F, at least `min_tets` (the paper's
/// 24,000) and at most `max_tets`; beyond the cap the plan says so (FitBodyPlan::capped).
#include "fissure/base/progress.hpp"
#include "fissure/exemplar/pattern_stats.hpp"
#include "fissure/fracture/fracture_scenario.hpp"
#include "fissure/fracture/prepared_body.hpp"
#include "fissure/mesh/tile.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fissure {

struct FitBodyOptions {
  double long_side = 1.0;              ///< m, the tile's longer side when `tile` is not given
  double thickness = 0.02;             ///< m
  std::optional<TileSpec> tile;        ///< --body W,H,T: overrides the aspect rule
  int tets = 0;                        ///< > 0: this many tets, whatever the exemplar
  int tets_per_fragment = 120;         ///< the resolution rule (elements per exemplar fragment)
  int min_tets = 24000;
  int max_tets = 60000;                ///< the cap
  int load_grid = 8;                   ///< G: G × G tabulated load positions
  double load_inset = kDrawnLoadInset; ///< the grid spans [inset, 1 − inset] of each side
  std::vector<std::string> problems() const;
};

struct FitBodyPlan {
  TileSpec tile;
  int tets = 0;          ///< asked of the mesher
  int wanted_tets = 0;   ///< what the resolution rule asked before the cap
  bool capped = false;   ///< the rule asked more than max_tets
  std::string note;      ///< one line for the user when capped (empty otherwise)
};

/// The plan for an exemplar with `fragments` fragments whose frame is `aspect` = width / height.
/// Throws InvalidInput for invalid options or an aspect that is not positive and finite.
FitBodyPlan plan_fit_body(int fragments, double aspect, const FitBodyOptions& options);

class FitBody {
public:
  /// Meshes the tile (tetrahedralize, seed 0: the same mesh every time), prepares it for the
  /// base material's elastic constants and tabulates the G² unit-load fields. Cancellable.
  FitBody(const FitBodyPlan& plan, const FitBodyOptions& options, const ElasticMaterial& material, int threads = 1,
          ProgressSink* progress = nullptr, const CancelToken* cancel = nullptr);

  const FitBodyPlan& plan() const { return m_plan; }
  const PreparedBody& prepared() const { return *m_prepared; }
  const TetMesh& mesh() const { return m_prepared->mesh(); }
  int load_positions() const { return static_cast<int>(m_positions.size()); }
  /// The centre of load patch k on the top face, m.
  const Eigen::Vector3d& load_position(int k) const { return m_positions.at(static_cast<std::size_t>(k)); }
  /// The load position as fractions of the top face (0..1 along x and y), for the material's load rule.
  Eigen::Vector2d load_fraction(int k) const;
  /// σ⁰ (Pa) of a patch at position k pushing with `force` N: the tabulated unit field × force.
  void initial_stress(int k, double force, StressField& out) const;
  /// The top face's area, m² (the visible area the statistics are normalised by).
  double visible_area() const { return m_plan.tile.width * m_plan.tile.height; }
  /// Bytes held by the tabulated fields.
  std::size_t table_bytes() const { return m_unit_fields.size() * sizeof(float); }

private:
  FitBodyPlan m_plan;
  std::unique_ptr<PreparedBody> m_prepared;
  std::vector<Eigen::Vector3d> m_positions;
  Eigen::Matrix<double, 2, 3> m_box;
  std::vector<float> m_unit_fields;  ///< position-major: tets × 6 per position, row-major per tet
};

}  // namespace fissure
