// `vsil info VOLUME`: what a volume holds (size, type, spacing, value statistics), as text or
// JSON. Reads the volume like `render` does, so it is also the quick check of a file.
// `vsil info --gl [auto|osmesa|egl]`: the OpenGL context that back end makes (what `render`
// would run on), the back ends built in and the EGL devices --gl-device can pick.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/cli_gl_options.h"
#include "cli/cli_progress.h"
#include "cli/cli_volume_options.h"
#include "cli/commands.h"
#include "cli/volume_summary.h"
#include "core/error.h"
#include "core/json_input.h"
#include "core/transfer_function.h"
#include "io/volume_loader.h"

namespace vsil::cli {
namespace {

std::string toText(const Volume& volume, const Summary& s) {
  const DerivedDefaults derived = derivedDefaults(volume);
  std::ostringstream out;
  // Names from the command line or the file go through oneLine (control bytes as '?'), as in
  // errors: a newline or an escape sequence in a file name must not reach the terminal.
  out << "source    " << oneLine(volume.source) << "\n";
  if (!volume.format.empty()) out << "format    " << volume.format << "\n";
  out << "name      " << oneLine(volume.name) << "\n"
      << "dims      " << volume.dims.x << " x " << volume.dims.y << " x " << volume.dims.z << " ("
      << volume.voxelCount() << " samples)\n"
      << "type      " << sampleTypeName(volume.type());
  if (!volume.fileType.empty()) {
    out << " (the file's " << volume.fileType << "; " << volume.inexactSamples
        << (volume.inexactSamples == 1 ? " sample" : " samples") << " rounded)";
  }
  out << "\n";
  if (volume.rescale) {
    out << "rescale   value = " << volume.rescale->slope << " * stored + "
        << volume.rescale->intercept << "\n";
  }
  for (const Orientation& o : volume.orientations) {
    out << "placement " << oneLine(o.name) << " (" << oneLine(o.space) << "), axes " << o.axes
        << ", origin " << o.worldFromIndex[3].x << " " << o.worldFromIndex[3].y << " "
        << o.worldFromIndex[3].z << "\n";
  }
  if (volume.subset) {
    const VolumeSubset& subset = *volume.subset;
    out << "read      --crop " << subset.cropText() << " --stride " << subset.stride << " of "
        << subset.fileDims.x << " x " << subset.fileDims.y << " x " << subset.fileDims.z << "\n";
  }
  out << "spacing   " << volume.spacing.x << " " << volume.spacing.y << " " << volume.spacing.z
      << "\n"
      << "range     " << s.range.min << " .. " << s.range.max << "\n"
      << "mean      " << s.mean << "  (stddev " << s.stddev << ")\n"
      << "iso       " << derived.iso << "  (the default of --iso: Otsu's threshold)\n"
      << "window    " << derived.iso << " .. " << derived.windowHigh
      << "  (the default --window of mip, lmip, demip)\n"
      << "suggested: --tf " << suggestedTransferFunction(derived)
      << (inHounsfieldUnits(derived) ? "  (values in HU)" : "  (values not in HU)") << "\n"
      << "percentiles";
  for (std::size_t i = 0; i < std::size(kPercentiles); ++i) {
    out << "  p" << kPercentiles[i] << " " << s.percentiles[i];
  }
  out << "\nhistogram (" << kHistogramBins << " bins over the range)\n";
  const std::size_t largest = *std::max_element(s.histogram.begin(), s.histogram.end());
  for (int i = 0; i < kHistogramBins; ++i) {
    char line[96];
    const double share = 100.0 * double(s.histogram[i]) / double(volume.voxelCount());
    std::snprintf(line, sizeof line, "  %12.6g .. %-12.6g %12zu %6.2f%% ", binEdge(s, i),
                  binEdge(s, i + 1), s.histogram[i], share);
    out << line << std::string(largest ? 30 * s.histogram[i] / largest : 0, '#') << "\n";
  }
  return out.str();
}

struct InfoOptions {
  std::string volume;
  bool json = false;
  VolumeOptions load;
  GlOptions gl;
};

struct GlReport {
  gl::ContextInfo context;
  std::vector<std::string> built;       // back ends in this binary
  std::vector<std::string> eglDevices;  // "0: software"
  std::string noEglDevices;             // why there are none
};

GlReport glReport(const gl::ContextOptions& options) {
  GlReport report;
  report.context = gl::GlContext(options).info();
  for (gl::Backend backend : gl::builtBackends()) report.built.push_back(gl::backendName(backend));
  report.eglDevices = gl::describeEglDevices(&report.noEglDevices);
  return report;
}

nlohmann::ordered_json toJson(const GlReport& report) {
  nlohmann::ordered_json json = gl::contextInfoJson(report.context);
  json["built"] = report.built;
  json["egl_devices"] = report.eglDevices;
  if (report.eglDevices.empty()) json["egl_devices_none"] = report.noEglDevices;
  return json;
}

std::string toText(const GlReport& report) {
  const gl::ContextInfo& c = report.context;
  std::ostringstream out;
  out << "gl        " << gl::backendName(c.backend) << " (" << c.platform << ")\n"
      << "vendor    " << c.vendor << "\n"
      << "renderer  " << c.renderer << "\n"
      << "version   " << c.version << "\n"
      << "glsl      " << c.glslVersion << "\n"
      << "built     ";
  for (std::size_t i = 0; i < report.built.size(); ++i) out << (i ? ", " : "") << report.built[i];
  out << "\negl devices";
  if (report.eglDevices.empty()) out << "  none (" << report.noEglDevices << ")";
  for (const auto& device : report.eglDevices) out << "  " << device;
  out << "\n";
  return out.str();
}

void runInfo(const InfoOptions& options) {
  LoadOptions load = summaryLoadOptions(toLoadOptions(options.load));
  const std::optional<gl::ContextOptions> glOptions =
      options.gl.given ? std::optional(toContextOptions(options.gl)) : std::nullopt;
  if (options.volume.empty() && !glOptions) {
    throw InputError("info: give a VOLUME, or --gl for the OpenGL back end");
  }
  if (validateOnly()) return;
  const std::optional<GlReport> gl = glOptions ? std::optional(glReport(*glOptions)) : std::nullopt;
  std::optional<Volume> volume;
  std::optional<Summary> summary;
  if (!options.volume.empty()) {
    ProgressLine progress("reading " + options.volume);
    load.progress = progress.callback();
    volume = loadVolume(options.volume, load);
    progress.finish();  // before stdout, which a terminal shows on the same lines
    printVolumeWarnings(*volume);
    summary = summarize(*volume);
  }
  // Printed only once everything succeeded: an error leaves stdout empty.
  if (options.json) {
    nlohmann::ordered_json json =
        volume ? summaryJson(*volume, *summary) : nlohmann::ordered_json::object();
    if (gl) json["gl"] = toJson(*gl);
    std::cout << jsonText(json, 2) << "\n";
  } else {
    std::cout << (gl ? toText(*gl) : "") << (gl && volume ? "\n" : "")
              << (volume ? toText(*volume, *summary) : "");
  }
}

const CommandRegistration registerInfoCommand(20, [](CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command = app.add_subcommand(
      "info",
      "Print a volume's size, type, spacing and value statistics; with --gl, the OpenGL context");
  command->add_option("volume", options->volume,
                      "volume file (" + std::string(kVolumeFileKinds) +
                          "; raw with --dims/--type) or gen:NAME[:N]");
  command->add_flag("--json", options->json, "machine-readable output");
  addVolumeOptions(*command, options->load);
  addGlOptions(*command, options->gl, /*valueOptional=*/true);
  command->callback([options] { runInfo(*options); });
});

}  // namespace
}  // namespace vsil::cli
