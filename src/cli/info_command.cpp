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
#include "core/error.h"
#include "core/transfer_function.h"
#include "io/volume_loader.h"

namespace vsil::cli {
namespace {

constexpr int kHistogramBins = 16;
constexpr double kPercentiles[] = {1, 5, 25, 50, 75, 95, 99};

struct Summary {
  ValueRange range;
  double mean = 0.0;
  double stddev = 0.0;
  std::vector<std::size_t> histogram;  // kHistogramBins equal bins over [min, max]
  std::vector<float> percentiles;      // nearest-rank, one per kPercentiles entry
};

// The nearest-rank percentiles of the samples: counted for integer types (no copy of the
// volume), from a sorted copy for floats.
std::vector<float> percentilesOf(const Volume& volume, ValueRange range) {
  const double n = double(volume.voxelCount());
  std::vector<std::size_t> ranks;
  for (double p : kPercentiles) ranks.push_back(std::size_t(std::ceil(p / 100.0 * n)) - 1);
  std::vector<float> result;
  if (volume.type() == SampleType::Float32) {
    const auto samples = volume.samples<float>();
    std::vector<float> sorted(samples.begin(), samples.end());
    for (std::size_t rank : ranks) {
      std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(rank), sorted.end());
      result.push_back(sorted[rank]);
    }
    return result;
  }
  // Integer samples: at most 65536 distinct values from range.min on.
  const auto lowest = std::int64_t(range.min);
  std::vector<std::size_t> counts(std::size_t(std::int64_t(range.max) - lowest + 1), 0);
  volume.visit([&](auto samples) {
    for (auto v : samples) ++counts[std::size_t(std::int64_t(v) - lowest)];
  });
  std::size_t below = 0, value = 0;
  for (std::size_t rank : ranks) {  // ranks grow, so one walk over the counts serves them all
    while (below + counts[value] <= rank) below += counts[value++];
    result.push_back(float(lowest + std::int64_t(value)));
  }
  return result;
}

Summary summarize(const Volume& volume) {
  Summary s;
  s.range = valueRange(volume);
  double sum = 0.0, sumSquares = 0.0;
  s.histogram.assign(kHistogramBins, 0);
  const double width = double(s.range.max) - double(s.range.min);
  volume.visit([&](auto samples) {
    for (auto sample : samples) {
      const float value = float(sample);
      sum += value;
      sumSquares += double(value) * value;
      const int bin = width > 0 ? int((value - s.range.min) / width * kHistogramBins) : 0;
      ++s.histogram[std::min(bin, kHistogramBins - 1)];
    }
  });
  const double n = double(volume.voxelCount());
  s.mean = sum / n;
  s.stddev = std::sqrt(std::max(0.0, sumSquares / n - s.mean * s.mean));
  s.percentiles = percentilesOf(volume, s.range);
  return s;
}

double binEdge(const Summary& s, int i) {
  return s.range.min + (double(s.range.max) - s.range.min) * i / kHistogramBins;
}

nlohmann::ordered_json toJson(const Volume& volume, const Summary& s) {
  nlohmann::ordered_json percentiles = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < std::size(kPercentiles); ++i) {
    percentiles[std::to_string(int(kPercentiles[i]))] = s.percentiles[i];
  }
  nlohmann::ordered_json json = {
      {"source", volume.source},
      {"name", volume.name},
      {"dims", {volume.dims.x, volume.dims.y, volume.dims.z}},
      {"samples", volume.voxelCount()},
      {"type", sampleTypeName(volume.type())},
      {"spacing", {volume.spacing.x, volume.spacing.y, volume.spacing.z}},
  };
  if (auto read = describeRead<nlohmann::ordered_json>(volume); !read.is_null())
    json["read"] = read;
  if (auto file = describeFile<nlohmann::ordered_json>(volume); !file.is_null())
    json["file"] = file;
  json["min"] = s.range.min;
  json["max"] = s.range.max;
  json["mean"] = s.mean;
  json["stddev"] = s.stddev;
  const DerivedDefaults derived = derivedDefaults(volume);
  json["default_iso"] = derived.iso;
  json["default_window"] = {derived.iso, derived.windowHigh};
  json["suggested_tf"] = suggestedTransferFunction(derived);
  json["percentiles"] = percentiles;
  json["histogram"] = {{"min", s.range.min}, {"max", s.range.max}, {"counts", s.histogram}};
  return json;
}

std::string toText(const Volume& volume, const Summary& s) {
  const DerivedDefaults derived = derivedDefaults(volume);
  std::ostringstream out;
  out << "source    " << volume.source << "\n";
  if (!volume.format.empty()) out << "format    " << volume.format << "\n";
  out << "name      " << volume.name << "\n"
      << "dims      " << volume.dims.x << " x " << volume.dims.y << " x " << volume.dims.z << " ("
      << volume.voxelCount() << " samples)\n"
      << "type      " << sampleTypeName(volume.type());
  if (!volume.fileType.empty()) {
    out << " (the file's " << volume.fileType << "; " << volume.inexactSamples
        << " samples rounded)";
  }
  out << "\n";
  if (volume.rescale) {
    out << "rescale   value = " << volume.rescale->slope << " * stored + "
        << volume.rescale->intercept << "\n";
  }
  for (const Orientation& o : volume.orientations) {
    out << "placement " << o.name << " (" << o.space << "), axes " << o.axes << ", origin "
        << o.worldFromIndex[3].x << " " << o.worldFromIndex[3].y << " " << o.worldFromIndex[3].z
        << "\n";
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
  LoadOptions load = toLoadOptions(options.load);
  // The samples, and for floats the sorted copy the percentiles need (integers are counted).
  load.limits.taskBytes = [](glm::ivec3 dims, SampleType type) {
    const std::uint64_t voxels = std::uint64_t(dims.x) * std::uint64_t(dims.y) * dims.z;
    return voxels * sampleTypeSize(type) +
           (type == SampleType::Float32 ? voxels * 4 : 65536 * sizeof(std::size_t));
  };
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
        volume ? toJson(*volume, *summary) : nlohmann::ordered_json::object();
    if (gl) json["gl"] = toJson(*gl);
    std::cout << json.dump(2) << "\n";
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
