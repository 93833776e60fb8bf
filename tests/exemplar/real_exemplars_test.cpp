// The 15 real traced masks in ../shared/exemplars (third-party data, read in place, never copied)
// against the statistics of an independent implementation in ref-stats/.

#include "fissure/base/content_hash.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/exemplar/similarity.hpp"
#include "fissure/exemplar/stats_json.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>

namespace fissure {
namespace {
namespace fs = std::filesystem;

fs::path exemplar_dir() { return test::shared_dir() / "exemplars"; }

struct Case {
  const char* name;
  bool closed;  ///< a closed network (README: all but the two marked open)
};
const Case kCases[] = {
    {"kz-mudcrack-300", true},         {"kz-mudcrack-3-6", true},         {"ace-craquelure-fl187", true},
    {"ace-craquelure-ge230", true},    {"sh-craquelure-dutch784", true},  {"sh-craquelure-dutch335", true},
    {"sh-craquelure-dutch247", true},  {"sh-craquelure-dutch785", true},  {"sh-craquelure-dutch59", true},
    {"sh-craquelure-dutch792", true},  {"sh-craquelure-dutch898", true},  {"sh-craquelure-dutch903", true},
    {"sh-craquelure-dutch895", true},  {"sh-craquelure-flemish103", false}, {"sh-craquelure-dutch529", false},
};

// The reference's statistics as a PatternStats with Fissure's bins, built from its lists (the
// reference's own histograms use other definitions for junctions): fragment areas with the crack
// pixels given to the nearest fragment (as Fissure does), crack lengths over √(image area), and
// junctions counted in the 4 × 4 windows of the S3 histogram (pattern_stats.hpp).
PatternStats reference_stats(const nlohmann::json& ref) {
  PatternStats s;
  s.fragment_area_hist = Histogram::make(-6.0, 0.0, 24);
  for (double a : ref["fragments"]["areas_with_cracks"]) s.fragment_area_hist.add(std::log10(a));
  s.fragment_area_hist.normalize();
  s.crack_length_hist = Histogram::make(-4.0, 0.0, 16);
  for (double l : ref["cracks"]["lengths"]) s.crack_length_hist.add(std::log10(std::max(l, 1e-12)));
  s.crack_length_hist.normalize();
  const double w = ref["image"]["width"], h = ref["image"]["height"];
  constexpr int k = 4;
  std::vector<int> counts(k * k, 0);
  for (const auto& j : ref["junctions"]["list"]) {
    const int wx = std::clamp(static_cast<int>((j["x"].get<double>() + 0.5) / w * k), 0, k - 1);
    const int wy = std::clamp(static_cast<int>((j["y"].get<double>() + 0.5) / h * k), 0, k - 1);
    ++counts[static_cast<std::size_t>(wy * k + wx)];
  }
  s.junction_density_hist = Histogram::make(0.0, 5.0, 20);
  for (int count : counts) s.junction_density_hist.add(std::log10(1.0 + count * (k * k)));
  s.junction_density_hist.normalize();
  return s;
}

nlohmann::json read_reference(const std::string& name) {
  std::ifstream in(exemplar_dir() / "ref-stats" / (name + ".json"));
  return nlohmann::json::parse(in);
}

// Fissure's statistics of every shared exemplar, computed once for all the tests below.
const std::map<std::string, PatternStats>& our_stats() {
  static const std::map<std::string, PatternStats> stats = [] {
    std::map<std::string, PatternStats> out;
    for (const Case& c : kCases) out[c.name] = analyze_exemplar(exemplar_dir() / (std::string(c.name) + ".png")).stats;
    return out;
  }();
  return stats;
}

bool shared_exemplars_present() {
  for (const Case& c : kCases) {
    if (!fs::exists(exemplar_dir() / (std::string(c.name) + ".png")) ||
        !fs::exists(exemplar_dir() / "ref-stats" / (std::string(c.name) + ".json"))) {
      return false;
    }
  }
  return true;
}

class RealExemplar : public ::testing::TestWithParam<Case> {};

TEST_P(RealExemplar, CountsAgreeWithTheIndependentReference) {
  const Case c = GetParam();
  if (!shared_exemplars_present()) {
    GTEST_SKIP() << "shared exemplars not found at " << exemplar_dir() << " (set FISSURE_SHARED_DIR)";
  }
  const nlohmann::json ref = read_reference(c.name);
  const ExemplarAnalysis a = analyze_exemplar(exemplar_dir() / (std::string(c.name) + ".png"));
  const int ref_fragments = ref["fragments"]["count"], ref_junctions = ref["junctions"]["count"];
  const int ref_cracks = ref["cracks"]["count"];
  const Similarity d = pattern_similarity(a.stats, reference_stats(ref));
  std::printf("%-26s fragments %4d / %4d, junctions %4d / %4d, cracks %4d / %4d, mean angle %.1f, "
              "Eq. 5 to the reference %.4f (%.4f %.4f %.4f)\n",
              c.name, a.stats.fragment_count, ref_fragments, a.stats.junction_count, ref_junctions, a.stats.crack_count,
              ref_cracks, a.stats.mean_junction_angle_deg, d.total, d.fragment, d.crack, d.junction);
  if (c.closed) {
    // Issue 4: on the closed networks, fragments within 10 % and junctions within 15 %.
    EXPECT_LE(std::abs(a.stats.fragment_count - ref_fragments), 0.10 * ref_fragments);
    EXPECT_LE(std::abs(a.stats.junction_count - ref_junctions), 0.15 * ref_junctions);
    // Cracks within 12 %: the spread the pruning settings cause in the reference's own counts
    // (its README, "Robustness": doubling the spur length lowers crack and junction counts
    // ~12 %). Measured −8.5 % … 0 %.
    EXPECT_LE(std::abs(a.stats.crack_count - ref_cracks), 0.12 * ref_cracks);
  } else {
    // The two open patches hold 27 and 67 reference cracks; their noisy blobs are where the two
    // prunings differ most (README: up to 2.7× without pruning on these sh- crops). 25 %:
    // twice the closed networks' band. Measured −11 % and −19 %.
    EXPECT_LE(std::abs(a.stats.crack_count - ref_cracks), 0.25 * ref_cracks);
  }
  // Both implementations measure the crack width as area over skeleton length.
  const double ref_width = ref["crack_width_px"]["area_over_length"];
  EXPECT_NEAR(a.diagnostics.crack_width_px, ref_width, 0.15 * ref_width);

}
INSTANTIATE_TEST_SUITE_P(Shared, RealExemplar, ::testing::ValuesIn(kCases),
                         [](const auto& info) {
                           std::string name = info.param.name;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

// Mud cracks are Y-like, painting craquelure T-like (README: 15–17 % vs 52–84 % T junctions):
// the mean junction angle must send them to different relaxation modes.
TEST(RealExemplarAngles, MudIsIsotropicCraquelureIsDirectional) {
  const fs::path mud = exemplar_dir() / "kz-mudcrack-3-6.png";
  const fs::path craquelure = exemplar_dir() / "sh-craquelure-dutch784.png";
  if (!fs::exists(mud) || !fs::exists(craquelure)) GTEST_SKIP() << "shared exemplars not found";
  const PatternStats m = analyze_exemplar(mud).stats, c = analyze_exemplar(craquelure).stats;
  EXPECT_EQ(m.relaxation_mode, RelaxationMode::Isotropic) << m.mean_junction_angle_deg;
  EXPECT_EQ(c.relaxation_mode, RelaxationMode::Directional) << c.mean_junction_angle_deg;
  EXPECT_LT(static_cast<double>(m.t_count) / m.junction_count, 0.3);
  EXPECT_GT(static_cast<double>(c.t_count) / c.junction_count, 0.4);
}


// Eq. 5 between Fissure's statistics of each exemplar and the independent reference's, against
// the distances between different exemplars (measured: own reference 0.004–0.036 on the closed
// networks, 0.028 and 0.060 on the open ones; the closest two different exemplars, the dense
// rectangular craquelure crops dutch785 and dutch59, are 0.053 apart).
TEST(RealExemplarDistances, EachIsClosestToItsOwnReference) {
  if (!shared_exemplars_present()) GTEST_SKIP() << "shared exemplars not found at " << exemplar_dir();
  std::map<std::string, PatternStats> refs;
  for (const Case& c : kCases) refs[c.name] = reference_stats(read_reference(c.name));
  double closest_pair = 1e9;
  for (const Case& a : kCases) {
    SCOPED_TRACE(a.name);
    const double own = pattern_similarity(our_stats().at(a.name), refs.at(a.name)).total;
    // The two implementations must disagree less than two different patterns do: below 0.05 on
    // the closed networks (under the closest pair's 0.053); the open patches (7 and 17
    // fragments, where one fragment is 6–14 % of the area histogram) below 0.1, a third of
    // their distance to any other exemplar (≥ 0.30).
    EXPECT_LT(own, a.closed ? 0.05 : 0.1);
    for (const Case& b : kCases) {
      if (std::string(a.name) == b.name) continue;
      const double other = pattern_similarity(our_stats().at(a.name), refs.at(b.name)).total;
      EXPECT_LT(own, other) << "closer to the reference of " << b.name;
      closest_pair = std::min(closest_pair, pattern_similarity(refs.at(a.name), refs.at(b.name)).total);
    }
  }
  // The band above rests on this: the references of two different exemplars are ≥ 0.05 apart.
  EXPECT_GT(closest_pair, 0.05);
}

// Issue 9 moved the skeleton's and the region labels' working arrays to huge pages; the
// statistics of all 15 exemplars must keep their bytes. The digest of their JSON was computed by
// this test on the commit before that change (0a9ff0e's exemplar code; re-derived once without
// the checkout-dependent `source` path, on code whose bytes matched the old digest); any change
// to the analysis that moves a statistic changes it, and then it is re-derived on purpose.
TEST(RealExemplars, StatisticsKeepTheirBytes) {
#if defined(__SANITIZE_ADDRESS__)
  // The digest is of the uninstrumented build's bytes. Sanitizer instrumentation changes the
  // generated floating-point code (which a·b + c GCC fuses into an FMA, for one), and the last
  // bits of the statistics differ (CI's sanitizer pass: c8e0616a…). The plain pass checks it.
  GTEST_SKIP() << "bytes of the uninstrumented build; not comparable under AddressSanitizer";
#endif
  if (!shared_exemplars_present()) {
    GTEST_SKIP() << "shared exemplars not found at " << exemplar_dir() << " (set FISSURE_SHARED_DIR)";
  }
  ContentHasher hasher;
  for (const Case& c : kCases) {
    PatternStats stats = analyze_exemplar(exemplar_dir() / (std::string(c.name) + ".png")).stats;
    // `source` is the path the image was read from, which depends on where the checkout and the
    // shared folder are; the digest covers what was measured, so it names the exemplar instead.
    stats.source = c.name;
    hasher.add(pattern_stats_to_json(stats));
  }
  EXPECT_EQ(hasher.finish().hex(), "ef3773de89f29ddb24c989d2f8a0c9c2");
}

}  // namespace
}  // namespace fissure
