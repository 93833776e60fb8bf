#include "fissure/fracture/fracture_params.hpp"

#include "fissure/base/error.hpp"

#include <cassert>
#include <stdexcept>
#include <string>

namespace fissure {
namespace {

// The bounds, and why each is where it is. Every range is finite so that the stability tests
// can run each parameter at both ends; each is wide enough to hold every material Fissure is
// for (brittle solids, from drying mud to glass) and the fit's Table 3 priors of any of them.

// Strengths: drying mud and fresh plaster crack at kPa, glass fibres and ceramics at GPa; no
// engineering solid is stronger in tension than ~10 GPa.
constexpr double kMinStrength = 1e3;
constexpr double kMaxStrength = 1e10;
// Table 3 gives dσ_e and v_relax as 0–33 % of R_cm and R_cvar as 0–100 %: an absolute bound of
// kMaxStrength covers those priors for every R_cm in range. A stress rate, a relaxation or a
// spread larger than any strength adds nothing.
constexpr double kMaxStress = kMaxStrength;

// Built on first use (a function-local static), so a caller's own static initialiser can read it.
std::vector<ParameterInfo> build_table() {
  const FractureParams d;  // the defaults are the struct's, written once
  std::vector<ParameterInfo> t = {
      {"youngs_modulus", "--E", "Pa", 1e6, 1e12, false, false, d.youngs_modulus,
       "Young's modulus E (plaster 1e10, concrete 3e10, glass 7e10, porcelain tile 6e10)",
       "Table 2 (IN); soft rubber 1e6 to diamond 1.2e12"},
      // Closed at 0.49, not open at 0.5: the FEM's own range [0, 0.5) admits ν = 0.5 − 1e-7, whose
      // stiffness is too ill-conditioned to solve (λ/μ ~ 1e7), so "ν at the end of its range"
      // failed the stability test; 0.49 (λ/μ = 49) solves to a residual ≤ 1e-10 and holds every
      // brittle solid (glass 0.2, asphalt 0.35, drying clay 0.3–0.45).
      {"poisson_ratio", "--nu", "", 0.0, 0.49, false, false, d.poisson_ratio,
       "Poisson's ratio nu; linear tets lock as nu approaches 0.5 (docs/architecture.md)", "Table 2 (IN)"},
      {"density", "--rho", "kg/m^3", 1.0, 1e5, false, false, d.density,
       "Mass density rho (plaster 1200, concrete 2400, glass 2500); sets the body mass that l scales",
       "Table 2 (IN); aerogel ~1 to osmium 2.3e4"},
      {"resistance_mean", "--resistance", "Pa", kMinStrength, kMaxStrength, false, false, d.resistance_mean,
       "Mean resistance to fracture R_cm: the tensile (flexural) strength of an element",
       "Table 2 (IN, R_cm); drying mud ~1e3 to ceramics ~1e9"},
      {"fracture_toughness", "--toughness", "Pa*m^0.5", 0.0, 1e9, false, false, d.fracture_toughness,
       "Fracture toughness K_IC: the energy a running crack must pay per area (G_c = K_IC^2/E); 0: "
       "cracks are never arrested by energy",
       "not in the paper (GMD12's energy criterion, paper-gaps §3); glass 7.5e5, steels up to ~2e8"},
      {"resistance_correlation", "--resistance-correlation", "m", 0.0, 100.0, false, false, d.resistance_correlation,
       "Length over which the element resistance varies (a correlated random field, the same on any mesh of "
       "the body); 0: an independent draw per element",
       "not in the paper (mesh independence, docs/fracture.md)"},
      {"crack_turning", "--crack-turning", "", 0.0, 1.0, false, false, d.crack_turning,
       "How readily a running crack turns toward the local max principal stress direction: over a length "
       "r_relax*(1-b)/b (0: never, the paper's plane; 1: at once)",
       "not in the paper (crack paths, docs/fracture.md); Erdogan-Sih's maximum tangential stress"},
      {"star_biaxiality", "--star-biaxiality", "", 0.0, 1.0, false, false, d.star_biaxiality,
       "A crack opens as a three-armed star (arms 120 degrees apart, a Y junction) where the in-plane stress "
       "at its origin is at least this biaxial, lambda2/lambda1 (1: never, the paper's single crack)",
       "not in the paper (star cracks, docs/fracture.md); star cracks under equi-biaxial tension"},
      {"age", "--age", "age units", 0.0, 1e4, false, false, d.age,
       "Duration of the stress-map evolution (Algorithm 1); the stress rate is per age unit",
       "Table 2 (IN)"},
      {"stress_rate", "--stress-rate", "Pa/age unit", 0.0, kMaxStress, false, false, d.stress_rate,
       "Stress increase rate d(sigma)_e: in-plane tension added near the surface per age unit",
       "Table 3: 0-33 % of R_cm; paper-gaps §2 (tangent-plane tension)"},
      {"relax_radius", "--relax-radius", "m", 0.0, 100.0, true, false, d.relax_radius,
       "Radius r_relax of the relaxation kernel (Eq. 2) around a new crack",
       "Table 3: 0-100 % of sqrt(fragment area); paper-gaps §2"},
      {"relax_rate", "--relax-rate", "Pa", 0.0, kMaxStress, false, false, d.relax_rate,
       "Relaxation rate v_relax: stress removed at the crack (Eqs. 3-4), fading to 0 at r_relax",
       "Table 3: 0-33 % of R_cm"},
      {"resistance_stddev", "--resistance-stddev", "Pa", 0.0, kMaxStress, false, false, d.resistance_stddev,
       "Spread R_cvar of the per-element resistance, a standard deviation; draws are truncated at "
       "0.05 R_cm (resistance_field.hpp)",
       "Table 3: 0-100 % of R_cm; paper-gaps §2 (read as a standard deviation)"},
      {"load_factor", "--load-factor", "", 0.0, 30.0, false, false, d.load_factor,
       "Loading force magnitude l as a multiple of the body's weight: the load totals l * m_body * g newtons",
       "Table 3: 0-3000 % of body mass; paper-gaps §2"},
  };
  // Noise octaves (§5.3): amplitudes in metres (the crack surface's deviation from its plane,
  // at most a body's size), frequencies in 1/m (1e4: a 0.1 mm wavelength, far below any tet).
  static const char* const kAmplitudeNames[] = {"noise_amplitude_1", "noise_amplitude_2", "noise_amplitude_3",
                                                "noise_amplitude_4"};
  static const char* const kAmplitudeFlags[] = {"--noise-amplitude-1", "--noise-amplitude-2", "--noise-amplitude-3",
                                                "--noise-amplitude-4"};
  static const char* const kFrequencyNames[] = {"noise_frequency_1", "noise_frequency_2", "noise_frequency_3",
                                                "noise_frequency_4"};
  static const char* const kFrequencyFlags[] = {"--noise-frequency-1", "--noise-frequency-2", "--noise-frequency-3",
                                                "--noise-frequency-4"};
  for (std::size_t i = 0; i < 4; ++i) {
    t.push_back({kAmplitudeNames[i], kAmplitudeFlags[i], "m", 0.0, 10.0, false, false, d.noise[i].amplitude,
                 "Amplitude A_i of crack-surface noise octave i (simplex noise)", "Table 2 (IN, A_i), §5.3"});
    t.push_back({kFrequencyNames[i], kFrequencyFlags[i], "1/m", 0.0, 1e4, false, false, d.noise[i].frequency,
                 "Frequency f_i of crack-surface noise octave i", "Table 2 (IN, f_i), §5.3"});
  }
  t.push_back({"junction_density", "--junction-density", "1/normalised area", 0.0, 1e6, false, false,
               d.junction_density,
               "The exemplar's junction density, kept for the fit and the statistics panel; not a simulation input",
               "§5.4 (input); paper-gaps §2, §12 (decided: not a stopping rule)"});
  return t;
}

// Row indices of the fields that are not noise octaves, in table order.
enum Row : std::size_t {
  kYoungsModulus,
  kPoissonRatio,
  kDensity,
  kResistanceMean,
  kFractureToughness,
  kResistanceCorrelation,
  kCrackTurning,
  kStarBiaxiality,
  kAge,
  kStressRate,
  kRelaxRadius,
  kRelaxRate,
  kResistanceStddev,
  kLoadFactor,
  kFirstNoise,
  kJunctionDensity = kFirstNoise + 8,
  kRowCount,
};

}  // namespace

const std::vector<ParameterInfo>& fracture_parameter_table() {
  static const std::vector<ParameterInfo> table = build_table();
  assert(table.size() == kRowCount);
  return table;
}

int find_fracture_parameter(std::string_view name) {
  const auto& table = fracture_parameter_table();
  for (std::size_t i = 0; i < table.size(); ++i)
    if (name == table[i].name) return static_cast<int>(i);
  return -1;
}

const ParameterInfo& fracture_parameter_info(std::string_view name) {
  const int row = find_fracture_parameter(name);
  if (row < 0) throw std::logic_error("no fracture parameter named " + std::string(name));
  return fracture_parameter_table()[static_cast<std::size_t>(row)];
}

double& parameter_value(FractureParams& p, std::size_t row) {
  assert(row < kRowCount);
  switch (row) {
    case kYoungsModulus: return p.youngs_modulus;
    case kPoissonRatio: return p.poisson_ratio;
    case kDensity: return p.density;
    case kResistanceMean: return p.resistance_mean;
    case kFractureToughness: return p.fracture_toughness;
    case kResistanceCorrelation: return p.resistance_correlation;
    case kCrackTurning: return p.crack_turning;
    case kStarBiaxiality: return p.star_biaxiality;
    case kAge: return p.age;
    case kStressRate: return p.stress_rate;
    case kRelaxRadius: return p.relax_radius;
    case kRelaxRate: return p.relax_rate;
    case kResistanceStddev: return p.resistance_stddev;
    case kLoadFactor: return p.load_factor;
    case kJunctionDensity: return p.junction_density;
    default: {
      NoiseOctave& octave = p.noise[(row - kFirstNoise) / 2];
      return (row - kFirstNoise) % 2 == 0 ? octave.amplitude : octave.frequency;
    }
  }
}

double parameter_value(const FractureParams& params, std::size_t row) {
  return parameter_value(const_cast<FractureParams&>(params), row);
}

std::vector<std::string> FractureParams::problems(bool use_flags) const {
  std::vector<std::string> out;
  const auto& table = fracture_parameter_table();
  for (std::size_t i = 0; i < table.size(); ++i) {
    const ParameterInfo& info = table[i];
    std::string problem = parameter_problem(info, parameter_value(*this, i), use_flags ? info.flag : info.name);
    if (!problem.empty()) out.push_back(std::move(problem));
  }
  return out;
}

void FractureParams::validate() const { throw_if_problems("fracture parameters", problems()); }

const std::array<FitPrior, 5>& table3_priors() {
  static const std::array<FitPrior, 5> priors{{
      {"stress_rate", 0.0, 0.33, PriorReference::ResistanceMean},
      {"relax_radius", 0.0, 1.0, PriorReference::FragmentScale},
      {"relax_rate", 0.0, 0.33, PriorReference::ResistanceMean},
      {"resistance_stddev", 0.0, 1.0, PriorReference::ResistanceMean},
      {"load_factor", 0.0, 30.0, PriorReference::None},
  }};
  return priors;
}

const char* to_string(RelaxationChoice choice) {
  switch (choice) {
    case RelaxationChoice::Directional: return "directional";
    case RelaxationChoice::Isotropic: return "isotropic";
    case RelaxationChoice::FromExemplar: return "from-exemplar";
  }
  return "?";
}

std::optional<RelaxationChoice> parse_relaxation_choice(std::string_view text) {
  for (RelaxationChoice c : {RelaxationChoice::Directional, RelaxationChoice::Isotropic, RelaxationChoice::FromExemplar})
    if (text == to_string(c)) return c;
  return std::nullopt;
}

const char* relaxation_choice_names() { return "directional, isotropic, from-exemplar"; }

}  // namespace fissure
