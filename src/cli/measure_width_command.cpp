// vsil measure-width IMAGE [--line-color C] [--json FILE] [--depth FILE [--bins N] [--plot PNG]]
// Line widths of a finished illustration, sampled on the lines' medial axes (postfx/line_width.h).
#include <iomanip>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_parse.h"
#include "cli/cli_report.h"
#include "cli/cli_volume_options.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/depth_image.h"
#include "core/error.h"
#include "core/image_file.h"
#include "core/json_input.h"
#include "core/options.h"
#include "postfx/line_width.h"

namespace vsil::cli {
namespace {

struct MeasureWidthArgs {
  std::string image;
  std::string lineColor = "black";
  std::string json;
  std::string depth;
  std::string plot;
  int bins = 10;
  double binWidth = 1.0;
  std::optional<long long> maxMemoryMiB;
};

void run(const MeasureWidthArgs& args) {
  const Rgba color = parseOpaqueColor(args.lineColor, "--line-color",
                                      "lines are found by their red, green and blue alone");
  checkHistogramBinWidth("--bin-width", args.binWidth);
  const std::size_t maxBytes = maxMemoryBytes(args.maxMemoryMiB);
  OutputBatch outputs;  // both written, or neither
  outputs.claim("--plot", args.plot);
  if (!args.plot.empty()) requirePngName("--plot", args.plot);
  outputs.claim("--json", args.json);
  if (validateOnly()) return;
  const cv::Mat image = readImage(args.image);
  const cv::Mat1b mask = lineMaskFromImage(image, color);
  if (cv::countNonZero(mask) == 0) {
    throwInputError(args.image, "no pixel has the line colour " + args.lineColor);
  }
  const auto samples = measureLineWidths(mask, args.image, maxBytes);
  // Said on stderr and kept in the report (--json) beside the numbers they qualify.
  std::vector<std::string> warnings;
  if (std::string warning = regionsNotLinesWarning(mask, samples, args.image); !warning.empty()) {
    warnings.push_back(std::move(warning));
  }
  std::vector<double> widths;
  for (const auto& s : samples) widths.push_back(s.width);
  const WidthStatistics stats = summarizeWidths(widths, args.binWidth);

  nlohmann::json report = {{"image", args.image},
                           {"line_color", args.lineColor},
                           {"widths", widthStatisticsJson(stats)}};
  // The text report is printed once everything has succeeded: a failure (a --depth image of
  // another size) leaves nothing on stdout.
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << "samples " << stats.count << "  mean " << stats.mean
       << "  median " << stats.median << "  p05 " << stats.p05 << "  p95 " << stats.p95 << "  min "
       << stats.min << "  max " << stats.max << "\n";
  if (!args.depth.empty()) {
    const cv::Mat1f depth = decodeDepthImage(readImage(args.depth), args.depth);
    if (depth.size() != image.size()) {
      throwInputError(args.depth, "is not the size of " + args.image);
    }
    const auto bins = widthAgainstDepth(samples, depth, args.bins);
    if (std::string warning = emptyDepthBinsWarning(samples, bins, "--depth " + args.depth);
        !warning.empty()) {
      warnings.push_back(std::move(warning));
    }
    text << "depth from   to  count  mean  median\n";
    for (const auto& bin : bins) {
      text << std::setw(10) << bin.depthFrom << std::setw(5) << bin.depthTo << std::setw(7)
           << bin.count << std::setw(6) << bin.meanWidth << std::setw(8) << bin.medianWidth << "\n";
    }
    report["by_depth"] = depthBinsJson(bins);
    if (!args.plot.empty()) {
      outputs.add(args.plot, encodePng(args.plot, plotWidthAgainstDepth(samples, depth, bins)));
    }
  }
  report["warnings"] = warnings;
  printWarnings(warnings);
  if (!args.json.empty()) outputs.add(args.json, jsonText(report, 2) + "\n");
  outputs.commit();
  reportStream({args.json, args.plot}) << text.str();
}

const CommandRegistration registerMeasureWidthCommand(30, [](CLI::App& app) {
  auto args = std::make_shared<MeasureWidthArgs>();
  auto* command = app.add_subcommand(
      "measure-width", "measure line widths in an image: mean, median, percentiles, histogram");
  command->add_option("image", args->image, "the illustration (PNG)")->required();
  command->add_option("--line-color", args->lineColor,
                      "colour of the lines: a name or #rgb, #rrggbb (default black)");
  nonEmpty(command->add_option("--json", args->json, "write the report as JSON to this file"));
  nonEmpty(command->add_option("--depth", args->depth,
                               "the render's --depth-out image: report width against depth"));
  command->add_option("--bins", args->bins, "depth bins (with --depth)")
      ->check(CLI::Range(1, 1000));
  command->add_option("--bin-width", args->binWidth,
                      "histogram bin width in pixels (at least " +
                          formatNumber(kMinHistogramBinWidth) + ", default 1)");
  addMaxMemoryOption(*command, args->maxMemoryMiB);
  auto* plot =
      nonEmpty(command->add_option("--plot", args->plot, "plot width against depth (PNG)"));
  plot->needs("--depth");
  command->callback([args] { run(*args); });
});

}  // namespace
}  // namespace vsil::cli
