#include "generators/generators.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>
#include <thread>

#include "core/error.h"

namespace vsil {
namespace {

constexpr int kDefaultEdge = 64;

double clamp01(double t) {
  return std::clamp(t, 0.0, 1.0);
}

// A sample's value from its voxel coordinates (integers: samples sit at integer positions).
using Field = std::function<double(int x, int y, int z)>;

// Fills every sample of the volume, the field evaluated at the generator's voxel coordinates
// of the subset's samples, slices in parallel. Each sample depends only on its own
// coordinates, so the result does not depend on the number of threads.
void fill(Volume& volume, const VolumeSubset& subset, const Field& field) {
  const glm::ivec3 dims = volume.dims;
  const std::span<float> samples = volume.samples<float>();
  const int threads = std::clamp(int(std::thread::hardware_concurrency()), 1, 16);
  auto work = [&](int first) {
    for (int z = first; z < dims.z; z += threads) {
      for (int y = 0; y < dims.y; ++y) {
        float* row = &samples[volume.index(0, y, z)];
        const glm::ivec3 at = subset.lo + glm::ivec3(0, y, z) * subset.stride;
        for (int x = 0; x < dims.x; ++x) {
          row[x] = float(field(at.x + x * subset.stride, at.y, at.z));
        }
      }
    }
  };
  std::vector<std::jthread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
}

Field sphere(int n) {
  const double c = (n - 1) / 2.0;
  return [=](double x, double y, double z) {
    const double r = std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
    return clamp01(1.0 - r / (n / 2.0));
  };
}

Field cube(int n) {
  const double c = (n - 1) / 2.0;
  return [=](double x, double y, double z) {
    const double d = std::max({std::abs(x - c), std::abs(y - c), std::abs(z - c)});
    return clamp01(1.0 - d / (n / 2.0));
  };
}

Field spheres(int n) {
  const double c = (n - 1) / 2.0;
  const double sigma = n / 8.0;
  const double offset = n / 6.0;
  const double twoSigma2 = 2.0 * sigma * sigma;
  const double peak = 1.0 + std::exp(-(2 * offset) * (2 * offset) / twoSigma2);
  return [=](double x, double y, double z) {
    const double yz2 = (y - c) * (y - c) + (z - c) * (z - c);
    const double da = x - (c - offset), db = x - (c + offset);
    const double sum =
        std::exp(-(da * da + yz2) / twoSigma2) + std::exp(-(db * db + yz2) / twoSigma2);
    return clamp01(sum / peak);
  };
}

Field torus(int n) {
  const double c = (n - 1) / 2.0;
  const double ringRadius = n / 4.0;
  const double falloff = n / 8.0;
  return [=](double x, double y, double z) {
    const double rho = std::sqrt((x - c) * (x - c) + (y - c) * (y - c));
    const double d = std::sqrt((rho - ringRadius) * (rho - ringRadius) + (z - c) * (z - c));
    return clamp01(1.0 - d / falloff);
  };
}

Field marschnerLobb(int n) {
  constexpr double fM = 6.0, alpha = 0.25, pi = std::numbers::pi;
  const double scale = 2.0 / (n - 1);
  return [=](double x, double y, double z) {
    const double ux = -1.0 + scale * x, uy = -1.0 + scale * y, uz = -1.0 + scale * z;
    const double rho = std::cos(2.0 * pi * fM * std::cos(pi * std::sqrt(ux * ux + uy * uy) / 2.0));
    return (1.0 - std::sin(pi * uz / 2.0) + alpha * (1.0 + rho)) / (2.0 * (1.0 + alpha));
  };
}

Field hydrogen(int n) {
  const double c = (n - 1) / 2.0;
  const double a = n / 48.0;
  const double peak = 72.0 * a * a * std::exp(-2.0);
  return [=](double x, double y, double z) {
    const double qz = z - c;
    const double r2 = (x - c) * (x - c) + (y - c) * (y - c) + qz * qz;
    return clamp01(std::abs(3.0 * qz * qz - r2) * std::exp(-std::sqrt(r2) / (3.0 * a)) / peak);
  };
}

Field blobs(int n) {
  std::mt19937 engine(20240607u);
  // std::mt19937's output is fixed by the standard; the distributions are not, hence by hand.
  auto uniform = [&] { return double(engine() >> 8) * 0x1p-24; };
  // A Gaussian is separable: exp(-|p-m|²/2s²) = gx(x)·gy(y)·gz(z), so each blob keeps one table
  // per axis and a sample costs products, not exponentials (equal to the formula up to rounding).
  constexpr int kBlobs = 8;
  std::vector<double> tables(std::size_t(kBlobs) * 3 * n);
  auto table = [&tables, n](int blob, int axis) {
    return &tables[(std::size_t(blob) * 3 + axis) * n];
  };
  for (int k = 0; k < kBlobs; ++k) {
    double centre[3];
    for (double& m : centre) m = n * (0.25 + 0.5 * uniform());
    const double s = n * (1.0 / 24.0 + (1.0 / 10.0 - 1.0 / 24.0) * uniform());
    const double amplitude = 0.5 + 0.5 * uniform();
    for (int axis = 0; axis < 3; ++axis) {
      double* t = table(k, axis);
      for (int i = 0; i < n; ++i) {
        const double d = i - centre[axis];
        t[i] = std::exp(-d * d / (2.0 * s * s)) * (axis == 0 ? amplitude : 1.0);
      }
    }
  }
  return [tables = std::move(tables), n](int x, int y, int z) {
    double sum = 0.0;
    for (int k = 0; k < kBlobs; ++k) {
      const double* t = &tables[std::size_t(k) * 3 * n];
      sum += t[x] * t[n + y] * t[2 * n + z];
    }
    return std::min(1.0, sum);
  };
}

struct Generator {
  const char* name;
  Field (*make)(int n);
};

constexpr Generator kGenerators[] = {
    {"sphere", sphere},     {"spheres", spheres},
    {"torus", torus},       {"marschner-lobb", marschnerLobb},
    {"hydrogen", hydrogen}, {"blobs", blobs},
    {"cube", cube},
};

std::string validNames() {
  std::string list;
  for (const auto& g : kGenerators) list += (list.empty() ? "" : ", ") + std::string(g.name);
  return list;
}

[[noreturn]] void fail(const std::string& spec, const std::string& what) {
  throwInputError("gen:" + spec, what + " (generators: " + validNames() +
                                     "; spec gen:NAME[:N], N >= 2, default " +
                                     std::to_string(kDefaultEdge) + ")");
}

}  // namespace

std::vector<std::string> generatorNames() {
  std::vector<std::string> names;
  for (const auto& g : kGenerators) names.emplace_back(g.name);
  return names;
}

Volume generateVolume(const std::string& spec, const VolumeLimits& limits,
                      const ReadRegion& region) {
  const auto colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  int n = kDefaultEdge;
  if (colon != std::string::npos) {
    const std::string edge = spec.substr(colon + 1);
    const auto [end, ec] = std::from_chars(edge.data(), edge.data() + edge.size(), n);
    if (ec == std::errc::result_out_of_range && end == edge.data() + edge.size()) {
      fail(spec, "edge length '" + edge + "' is out of range");
    }
    if (edge.empty() || ec != std::errc() || end != edge.data() + edge.size()) {
      fail(spec, "edge length '" + edge + "' is not an integer");
    }
    if (n < 2) fail(spec, "edge length " + std::to_string(n) + " is below 2");
  }
  const auto* generator = std::find_if(std::begin(kGenerators), std::end(kGenerators),
                                       [&](const Generator& g) { return name == g.name; });
  if (generator == std::end(kGenerators)) fail(spec, "unknown generator '" + name + "'");

  Volume volume;
  volume.name = name;
  volume.source = "gen:" + name + ":" + std::to_string(n);
  const VolumeSubset subset =
      planVolume(volume.source, glm::ivec3(n), SampleType::Float32, limits, region);
  volume.dims = subset.dims();
  volume.spacing = glm::dvec3(subset.stride);
  if (!subset.whole()) volume.subset = subset;
  volume.allocate(SampleType::Float32);
  fill(volume, subset, generator->make(n));
  return volume;
}

}  // namespace vsil
