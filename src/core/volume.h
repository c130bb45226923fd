#pragma once
// A scalar volume on a regular grid: the single in-memory form every reader and generator
// produces and every technique consumes. Samples stay in their file's own type (one byte per
// voxel for 8-bit data), so a volume costs what its file holds; consumers read them through a
// typed view for fast loops (visit, samples<T>) or as floats one at a time (at, value).
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "core/limits.h"
#include "core/options.h"
#include "core/volume_region.h"

namespace vsil {

// The types a volume keeps its samples in, in the data's own units. Files with other types
// convert when read (io/sample_codec.h): float64 and 32/64-bit integers to Float32, counting
// the samples whose value changed (Volume::inexactSamples).
enum class SampleType { UInt8, Int8, UInt16, Int16, Float32 };
inline constexpr SampleType kSampleTypes[] = {SampleType::UInt8, SampleType::Int8,
                                              SampleType::UInt16, SampleType::Int16,
                                              SampleType::Float32};

const char* sampleTypeName(SampleType type);  // "uint8", "int8", "uint16", "int16", "float32"
std::size_t sampleTypeSize(SampleType type);  // bytes per sample
bool isIntegerType(SampleType type);

// A volume's samples of one C++ type: owned (a vector, or memory the volume alone holds, kept
// by `keepAlive`: a large volume's own mapping, the DICOM child process's memfd), or borrowed
// from memory that another owner keeps alive (a numpy array wrapped by the Python module), so
// that wrapping copies nothing. Copying an owned buffer copies the samples (into a vector); copying
// a borrowed one shares them, as numpy views do.
template <typename C>
class SampleBuffer {
 public:
  using value_type = C;
  SampleBuffer() = default;
  explicit SampleBuffer(std::size_t count) : owned_(count) {}
  SampleBuffer(C* data, std::size_t count, std::shared_ptr<void> keepAlive, bool borrowed)
      : where_(borrowed ? Where::Borrowed : Where::Held),
        external_(data),
        externalCount_(count),
        keepAlive_(std::move(keepAlive)) {}
  SampleBuffer(const SampleBuffer& other) { *this = other; }
  SampleBuffer& operator=(const SampleBuffer& other) {
    if (this == &other) return *this;
    if (other.where_ == Where::Held) {
      *this = SampleBuffer();
      owned_.assign(other.external_, other.external_ + other.externalCount_);
    } else {
      owned_ = other.owned_;
      where_ = other.where_;
      external_ = other.external_;
      externalCount_ = other.externalCount_;
      keepAlive_ = other.keepAlive_;
    }
    return *this;
  }
  SampleBuffer(SampleBuffer&&) noexcept = default;
  SampleBuffer& operator=(SampleBuffer&&) noexcept = default;

  bool borrowed() const { return where_ == Where::Borrowed; }
  std::span<C> span() {
    return where_ == Where::Vector ? std::span<C>(owned_) : std::span<C>(external_, externalCount_);
  }
  std::span<const C> span() const {
    return where_ == Where::Vector ? std::span<const C>(owned_)
                                   : std::span<const C>(external_, externalCount_);
  }
  std::size_t size() const { return span().size(); }
  const C& operator[](std::size_t i) const { return span()[i]; }

