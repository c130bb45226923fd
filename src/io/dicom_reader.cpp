// DICOM series through GDCM (the library VTK and ITK use): a folder of slices, or one slice file
// standing for its series in its folder. GDCM's Scanner reads the headers; the slices are
// sorted by Image Position (Patient) along the slice normal — never by file name or Instance
// Number — and must be evenly spaced (a missing slice is an error, not a stretched volume).
// The series' dims and type are checked against the limits before any pixel data is decoded;
// then GDCM decodes each kept slice (raw, RLE, JPEG, JPEG-LS, JPEG 2000: whatever it has
// codecs for) and the samples go through the sink with Rescale Slope/Intercept applied (CT in
// Hounsfield units). Several series in a folder: the one with the most slices, unless
// LoadOptions::series names another; the others are listed in a warning. A multi-frame file
// (enhanced CT/MR: all slices in one file) is read the same way, its frames standing for the
// slices: each frame's position from its Plane Position Sequence in the Per-frame Functional
// Groups, the orientation from the Plane Orientation Sequence (per frame or shared).
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmReader.h>
#include <gdcmScanner.h>
#include <gdcmTrace.h>
#include <gdcmTransferSyntax.h>
#include <gdcmUIDs.h>

#include "core/error.h"
#include "core/options.h"
#include "core/unique_fd.h"
#include "core/upright.h"
#include "io/dicom_child.h"
#include "io/dicom_plugin.h"
#include "io/file_access.h"
#include "io/readers.h"
#include "io/text_fields.h"

namespace vsil::io {
namespace {

const gdcm::Tag kSeriesUid(0x0020, 0x000e);
const gdcm::Tag kImagePosition(0x0020, 0x0032);
const gdcm::Tag kImageOrientation(0x0020, 0x0037);
const gdcm::Tag kRows(0x0028, 0x0010);
const gdcm::Tag kColumns(0x0028, 0x0011);
const gdcm::Tag kModality(0x0008, 0x0060);
const gdcm::Tag kSeriesDescription(0x0008, 0x103e);
const gdcm::Tag kNumberOfFrames(0x0028, 0x0008);
// Enhanced multi-frame objects: functional groups, their sequences and what they hold.
const gdcm::Tag kSharedGroups(0x5200, 0x9229);
const gdcm::Tag kPerFrameGroups(0x5200, 0x9230);
const gdcm::Tag kPlanePositionSequence(0x0020, 0x9113);
const gdcm::Tag kPlaneOrientationSequence(0x0020, 0x9116);
const gdcm::Tag kPixelValueTransformationSequence(0x0028, 0x9145);
const gdcm::Tag kPixelMeasuresSequence(0x0028, 0x9110);
const gdcm::Tag kPixelSpacing(0x0028, 0x0030);
const gdcm::Tag kRescaleIntercept(0x0028, 0x1052);
const gdcm::Tag kRescaleSlope(0x0028, 0x1053);
const gdcm::Tag kPixelData(0x7fe0, 0x0010);

// Slices whose spacing differs from the series' by more than this share are a gap.
constexpr double kSpacingTolerance = 0.01;

std::string trimmed(const char* value) {
  return value ? std::string(trim(std::string_view(value))) : std::string();
}

// A free-text value (a Series Description) as UTF-8: as it is where it is UTF-8 (ASCII, or
// Specific Character Set ISO_IR 192); otherwise read as Latin-1 (ISO_IR 100, the most common
// other one), each byte its own character, so that "Sch\xe4del" is not printed as an invalid
// byte.
std::string textAsUtf8(const std::string& bytes) {
  std::size_t i = 0;
  bool utf8 = true;
  while (utf8 && i < bytes.size()) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    const std::size_t length = c < 0x80         ? 1
                               : (c >> 5) == 6  ? 2
                               : (c >> 4) == 14 ? 3
                               : (c >> 3) == 30 ? 4
                                                : 0;
    utf8 = length > 0 && i + length <= bytes.size();
    for (std::size_t k = 1; utf8 && k < length; ++k) {
      utf8 = (static_cast<unsigned char>(bytes[i + k]) >> 6) == 2;
    }
    i += length;
  }
  if (utf8) return bytes;
  std::string text;
  for (const char byte : bytes) {
    const auto c = static_cast<unsigned char>(byte);
    if (c < 0x80) {
      text += byte;
    } else {
      text += char(0xc0 | (c >> 6));
      text += char(0x80 | (c & 0x3f));
    }
  }
  return text;
}

// "a\b\c" -> numbers; empty when the value is missing or not `count` finite numbers.
std::vector<double> parseNumbers(const char* value, std::size_t count) {
  std::vector<double> numbers;
  if (!value) return numbers;
  std::string text(value);
  std::replace(text.begin(), text.end(), '\\', ' ');
  std::istringstream in(text);
  double number = 0;
  while (in >> number) {
    if (!std::isfinite(number)) return {};
    numbers.push_back(number);
  }
  if (numbers.size() != count) return {};
  return numbers;
}

StoredType storedTypeOfPixels(const std::string& where, const gdcm::PixelFormat& format) {
  if (format.GetSamplesPerPixel() != 1) {
    throwInputError(where, std::to_string(format.GetSamplesPerPixel()) +
                               " samples per pixel (colour) is not supported: vsil reads "
                               "scalar (monochrome) images");
  }
  switch (format.GetScalarType()) {
    case gdcm::PixelFormat::UINT8:
      return StoredType::UInt8;
    case gdcm::PixelFormat::INT8:
      return StoredType::Int8;
    case gdcm::PixelFormat::UINT16:
      return StoredType::UInt16;
    case gdcm::PixelFormat::INT16:
      return StoredType::Int16;
    case gdcm::PixelFormat::UINT32:
      return StoredType::UInt32;
    case gdcm::PixelFormat::INT32:
      return StoredType::Int32;
    case gdcm::PixelFormat::FLOAT32:
      return StoredType::Float32;
    case gdcm::PixelFormat::FLOAT64:
      return StoredType::Float64;
    default:
      throwInputError(where, std::string("pixel format ") + format.GetScalarTypeAsString() +
                                 " is not supported (8-, 16- and 32-bit integers, float)");
  }
}

// GDCM checks some of its preconditions with assert(), which Debian's build keeps: a malformed
// file can abort the process inside GDCM (a File Meta Information cut short trips
// `is.good()` in FileMetaInformation::ReadCompat; libFuzzer found it within 52 inputs:
// tests/bad_inputs/dicom_gdcm_assert/slice.dcm). So GDCM reads in a child process
// (io/dicom_child.h), and each call into GDCM that reads files runs inside one of these
// (withinGdcm): stderr goes to /dev/null (assert's own line included; GDCM's warnings go to
// GdcmWarnings anyway), and gdcmCallRunning tells the child's SIGABRT handler that the abort
// is GDCM's.
class GdcmCall {
 public:
  GdcmCall() : stderr_(::dup(STDERR_FILENO)) {
    const UniqueFd null(::open("/dev/null", O_WRONLY | O_CLOEXEC));
    if (null.valid() && stderr_.valid()) ::dup2(null.get(), STDERR_FILENO);
    gdcmCallRunning = 1;
  }
  ~GdcmCall() {
    gdcmCallRunning = 0;
    if (stderr_.valid()) ::dup2(stderr_.get(), STDERR_FILENO);
  }
  GdcmCall(const GdcmCall&) = delete;
  GdcmCall& operator=(const GdcmCall&) = delete;

