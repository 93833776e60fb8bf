// Material files: exact round trip, one clear message naming the file and the key for every kind
// of bad file, atomic writes, thousands of corrupted files read or refused without a crash, and
// the bundled materials in assets/materials.

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/fracture/material_file.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>

namespace fissure {
namespace {
namespace fs = std::filesystem;

const std::vector<std::string> kBundled = {"asphalt", "ceramic-tile", "concrete", "glass", "plaster"};

fs::path bundled_path(const std::string& name) { return test::source_dir() / "assets" / "materials" / (name + ".json"); }

FractureMaterial sample_material() {
  FractureMaterial m;
  m.name = "slate";
  m.description = "A test material, \"quoted\" and ü";
  m.provenance = {"first source", "second source"};
  m.params.relaxation = RelaxationChoice::Isotropic;
  m.params.relax_radius = 0.1 + 1e-17;  // not a short decimal: the round trip must be exact
  m.params.age = 1.0 / 3.0;
  return m;
}

void expect_same(const FractureMaterial& a, const FractureMaterial& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.provenance, b.provenance);
  EXPECT_EQ(a.params.relaxation, b.params.relaxation);
  for (std::size_t i = 0; i < fracture_parameter_table().size(); ++i) {
    const double x = parameter_value(a.params, i), y = parameter_value(b.params, i);
    EXPECT_EQ(std::memcmp(&x, &y, sizeof x), 0) << fracture_parameter_table()[i].name << ": " << x << " vs " << y;
  }
}

TEST(MaterialFile, RoundTripIsExact) {
  const FractureMaterial m = sample_material();
  expect_same(material_from_json(material_to_json(m), "m.json"), m);
  // Seeded property test: any valid values, uniform in each range and in log scale for the wide
  // ones, come back bit for bit.
  Rng rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    FractureMaterial r = m;
    for (std::size_t i = 0; i < fracture_parameter_table().size(); ++i) {
      const ParameterInfo& info = fracture_parameter_table()[i];
      const double lo = std::max(info.min, info.max * 1e-12);
      double v = info.max / info.min > 1e3 || info.min == 0.0 ? std::exp(rng.uniform(std::log(lo), std::log(info.max)))
                                                             : rng.uniform(info.min, info.max);
      if (parameter_problem(info, v, "") != "") v = info.default_value;
      parameter_value(r.params, i) = v;
    }
    r.params.relaxation = static_cast<RelaxationChoice>(rng.uniform_index(3));
    expect_same(material_from_json(material_to_json(r), "r.json"), r);
  }
}

// A material as `fissure fit` writes it (values awkward on purpose: not short decimals).
FractureMaterial fitted_sample() {
  FractureMaterial m = sample_material();
  MaterialFit f;
  f.method = "smc";
  f.trials = 20000;
  f.seed = 18446744073709551615ULL;  // the largest seed: must survive JSON's integer range
  f.error = 0.1 + 1e-17;
  f.error_stddev = 1.0 / 7.0;
  f.error_seeds = 8;
  f.score = 0.09;
  f.exemplar.source = "mud.png";
  f.exemplar.total_area = 250000.0;
  f.exemplar.fragment_area_hist = Histogram::make(-6.0, 0.0, 24);
  f.exemplar.fragment_area_hist.add(-2.0);
  f.exemplar.fragment_area_hist.normalize();
  f.exemplar.crack_length_hist = Histogram::make(-4.0, 0.0, 16);
  f.exemplar.junction_density_hist = Histogram::make(0.0, 5.0, 20);
  f.exemplar.junction_angle_hist = Histogram::make(0.0, 360.0, 36);
  f.exemplar.fragment_count = 1;
  f.exemplar.fragment_areas = {1.0 / 3.0};
  f.age = 3.0;
  f.body_width = 1.0;
  f.body_height = 2.0 / 3.0;
  f.body_thickness = 0.02;
  f.body_tets = 24000;
  f.tets_per_fragment = 120;
  f.min_tets = 24000;
  f.max_tets = 60000;
  f.capped = true;
  f.note = "capped, \"quoted\"";
  f.fragment_scale = 0.1 / 3.0;
  f.load_grid = 8;
  f.load_inset = 0.15;
  f.load_reference_stress = 1e5 / 3.0;
  f.supports = "rim-rollers";
  f.posterior_mean = {1e6 / 3.0, 0.1, 2e6, 3e6, 10.0 / 3.0};
  f.posterior_stddev = {1.0, 2.0, 3.0, 4.0, 5.0};
  f.samples = {{1, 2, 3, 4, 5}, {1.0 / 3.0, 0.1, 0.2, 0.3, 0.4}};
  f.weights = {0.25, 0.75};
  m.fit = f;
  return m;
}

