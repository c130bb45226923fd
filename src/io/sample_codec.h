#pragma once
// Sample types as files store them, and the in-memory SampleType each is kept as.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/volume.h"

namespace vsil::io {

class SampleSink;

// What a file may hold. UInt8 .. Float32 are kept as they are; the others are kept as Float32
// (keptSampleType), counting the samples whose value changed (Volume::inexactSamples): Float64
// when every value is finite in float, and the 32- and 64-bit integers, exact up to 2^24.
enum class StoredType {
  UInt8,
  Int8,
  UInt16,
  Int16,
  Float32,
  Float64,
  Int32,
  UInt32,
  Int64,
  UInt64
};

// Whether `type` is one of the 32- and 64-bit integer types kept as Float32.
bool isWideInteger(StoredType type);

std::size_t storedSize(StoredType type);
const char* storedTypeName(StoredType type);
SampleType keptSampleType(StoredType type);
// The type a volume keeps for `type` read through `rescale`: Float32 unless it is the identity.
SampleType keptSampleType(StoredType type, const Rescale& rescale);
StoredType storedTypeOf(SampleType type);

// Payload bytes for `dims` samples of `type`, once planVolume has passed (so the product cannot
// overflow); written out once so every reader states sizes the same way.
std::uint64_t payloadBytes(glm::ivec3 dims, StoredType type);
// "128x128x128 uint8", for messages.
std::string describeLayout(glm::ivec3 dims, StoredType type);

// What may follow the samples of a text payload: a keyword or nothing (legacy VTK, where other
// sections follow), or whitespace alone (NRRD, MetaImage). A value more means the header's sizes
// are not the file's.
enum class TextAfterSamples { KeywordOrNothing, WhitespaceOnly };

// Parses the sink's file sample count of whitespace-separated numbers (ASCII payloads) into
// `sink`. Integer types must hold integers within their range; floats must be finite (and,
// for Float64, within float range). Throws InputError naming `where` and the sample.
void parseTextSamples(const std::string& where, std::string_view text, StoredType type,
                      SampleSink& sink, TextAfterSamples after);

}  // namespace vsil::io
