#pragma once
/// The picture of a fit (`fissure fit --report`): the exemplar's tracing beside a fitted pattern,
/// their three Eq. 5 histograms overlaid (comparison_report.hpp).
#include "fissure/exemplar/crack_image.hpp"
#include "fissure/fit/fit_files.hpp"

#include <filesystem>

namespace fissure {

/// The evaluation trial a report draws: the one whose error is the median of the result's
/// evaluation errors (the lower middle for an even count; 0 without evaluations), so the picture
/// shows a typical fitted pattern, not the luckiest.
std::uint64_t median_evaluation_trial(const FitResult& result);

/// Re-simulates the winner as evaluation trial median_evaluation_trial(result), draws it and
/// writes the report beside `exemplar_drawing` (the traced image as loaded). Throws IoError when
/// the file cannot be written.
void write_fit_report(const std::filesystem::path& path, const GreyImage& exemplar_drawing, const FitSettings& settings,
                      const FitProblem& problem, const FitResult& result);

}  // namespace fissure