TEST(MaterialFile, FitRecordRoundTripsExactly) {
  const FractureMaterial m = fitted_sample();
  const std::string text = material_to_json(m);
  const FractureMaterial back = material_from_json(text, "fitted.json");
  expect_same(back, m);
  ASSERT_TRUE(back.fit.has_value());
  // Writing what was read gives the same bytes: every field, every bit.
  EXPECT_EQ(material_to_json(back), text);
  EXPECT_EQ(back.fit->seed, m.fit->seed);
  EXPECT_EQ(back.fit->samples, m.fit->samples);
  EXPECT_EQ(back.fit->exemplar.fragment_area_hist.p, m.fit->exemplar.fragment_area_hist.p);
  EXPECT_EQ(back.fit->load_reference_stress, m.fit->load_reference_stress);
  // A fit written before the reference stress reads with 0 (its load stays l·m·g); a reference
  // stress that is not positive is refused.
  nlohmann::json older = nlohmann::json::parse(text);
  older["fit"]["load"].erase("reference_stress");
  EXPECT_EQ(material_from_json(older.dump(), "older.json").fit->load_reference_stress, 0.0);
  older["fit"]["load"]["reference_stress"] = -1.0;
  EXPECT_THROW(material_from_json(older.dump(), "older.json"), IoError);
  // A version-1 file (every bundled material, and files written before the fit existed) still reads.
  nlohmann::json old = nlohmann::json::parse(material_to_json(sample_material()));
  old["version"] = 1;
  EXPECT_FALSE(material_from_json(old.dump(), "old.json").fit.has_value());
}

std::string io_error_of(const std::string& text) {
  try {
    material_from_json(text, "slate.json");
  } catch (const IoError& e) {
    return e.what();
  } catch (const InvalidInput& e) {
    return std::string("InvalidInput: ") + e.what();
  }
  return "accepted";
}

nlohmann::json valid_json() { return nlohmann::json::parse(material_to_json(sample_material())); }

