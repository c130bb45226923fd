#include "harness/table_registry.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "harness/text_table.h"
#include "tables/fft_table.h"
#include "tables/nk3_table.h"

namespace vsil::bench {
namespace {

// fft: broadening's FFT blur against OpenCV's spatial GaussianBlur (tables/fft_table.h). Two
// JSON rows per (size, sigma), technique "fft" and "spatial"; --frames sets the repetitions.
TableResult runFftTable(const BenchOptions& options, Progress& progress) {
  FftTableSpec spec;
  if (!options.sizes.empty()) spec.sizes = options.sizes;
  spec.repetitions = options.frames;
  progress.setTotalCases(1);
  progress.startCase("fft: " + std::to_string(spec.sizes.size() * spec.sigmas.size()) +
                     " sizes × sigmas, " + std::to_string(spec.repetitions) + " repetitions each");
  const auto measured = measureFftTable(spec);
  progress.finish();

  TableResult table;
  table.name = "fft";
  table.title = "Broadening cost against sigma: FFT (FFTW, zero padded) vs OpenCV GaussianBlur, ms";
  TextTable text({"size", "sigma", "FFT ms", "[min–max]", "spatial ms", "[min–max]", "FFT/spatial",
                  "max diff", "check"});
  table.plot.title = "fft: blur time per image (ms)";
  table.plot.valueLabel = "ms";
  table.plot.series = {{"FFT", false}, {"GaussianBlur", false}};
  // The two filters compute the same convolution (zero outside the image); they may differ by
  // float round-off and by the spatial kernel's truncation at 3 sigma (OpenCV's default size).
  // Values are in [0, 1] (a line image); 1e-2 catches a wrong sigma or a shifted image.
  constexpr double kMaxDifference = 1e-2;
  for (const auto& r : measured) {
    const std::string check =
        r.maxDifference <= kMaxDifference ? "ok" : "FAILED: FFT and spatial results differ";
    char cells[6][48];
    std::snprintf(cells[0], 48, "%.3f", r.fftMs);
    std::snprintf(cells[1], 48, "[%.3f–%.3f]", r.fftMinMs, r.fftMaxMs);
    std::snprintf(cells[2], 48, "%.3f", r.spatialMs);
    std::snprintf(cells[3], 48, "[%.3f–%.3f]", r.spatialMinMs, r.spatialMaxMs);
    std::snprintf(cells[4], 48, "%.2f", r.ratio);
    std::snprintf(cells[5], 48, "%.1e", r.maxDifference);
    char sigma[16];
    std::snprintf(sigma, sizeof sigma, "%g", r.sigma);
    const std::string size = std::to_string(r.size) + "²";
    text.addRow({size, sigma, cells[0], cells[1], cells[2], cells[3], cells[4], cells[5], check});
    if (check != "ok") table.failures.push_back("fft " + size + " sigma " + sigma + ": " + check);
    table.plot.groups.push_back(size + " σ" + sigma);
    table.plot.values.push_back({r.fftMs, r.spatialMs});
    for (const bool fft : {true, false}) {
      const double med = fft ? r.fftMs : r.spatialMs;
      table.rows.push_back({{"table", "fft"},
                            {"dataset", "lines"},
                            {"width", r.size},
                            {"height", r.size},
                            {"technique", fft ? "fft" : "spatial"},
                            {"sigma", r.sigma},
                            {"frames", spec.repetitions},
                            {"ms_median", med},
                            {"ms_min", fft ? r.fftMinMs : r.spatialMinMs},
                            {"ms_max", fft ? r.fftMaxMs : r.spatialMaxMs},
                            {"fps", med > 0 ? 1000.0 / med : 0.0},
                            {"ratio_fft_over_spatial", r.ratio},
                            {"max_difference", r.maxDifference},
                            {"check", check}});
    }
  }
  table.text = text.plain();
  table.markdown = text.markdown();
  table.notes.push_back(
      "image: 40 one-pixel circles (fixed seed); FFT plans and kernel spectra cached before "
      "timing; single thread");
  return table;
}

std::vector<TableDefinition> makeRegistry() {
  return {
      {"nk3", "Nagy–Klein Table 3: RA, OPS and BS frame rates per dataset and window",
       nk3DatasetNames(), runNk3Table, ""},
      {"fft", "broadening cost against sigma: FFT vs OpenCV GaussianBlur", {}, runFftTable, ""},
      {"dv1",
       "Díaz–Vázquez Table 1: MIP, DEMIP and DVR composite frame rates",
       {},
       {},
       "the mip and demip techniques and DVR compositing do not exist yet"},
      {"illustrate",
       "Ebert–Rheingans volume illustration frame rates",
       {},
       {},
       "the illustrate technique does not exist yet"},
      {"semantic",
       "Rautek et al. semantic rendering frame rates",
       {},
       {},
       "the semantic technique does not exist yet"},
  };
}

}  // namespace

const std::vector<TableDefinition>& tableRegistry() {
  static const std::vector<TableDefinition> registry = makeRegistry();
  return registry;
}

const TableDefinition& implementedTable(const std::string& name) {
  std::string known;
  for (const auto& table : tableRegistry()) {
    known += (known.empty() ? "" : ", ") + table.name;
    if (table.name != name) continue;
    if (!table.run) {
      throw InputError("--table " + name + ": not implemented yet (" + table.missingTechnique +
                       ")");
    }
    return table;
  }
  throw InputError("--table " + name + ": unknown table (known: " + known + ")");
}

}  // namespace vsil::bench