 private:
  const UniqueFd stderr_;  // the real stderr while GDCM runs
};

// What `call` (a call into GDCM that reads files) returns, run inside a GdcmCall.
template <typename Call>
auto withinGdcm(Call&& call) {
  const GdcmCall guard;
  return call();
}

// GDCM allocates a data element's declared length before it reads the value, so a few bytes
// that claim gigabytes cost them before GDCM finds the file too short (libFuzzer: a 1 KiB slice
// whose element (f0f0,f0f0) has no valid VR, read as implicit with the length 0xf0f0f0f0,
// took 3.8 GiB in the Scanner). Before GDCM opens a file with the DICM preamble, this walks its
// data elements (into sequences and items, skipping values unread) and names the first whose
// declared length runs past the file's end (empty text when none does). It reads an element as
// GDCM does: the File Meta group in explicit VR little endian, then the transfer syntax's
// encoding, an element without a valid VR as implicit. Deflated data sets are not walked.
// Checked against pydicom's 68 test files (real-world encodings, GDCM's and DCMTK's among
// them; tests/io/python/test_pydicom_test_files.py): it names only the one that is truncated
// before its pixel data (rtplan_truncated.dcm).
struct ElementProblem {
  std::string text;
  bool inPixelData = false;  // the file ends inside its Pixel Data (7fe0,0010)
};
ElementProblem overlongElement(const std::string& file) {
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(file, error);
  if (error || size < 132) return {};
  std::optional<FileReader> opened;
  try {
    opened.emplace(file);  // one vsil cannot open is GDCM's to judge, as before
  } catch (const InputError&) {
    return {};
  }
  const FileReader& reader = *opened;
  std::uint8_t magic[4];
  reader.readAt(128, magic);
  if (std::string(reinterpret_cast<const char*>(magic), 4) != "DICM") return {};
  constexpr std::uint32_t kUndefined = 0xffffffff;
  constexpr std::uint64_t kMostElements = 4'000'000;  // beyond: give up, GDCM decides
  bool inMeta = true, explicitVr = true, bigEndian = false;
  bool inFragments = false;  // in encapsulated pixel data: items hold bytes, not elements
  std::string transferSyntax;
  const auto u16 = [&](const std::uint8_t* b) {
    return std::uint32_t(bigEndian && !inMeta ? (b[0] << 8) | b[1] : b[0] | (b[1] << 8));
  };
  const auto u32 = [&](const std::uint8_t* b) {
    return bigEndian && !inMeta ? (std::uint32_t(u16(b)) << 16) | u16(b + 2)
                                : std::uint32_t(u16(b)) | (std::uint32_t(u16(b + 2)) << 16);
  };
  const auto isVr = [](const std::uint8_t* b) {
    static const std::string kVrs =
        "AE AS AT CS DA DS DT FL FD IS LO LT OB OD OF OL OV OW PN SH SL SQ SS ST SV TM UC UI UL "
        "UN UR US UT UV";
    const std::string vr(reinterpret_cast<const char*>(b), 2);
    return std::isupper(b[0]) && std::isupper(b[1]) && kVrs.find(vr) != std::string::npos;
  };
  std::uint64_t at = 132;
  for (std::uint64_t count = 0; at + 8 <= size && count < kMostElements; ++count) {
    std::uint8_t header[12] = {};
    reader.readAt(at, std::span(header, std::size_t(std::min<std::uint64_t>(12, size - at))));
    if (inMeta && (header[0] | (header[1] << 8)) != 0x0002) {
      inMeta = false;  // the data set, in the transfer syntax's encoding
      const std::string ts = trimmed(transferSyntax.c_str());
      if (ts == "1.2.840.10008.1.2.1.99") return {};  // deflated
      explicitVr = ts != "1.2.840.10008.1.2";
      bigEndian = ts == "1.2.840.10008.1.2.2";
    }
    const std::uint32_t group = u16(header), element = u16(header + 2);
    const auto beyondEnd = [&](std::uint64_t length, std::uint64_t valueAt) {
      if (group == 0x7fe0 || inFragments) {
        return ElementProblem{"the file ends inside its pixel data (truncated)", true};
      }
      char tag[16];
      std::snprintf(tag, sizeof tag, "(%04x,%04x)", group, element);
      return ElementProblem{"its data element " + std::string(tag) + " at byte " +
                                std::to_string(at) + " declares " + std::to_string(length) +
                                " bytes, " + std::to_string(size - valueAt) +
                                " are left in the file (a malformed or truncated DICOM file)",
                            false};
    };
    if (group == 0xfffe) {  // an item or a delimiter: a length, no VR; an item's elements follow
      const std::uint32_t length = u32(header + 4);
      if (element == 0xe000 && length != kUndefined && length > size - (at + 8)) {
        return beyondEnd(length, at + 8);
      }
      at += 8;
      if (inFragments && element == 0xe000 && length != kUndefined) at += length;
      if (element == 0xe0dd) inFragments = false;
      continue;
    }
    const bool hasVr = (inMeta || explicitVr) && isVr(header + 4);
    const std::string vr = hasVr ? std::string(reinterpret_cast<const char*>(header + 4), 2) : "";
    const bool longForm =
        std::string("OB OD OF OL OV OW SQ SV UC UN UR UT UV").find(vr) != std::string::npos &&
        !vr.empty();
    const std::uint64_t valueAt = at + (longForm ? 12 : 8);
    if (valueAt > size) return {};
    const std::uint32_t length = !hasVr     ? u32(header + 4)
                                 : longForm ? u32(header + 8)
                                            : u16(header + 6);
    if (length == kUndefined) {  // a sequence or encapsulated pixel data: its items follow
      inFragments = vr == "OB" || vr == "OW" || (group == 0x7fe0 && element == 0x0010);
      at = valueAt;
      continue;
    }
    if (length > size - valueAt) return beyondEnd(length, valueAt);
    if (inMeta && element == 0x0010 && length <= 64) {
      std::vector<std::uint8_t> value(length);
      reader.readAt(valueAt, value);
      transferSyntax.assign(value.begin(), value.end());
    }
    bool sequence = vr == "SQ";
    if (!hasVr && length >= 4) {  // implicit VR: a sequence when its value starts with an item
      std::uint8_t first[4];
      reader.readAt(valueAt, first);
      sequence = u16(first) == 0xfffe && u16(first + 2) == 0xe000;
    }
    at = sequence ? valueAt : valueAt + length;
  }
  return {};
}

struct Slice {
  std::string file;
  double position = 0;  // along the normal
  glm::dvec3 origin{0.0};
  int frame = -1;  // its frame (from 0) in a multi-frame file; -1 for a file of one slice
};

struct Series {
  std::string uid;
  std::vector<std::string> files;
};

// The files of `folder` (not its subfolders, nor hidden files but the one named, `given`), links
// followed, by name: what gdcm::Directory lists, except that it stops at the first entry that
// is neither a file nor a folder (a FIFO, a socket, a link to nothing or in a loop) and so lost
// every slice listed after it; here such an entry is left out with a warning.
std::vector<std::string> folderFiles(const std::string& where, const std::string& folder,
                                     const std::string& given, std::vector<std::string>& warnings) {
  namespace fs = std::filesystem;
  std::vector<fs::path> entries;
  std::error_code error;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    entries.push_back(it->path());
  }
  if (error) throwInputError(where, "cannot list its folder: " + error.message());
  std::sort(entries.begin(), entries.end());
  std::vector<std::string> files;
  for (const fs::path& entry : entries) {
    const std::string name = entry.filename().string();
    if (name.starts_with('.') && name != given) continue;
    const fs::file_status status = fs::status(entry, error);
    if (fs::is_regular_file(status)) {
      files.push_back(entry.string());
    } else if (!fs::is_directory(status)) {
      // Not found: a link to nothing. An error otherwise: a loop of links, a folder the link
      // passes through that cannot be searched.
      const std::string why = status.type() == fs::file_type::not_found ? "a link to nothing"
                              : error                                   ? error.message()
                                                                        : "not a regular file";
      warnings.push_back(where + ": left out " + quote(name) + ": " + why);
    }
  }
  return files;
}

