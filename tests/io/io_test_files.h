#pragma once
// Writing small volume files for the reader tests: byte encodings, compression, base64.
// Header-only; each test writes its files into vsil::test::scratchDir().
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include "core/error.h"
#include "core/volume.h"

namespace vsil::test {

using Bytes = std::vector<std::uint8_t>;

inline void writeFile(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), std::streamsize(text.size()));
}
inline void writeFile(const std::filesystem::path& path, const Bytes& bytes) {
  writeFile(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}
inline std::string asText(const Bytes& bytes) {
  return {bytes.begin(), bytes.end()};
}

// Appends `value`'s `size` low bytes (or its float bits) in the given byte order.
inline void appendWord(Bytes& out, std::uint64_t value, std::size_t size, bool bigEndian) {
  for (std::size_t i = 0; i < size; ++i) {
    const std::size_t shift = 8 * (bigEndian ? size - 1 - i : i);
    out.push_back(std::uint8_t(value >> shift));
  }
}

// `values` stored as `type` samples in the given byte order (values must fit the type).
inline Bytes encodeSamples(const std::vector<float>& values, SampleType type, bool bigEndian) {
  Bytes out;
  for (float v : values) {
    switch (type) {
      case SampleType::UInt8:
        out.push_back(std::uint8_t(v));
        break;
      case SampleType::Int8:
        out.push_back(std::uint8_t(std::int8_t(v)));
        break;
      case SampleType::UInt16:
        appendWord(out, std::uint16_t(v), 2, bigEndian);
        break;
      case SampleType::Int16:
        appendWord(out, std::uint16_t(std::int16_t(v)), 2, bigEndian);
        break;
      case SampleType::Float32: {
        std::uint32_t bits;
        std::memcpy(&bits, &v, 4);
        appendWord(out, bits, 4, bigEndian);
        break;
      }
    }
  }
  return out;
}

// 32- or 64-bit integers (`size` bytes each, two's complement) in the given byte order.
inline Bytes encodeIntegers(const std::vector<std::int64_t>& values, std::size_t size,
                            bool bigEndian) {
  Bytes out;
  for (std::int64_t v : values) appendWord(out, std::uint64_t(v), size, bigEndian);
  return out;
}

// A file of 32- or 64-bit integers and what a reader keeps of it (float32, the samples rounded
// counted, the file's type named): `type` as the format spells it, `fileType` as vsil names it.
struct WideIntegerCase {
  const char* type;
  const char* fileType;              // int32, uint32, int64, uint64
  std::size_t size;                  // bytes per sample
  std::vector<std::int64_t> values;  // unsigned ones as their bits
  std::vector<float> kept;
  std::uint64_t inexact;

  bool isUnsigned() const { return fileType[0] == 'u'; }
  // The values as ASCII payloads write them, whitespace after each.
  std::string text(const char* separator) const {
    std::string out;
    for (std::int64_t v : values) {
      out += (isUnsigned() ? std::to_string(std::uint64_t(v)) : std::to_string(v)) + separator;
    }
    return out;
  }
};

// A volume's samples as floats (Volume::value), to compare with the values a test wrote.
inline std::vector<float> floatsOf(const Volume& volume) {
  std::vector<float> values(volume.sampleCount());
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = volume.value(i);
  return values;
}

// What a reader must keep of a WideIntegerCase's file.
inline void expectWideIntegersKept(const Volume& volume, const WideIntegerCase& c) {
  EXPECT_EQ(volume.type(), SampleType::Float32);
  EXPECT_EQ(volume.fileType, c.fileType);
  EXPECT_EQ(floatsOf(volume), c.kept);
  EXPECT_EQ(volume.inexactSamples, c.inexact);
}

// Deflate with a zlib (windowBits 15) or gzip (15 + 16) wrapper.
inline Bytes deflateBytes(const Bytes& in, bool gzip) {
  z_stream s{};
  deflateInit2(&s, 6, Z_DEFLATED, gzip ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY);
  Bytes out(deflateBound(&s, uLong(in.size())) + 32);
  s.next_in = const_cast<Bytef*>(in.data());
  s.avail_in = uInt(in.size());
  s.next_out = out.data();
  s.avail_out = uInt(out.size());
  deflate(&s, Z_FINISH);
  out.resize(s.total_out);
  deflateEnd(&s);
  return out;
}

// One LZ4 block (vtkLZ4DataCompressor's format).
inline Bytes lz4Bytes(const Bytes& in) {
  Bytes out(std::size_t(LZ4_compressBound(int(in.size()))));
  const int size =
      LZ4_compress_default(reinterpret_cast<const char*>(in.data()),
                           reinterpret_cast<char*>(out.data()), int(in.size()), int(out.size()));
  out.resize(std::size_t(size));
  return out;
}

// One xz stream (vtkLZMADataCompressor's format: lzma_easy_buffer_encode).
inline Bytes xzBytes(const Bytes& in) {
  Bytes out(lzma_stream_buffer_bound(in.size()));
  std::size_t size = 0;
  lzma_easy_buffer_encode(6, LZMA_CHECK_CRC64, nullptr, in.data(), in.size(), out.data(), &size,
                          out.size());
  out.resize(size);
  return out;
}

inline std::string encodeBase64(const Bytes& in) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t b = std::uint32_t(in[i]) << 16 |
                            (i + 1 < in.size() ? std::uint32_t(in[i + 1]) << 8 : 0) |
                            (i + 2 < in.size() ? std::uint32_t(in[i + 2]) : 0);
    out += alphabet[b >> 18 & 63];
    out += alphabet[b >> 12 & 63];
    out += i + 1 < in.size() ? alphabet[b >> 6 & 63] : '=';
    out += i + 2 < in.size() ? alphabet[b & 63] : '=';
  }
  return out;
}

