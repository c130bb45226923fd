#include "io/sample_codec.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/error.h"
#include "io/sample_sink.h"
#include "io/text_fields.h"

namespace vsil::io {

std::size_t storedSize(StoredType type) {
  switch (type) {
    case StoredType::UInt8:
    case StoredType::Int8:
      return 1;
    case StoredType::UInt16:
    case StoredType::Int16:
      return 2;
    case StoredType::Float32:
    case StoredType::Int32:
    case StoredType::UInt32:
      return 4;
    case StoredType::Float64:
    case StoredType::Int64:
    case StoredType::UInt64:
      return 8;
  }
  return 1;
}

bool isWideInteger(StoredType type) {
  return type == StoredType::Int32 || type == StoredType::UInt32 || type == StoredType::Int64 ||
         type == StoredType::UInt64;
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
    case StoredType::Int32:
      return "int32";
    case StoredType::UInt32:
      return "uint32";
    case StoredType::Int64:
      return "int64";
    case StoredType::UInt64:
      return "uint64";
  }
  return "unknown";
}

SampleType keptSampleType(StoredType type) {
  switch (type) {
    case StoredType::UInt8:
      return SampleType::UInt8;
    case StoredType::Int8:
      return SampleType::Int8;
    case StoredType::UInt16:
      return SampleType::UInt16;
    case StoredType::Int16:
      return SampleType::Int16;
    case StoredType::Float32:
    case StoredType::Float64:
    case StoredType::Int32:
    case StoredType::UInt32:
    case StoredType::Int64:
    case StoredType::UInt64:
      return SampleType::Float32;
  }
  return SampleType::Float32;
}

SampleType keptSampleType(StoredType type, const Rescale& rescale) {
  return rescale.identity() ? keptSampleType(type) : SampleType::Float32;
}

StoredType storedTypeOf(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
      return StoredType::UInt8;
    case SampleType::Int8:
      return StoredType::Int8;
    case SampleType::UInt16:
      return StoredType::UInt16;
    case SampleType::Int16:
      return StoredType::Int16;
    case SampleType::Float32:
      return StoredType::Float32;
  }
  return StoredType::Float32;
}

std::uint64_t payloadBytes(glm::ivec3 dims, StoredType type) {
  return std::uint64_t(dims.x) * std::uint64_t(dims.y) * std::uint64_t(dims.z) * storedSize(type);
}

std::string describeLayout(glm::ivec3 dims, StoredType type) {
  return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z) +
         " " + storedTypeName(type);
}

void parseTextSamples(const std::string& where, std::string_view text, StoredType type,
                      SampleSink& sink, TextAfterSamples after) {
  const std::uint64_t count = sink.fileSamples();
  // Each value takes at least one character and one separator: a short text is refused before
  // any value is parsed.
  if (count > 0 && text.size() < 2 * count - 1) {
    throwInputError(where, "holds " + std::to_string(text.size()) + " characters, too few for " +
                               std::to_string(count) + " values");
  }
  const char* p = text.data();
  const char* end = text.data() + text.size();
  // Whitespace as a C++ stream (VTK's reader) skips it: form feed and vertical tab too.
  auto isSpace = [](char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
  };
  const bool isFloat = type == StoredType::Float32 || type == StoredType::Float64;
  // Integer ranges as doubles; text integers beyond 2^53 are read as the nearest double.
  double lo = 0.0, hi = 0.0;
  switch (type) {
    case StoredType::UInt8:
      hi = 255.0;
      break;
    case StoredType::Int8:
      lo = -128.0, hi = 127.0;
      break;
    case StoredType::UInt16:
      hi = 65535.0;
      break;
    case StoredType::Int16:
      lo = -32768.0, hi = 32767.0;
      break;
    case StoredType::Int32:
      lo = -0x1p31, hi = 0x1p31 - 1;
      break;
    case StoredType::UInt32:
      hi = 0x1p32 - 1;
      break;
    case StoredType::Int64:
      lo = -0x1p63, hi = 0x1p63;
      break;
    case StoredType::UInt64:
      hi = 0x1p64;
      break;
    case StoredType::Float32:
    case StoredType::Float64:
      break;
  }
  for (std::uint64_t i = 0; i < count; ++i) {
    while (p < end && isSpace(*p)) ++p;
    if (p == end) {
      throwInputError(
          where, "holds " + std::to_string(i) + " values, " + std::to_string(count) + " expected");
    }
    const char* start = p;
    while (p < end && !isSpace(*p)) ++p;
    const std::string_view token(start, std::size_t(p - start));
    const double value = parseReal(where, "sample " + std::to_string(i), token);
    if (isFloat) {
      checkFloat32(where, i, value);
    } else if (!(value >= lo && value <= hi) || value != std::floor(value)) {
      throwInputError(where, "sample " + std::to_string(i) + " " + quote(token) + " is not a " +
                                 storedTypeName(type) + " value");
    }
    sink.putValue(i, value);
  }
  while (p < end && (isSpace(*p) || *p == '\0')) ++p;  // a writer's padding is no value
  // A value starts with a digit, a sign or a point, or with nan or inf (as the samples may be,
  // "nan(0x1)" and "infinity" included); no keyword of a later section does.
  const char* tokenEnd = p;
  while (tokenEnd < end && !isSpace(*tokenEnd) && *tokenEnd != '\0') ++tokenEnd;
  std::string next(p, tokenEnd);
  std::transform(next.begin(), next.end(), next.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  const bool startsValue =
      p != end && (std::isdigit(static_cast<unsigned char>(*p)) || *p == '+' || *p == '-' ||
                   *p == '.' || next.starts_with("nan") || next.starts_with("inf"));
  if (after == TextAfterSamples::WhitespaceOnly ? p != end : startsValue) {
    throwInputError(
        where, "holds more than the " + std::to_string(count) + " values its header's sizes give");
  }
  sink.finish();
}

}  // namespace vsil::io