// For the "missing slice?" error: the folder's files that hold no image slice, where one may
// be the slice missing (unreadable, cut, not DICOM).
std::string notSliceNote(const std::vector<std::string>& notSlices) {
  if (notSlices.empty()) return "";
  return " (" + std::to_string(notSlices.size()) +
         (notSlices.size() == 1 ? " file of the folder is" : " files of the folder are") +
         " not read as a DICOM slice: " + quote(notSlices.front()) +
         (notSlices.size() > 1 ? ", ..." : "") + ")";
}

// The DICOM files of `folder` (not its subfolders) grouped by series, largest first.
// `given`: the file name the caller named (empty for a folder). A file whose header would make
// GDCM allocate beyond it (overlongElement) is left out of the scan, as GDCM would leave it
// once it failed to read it, with a warning; the file named is refused instead. Files that end
// inside their pixel data are scanned and go into `cutInPixelData`: a slice of the series read
// is refused before GDCM decodes it (refuseTruncatedPixelData). `notSlices`: the names of the
// files looked at that hold no DICOM image slice (not DICOM, no image, left out), for the
// "missing slice?" error, where such a file may be the slice missing.
std::vector<Series> scanSeries(const std::string& where, const std::string& folder,
                               const std::string& given, gdcm::Scanner& scanner,
                               std::vector<std::string>& warnings,
                               std::set<std::string>& cutInPixelData,
                               std::vector<std::string>& notSlices) {
  const std::vector<std::string> listed = folderFiles(where, folder, given, warnings);
  for (const gdcm::Tag& tag : {kSeriesUid, kImagePosition, kImageOrientation, kRows, kColumns,
                               kModality, kSeriesDescription, kNumberOfFrames}) {
    scanner.AddTag(tag);
  }
  if (listed.empty()) {
    throwInputError(where,
                    "is a folder without files (a DICOM series is read from a folder of "
                    "slices)");
  }
  std::vector<std::string> files;  // the ones GDCM may read
  std::string leftOut;             // the first file left out, and why
  for (const std::string& file : listed) {
    const ElementProblem problem = overlongElement(file);
    if (problem.inPixelData) cutInPixelData.insert(file);
    if (problem.text.empty() || problem.inPixelData) {
      files.push_back(file);
      continue;
    }
    const std::string name = std::filesystem::path(file).filename().string();
    if (name == given) throwInputError(where, problem.text);
    warnings.push_back(where + ": left out " + quote(name) + ": " + problem.text);
    notSlices.push_back(name);
    if (leftOut.empty()) leftOut = "; left out " + quote(name) + ": " + problem.text;
  }
  if (!withinGdcm([&] { return scanner.Scan(files); })) {
    throwInputError(where, "GDCM cannot scan its files");
  }
  std::map<std::string, Series> byUid;
  for (const std::string& file : files) {
    const std::string uid =
        scanner.IsKey(file.c_str()) ? trimmed(scanner.GetValue(file.c_str(), kSeriesUid)) : "";
    if (uid.empty() || !scanner.GetValue(file.c_str(), kRows)) {  // not DICOM, or no image
      notSlices.push_back(std::filesystem::path(file).filename().string());
      continue;
    }
    byUid[uid].uid = uid;
    byUid[uid].files.push_back(file);
  }
  if (byUid.empty()) {
    throwInputError(where, "holds no DICOM image slices (" + std::to_string(listed.size()) +
                               (listed.size() == 1 ? " file" : " files") + " looked at" + leftOut +
                               ")");
  }
  std::vector<Series> series;
  for (auto& [uid, s] : byUid) series.push_back(std::move(s));
  std::stable_sort(series.begin(), series.end(), [](const Series& a, const Series& b) {
    return a.files.size() > b.files.size();
  });
  return series;
}

