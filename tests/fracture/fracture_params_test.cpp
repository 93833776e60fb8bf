// The parameter table of FractureParams: one row per scalar, ranges that hold the defaults and
// the fit's Table 3 priors, accessors that reach every field once, messages that name the key
// (or the flag) and the range, and the docs table generated from it.

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/atomic_file.hpp"
#include "fissure/fracture/fracture_params.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

namespace fissure {
namespace {

const std::vector<ParameterInfo>& table() { return fracture_parameter_table(); }

// The smallest and largest valid values of a row (one ulp inside an excluded bound).
double lowest(const ParameterInfo& p) { return p.min_exclusive ? std::nextafter(p.min, p.max) : p.min; }
double highest(const ParameterInfo& p) { return p.max_exclusive ? std::nextafter(p.max, p.min) : p.max; }

TEST(FractureParameterTable, RowsAreUniqueAndHoldTheirDefaults) {
  // Table 2's 11 scalars (with K_IC), the resistance correlation, crack turning, star biaxiality,
  // 4 noise octaves × 2, junction density
  ASSERT_EQ(table().size(), 23u);
  std::set<std::string> names, flags;
  const FractureParams defaults;
  for (std::size_t i = 0; i < table().size(); ++i) {
    const ParameterInfo& p = table()[i];
    SCOPED_TRACE(p.name);
    EXPECT_TRUE(names.insert(p.name).second);
    EXPECT_TRUE(flags.insert(p.flag).second);
    EXPECT_EQ(std::string(p.flag).rfind("--", 0), 0u);
    EXPECT_EQ(find_fracture_parameter(p.name), static_cast<int>(i));
    EXPECT_TRUE(std::isfinite(p.min) && std::isfinite(p.max) && p.min < p.max);
    EXPECT_EQ(p.default_value, parameter_value(defaults, i));
    EXPECT_EQ(parameter_problem(p, p.default_value, p.name), "");
    EXPECT_GT(std::string(p.help).size(), 10u);
    EXPECT_GT(std::string(p.reference).size(), 5u);
  }
  EXPECT_EQ(find_fracture_parameter("relaxation"), -1);  // not a number: parse_relaxation_choice
  EXPECT_EQ(find_fracture_parameter("nope"), -1);
  // Flags the fracture command has for other things must not be taken by a parameter.
  for (const char* taken : {"--load", "--fix", "--seed", "--fragments", "--material", "--up", "--tets", "--view"})
    EXPECT_EQ(flags.count(taken), 0u) << taken;
}

// Each row reaches its own field: writing row i changes row i only, and the noise rows map to
// octave (i − first) / 2, amplitude first.
TEST(FractureParameterTable, AccessorsReachEveryFieldOnce) {
  for (std::size_t i = 0; i < table().size(); ++i) {
    FractureParams p;
    parameter_value(p, i) = -1234.5;
    for (std::size_t j = 0; j < table().size(); ++j) {
      EXPECT_EQ(parameter_value(p, j) == -1234.5, i == j) << table()[i].name << " / " << table()[j].name;
    }
  }
  FractureParams p;
  parameter_value(p, static_cast<std::size_t>(find_fracture_parameter("noise_frequency_3"))) = 77.0;
  parameter_value(p, static_cast<std::size_t>(find_fracture_parameter("noise_amplitude_4"))) = 0.25;
  EXPECT_EQ(p.noise[2].frequency, 77.0);
  EXPECT_EQ(p.noise[3].amplitude, 0.25);
  parameter_value(p, static_cast<std::size_t>(find_fracture_parameter("relax_radius"))) = 0.5;
  EXPECT_EQ(p.relax_radius, 0.5);
}

// The fit samples Table 3 as fractions of R_cm (and l as a multiple of the body's weight): the
// absolute ranges must hold those priors for every R_cm in range, and the paper's own bounds.
TEST(FractureParameterTable, RangesHoldTheTable3Priors) {
  const auto row = [](const char* name) { return table()[static_cast<std::size_t>(find_fracture_parameter(name))]; };
  const ParameterInfo rcm = row("resistance_mean");
  const auto& priors = table3_priors();
  const char* const paper_order[] = {"stress_rate", "relax_radius", "relax_rate", "resistance_stddev", "load_factor"};
  for (std::size_t k = 0; k < priors.size(); ++k) {
    const FitPrior& prior = priors[k];
    SCOPED_TRACE(prior.name);
    EXPECT_STREQ(prior.name, paper_order[k]);
    ASSERT_GE(find_fracture_parameter(prior.name), 0);
    const ParameterInfo info = row(prior.name);
    EXPECT_EQ(prior.min_fraction, 0.0);  // every Table 3 range starts at 0 %
    switch (prior.reference) {
      case PriorReference::ResistanceMean:
        for (double r : {rcm.min, rcm.default_value, rcm.max}) {
          EXPECT_EQ(parameter_problem(info, prior.min_fraction * r, prior.name), "");
          EXPECT_EQ(parameter_problem(info, prior.max_fraction * r, prior.name), "");
        }
        break;
      case PriorReference::FragmentScale:
        // r_relax > 0: the fit draws from (0, 1] × √(fragment area); any body Fissure meshes
        // (≤ 100 m) has fragments smaller than itself.
        EXPECT_TRUE(info.min_exclusive);
        EXPECT_EQ(info.min, 0.0);
        EXPECT_EQ(prior.max_fraction, 1.0);
        break;
      case PriorReference::None:
        EXPECT_EQ(info.min, prior.min_fraction);
        EXPECT_EQ(info.max, prior.max_fraction);  // 3000 % of the body's weight
        break;
    }
  }
  EXPECT_EQ(priors[0].max_fraction, 0.33);
  EXPECT_EQ(priors[2].max_fraction, 0.33);
  EXPECT_EQ(priors[3].max_fraction, 1.0);
  EXPECT_EQ(row("age").min, 0.0);
  for (int i = 1; i <= 4; ++i) {
    EXPECT_EQ(row(("noise_amplitude_" + std::to_string(i)).c_str()).min, 0.0);
    EXPECT_EQ(row(("noise_frequency_" + std::to_string(i)).c_str()).min, 0.0);
  }
}

TEST(FractureParams, ProblemsNameTheKeyOrFlagAndTheRange) {
  EXPECT_TRUE(FractureParams{}.problems().empty());
  EXPECT_NO_THROW(FractureParams{}.validate());
  // Both ends of every range are valid; one step beyond either is refused, naming the row.
  for (std::size_t i = 0; i < table().size(); ++i) {
    const ParameterInfo& info = table()[i];
    SCOPED_TRACE(info.name);
    for (double v : {lowest(info), highest(info)}) {
      FractureParams p;
      parameter_value(p, i) = v;
      EXPECT_TRUE(p.problems().empty()) << p.problems()[0];
    }
    const double below = info.min_exclusive ? info.min : std::nextafter(info.min, -INFINITY);
    const double above = info.max_exclusive ? info.max : std::nextafter(info.max, INFINITY);
    for (double v : {below, above, std::numeric_limits<double>::quiet_NaN()}) {
      FractureParams p;
      parameter_value(p, i) = v;
      ASSERT_EQ(p.problems().size(), 1u);
      EXPECT_EQ(p.problems()[0], parameter_problem(info, v, info.name));
      EXPECT_EQ(p.problems(true)[0], parameter_problem(info, v, info.flag));
    }
  }
  FractureParams p;
  p.relax_radius = -1.0;
  p.poisson_ratio = 0.62;
  ASSERT_EQ(p.problems().size(), 2u);
  EXPECT_EQ(p.problems()[0], "poisson_ratio 0.62 is outside [0, 0.49]");
  EXPECT_EQ(p.problems()[1], "relax_radius -1 is outside (0, 100] m");
  EXPECT_EQ(p.problems(true)[1], "--relax-radius -1 is outside (0, 100] m");
  try {
    p.validate();
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(),
                 "fracture parameters: poisson_ratio 0.62 is outside [0, 0.49]; relax_radius -1 is outside (0, 100] m");
  }
}

TEST(RelaxationChoice, NamesRoundTrip) {
  for (RelaxationChoice c : {RelaxationChoice::Directional, RelaxationChoice::Isotropic, RelaxationChoice::FromExemplar}) {
    EXPECT_EQ(parse_relaxation_choice(to_string(c)), c);
    EXPECT_NE(std::string(relaxation_choice_names()).find(to_string(c)), std::string::npos);
  }
  for (const char* bad : {"", "Directional", "isotropic ", "eq3", "from_exemplar"})
    EXPECT_FALSE(parse_relaxation_choice(bad).has_value()) << bad;
}

// The table of docs/materials.md, rendered from fracture_parameter_table(): the docs cannot
// drift from the code. On a failure the expected block is printed to paste in.
std::string range_text(const ParameterInfo& p) {
  return std::string(p.min_exclusive ? "(" : "[") + format_number(p.min) + ", " + format_number(p.max) +
         (p.max_exclusive ? ")" : "]");
}

std::string rendered_table() {
  std::string out = "| Key | Flag | Unit | Range | Default | Meaning | Reference |\n|---|---|---|---|---|---|---|\n";
  for (const ParameterInfo& p : table()) {
    out += std::string("| `") + p.name + "` | `" + p.flag + "` | " + (p.unit[0] ? p.unit : "–") + " | " + range_text(p) +
           " | " + format_number(p.default_value) + " | " + p.help + " | " + p.reference + " |\n";
  }
  out += "| `relaxation` | `--relaxation` | – | " + std::string(relaxation_choice_names()) + " | " +
         to_string(FractureParams{}.relaxation) +
         " | Stress relaxation around a new crack: Eq. 3, Eq. 4, or chosen from the exemplar's mean junction angle"
         " | §5.2 |\n";
  return out;
}

TEST(FractureParameterTable, DocsTableIsGeneratedFromIt) {
  const std::string doc = read_file(test::source_dir() / "docs" / "materials.md");
  const std::string begin = "<!-- parameter table: generated by fracture_params_test, do not edit -->\n";
  const std::string end = "<!-- end of parameter table -->";
  const std::size_t a = doc.find(begin);
  const std::size_t b = doc.find(end);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  EXPECT_EQ(doc.substr(a + begin.size(), b - a - begin.size()), rendered_table()) << "expected:\n" << rendered_table();
}

}  // namespace
}  // namespace fissure
