#pragma once
// Checks of command-line values that CLI11 does not make: finiteness (CLI11's Range lets NaN
// through, and "inf" overflows later conversions), whole counts written in scientific notation
// ("--tets 5e7"), and the output names the writers accept.

#include "fissure/fem/elastic_material.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace fissure::cli {

/// A floating option's value must be a finite number: "'nan' is not a finite number".
CLI::Validator finite_number();

/// A floating option's value must be a finite number in [lo, hi]: "nan is not a finite number",
/// "1e+06 is outside [0, 100]" (CLI11 prefixes the option name). Used by every floating option.
CLI::Validator finite_in(double lo, double hi);

/// A value of a parameter table's row (elastic or fracture): a finite number in the row's range,
/// which the help shows ("NUM:in (0, 100] m"); outside it, "0 is outside (0, 100] m", a
/// command-line error like any other flag's.
CLI::Validator parameter_range(const ParameterInfo& info);

/// A count: a whole number in [lo, hi], also written as "2e6". Store it in a double (CLI11's
/// integer conversion refuses "5e7") and convert with std::lround after parsing.
CLI::Validator count_in(double lo, double hi);

/// A seed: a whole number in [0, 2^64 − 1], written in decimal. CLI11 reads "-5" into an
/// unsigned seed as 2^64 − 5 and saturates anything larger than 2^64 − 1, both silently.
CLI::Validator seed_value();

/// The extension of `path`, lower-case (".glb"), or empty.
std::string lower_extension(const std::string& path);

/// An image output: its name ends in .png (any case), or has no extension (/dev/null, a
/// pipe). A PNG written under "x.jpg" is opened by most tools as a corrupt JPEG.
CLI::Validator png_path();

}  // namespace fissure::cli