// "JPEG-LS Lossless Image Compression" for a transfer syntax's UID (the UID when GDCM has no name).
std::string transferSyntaxName(const gdcm::TransferSyntax& syntax) {
  const char* uidText = gdcm::TransferSyntax::GetTSString(syntax);
  gdcm::UIDs uid;
  if (uidText && uid.SetFromUID(uidText) && uid.GetName()) return uid.GetName();
  return uidText ? uidText : "unknown transfer syntax";
}

// Collects GDCM's warnings while it lives instead of letting GDCM print them. A slice whose
// file ends inside its pixel data reads "successfully", padded with zeros, and only a warning
// tells: the reader turns that warning into an error.
class GdcmWarnings {
 public:
  GdcmWarnings() {
    gdcm::Trace::SetError(false);
    gdcm::Trace::SetWarningStream(text_);
    gdcm::Trace::SetWarning(true);
  }
  ~GdcmWarnings() {
    gdcm::Trace::SetWarning(false);
    gdcm::Trace::SetWarningStream(std::cerr);
  }
  GdcmWarnings(const GdcmWarnings&) = delete;
  GdcmWarnings& operator=(const GdcmWarnings&) = delete;
  // Whether GDCM warned of incomplete pixel data since the last call.
  bool incompletePixelData() {
    const bool incomplete = text_.str().find("Incomplete Pixel Data") != std::string::npos;
    text_.str("");
    return incomplete;
  }

 private:
  std::ostringstream text_;
};

// How messages name a slice: its file name in the folder (the folder is named already).
std::string fileLabel(const std::string& file) {
  return quote(std::filesystem::path(file).filename().string());
}

// How messages name a slice: "slice 'IM0002'", or "frame 3 of 'enhanced.dcm'" (from 1).
std::string sliceLabel(const Slice& slice) {
  return slice.frame < 0
             ? "slice " + fileLabel(slice.file)
             : "frame " + std::to_string(slice.frame + 1) + " of " + fileLabel(slice.file);
}

// Before GDCM reads a slice's pixel data: refuses the slice when its file ends inside them
// (scanSeries found it), so GDCM allocates no more than the file holds.
void refuseTruncatedPixelData(const std::string& path, const Slice& slice,
                              const std::set<std::string>& cutInPixelData) {
  if (cutInPixelData.count(slice.file)) {
    throwInputError(path, (slice.frame < 0 ? "slice " : "") + fileLabel(slice.file) +
                              ": the file ends inside its pixel data (truncated)");
  }
}

// The text of a data element (empty when it is absent or holds none).
std::string textOf(const gdcm::DataSet& dataSet, const gdcm::Tag& tag) {
  if (!dataSet.FindDataElement(tag)) return {};
  const gdcm::ByteValue* value = dataSet.GetDataElement(tag).GetByteValue();
  return value ? std::string(value->GetPointer(), value->GetLength()) : std::string();
}

// The text of `tag` in the first item of `sequence` (a functional group's macro), or empty.
std::string textInSequence(const gdcm::DataSet& dataSet, const gdcm::Tag& sequence,
                           const gdcm::Tag& tag) {
  if (!dataSet.FindDataElement(sequence)) return {};
  const gdcm::SmartPointer<gdcm::SequenceOfItems> items =
      dataSet.GetDataElement(sequence).GetValueAsSQ();
  if (!items || items->GetNumberOfItems() < 1) return {};
  return textOf(items->GetItem(1).GetNestedDataSet(), tag);
}

// What a multi-frame file says of its frames beyond their positions.
struct FrameGeometry {
  std::vector<double> orientation;   // Image Orientation (Patient): 6 numbers
  std::vector<double> pixelSpacing;  // Pixel Spacing (rows, columns); empty: GDCM's
  std::vector<double> rescale;       // slope, intercept where the frames carry them; else empty
};

