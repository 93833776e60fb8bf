// fissure analyze IMAGE [--json out.json] [--overlay out.png]

#include "cli_common.hpp"
#include "image_options.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "interruption.hpp"
#include "option_checks.hpp"
#include "terminal_progress.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/distinct_files.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
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
  o.image.max_pixels = max_pixels(args.max_megapixels);
  o.graph.min_fragment_px = args.min_fragment_px;
  o.graph.spur_factor = args.spur_factor;
  o.stats.exclude_border_fragments = args.exclude_border_fragments;
  o.keep_pixel_layers = !args.overlay.empty();
  return o;
}

int run_analyze(const AnalyzeArgs& args) {
  if (!args.json.empty()) check_output_path(args.json);
  if (!args.overlay.empty()) check_output_path(args.overlay);
  check_distinct_files({{"the input image", args.image}}, {{"--json", args.json}, {"--overlay", args.overlay}});
  TerminalProgress progress(args.quiet);
  Stopwatch clock;
  ExemplarAnalysis a;
  {
    AbandonableWork work;
    progress.stage("analysing " + args.image);
    a = analyze_image(args.image, analysis_options(args));
  }
  throw_if_interrupted();
  const double ms = clock.milliseconds();
  progress.stage("writing");
  if (!args.json.empty()) save_pattern_stats(args.json, a.stats);
  if (!args.overlay.empty()) write_overlay(args.overlay, a);
  progress.clear();
  if (!args.quiet) {
    // With --json - (or --overlay -) the result owns stdout; the summary goes to stderr.
    std::FILE* out = args.json == "-" || args.overlay == "-" ? stderr : stdout;
    const PatternStats& s = a.stats;
    const double median_area = s.fragment_areas.empty() ? 0.0 : s.fragment_areas[s.fragment_areas.size() / 2];
    std::fprintf(out, "%s: %d x %d px, %s cracks %s px wide, %lld ms\n", args.image.c_str(), a.mask.width, a.mask.height,
                 a.mask.light_cracks ? "light" : "dark", format_number(a.diagnostics.crack_width_px, 3).c_str(),
                 std::llround(ms));
    std::fprintf(out, "  S1 fragments: %d (%d touch the border), median area %s\n", s.fragment_count,
                 s.fragments_touching_border, format_number(median_area, 4).c_str());
    std::fprintf(out, "  S2 cracks:    %d, total length %s, %d free ends, %d at the border\n", s.crack_count,
                 format_number(s.total_crack_length, 4).c_str(), s.end_count, s.border_end_count);
    std::fprintf(out, "  S3 junctions: %d (T %d, Y %d, X %d), mean junction angle %s deg -> %s relaxation\n",
                 s.junction_count, s.t_count, s.y_count, s.x_count, format_number(s.mean_junction_angle_deg, 3).c_str(),
                 to_string(s.relaxation_mode));
  }
  return kExitOk;
}

}  // namespace


void register_analyze(CLI::App& app, Action& action) {
  auto args = std::make_shared<AnalyzeArgs>();
  auto* cmd = app.add_subcommand("analyze", std::string(command_info("analyze").summary));
  add_threads_option(*cmd);
  cmd->add_option("IMAGE", args->image, "Traced cracks: PNG, JPEG, TIFF or BMP, lines of either polarity")->required();
  cmd->add_option("--json", args->json, "Write the statistics as JSON (input of fissure compare); - for stdout");
  cmd->add_option("--overlay", args->overlay, "Write a PNG showing fragments, skeleton, junctions (T red, Y blue, X magenta) "
                                              "and ends (free yellow, border green)")
      ->check(png_path());
  cmd->add_option("--polarity", args->polarity, "Crack colour: auto (the minority class), light or dark")
      ->check(CLI::IsMember({"auto", "light", "dark"}))
      ->default_val("auto");
  cmd->add_option("--threshold", args->threshold, "Grey level between crack and background (default: Otsu)")
      ->check(CLI::Range(0, 255));
  cmd->add_option("--roi", args->roi, "Mask of the fractured area, same size as the image (non-zero inside)");
  add_max_megapixels_option(*cmd, args->max_megapixels);
  cmd->add_option("--min-fragment-px", args->min_fragment_px, "Regions smaller than this are crack noise, not fragments")
      ->default_val(32)
      ->check(CLI::Range(1, 1'000'000));
  cmd->add_option("--spur-factor", args->spur_factor, "Prune free-end branches shorter than this many crack widths")
      ->default_val(2.0)
      ->check(finite_in(0.0, 100.0));
  cmd->add_flag("--exclude-border-fragments", args->exclude_border_fragments,
                "Leave fragments cut by the image border out of S1");
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing on success, no progress");
  cmd->callback([&action, args] { action = [args] { return run_analyze(*args); }; });
}

}  // namespace fissure::cli
