#pragma once
// Where readers put a file's samples: straight into the Volume's own buffer, decoded from the
// file's byte order and type, keeping only the samples of its subset (--crop, --stride). No
// reader holds a second copy of the volume: binary payloads come in pieces (a row, a chunk of
// rows, an inflated block) and text payloads one value at a time.
#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/volume.h"
#include "io/sample_codec.h"

namespace vsil::io {

// Throws InputError "<where>: sample <index> is NaN" (or "is infinite") unless `value` is finite:
// what every reader, and vsil.Volume over a numpy array, refuses to render.
void checkFinite(const std::string& where, std::uint64_t index, double value);
// checkFinite, and "<where>: sample <index> <what>(<value>) is beyond the float32 range" for a
// finite value that float32 cannot hold; `what` ("" or "rescaled ") names it.
void checkFloat32(const std::string& where, std::uint64_t index, double value,
                  const char* what = "");

class SampleSink {
 public:
  // `volume` holds subset.dims() samples of keptSampleType(fileType, rescale)
  // (Volume::allocate); each stored value v is kept as rescale.slope * v + rescale.intercept.
  SampleSink(const std::string& where, Volume& volume, const VolumeSubset& subset,
             StoredType fileType, bool bigEndian, Rescale rescale = {});

  const std::string& where() const { return where_; }
  std::uint64_t fileSamples() const { return fileSamples_; }
  std::size_t sampleSize() const { return size_; }
  // Bytes of the file's payload that hold kept samples: the rows kept, from the first to the
  // last kept sample of each.
  std::uint64_t neededBytes() const;

  // File samples firstSample, firstSample + 1, ... in the file's encoding (a whole number of
  // samples). Those in the subset are decoded into the volume: NaN or infinite floats, and
  // float64 beyond float range, throw InputError naming `where` and the file's sample index.
  // Calls for disjoint runs may come from several threads at once.
  void put(std::uint64_t firstSample, std::span<const std::uint8_t> bytes);
  // Sequential input from file sample `firstSample` on, in pieces of any size (a piece may end
  // within a sample). Appenders over disjoint runs may work from several threads at once.
  class Appender {
   public:
    Appender(SampleSink& sink, std::uint64_t firstSample) : sink_(sink), next_(firstSample) {}
    void append(std::span<const std::uint8_t> bytes);
    std::uint64_t nextSample() const { return next_; }
    bool withinSample() const { return !partial_.empty(); }

   private:
    SampleSink& sink_;
    std::uint64_t next_;
    std::vector<std::uint8_t> partial_;  // the bytes of a sample split between pieces
  };
  // The same from the file's first sample on, for a single stream.
  void append(std::span<const std::uint8_t> bytes) { appender_.append(bytes); }
  // File sample `index` from text, already checked against the file's type.
  void putValue(std::uint64_t index, double value);

  // The file's sample runs that hold kept samples, in file order: each kept row from its first
  // to its last kept sample, adjacent runs merged, each at most maxBytes (at least one sample).
  void forEachRun(
      std::uint64_t maxBytes,
      const std::function<void(std::uint64_t firstSample, std::uint64_t count)>& f) const;

  // After the last append: throws InputError unless every sample of the file arrived. Records
  // the conversion's inexact samples in the volume.
  void finishAppending();
  // Records the conversion's inexact samples in the volume, with a warning when there are any
  // (after put / putValue).
  void finish();

 private:
  // File samples of type FileC through the rescale (in double) into float32, each checked
  // finite and within float range, counting those float32 rounds.
  template <typename FileC>
  void decodeViaDouble(float* out, const std::uint8_t* in, std::size_t inStep, std::size_t count,
                       std::uint64_t firstSample);
  template <typename Out>
  void decode(Out* out, const std::uint8_t* in, std::size_t inStep, std::size_t count,
              std::uint64_t firstSample);
  void decodeRun(std::size_t keptIndex, const std::uint8_t* in, std::size_t inStep,
                 std::size_t count, std::uint64_t firstSample);
  bool rowKept(std::uint64_t row) const;

  std::string where_;
  Volume& volume_;
  VolumeSubset subset_;
  StoredType fileType_;
  bool swap_;  // the file's byte order differs from this machine's
  Rescale rescale_;
  std::size_t size_;
  std::uint64_t fileSamples_;
  bool whole_;
  std::atomic<std::uint64_t> inexact_{0};
  Appender appender_{*this, 0};
};

}  // namespace vsil::io