// A multi-frame file's frames as slices (positions from each frame's Plane Position Sequence in
// the Per-frame Functional Groups) and what they share. Every other attribute is taken from the
// frame's functional groups, else the Shared Functional Groups, else the top level, and must be
// the same for every frame: vsil applies one orientation, pixel spacing and rescale.
FrameGeometry multiFrameSlices(const std::string& path, const std::string& file, int frames,
                               std::vector<Slice>& slices) {
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  // Up to the pixel data, and without them: ReadUpToTag reads the value of the tag it stops at
  // unless that tag is skipped, and a file cut short inside them (refused later, by
  // refuseTruncatedPixelData) would have GDCM allocate their declared length here.
  const std::set<gdcm::Tag> skip{kPixelData};
  if (!withinGdcm([&] { return reader.ReadUpToTag(kPixelData, skip); })) {
    throwInputError(path, "GDCM cannot read " + fileLabel(file));
  }
  const gdcm::DataSet& top = reader.GetFile().GetDataSet();
  const auto sequenceOf = [&](const gdcm::Tag& tag) {
    return top.FindDataElement(tag) ? top.GetDataElement(tag).GetValueAsSQ()
                                    : gdcm::SmartPointer<gdcm::SequenceOfItems>();
  };
  const gdcm::SmartPointer<gdcm::SequenceOfItems> shared = sequenceOf(kSharedGroups);
  const gdcm::SmartPointer<gdcm::SequenceOfItems> perFrame = sequenceOf(kPerFrameGroups);
  if (!perFrame || perFrame->GetNumberOfItems() != std::size_t(frames)) {
    throwInputError(path, fileLabel(file) + " holds " + std::to_string(frames) +
                              " frames but no Per-frame Functional Groups Sequence (5200,9230) "
                              "with an item per frame: their positions are unknown");
  }
  const gdcm::DataSet* sharedGroups =
      shared && shared->GetNumberOfItems() >= 1 ? &shared->GetItem(1).GetNestedDataSet() : nullptr;
  // `count` numbers of `tag` in the macro `sequence`: the frame's, else the shared, else the
  // top level's `tag`; empty when none holds them.
  const auto numbers = [&](const gdcm::DataSet& groups, const gdcm::Tag& sequence,
                           const gdcm::Tag& tag, std::size_t count) {
    std::string text = textInSequence(groups, sequence, tag);
    if (text.empty() && sharedGroups) text = textInSequence(*sharedGroups, sequence, tag);
    if (text.empty()) text = textOf(top, tag);
    return parseNumbers(text.c_str(), count);
  };
  FrameGeometry geometry;
  for (int k = 0; k < frames; ++k) {
    const gdcm::DataSet& groups = perFrame->GetItem(std::size_t(k) + 1).GetNestedDataSet();
    const Slice frame{file, 0, glm::dvec3(0.0), k};
    const std::vector<double> ipp =
        parseNumbers(textInSequence(groups, kPlanePositionSequence, kImagePosition).c_str(), 3);
    if (ipp.empty()) {
      throwInputError(path, sliceLabel(frame) +
                                " lacks a valid Image Position (Patient) (0020,0032) in its "
                                "Plane Position Sequence (0020,9113)");
    }
    const std::vector<double> iop =
        numbers(groups, kPlaneOrientationSequence, kImageOrientation, 6);
    if (iop.empty()) {
      throwInputError(path,
                      sliceLabel(frame) + " lacks a valid Image Orientation (Patient) (0020,0037)");
    }
    const std::vector<double> spacing = numbers(groups, kPixelMeasuresSequence, kPixelSpacing, 2);
    const std::vector<double> slope =
        numbers(groups, kPixelValueTransformationSequence, kRescaleSlope, 1);
    const std::vector<double> intercept =
        numbers(groups, kPixelValueTransformationSequence, kRescaleIntercept, 1);
    const std::vector<double> rescale = slope.empty() || intercept.empty()
                                            ? std::vector<double>{}
                                            : std::vector<double>{slope[0], intercept[0]};
    if (k == 0) geometry = {iop, spacing, rescale};
    const auto differs = [](const std::vector<double>& a, const std::vector<double>& b) {
      if (a.size() != b.size()) return true;
      for (std::size_t i = 0; i < a.size(); ++i) {
        if (std::abs(a[i] - b[i]) > 1e-4 * std::max(1.0, std::abs(b[i]))) return true;
      }
      return false;
    };
    const char* what = differs(iop, geometry.orientation)        ? "Image Orientation (Patient)"
                       : differs(spacing, geometry.pixelSpacing) ? "Pixel Spacing"
                       : differs(rescale, geometry.rescale)      ? "Rescale Slope/Intercept"
                                                                 : nullptr;
    if (what) {
      throwInputError(path, sliceLabel(frame) + " has another " + what +
                                " than frame 1: vsil reads frames that share it");
    }
    slices.push_back({file, 0, glm::dvec3(ipp[0], ipp[1], ipp[2]), k});
  }
  return geometry;
}

}  // namespace

