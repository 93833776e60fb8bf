// fissure analyze IMAGE [--json out.json] [--overlay out.png]

#include "cli_common.hpp"
#include "commands.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/exemplar/overlay.hpp"
#include "fissure/exemplar/stats_json.hpp"

#include <cstdio>

namespace fissure::cli {
namespace {

struct AnalyzeArgs {
  std::string image;
  std::string json;
  std::string overlay;
  std::string polarity = "auto";
  int threshold = -1;
  std::string roi;
  double max_megapixels = 64.0;
  int min_fragment_px = 32;
  double spur_factor = 2.0;
  bool exclude_border_fragments = false;
  bool quiet = false;
};

ExemplarAnalysisOptions analysis_options(const AnalyzeArgs& args) {
  ExemplarAnalysisOptions o;
  o.image.polarity = args.polarity == "light" ? CrackPolarity::LightOnDark
                     : args.polarity == "dark" ? CrackPolarity::DarkOnLight
                                               : CrackPolarity::Auto;
  o.image.threshold = args.threshold;
  o.image.roi_path = args.roi;
  if (!(args.max_megapixels > 0.0)) throw InvalidInput("--max-megapixels must be positive");
  o.image.max_pixels = static_cast<std::int64_t>(args.max_megapixels * 1e6);
  o.graph.min_fragment_px = args.min_fragment_px;
  o.graph.spur_factor = args.spur_factor;
  o.stats.exclude_border_fragments = args.exclude_border_fragments;
  o.keep_pixel_layers = !args.overlay.empty();
  return o;
}

int run_analyze(const AnalyzeArgs& args) {
  if (!args.json.empty()) check_output_path(args.json);
  if (!args.overlay.empty()) check_output_path(args.overlay);
  Stopwatch clock;
  const ExemplarAnalysis a = analyze_exemplar(args.image, analysis_options(args));
  const double ms = clock.milliseconds();
  if (!args.json.empty()) save_pattern_stats(args.json, a.stats);
  if (!args.overlay.empty()) write_overlay(args.overlay, a);
  if (!args.quiet) {
    const PatternStats& s = a.stats;
    std::printf("%s: %d x %d px, %s cracks %.1f px wide, %.0f ms\n", args.image.c_str(), a.mask.width, a.mask.height,
                a.mask.light_cracks ? "light" : "dark", a.diagnostics.crack_width_px, ms);
    std::printf("  S1 fragments: %d (%d touch the border), median area %.4g\n", s.fragment_count,
                s.fragments_touching_border, s.fragment_areas.empty() ? 0.0 : s.fragment_areas[s.fragment_areas.size() / 2]);
    std::printf("  S2 cracks:    %d, total length %.4g, %d free ends, %d at the border\n", s.crack_count,
                s.total_crack_length, s.end_count, s.border_end_count);
    std::printf("  S3 junctions: %d (T %d, Y %d, X %d), mean junction angle %.1f deg -> %s relaxation\n",
                s.junction_count, s.t_count, s.y_count, s.x_count, s.mean_junction_angle_deg, to_string(s.relaxation_mode));
  }
  return kExitOk;
}

}  // namespace


void register_analyze(CLI::App& app, Action& action) {
  auto args = std::make_shared<AnalyzeArgs>();
  auto* cmd = app.add_subcommand("analyze", "Crack statistics of a traced crack image (paper S1-S3): fragments, cracks, "
                                            "junctions and junction angles");
  cmd->add_option("IMAGE", args->image, "Traced cracks: PNG, JPEG, TIFF or BMP, lines of either polarity")->required();
  cmd->add_option("--json", args->json, "Write the statistics as JSON (input of fissure compare)");
  cmd->add_option("--overlay", args->overlay, "Write a PNG showing fragments, skeleton, junctions (T red, Y blue, X magenta) "
                                              "and ends (free yellow, border green)");
  cmd->add_option("--polarity", args->polarity, "Crack colour: auto (the minority class), light or dark")
      ->check(CLI::IsMember({"auto", "light", "dark"}))
      ->default_val("auto");
  cmd->add_option("--threshold", args->threshold, "Grey level between crack and background (default: Otsu)")
      ->check(CLI::Range(0, 255));
  cmd->add_option("--roi", args->roi, "Mask of the fractured area, same size as the image (non-zero inside)");
  cmd->add_option("--max-megapixels", args->max_megapixels, "Refuse larger images before decoding them")->default_val(64);
  cmd->add_option("--min-fragment-px", args->min_fragment_px, "Regions smaller than this are crack noise, not fragments")
      ->default_val(32)
      ->check(CLI::Range(1, 1'000'000));
  cmd->add_option("--spur-factor", args->spur_factor, "Prune free-end branches shorter than this many crack widths")
      ->default_val(2.0)
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_flag("--exclude-border-fragments", args->exclude_border_fragments,
                "Leave fragments cut by the image border out of S1");
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing on success");
  cmd->callback([&action, args] { action = [args] { return run_analyze(*args); }; });
}

}  // namespace fissure::cli
