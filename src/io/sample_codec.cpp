#include "io/sample_codec.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "io/text_fields.h"

namespace vsil::io {
namespace {

template <typename Unsigned>
Unsigned loadUnsigned(const std::uint8_t* p, bool bigEndian) {
  Unsigned value = 0;
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i) {
    const std::size_t shift = 8 * (bigEndian ? sizeof(Unsigned) - 1 - i : i);
    value = Unsigned(value | Unsigned(Unsigned(p[i]) << shift));
  }
  return value;
}

[[noreturn]] void badSample(const std::string& where, std::size_t index, const std::string& what) {
  throwInputError(where, "sample " + std::to_string(index) + " " + what);
}

void checkFinite(const std::string& where, std::size_t index, double value) {
  if (std::isnan(value)) badSample(where, index, "is NaN");
  if (std::isinf(value)) badSample(where, index, "is infinite");
}

// Float64 converts only when the value survives as a finite float.
float narrowToFloat(const std::string& where, std::size_t index, double value) {
  checkFinite(where, index, value);
  if (std::abs(value) > double(std::numeric_limits<float>::max())) {
    badSample(where, index, "(" + std::to_string(value) + ") is beyond the float32 range");
  }
  return float(value);
}

}  // namespace

std::size_t storedSize(StoredType type) {
  switch (type) {
    case StoredType::UInt8:
    case StoredType::Int8:
      return 1;
    case StoredType::UInt16:
    case StoredType::Int16:
      return 2;
    case StoredType::Float32:
      return 4;
    case StoredType::Float64:
      return 8;
  }
  return 1;
}

const char* storedTypeName(StoredType type) {
  switch (type) {
    case StoredType::UInt8:
      return "uint8";
    case StoredType::Int8:
      return "int8";
    case StoredType::UInt16:
      return "uint16";
    case StoredType::Int16:
      return "int16";
    case StoredType::Float32:
      return "float32";
    case StoredType::Float64:
      return "float64";
  }
  return "unknown";
}

SampleType sampleTypeOf(StoredType type) {
  switch (type) {
    case StoredType::UInt8:
      return SampleType::UInt8;
    case StoredType::Int8:
    case StoredType::Int16:
      return SampleType::Int16;
    case StoredType::UInt16:
      return SampleType::UInt16;
    case StoredType::Float32:
    case StoredType::Float64:
      return SampleType::Float32;
  }
  return SampleType::Float32;
}

StoredType storedTypeOf(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
      return StoredType::UInt8;
    case SampleType::UInt16:
      return StoredType::UInt16;
    case SampleType::Int16:
      return StoredType::Int16;
    case SampleType::Float32:
      return StoredType::Float32;
  }
  return StoredType::Float32;
}

std::size_t payloadBytes(glm::ivec3 dims, StoredType type) {
  return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z) * storedSize(type);
}

std::string describeLayout(glm::ivec3 dims, StoredType type) {
  return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z) +
         " " + storedTypeName(type);
}

std::vector<float> decodeSamples(const std::string& where, std::span<const std::uint8_t> bytes,
                                 StoredType type, bool bigEndian) {
  const std::size_t size = storedSize(type);
  const std::size_t count = bytes.size() / size;
  std::vector<float> samples(count);
  const std::uint8_t* p = bytes.data();
  for (std::size_t i = 0; i < count; ++i, p += size) {
    switch (type) {
      case StoredType::UInt8:
        samples[i] = float(*p);
        break;
      case StoredType::Int8:
        samples[i] = float(std::int8_t(*p));
        break;
      case StoredType::UInt16:
        samples[i] = float(loadUnsigned<std::uint16_t>(p, bigEndian));
        break;
      case StoredType::Int16:
        samples[i] = float(std::int16_t(loadUnsigned<std::uint16_t>(p, bigEndian)));
        break;
      case StoredType::Float32: {
        const float value = std::bit_cast<float>(loadUnsigned<std::uint32_t>(p, bigEndian));
        checkFinite(where, i, value);
        samples[i] = value;
        break;
      }
      case StoredType::Float64:
        samples[i] = narrowToFloat(
            where, i, std::bit_cast<double>(loadUnsigned<std::uint64_t>(p, bigEndian)));
        break;
    }
  }
  return samples;
}

std::vector<float> parseTextSamples(const std::string& where, std::string_view text,
                                    std::size_t count, StoredType type) {
  // Each value takes at least one character and one separator: a short text is refused before
  // the samples are allocated.
  if (count > 0 && text.size() < 2 * count - 1) {
    throwInputError(where, "holds " + std::to_string(text.size()) + " characters, too few for " +
                               std::to_string(count) + " values");
  }
  std::vector<float> samples(count);
  const char* p = text.data();
  const char* end = text.data() + text.size();
  auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  for (std::size_t i = 0; i < count; ++i) {
    while (p < end && isSpace(*p)) ++p;
    if (p == end) {
      throwInputError(
          where, "holds " + std::to_string(i) + " values, " + std::to_string(count) + " expected");
    }
    const char* start = p;
    while (p < end && !isSpace(*p)) ++p;
    const std::string_view token(start, std::size_t(p - start));
    const double value = parseReal(where, "sample " + std::to_string(i), token);
    switch (type) {
      case StoredType::Float32:
      case StoredType::Float64:
        samples[i] = narrowToFloat(where, i, value);
        break;
      default: {
        const double lo = type == StoredType::UInt8 || type == StoredType::UInt16 ? 0.0
                          : type == StoredType::Int8                              ? -128.0
                                                                                  : -32768.0;
        const double hi = type == StoredType::UInt8    ? 255.0
                          : type == StoredType::Int8   ? 127.0
                          : type == StoredType::UInt16 ? 65535.0
                                                       : 32767.0;
        if (!(value >= lo && value <= hi) || value != std::floor(value)) {
          badSample(where, i, quote(token) + " is not a " + storedTypeName(type) + " value");
        }
        samples[i] = float(value);
      }
    }
  }
  return samples;
}

}  // namespace vsil::io