 private:
  enum class Where { Vector, Held, Borrowed };  // owned_, or external_ kept by keepAlive_
  std::vector<C> owned_;
  Where where_ = Where::Vector;
  C* external_ = nullptr;
  std::size_t externalCount_ = 0;
  std::shared_ptr<void> keepAlive_;
};

using SampleStorage = std::variant<SampleBuffer<std::uint8_t>, SampleBuffer<std::int8_t>,
                                   SampleBuffer<std::uint16_t>, SampleBuffer<std::int16_t>,
                                   SampleBuffer<float>>;  // in SampleType's order
template <SampleType T>
using SampleCType = typename std::variant_alternative_t<std::size_t(T), SampleStorage>::value_type;
template <typename C>
constexpr SampleType sampleTypeFor() {
  if constexpr (std::is_same_v<C, std::uint8_t>)
    return SampleType::UInt8;
  else if constexpr (std::is_same_v<C, std::int8_t>)
    return SampleType::Int8;
  else if constexpr (std::is_same_v<C, std::uint16_t>)
    return SampleType::UInt16;
  else if constexpr (std::is_same_v<C, std::int16_t>)
    return SampleType::Int16;
  else if constexpr (std::is_same_v<C, float>)
    return SampleType::Float32;
  else
    static_assert(sizeof(C) == 0, "not a sample type");
}

// A linear map a file asks to apply to its stored values (NIfTI scl_slope / scl_inter, DICOM
// Rescale Slope / Intercept): value = slope * stored + intercept.
struct Rescale {
  double slope = 1.0;
  double intercept = 0.0;
  bool identity() const { return slope == 1.0 && intercept == 0.0; }
};

// A file's transform from sample indices (i, j, k) to world coordinates, e.g. a NIfTI sform.
struct Orientation {
  std::string name;                // "qform", "sform", "patient" (DICOM)
  std::string space;               // what the world frame is: "scanner", "MNI152", "LPS", ...
  glm::dmat4 worldFromIndex{1.0};  // column-major, as GLM; world = M * (i, j, k, 1)
  // The world axis each index axis runs most along, e.g. "RAS": i toward Right, j toward
  // Anterior, k toward Superior (the letters name the positive direction).
  std::string axes;
};

class Volume {
 public:
  std::string name;    // dataset name: a file's base name without extension, or the generator's
  std::string source;  // the path or generator spec it was made from
  glm::ivec3 dims{0};  // samples along x (fastest in memory), y, z
  glm::dvec3 spacing{1.0};  // distance between sample centres along x, y, z (any unit)
  // The file's sample type when the volume keeps another ("float64" kept as float32), else "".
  std::string fileType;
  // Samples whose value changed in that conversion (float64 values that float32 rounds,
  // integers beyond 2^24 that it cannot hold).
  std::uint64_t inexactSamples = 0;
  // The file's rescale, when it has one that changes values (the volume then keeps float32 and
  // its samples are the rescaled values, e.g. CT in Hounsfield units).
  std::optional<Rescale> rescale;
  // Set when only part of the file was read (--crop, --stride): which part.
  std::optional<VolumeSubset> subset;
  // The file's format and variant, for `vsil info` and --meta-out ("NIfTI-1 (.nii.gz)"); ""
  // for generated volumes and arrays.
  std::string format;
  // What the reader found worth telling but not refusing (samples float32 rounded, other DICOM
  // series in the folder), one line each; the commands print them as warnings.
  std::vector<std::string> warnings;
  // The file's placement of the samples in a world frame, when it states one (NIfTI qform and
  // sform, DICOM patient position): recorded, not applied — vsil renders in index space
  // scaled by the spacing.
  std::vector<Orientation> orientations;

  // Sizes the samples for `dims` in `type`, all zero (replacing any previous samples).
  void allocate(SampleType type);
  // Uses `samples` (voxelCount() of them, x fastest) in place, without a copy; `keepAlive`
  // owns that memory and is released with the last volume that shares it.
  template <typename C>
  void borrow(C* samples, std::shared_ptr<void> keepAlive) {
    samples_.emplace<SampleBuffer<C>>(samples, voxelCount(), std::move(keepAlive), true);
  }
  // As allocate, but the samples are `memory`'s bytes as they are (a fresh memfd mapping: all
  // zero); it must hold sampleTypeSize(type) * voxelCount() bytes, aligned for `type`, and the
  // volume alone uses it from now on (not borrowed: a copy of the volume copies the samples).
  void allocateIn(SampleType type, std::shared_ptr<void> memory);
  // A volume with `owner`'s fields whose samples borrow owner's, kept alive by it: a copy that
  // costs no samples (the Python module hands its volumes to a RenderJob this way).
  static Volume sharing(const std::shared_ptr<Volume>& owner);
  // Whether the samples are borrowed (borrow) rather than owned.
  bool borrowsSamples() const {
    return std::visit([](const auto& buffer) { return buffer.borrowed(); }, samples_);
  }
  SampleType type() const { return SampleType(samples_.index()); }
  std::size_t sampleCount() const;
  std::size_t sampleBytes() const { return sampleCount() * sampleTypeSize(type()); }

  std::size_t voxelCount() const {
    return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  }
  std::size_t index(int x, int y, int z) const {
    return (std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) +
           std::size_t(x);
  }
  // One sample as a float (exact for every SampleType), for CPU references and statistics.
  float value(std::size_t index) const {
    return std::visit([index](const auto& samples) { return float(samples[index]); }, samples_);
  }
  float at(int x, int y, int z) const { return value(index(x, y, z)); }

  // The samples in their own C++ type, x fastest, then y, then z. C must be type()'s type
  // (std::logic_error otherwise).
  template <typename C>
  std::span<C> samples() {
    return checkedBuffer<C>(samples_).span();
  }
  template <typename C>
  std::span<const C> samples() const {
    return checkedBuffer<C>(samples_).span();
  }
  // Calls f(std::span<const C>) (or std::span<C> on a non-const volume) with the samples in
  // their own type; returns what f returns. One instantiation of f per SampleType.
  template <typename F>
  decltype(auto) visit(F&& f) const {
    return std::visit([&f](const auto& v) -> decltype(auto) { return f(v.span()); }, samples_);
  }
  template <typename F>
  decltype(auto) visit(F&& f) {
    return std::visit([&f](auto& v) -> decltype(auto) { return f(v.span()); }, samples_);
  }

