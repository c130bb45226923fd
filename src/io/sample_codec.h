#pragma once
// Sample types as files store them, and their conversion to the in-memory floats of a Volume.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/volume.h"

namespace vsil::io {

// What a file may hold. Int8 and Float64 have no SampleType of their own: Int8 loads as Int16
// (the narrowest type that holds it), Float64 as Float32 when every value fits a finite float.
enum class StoredType { UInt8, Int8, UInt16, Int16, Float32, Float64 };

std::size_t storedSize(StoredType type);
const char* storedTypeName(StoredType type);
SampleType sampleTypeOf(StoredType type);
StoredType storedTypeOf(SampleType type);

// Expected payload bytes for `dims` samples of `type`, after checkVolumeSize has passed (so the
// product cannot overflow); written out once so every reader states sizes the same way.
std::size_t payloadBytes(glm::ivec3 dims, StoredType type);
// "128x128x128 uint8", for messages.
std::string describeLayout(glm::ivec3 dims, StoredType type);

// Converts `bytes` (a whole number of samples) to floats. Throws InputError naming `where` and
// the first sample index that is NaN or infinite, or (Float64) beyond float range.
std::vector<float> decodeSamples(const std::string& where, std::span<const std::uint8_t> bytes,
                                 StoredType type, bool bigEndian);

// Parses `count` whitespace-separated numbers (ASCII payloads). Integer types must hold integers
// within their range; floats must be finite.
std::vector<float> parseTextSamples(const std::string& where, std::string_view text,
                                    std::size_t count, StoredType type);

}  // namespace vsil::io