// A small volume's values that fit every sample type: 0, 1, ..., with a negative and a
// fractional value for the signed and float types.
inline std::vector<float> testValues(glm::ivec3 dims, SampleType type) {
  std::vector<float> values(std::size_t(dims.x) * dims.y * dims.z);
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = float((i * 37) % 251);
    if (type == SampleType::Int8) values[i] = float(int(values[i]) - 125);
    if (type == SampleType::UInt16) values[i] *= 251.0f;
    if (type == SampleType::Int16) values[i] = values[i] * 100.0f - 12000.0f;
    if (type == SampleType::Float32) values[i] = values[i] * 0.37f - 20.5f;
  }
  return values;
}

// One line of a fixture manifest (tests/io/<format>/fixtures.txt, written by that folder's
// make_fixtures.py without vsil): a file and what a reader must find in it; `rest` holds the
// line's further, format-specific fields.
struct FixtureExpectation {
  std::string file;
  glm::ivec3 dims{0};
  glm::dvec3 spacing{0.0};
  std::string keptType;
  std::string fileType;  // "" when kept as stored ("-" in the manifest)
  std::uint64_t inexact = 0;
  double sum = 0, first = 0, last = 0;  // of the samples as kept, summed in file order
  std::vector<std::string> rest;
};

inline std::vector<FixtureExpectation> readFixtureManifest(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<FixtureExpectation> fixtures;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    FixtureExpectation f;
    fields >> f.file >> f.dims.x >> f.dims.y >> f.dims.z >> f.spacing.x >> f.spacing.y >>
        f.spacing.z >> f.keptType >> f.fileType >> f.inexact >> f.sum >> f.first >> f.last;
    if (f.fileType == "-") f.fileType.clear();
    for (std::string field; fields >> field;) f.rest.push_back(field);
    fixtures.push_back(f);
  }
  return fixtures;
}

// Checks `volume` against the manifest line: dims, spacing, types, rounding, and the samples'
// sum (in double, in file order, as make_fixtures.py adds them), first and last.
inline void expectFixtureRead(const Volume& volume, const FixtureExpectation& f) {
  EXPECT_EQ(volume.dims, f.dims);
  EXPECT_EQ(volume.spacing, f.spacing);
  EXPECT_EQ(sampleTypeName(volume.type()), f.keptType);
  EXPECT_EQ(volume.fileType, f.fileType);
  EXPECT_EQ(volume.inexactSamples, f.inexact);
  double sum = 0;
  for (std::size_t i = 0; i < volume.sampleCount(); ++i) sum += double(volume.value(i));
  EXPECT_EQ(sum, f.sum);
  EXPECT_EQ(double(volume.value(0)), f.first);
  EXPECT_EQ(double(volume.value(volume.sampleCount() - 1)), f.last);
}

// A fixture's file name as a test name ("int16_gzip.nii.gz" -> "int16_gzip_nii_gz").
inline std::string fixtureTestName(std::string file) {
  for (char& c : file) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return file;
}

// Expects `load()` to throw an InputError whose message is one line, starts with `prefix` and
// contains each of `parts`; returns the message (empty when nothing was thrown).
template <typename Load>
std::string expectInputError(Load&& load, const std::string& prefix,
                             std::initializer_list<std::string> parts) {
  try {
    load();
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "message: " << message << "\nprefix: " << prefix;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    for (const auto& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos)
          << "message: " << message << "\nlacks: " << part;
    }
    return message;
  }
  ADD_FAILURE() << "no InputError; expected one starting with " << prefix;
  return {};
}

}  // namespace vsil::test