 private:
  template <typename C, typename Storage>
  static auto& checkedBuffer(Storage& storage) {
    auto* buffer = std::get_if<SampleBuffer<C>>(&storage);
    if (!buffer) throw std::logic_error("Volume::samples: not the volume's sample type");
    return *buffer;
  }

  SampleStorage samples_;
};

struct ValueRange {
  float min = 0.0f;
  float max = 0.0f;
};
ValueRange valueRange(const Volume& volume);

// The iso value a technique uses when none is given, one a user would pick: Otsu's threshold
// (otsuLevel) over the samples in 256 levels of the value range, in the middle of the gap between
// the two classes where there is one; the range's minimum for a constant volume.
float defaultIso(const Volume& volume);
// The same for a volume whose valueRange is known (a pass over the samples saved).
float defaultIso(const Volume& volume, ValueRange range);

// The facts option defaults are derived from (core/options.h), for this volume, from one pass
// over its samples: defaultIso, and the high end of the default grey window of the MIP family
// (mip, lmip, demip), which runs from Otsu's threshold (air and noise lie below it and show as
// background) to the top of the 256-level bin holding the 99.5th percentile of the samples above
// it (a few outliers, metal in a CT, do not darken the rest; on 8-bit data that is the exact
// percentile's level). Where nothing lies above the threshold (a constant volume) the top lies a
// thousandth of the value range above it, or one data unit for a constant volume: LO < HI.
inline constexpr double kDefaultWindowQuantile = 0.995;
DerivedDefaults derivedDefaults(const Volume& volume);
// The same for a volume whose valueRange is known (a pass over the samples saved).
DerivedDefaults derivedDefaults(const Volume& volume, ValueRange range);
// The same from the 256-level histogram of the samples (a volume split across processes sums
// its slabs' levelCounts): equal to derivedDefaults for volumes of up to 2^24 samples, which it
// histograms whole (larger ones it subsamples).
using LevelCounts = std::array<std::uint64_t, 256>;
LevelCounts levelCounts(const Volume& volume, ValueRange range, int zBegin, int zEnd);
// Otsu's threshold of a 256-level histogram whose counts sum to `total`: the level t maximizing
// the between-class variance q1·q2·(μ1 − μ2)² of the classes ≤ t and > t, the first such level
// on ties, levels whose classes hold less than FLT_EPSILON of the samples skipped. This is
// cv::threshold's THRESH_OTSU on an 8-bit image with this histogram, in its order of arithmetic
// (tested equal to it), from the counts instead of an image of every sample.
int otsuLevel(const LevelCounts& counts, std::uint64_t total);
DerivedDefaults derivedDefaultsFromCounts(ValueRange range, const LevelCounts& counts);

// Limits checked before a reader allocates or reads any payload. maxBytes bounds the memory of
// the whole task the volume is read for (default: half the physical memory, core/limits.h);
// maxDimension bounds each axis of the volume as kept (the GL 3D texture limit, 2048).
struct VolumeLimits {
  std::size_t maxBytes = limits::defaultMemoryBytes();
  int maxDimension = limits::kMaxVolumeSide;
  // What the whole task needs, samples included, for a volume of these dims and type (a render:
  // samples, texture, brick maxima and images; limits::renderVolumeBytes), and how the error
  // names the task: "<task> 512x512x512 uint8 samples<taskDetail> needs ...". Unset: the
  // samples alone.
  std::function<std::uint64_t(glm::ivec3 dims, SampleType type)> taskBytes;
  std::string task = "reading";
  std::string taskDetail;  // e.g. " at --size 512x512"
  // For a render: the largest brick texture in bytes (--max-texture-mib; core/brick_layout.h).
  // A volume beyond it is cut into more bricks, which taskBytes counts; nothing is refused here.
  std::uint64_t maxTextureBytes = limits::kMaxTextureBytes;
};

// Resolves what a reader keeps of a file of `fileDims` and checks it against the limits:
// throws InputError naming `where` when fileDims are not positive, the region (--crop) lies
// outside them, an axis of the kept volume exceeds maxDimension, or the samples in `type`
// (or taskBytes) exceed maxBytes:
// "<where>: reading 512x512x512 uint8 samples needs 128 MiB,
// over the --max-memory limit of 100 MiB; read less with --crop ... or --stride N, or raise
// --max-memory". Nothing is allocated.
VolumeSubset planVolume(const std::string& where, glm::ivec3 fileDims, SampleType type,
                        const VolumeLimits& limits, const ReadRegion& region = {});

}  // namespace vsil