TEST(MaterialFile, EveryKeyIsChecked) {
  struct Case {
    const char* expected;
    void (*spoil)(nlohmann::json&);
  };
  const Case cases[] = {
      {"missing key parameters.age", [](nlohmann::json& j) { j["parameters"].erase("age"); }},
      {"missing key parameters.relaxation", [](nlohmann::json& j) { j["parameters"].erase("relaxation"); }},
      {"missing key name", [](nlohmann::json& j) { j.erase("name"); }},
      {"missing key parameters", [](nlohmann::json& j) { j.erase("parameters"); }},
      {"parameters.age is string, not a number", [](nlohmann::json& j) { j["parameters"]["age"] = "old"; }},
      {"parameters.density is boolean, not a number", [](nlohmann::json& j) { j["parameters"]["density"] = true; }},
      {"parameters.noise_frequency_2 is null, not a number",
       [](nlohmann::json& j) { j["parameters"]["noise_frequency_2"] = nullptr; }},
      {"unknown key parameters.\"relax_raduis\" (did you mean parameters.relax_radius?)",
       [](nlohmann::json& j) { j["parameters"]["relax_raduis"] = 1; }},
      {"unknown key parameters.\"colour\"", [](nlohmann::json& j) { j["parameters"]["colour"] = 1; }},
      {"unknown key \"descripton\" (did you mean description?)", [](nlohmann::json& j) { j["descripton"] = ""; }},
      {"parameters.relaxation is \"sideways\", not one of directional, isotropic, from-exemplar",
       [](nlohmann::json& j) { j["parameters"]["relaxation"] = "sideways"; }},
      {"parameters.relaxation is 3, not one of", [](nlohmann::json& j) { j["parameters"]["relaxation"] = 3; }},
      {"parameters is array, not an object", [](nlohmann::json& j) { j["parameters"] = nlohmann::json::array(); }},
      {"name is number, not a string", [](nlohmann::json& j) { j["name"] = 5; }},
      {"name is empty", [](nlohmann::json& j) { j["name"] = ""; }},
      {"description is object, not a string", [](nlohmann::json& j) { j["description"] = nlohmann::json::object(); }},
      {"provenance is string, not an array of strings", [](nlohmann::json& j) { j["provenance"] = "a book"; }},
      {"provenance[1] is number, not a string", [](nlohmann::json& j) { j["provenance"][1] = 2; }},
      {"schema \"fissure-project\" is not \"fissure-material\" (not a Fissure material file)",
       [](nlohmann::json& j) { j["schema"] = "fissure-project"; }},
      {"missing key schema", [](nlohmann::json& j) { j.erase("schema"); }},
      {"version 3 is not a supported version (1 to 2)", [](nlohmann::json& j) { j["version"] = 3; }},
      {"version 0 is not a supported version (1 to 2)", [](nlohmann::json& j) { j["version"] = 0; }},
      {"version \"1\" is not a supported version (1 to 2)", [](nlohmann::json& j) { j["version"] = "1"; }},
      {"version 1.5 is not a supported version (1 to 2)", [](nlohmann::json& j) { j["version"] = 1.5; }},
      {"unknown key \"fit\"", [](nlohmann::json& j) {
         j["version"] = 1;  // version 1 had no fit record
         j["fit"] = nlohmann::json::object();
       }},
      {"missing key fit.method", [](nlohmann::json& j) { j["fit"] = nlohmann::json::object(); }},
      {"unknown key fit.\"methd\" (did you mean fit.method?)", [](nlohmann::json& j) { j["fit"] = {{"methd", "paper"}}; }},
      {"the document is array, not an object", [](nlohmann::json& j) { j = nlohmann::json::array({1}); }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    nlohmann::json j = valid_json();
    c.spoil(j);
    const std::string message = io_error_of(j.dump(2));
    EXPECT_EQ(message.rfind("slate.json: not a valid material file: ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
  // Optional keys may be left out.
  nlohmann::json j = valid_json();
  j.erase("description");
  j.erase("provenance");
  EXPECT_EQ(io_error_of(j.dump()), "accepted");
}

TEST(MaterialFile, RepeatedKeyIsRefused) {
  std::string text = material_to_json(sample_material());
  const std::size_t at = text.find("\"age\":");
  text.insert(at, "\"age\": 5,\n    ");
  EXPECT_EQ(io_error_of(text), "slate.json: not a valid material file: key parameters.age appears twice");
  text = material_to_json(sample_material());
  text.insert(text.find("\"name\":"), "\"name\": \"x\", ");
  EXPECT_EQ(io_error_of(text), "slate.json: not a valid material file: key name appears twice");
}

TEST(MaterialFile, OutOfRangeValuesNameKeyAndRange) {
  nlohmann::json j = valid_json();
  j["parameters"]["relax_radius"] = -1;
  EXPECT_EQ(io_error_of(j.dump()),
            "InvalidInput: slate.json: material \"slate\": parameters.relax_radius -1 is outside (0, 100] m");
  j["parameters"]["poisson_ratio"] = 0.62;
  j["parameters"]["load_factor"] = 31;
  EXPECT_EQ(io_error_of(j.dump()),
            "InvalidInput: slate.json: material \"slate\": parameters.poisson_ratio 0.62 is outside [0, 0.49]; "
            "parameters.relax_radius -1 is outside (0, 100] m; parameters.load_factor 31 is outside [0, 30]");
  // An infinity arrives as a huge exponent: refused by the parser, one line.
  std::string text = valid_json().dump();
  const std::string key = "\"age\":";
  const std::size_t at = text.find(key) + key.size();
  text.replace(at, text.find(',', at) - at, "1e999");
  EXPECT_NE(io_error_of(text).find("slate.json: not a valid material file: number overflow parsing '1e999'"),
            std::string::npos)
      << io_error_of(text);
}

TEST(MaterialFile, SyntaxErrorIsOneClearLine) {
  const std::string message = io_error_of("{\n  \"schema\": \"fissure-material\",\n  \"version\": nope\n}");
  EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
  EXPECT_NE(message.find("slate.json: not a valid material file: syntax error at line 3, column"), std::string::npos)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(io_error_of("").find("slate.json: not a valid material file: syntax error"), std::string::npos);
}

TEST(MaterialFile, WritesAtomicallyAndNeverWritesAnInvalidMaterial) {
  const fs::path dir = test::fresh_temp_dir("material_file");
  const fs::path path = dir / "slate.json";
  save_material(path, sample_material());
  expect_same(load_material(path), sample_material());
  const std::string before = read_file(path);
  // An invalid material is refused before anything is written: the old file stays.
  FractureMaterial bad = sample_material();
  bad.params.density = -5;
  try {
    save_material(path, bad);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "material \"slate\": density -5 is outside [1, 100000] kg/m^3");
  }
  EXPECT_EQ(read_file(path), before);
  bad = sample_material();
  bad.name.clear();
  EXPECT_THROW(save_material(path, bad), InvalidInput);
  EXPECT_EQ(read_file(path), before);
  // A fit record the reader would refuse (no resolution rule) is refused the same way.
  bad = fitted_sample();
  bad.name = "slate";
  bad.fit->tets_per_fragment = 0;
  try {
    save_material(path, bad);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fit.resolution.tets_per_fragment 0"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_file(path), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no temporary left
  // An unwritable place and a missing file are IoErrors naming the file.
  try {
    save_material(dir / "missing" / "x.json", sample_material());
    ADD_FAILURE() << "accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "missing").string()), std::string::npos) << e.what();
  }
  try {
    load_material(dir / "absent.json");
    ADD_FAILURE() << "accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("absent.json"), std::string::npos) << e.what();
  }
}

// --- Fuzzing -------------------------------------------------------------------------------

// 1–4 byte edits: a byte changed, a run deleted, a run inserted, the text cut, or a number's
// digits replaced by a huge one (the patterns of tests/io/import_fuzz_test.cpp).
std::string corrupt_bytes(std::string text, Rng& rng) {
  static const char* const kHuge[] = {"1e999", "-1e999", "1e308", "18446744073709551616", "-0", "1e-400", "99999999999"};
  const int edits = 1 + static_cast<int>(rng.uniform_index(4));
  for (int e = 0; e < edits && !text.empty(); ++e) {
    const std::size_t at = rng.uniform_index(text.size());
    switch (rng.uniform_index(5)) {
      case 0: text[at] = static_cast<char>(rng.uniform_index(256)); break;
      case 1: text.erase(at, 1 + rng.uniform_index(16)); break;
      case 2: text.insert(at, std::string(1 + rng.uniform_index(8), static_cast<char>(rng.uniform_index(256)))); break;
      case 3: text.resize(at); break;
      default: {
        const std::size_t digit = text.find_first_of("0123456789", at);
        if (digit == std::string::npos) break;
        const std::size_t stop = text.find_first_not_of("0123456789.e+-", digit);
        text.replace(digit, (stop == std::string::npos ? text.size() : stop) - digit, kHuge[rng.uniform_index(7)]);
      }
    }
  }
  return text;
}

// Structural edits that keep the JSON valid: a value replaced by one of another type or
// another number, a key deleted, a key added or renamed, an object swapped for an array.
nlohmann::json random_value(Rng& rng) {
  switch (rng.uniform_index(8)) {
    case 0: return nullptr;
    case 1: return rng.uniform() < 0.5;
    case 2: return static_cast<std::int64_t>(rng.next_u64());
    case 3: return rng.uniform(-1e12, 1e12);
    case 4: return std::exp(rng.uniform(-700, 700)) * (rng.uniform() < 0.5 ? -1 : 1);
    case 5: return "directional";
    case 6: return nlohmann::json::array({1, "x"});
    default: return nlohmann::json::object({{"age", 1}});
  }
}

std::string corrupt_structure(nlohmann::json j, Rng& rng) {
  const int edits = 1 + static_cast<int>(rng.uniform_index(3));
  for (int e = 0; e < edits; ++e) {
    nlohmann::json& target = rng.uniform() < 0.7 && j.contains("parameters") && j["parameters"].is_object()
                                 ? j["parameters"]
                                 : j;
    if (!target.is_object() || target.empty()) break;
    auto it = target.begin();
    std::advance(it, static_cast<long>(rng.uniform_index(target.size())));
    const std::string key = it.key();
    switch (rng.uniform_index(4)) {
      case 0: target[key] = random_value(rng); break;
      case 1: target.erase(key); break;
      case 2: target[key + "_x"] = random_value(rng); break;
      default: {
        nlohmann::json value = target[key];
        target.erase(key);
        target[key.substr(0, key.size() / 2)] = value;
      }
    }
  }
  return j.dump(rng.uniform() < 0.5 ? -1 : 2);
}

// Read or refused with IoError / InvalidInput naming the file on one line; a file that is read
// is a valid material that round-trips.
void expect_read_or_refused(const std::string& text, int& read, int& refused) {
  try {
    const FractureMaterial m = material_from_json(text, "fuzz.json");
    EXPECT_TRUE(m.params.problems().empty());
    expect_same(material_from_json(material_to_json(m), "again.json"), m);
    ++read;
    return;
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("fuzz.json: ", 0), 0u) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind("fuzz.json: material ", 0), 0u) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "untyped error: " << e.what() << "\nfor: " << text;
  }
  ++refused;
}

TEST(MaterialFileFuzz, CorruptedFilesAreReadOrRefused) {
  int read = 0, refused = 0;
  for (const std::string& name : kBundled) {
    const std::string text = read_file(bundled_path(name));
    const nlohmann::json j = nlohmann::json::parse(text);
    Rng rng = Rng::derive(2026, "material fuzz", std::hash<std::string>{}(name) % 1000);
    for (int i = 0; i < 600; ++i) expect_read_or_refused(corrupt_bytes(text, rng), read, refused);
    for (int i = 0; i < 400; ++i) expect_read_or_refused(corrupt_structure(j, rng), read, refused);
  }
  // A fitted material: the fit record's reader meets the same corruptions.
  {
    const std::string text = material_to_json(fitted_sample());
    const nlohmann::json j = nlohmann::json::parse(text);
    Rng rng = Rng::derive(2026, "material fuzz", 999);
    int fit_read = 0, fit_refused = 0;
    for (int i = 0; i < 300; ++i) expect_read_or_refused(corrupt_bytes(text, rng), fit_read, fit_refused);
    for (int i = 0; i < 300; ++i) expect_read_or_refused(corrupt_structure(j, rng), fit_read, fit_refused);
    EXPECT_GT(fit_read, 5);
    EXPECT_GT(fit_refused, 300);
  }
  // 5000 files. Most edits break the file; some (a changed digit, a deleted optional key) leave
  // a valid one. Both outcomes must occur, or the corruption is not exercising the reader.
  EXPECT_EQ(read + refused, 5000);
  EXPECT_GT(read, 50);
  EXPECT_GT(refused, 3000);
}

// --- Bundled materials ---------------------------------------------------------------------

TEST(BundledMaterials, EveryShippedMaterialLoadsAndIsPlausible) {
  const std::vector<std::string> names = bundled_material_names();
  for (const std::string& name : kBundled) {
    SCOPED_TRACE(name);
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end());
    const FractureMaterial m = load_material(find_material(name));
    EXPECT_EQ(m.name, name);
    EXPECT_FALSE(m.description.empty());
    EXPECT_GE(m.provenance.size(), 2u);  // the physical values' source and the hand-set parameters
    EXPECT_TRUE(m.params.problems().empty());
    // Hand-set fracture parameters inside the paper's Table 3 priors relative to R_cm (r_relax's
    // reference, the fragment size, depends on the body: it is only checked by its range).
    const FractureParams& p = m.params;
    for (const FitPrior& prior : table3_priors()) {
      if (prior.reference == PriorReference::FragmentScale) continue;
      const double value = parameter_value(p, static_cast<std::size_t>(find_fracture_parameter(prior.name)));
      const double scale = prior.reference == PriorReference::ResistanceMean ? p.resistance_mean : 1.0;
      EXPECT_GE(value, prior.min_fraction * scale) << prior.name;
      EXPECT_LE(value, prior.max_fraction * scale) << prior.name;
    }
    // Something must be able to crack: a load, or tension growing over the age.
    EXPECT_GT(p.load_factor + p.stress_rate * p.age, 0.0);
    // Brittle: the strength is far below the modulus (strain to failure < 1 %).
    EXPECT_LT(p.resistance_mean, 0.01 * p.youngs_modulus);
    for (const NoiseOctave& o : p.noise) EXPECT_GT(o.amplitude * o.frequency, 0.0);
  }
  // The default material is the struct's defaults.
  FractureMaterial defaults;
  defaults.params = FractureParams{};
  defaults.name = kDefaultMaterialName;
  const FractureMaterial tile = load_material(find_material(kDefaultMaterialName));
  defaults.description = tile.description;
  defaults.provenance = tile.provenance;
  expect_same(tile, defaults);
}

TEST(BundledMaterials, FoundByNameOrPath) {
  const std::vector<fs::path> dirs = material_directories();
  ASSERT_FALSE(dirs.empty());
  EXPECT_NE(std::find(dirs.begin(), dirs.end(), test::source_dir() / "assets" / "materials"), dirs.end());
  EXPECT_EQ(fs::canonical(find_material("glass")), fs::canonical(bundled_path("glass")));
  // Paths are returned as they are, whether or not they exist.
  EXPECT_EQ(find_material("./glass"), fs::path("./glass"));
  EXPECT_EQ(find_material("mine.json"), fs::path("mine.json"));
  for (const char* unknown : {"granite", ""}) {
    try {
      find_material(unknown);
      ADD_FAILURE() << "found " << unknown;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(" is not a file or a known material (known: asphalt, ceramic-tile, "
                                           "concrete, glass, plaster"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace fissure