Volume readDicomSeriesWithGdcm(const std::string& path, const LoadOptions& options) {
  const std::filesystem::path given(path);
  const bool folderGiven = fileTypeAt(given, path) == std::filesystem::file_type::directory;
  if (!folderGiven) regularFileSize(path);
  const std::string folder =
      folderGiven ? path : (given.has_parent_path() ? given.parent_path().string() : ".");

  // GDCM's messages would go to stderr; vsil's errors say what is wrong in one line.
  GdcmWarnings gdcmWarnings;
  gdcm::Scanner scanner;
  std::vector<std::string> warnings;
  std::set<std::string> cutInPixelData;
  std::vector<std::string> notSlices;
  const std::vector<Series> all =
      scanSeries(path, folder, folderGiven ? std::string() : given.filename().string(), scanner,
                 warnings, cutInPixelData, notSlices);
  // The series: --series, else the given file's, else the largest.
  std::string wanted = options.series;
  if (wanted.empty() && !folderGiven) {
    // The scanner names files as its folder listing did ("./a.dcm" for "a.dcm"): the given
    // file is the one with its name.
    std::string given_series;
    for (const Series& s : all) {
      for (const std::string& file : s.files) {
        if (std::filesystem::path(file).filename() == given.filename()) given_series = s.uid;
      }
    }
    if (given_series.empty()) throwInputError(path, "is not a DICOM image slice GDCM can read");
    wanted = given_series;
  }
  const Series* chosen = &all.front();
  if (!wanted.empty()) {
    const auto it =
        std::find_if(all.begin(), all.end(), [&](const Series& s) { return s.uid == wanted; });
    if (it == all.end()) {
      std::string known;
      for (const Series& s : all) known += (known.empty() ? "" : ", ") + printableText(s.uid);
      throwInputError(path, "has no series " + quote(wanted) + " (series: " + known + ")");
    }
    chosen = &*it;
  }
  auto describe = [&](const Series& s) {
    const char* first = s.files.front().c_str();
    const std::string description =
        textAsUtf8(trimmed(scanner.GetValue(first, kSeriesDescription)));
    return printableText(s.uid) + " (" + std::to_string(s.files.size()) + " slices" +
           (description.empty() ? "" : ", " + quote(description)) + ")";
  };
  if (all.size() > 1 && options.series.empty()) {
    std::string others;
    for (const Series& s : all) {
      if (&s != chosen) others += (others.empty() ? "" : "; ") + describe(s);
    }
    warnings.push_back(path + ": " + std::to_string(all.size()) + " series; reading " +
                       describe(*chosen) + "; choose another with --series UID: " + others);
  }

  // Geometry from the headers: one orientation, positions along its normal, even spacing.
  const char* firstFile = chosen->files.front().c_str();
  const std::vector<double> numberOfFrames =
      parseNumbers(scanner.GetValue(firstFile, kNumberOfFrames), 1);
  if (!numberOfFrames.empty() && (numberOfFrames[0] < 1 || numberOfFrames[0] > 65535 ||
                                  numberOfFrames[0] != std::floor(numberOfFrames[0]))) {
    throwInputError(path, fileLabel(chosen->files.front()) + " has Number of Frames (0028,0008) " +
                              formatNumber(numberOfFrames[0]) + ": not a count of 1 to 65535");
  }
  const int frames = numberOfFrames.empty() ? 1 : int(numberOfFrames[0]);
  std::vector<Slice> slices;
  std::vector<double> iop;
  FrameGeometry frameGeometry;  // multi-frame files only
  if (frames > 1) {
    if (chosen->files.size() > 1) {
      throwInputError(path, "series " + chosen->uid + " has " +
                                std::to_string(chosen->files.size()) + " files, " +
                                fileLabel(chosen->files.front()) + " of " + std::to_string(frames) +
                                " frames: a series of multi-frame files is not supported");
    }
    frameGeometry = multiFrameSlices(path, chosen->files.front(), frames, slices);
    iop = frameGeometry.orientation;
  } else {
    iop = parseNumbers(scanner.GetValue(firstFile, kImageOrientation), 6);
  }
  if (iop.empty()) {
    throwInputError(path, "slice " + fileLabel(chosen->files.front()) +
                              " lacks a valid Image Orientation (Patient) (0020,0037)");
  }
  const glm::dvec3 rowDir(iop[0], iop[1], iop[2]), columnDir(iop[3], iop[4], iop[5]);
  if (glm::length(glm::cross(rowDir, columnDir)) < 1e-3) {
    throwInputError(path, "slice " + fileLabel(chosen->files.front()) +
                              ": Image Orientation (Patient) has no slice normal (its row and "
                              "column directions are zero or parallel)");
  }
  const glm::dvec3 normal = glm::normalize(glm::cross(rowDir, columnDir));
  const std::string rows = trimmed(scanner.GetValue(firstFile, kRows));
  const std::string columns = trimmed(scanner.GetValue(firstFile, kColumns));
  for (Slice& frame : slices) frame.position = glm::dot(frame.origin, normal);
  for (const std::string& file : frames > 1 ? std::vector<std::string>() : chosen->files) {
    const char* name = file.c_str();
    const std::vector<double> ipp = parseNumbers(scanner.GetValue(name, kImagePosition), 3);
    if (ipp.empty()) {
      throwInputError(
          path, "slice " + fileLabel(file) + " lacks a valid Image Position (Patient) (0020,0032)");
    }
    std::vector<double> own = parseNumbers(scanner.GetValue(name, kImageOrientation), 6);
    for (std::size_t i = 0; i < 6 && !own.empty(); ++i) {
      if (std::abs(own[i] - iop[i]) > 1e-4) own.clear();
    }
    if (own.empty()) {
      throwInputError(path, "slice " + fileLabel(file) +
                                " has another Image Orientation (Patient) than the series' first");
    }
    if (trimmed(scanner.GetValue(name, kRows)) != rows ||
        trimmed(scanner.GetValue(name, kColumns)) != columns) {
      throwInputError(path, "slice " + fileLabel(file) + " is " +
                                trimmed(scanner.GetValue(name, kColumns)) + " x " +
                                trimmed(scanner.GetValue(name, kRows)) + " pixels, slice " +
                                fileLabel(chosen->files.front()) + " " + columns + " x " + rows +
                                ": the slices of a series must have one size");
    }
    const glm::dvec3 origin(ipp[0], ipp[1], ipp[2]);
    slices.push_back({file, glm::dot(origin, normal), origin});
  }
  std::sort(slices.begin(), slices.end(),
            [](const Slice& a, const Slice& b) { return a.position < b.position; });
  double spacingZ = 1.0;
  if (slices.size() > 1) {
    // The median gap is the series' spacing even with slices missing; every gap must match it.
    std::vector<double> gaps;
    for (std::size_t i = 1; i < slices.size(); ++i) {
      gaps.push_back(slices[i].position - slices[i - 1].position);
    }
    std::nth_element(gaps.begin(), gaps.begin() + std::ptrdiff_t(gaps.size() / 2), gaps.end());
    spacingZ = gaps[gaps.size() / 2];
    for (std::size_t i = 1; i < slices.size(); ++i) {
      const double gap = slices[i].position - slices[i - 1].position;
      const Slice &before = slices[i - 1], &after = slices[i];
      if (gap <= spacingZ * kSpacingTolerance) {
        throwInputError(
            path,
            (frames > 1 ? "frames " + std::to_string(before.frame + 1) + " and " +
                              std::to_string(after.frame + 1) + " of " + fileLabel(before.file)
                        : "slices " + fileLabel(before.file) + " and " + fileLabel(after.file)) +
                " lie at the same position " + formatNumber(after.position) + " along the normal");
      }
      if (std::abs(gap - spacingZ) > spacingZ * kSpacingTolerance) {
        throwInputError(
            path, (frames > 1 ? "frames" : "slices") + std::string(" are unevenly spaced: ") +
                      formatNumber(gap) + " between positions " + formatNumber(before.position) +
                      " and " + formatNumber(after.position) + " (" +
                      (frames > 1 ? sliceLabel(before) + ", " + sliceLabel(after)
                                  : fileLabel(before.file) + ", " + fileLabel(after.file)) +
                      "), " + formatNumber(spacingZ) + " between most: a missing " +
                      (frames > 1 ? "frame?" : "slice?") + notSliceNote(notSlices));
      }
    }
    // Exact for evenly spaced slices, averaging the positions' rounding.
    spacingZ = (slices.back().position - slices.front().position) / double(slices.size() - 1);
  }

  // The first slice's full header: pixel format, spacing, rescale, transfer syntax.
  gdcm::ImageReader first;
  refuseTruncatedPixelData(path, slices.front(), cutInPixelData);
  first.SetFileName(slices.front().file.c_str());
  if (!withinGdcm([&] { return first.Read(); })) {
    throwInputError(path, "GDCM cannot read slice " + fileLabel(slices.front().file));
  }
  const gdcm::Image& firstImage = first.GetImage();
  const std::string firstWhere = path + ": slice " + fileLabel(slices.front().file);
  const int framesDecoded =
      firstImage.GetNumberOfDimensions() == 3 ? int(firstImage.GetDimension(2)) : 1;
  if (framesDecoded != frames) {
    throwInputError(path, fileLabel(slices.front().file) + " holds " +
                              std::to_string(framesDecoded) + " frames where its Number of " +
                              "Frames (0028,0008) says " + std::to_string(frames));
  }
  // GDCM reads a Pixel Spacing it cannot parse (nan, abc) or one of 0 as 1, and a Rescale
  // Slope of nan or inf as none: the values as written are checked here instead.
  const gdcm::DataSet& firstSet = first.GetFile().GetDataSet();
  // An element's value as written, up to a NUL and trimmed ("" where the slice has none).
  const auto writtenText = [](const gdcm::DataSet& set, const gdcm::Tag& tag) {
    std::string text = textOf(set, tag);
    text.erase(std::find(text.begin(), text.end(), '\0'), text.end());
    return std::string(trim(text));
  };
  const auto checkWritten = [&](const gdcm::Tag& tag, const std::string& name, std::size_t count,
                                const std::string& needed, auto valid) {
    const std::string text = writtenText(firstSet, tag);
    if (text.empty()) return;
    const std::vector<double> values = parseNumbers(text.c_str(), count);
    if (values.empty() || !std::all_of(values.begin(), values.end(), valid)) {
      throwInputError(path, "slice " + fileLabel(slices.front().file) + " has " + name + " " +
                                quote(text.substr(0, 40)) + ": " + needed);
    }
  };
  checkWritten(kPixelSpacing, "Pixel Spacing (0028,0030)", 2, "not two positive distances",
               [](double v) { return v > 0; });
  const std::string firstPixelSpacing = writtenText(firstSet, kPixelSpacing);
  checkWritten(kRescaleSlope, "Rescale Slope (0028,1053)", 1, "not a finite number other than 0",
               [](double v) { return v != 0; });
  checkWritten(kRescaleIntercept, "Rescale Intercept (0028,1052)", 1, "not a finite number",
               [](double) { return true; });
  const StoredType type = storedTypeOfPixels(firstWhere, firstImage.GetPixelFormat());
  const glm::ivec3 dims =
      parseDims(path, "Columns, Rows, slices",
                std::to_string(firstImage.GetColumns()) + " " +
                    std::to_string(firstImage.GetRows()) + " " + std::to_string(slices.size()));
  // A multi-frame file's own functional groups where they say (GDCM reads only some of them).
  Rescale rescale{firstImage.GetSlope(), firstImage.GetIntercept()};
  if (!frameGeometry.rescale.empty()) {
    rescale = {frameGeometry.rescale[0], frameGeometry.rescale[1]};
  }
  if (!std::isfinite(rescale.slope) || !std::isfinite(rescale.intercept) || rescale.slope == 0) {
    throwInputError(path, "slice " + fileLabel(slices.front().file) + " has Rescale Slope " +
                              formatNumber(rescale.slope) + " and Intercept " +
                              formatNumber(rescale.intercept));
  }
  planVolume(path, dims, keptSampleType(type, rescale), options.limits, options.region);
  const glm::dvec3 spacing =
      frameGeometry.pixelSpacing.empty()
          ? glm::dvec3(firstImage.GetSpacing(0), firstImage.GetSpacing(1), spacingZ)
          : glm::dvec3(frameGeometry.pixelSpacing[1], frameGeometry.pixelSpacing[0], spacingZ);
  if (!std::isfinite(spacing.x) || !std::isfinite(spacing.y) || spacing.x <= 0 || spacing.y <= 0) {
    throwInputError(path, "slice " + fileLabel(slices.front().file) + " has Pixel Spacing " +
                              formatNumber(spacing.y) + "\\" + formatNumber(spacing.x) +
                              ": not positive");
  }

  // Slices shifted in-plane from one to the next (a gantry tilt, or a series put together
  // wrongly) are read as a straight stack: the picture is not sheared as the patient is. Said
  // where the shift passes half a pixel; a tilt's regular step is kept in the patient placement.
  glm::dvec3 sliceStep = normal * spacingZ;
  if (slices.size() > 1) {
    const glm::dvec3 step =
        (slices.back().origin - slices.front().origin) / double(slices.size() - 1);
    const auto inPlane = [&](glm::dvec3 v) {
      return glm::length(v - normal * glm::dot(v, normal));
    };
    // irregular: the farthest slice from the line of equal steps; unequalStep: the largest
    // in-plane difference of one slice-to-slice step from the mean step (a single jump, a
    // patient's or table's movement, keeps every slice near the line, not its steps equal).
    double largest = 0, irregular = 0, unequalStep = 0;
    for (std::size_t i = 1; i < slices.size(); ++i) {
      const glm::dvec3 offset = slices[i].origin - slices.front().origin;
      largest = std::max(largest, inPlane(offset));
      irregular = std::max(irregular, glm::length(offset - step * double(i)));
      unequalStep = std::max(unequalStep, inPlane(slices[i].origin - slices[i - 1].origin - step));
    }
    const double halfPixel = 0.5 * std::min(spacing.x, spacing.y);
    const double shift = inPlane(step);
    // Steps equal to a quarter of the shift or a quarter of a pixel: positions written to 0.1 mm
    // (or 0.01) make a small tilt's steps differ by that much (round 15), a jump by more.
    const bool equalSteps = unequalStep <= std::max(0.25 * shift, 0.5 * halfPixel);
    const auto rounded = [](double v) { return formatNumber(std::round(v * 100) / 100); };
    if (largest > halfPixel && irregular <= halfPixel && equalSteps) {
      sliceStep = step;
      warnings.push_back(path + ": slices shift in-plane by " + rounded(shift) +
                         " per slice (a gantry tilt of " +
                         rounded(std::atan2(shift, spacingZ) * 180 / std::numbers::pi) +
                         " degrees): read as a straight stack, not sheared as the patient is");
    } else if (largest > halfPixel) {
      warnings.push_back(path + ": slices lie shifted in-plane, up to " + rounded(largest) +
                         " from the first and not in steps: read as a straight stack");
    }
  }

  Volume volume = startVolume(path, dims, type, spacing, options, rescale);
  // File text shown as it is read: no control bytes, valid UTF-8 (round 15: an escape sequence
  // and a newline in a Modality reached the terminal through info's format line).
  const std::string modality = printableText(trimmed(scanner.GetValue(firstFile, kModality)));
  volume.format = std::string(frames > 1 ? "DICOM multi-frame (" : "DICOM series (") +
                  (modality.empty() ? std::string() : modality + ", ") +
                  std::to_string(slices.size()) + (frames > 1 ? " frames, " : " slices, ") +
                  transferSyntaxName(firstImage.GetTransferSyntax()) + ")";
  // The folder's own name, also for "series/", "." or a bare file name.
  std::filesystem::path named = std::filesystem::absolute(folder).lexically_normal();
  if (!named.has_filename()) named = named.parent_path();
  volume.name = named.filename().string();
  if (volume.name.empty()) volume.name = "dicom";  // the root folder
  volume.warnings = warnings;
  const VolumeSubset subset = subsetOf(volume);
  const glm::dmat4 worldFromFile(glm::dvec4(rowDir * spacing.x, 0),
                                 glm::dvec4(columnDir * spacing.y, 0), glm::dvec4(sliceStep, 0),
                                 glm::dvec4(slices.front().origin, 1));
  volume.orientations.push_back({"patient", "LPS", worldFromFile * fileFromKept(subset),
                                 // DICOM's patient frame: +x Left, +y Posterior, +z Superior.
                                 anatomicalAxes(glm::dmat3(rowDir, columnDir, normal), "LPS")});

  // Decode the kept slices in order; each must match the first's size, format and rescale.
  SampleSink sink(path, volume, subset, type, /*bigEndian=*/false, rescale);
  const std::uint64_t sliceSamples = std::uint64_t(dims.x) * std::uint64_t(dims.y);
  const std::uint64_t sliceBytes = sliceSamples * storedSize(type);
  std::vector<char> buffer;
  // `image`'s pixels into `buffer`, which must come to `bytes` (`where` names it in errors).
  const auto decode = [&](const gdcm::Image& image, const std::string& where, std::uint64_t bytes) {
    if (image.GetBufferLength() != bytes) {
      throwInputError(path, where + " decodes to " + std::to_string(image.GetBufferLength()) +
                                " bytes, " + std::to_string(bytes) + " expected");
    }
    if (gdcmWarnings.incompletePixelData()) {
      throwInputError(path, where + ": the file ends inside its pixel data (truncated)");
    }
    // Native (not encapsulated) pixels are the element's bytes: GDCM copies what there is and
    // leaves the rest of a short element as zeros.
    if (const gdcm::ByteValue* stored = image.GetDataElement().GetByteValue();
        stored && !image.GetTransferSyntax().IsEncapsulated() && stored->GetLength() < bytes) {
      throwInputError(path, where + ": its Pixel Data (7fe0,0010) holds " +
                                std::to_string(stored->GetLength()) + " bytes, " +
                                std::to_string(bytes) + " expected");
    }
    buffer.resize(std::size_t(bytes));
    if (!withinGdcm([&] { return image.GetBuffer(buffer.data()); })) {
      throwInputError(path, "GDCM cannot decode the pixel data of " + where + " (" +
                                transferSyntaxName(image.GetTransferSyntax()) + ")");
    }
  };
  std::uint64_t done = 0;
  if (frames > 1) {
    // One file, decoded whole (GDCM decodes a multi-frame image at once); its frames are put
    // in position order.
    decode(firstImage, fileLabel(slices.front().file), sliceBytes * std::uint64_t(frames));
    for (int z = subset.lo.z; z < subset.hi.z; z += subset.stride) {
      const auto* frame = reinterpret_cast<const std::uint8_t*>(buffer.data()) +
                          std::size_t(slices[std::size_t(z)].frame) * std::size_t(sliceBytes);
      sink.put(std::uint64_t(z) * sliceSamples, std::span(frame, std::size_t(sliceBytes)));
      done += sliceBytes;
      if (options.progress) options.progress(done, sliceBytes * std::uint64_t(volume.dims.z));
    }
    sink.finish();
    return volume;
  }
  for (int z = subset.lo.z; z < subset.hi.z; z += subset.stride) {
    const Slice& slice = slices[std::size_t(z)];
    const std::string where = "slice " + fileLabel(slice.file);
    gdcm::ImageReader reader;
    refuseTruncatedPixelData(path, slice, cutInPixelData);
    reader.SetFileName(slice.file.c_str());
    gdcmWarnings.incompletePixelData();  // forget what came before this slice
    if (!withinGdcm([&] { return reader.Read(); })) {
      throwInputError(path, "GDCM cannot read " + where);
    }
    const gdcm::Image& image = reader.GetImage();
    if (int(image.GetColumns()) != dims.x || int(image.GetRows()) != dims.y ||
        storedTypeOfPixels(path + ": " + where, image.GetPixelFormat()) != type ||
        image.GetSlope() != rescale.slope || image.GetIntercept() != rescale.intercept) {
      throwInputError(path, where +
                                " differs from the first slice in size, pixel format or "
                                "Rescale Slope/Intercept");
    }
    // GDCM reads a Pixel Spacing it cannot parse, or of 0, as 1: each slice's as written must
    // be the first slice's (checked above), or the volume's x and y spacing would be a guess.
    if (const std::string text = writtenText(reader.GetFile().GetDataSet(), kPixelSpacing);
        text != firstPixelSpacing) {
      const std::vector<double> values = parseNumbers(text.c_str(), 2);
      const std::vector<double> expected = parseNumbers(firstPixelSpacing.c_str(), 2);
      const auto close = [](double a, double b) {
        return std::abs(a - b) <= 1e-6 * std::max(std::abs(a), std::abs(b));
      };
      if (values.size() != 2 || expected.size() != 2 || !close(values[0], expected[0]) ||
          !close(values[1], expected[1])) {
        throwInputError(path, where + " has Pixel Spacing (0028,0030) " +
                                  quote(text.substr(0, 40)) + " where the first slice has " +
                                  quote(firstPixelSpacing.substr(0, 40)) +
                                  ": the slices of one volume share their spacing");
      }
    }
    decode(image, where, sliceBytes);
    sink.put(std::uint64_t(z) * sliceSamples,
             std::span(reinterpret_cast<const std::uint8_t*>(buffer.data()), buffer.size()));
    done += sliceBytes;
    if (options.progress) options.progress(done, sliceBytes * std::uint64_t(volume.dims.z));
  }
  sink.finish();
  return volume;
}

}  // namespace vsil::io
