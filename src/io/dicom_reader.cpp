// DICOM series through GDCM (the library VTK and ITK use): a folder of slices, or one slice file
// standing for its series in its folder. GDCM's Scanner reads the headers; the slices are
// sorted by Image Position (Patient) along the slice normal — never by file name or Instance
// Number — and must be evenly spaced (a missing slice is an error, not a stretched volume).
// The series' dims and type are checked against the limits before any pixel data is decoded;
// then GDCM decodes each kept slice (raw, RLE, JPEG, JPEG-LS, JPEG 2000: whatever it has
// codecs for) and the samples go through the sink with Rescale Slope/Intercept applied (CT in
// Hounsfield units). Several series in a folder: the one with the most slices, unless
// LoadOptions::series names another; the others are listed in a warning.
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

#include <gdcmDirectory.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmScanner.h>
#include <gdcmTrace.h>
#include <gdcmTransferSyntax.h>
#include <gdcmUIDs.h>

#include "core/error.h"
#include "core/options.h"
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

// Slices whose spacing differs from the series' by more than this share are a gap.
constexpr double kSpacingTolerance = 0.01;

std::string trimmed(const char* value) {
  return value ? std::string(trim(std::string_view(value))) : std::string();
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
// tests/bad_inputs/dicom_gdcm_assert/slice.dcm). Each call into GDCM that reads files runs
// inside one of these (withinGdcm): stderr goes to /dev/null (assert's own line included; GDCM's
// warnings go to GdcmWarnings anyway), and SIGABRT prints vsil's one-line error naming what is read
// on the real stderr and exits 2 instead of dumping core. Nothing has been written then: a volume
// is read before any output.
class GdcmCall {
 public:
  explicit GdcmCall(const std::string& where)
      : message_("vsil: " + where +
                 ": GDCM failed one of its internal checks reading it (a malformed DICOM "
                 "file)\n"),
        stderr_(::dup(STDERR_FILENO)) {
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0 && stderr_ >= 0) ::dup2(null, STDERR_FILENO);
    if (null >= 0) ::close(null);
    active_ = this;
    struct sigaction action = {};
    action.sa_handler = &GdcmCall::onAbort;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGABRT, &action, &previous_);
  }
  ~GdcmCall() {
    ::sigaction(SIGABRT, &previous_, nullptr);
    active_ = nullptr;
    if (stderr_ >= 0) {
      ::dup2(stderr_, STDERR_FILENO);
      ::close(stderr_);
    }
  }
  GdcmCall(const GdcmCall&) = delete;
  GdcmCall& operator=(const GdcmCall&) = delete;

 private:
  static void onAbort(int) {  // async-signal-safe: write and _exit only
    if (active_) {
      const int fd = active_->stderr_ >= 0 ? active_->stderr_ : STDERR_FILENO;
      [[maybe_unused]] const auto written =
          ::write(fd, active_->message_.data(), active_->message_.size());
    }
    ::_exit(2);
  }
  static inline GdcmCall* active_ = nullptr;
  const std::string message_;
  const int stderr_;  // the real stderr while GDCM runs
  struct sigaction previous_ = {};
};

// What `call` (a call into GDCM that reads files) returns, run inside a GdcmCall.
template <typename Call>
auto withinGdcm(const std::string& where, Call&& call) {
  const GdcmCall guard(where);
  return call();
}

struct Slice {
  std::string file;
  double position = 0;  // along the normal
  glm::dvec3 origin{0.0};
};

struct Series {
  std::string uid;
  std::vector<std::string> files;
};

// The DICOM files of `folder` (not its subfolders) grouped by series, largest first.
std::vector<Series> scanSeries(const std::string& where, const std::string& folder,
                               gdcm::Scanner& scanner) {
  gdcm::Directory directory;
  directory.Load(folder, false);
  const auto& files = directory.GetFilenames();
  for (const gdcm::Tag& tag : {kSeriesUid, kImagePosition, kImageOrientation, kRows, kColumns,
                               kModality, kSeriesDescription}) {
    scanner.AddTag(tag);
  }
  if (files.empty()) {
    throwInputError(where,
                    "is a folder without files (a DICOM series is read from a folder of "
                    "slices)");
  }
  if (!withinGdcm(where, [&] { return scanner.Scan(files); })) {
    throwInputError(where, "GDCM cannot scan its files");
  }
  std::map<std::string, Series> byUid;
  for (const std::string& file : files) {
    if (!scanner.IsKey(file.c_str())) continue;  // not DICOM
    const std::string uid = trimmed(scanner.GetValue(file.c_str(), kSeriesUid));
    if (uid.empty() || !scanner.GetValue(file.c_str(), kRows)) continue;  // no image
    byUid[uid].uid = uid;
    byUid[uid].files.push_back(file);
  }
  if (byUid.empty()) {
    throwInputError(where, "holds no DICOM image slices (" + std::to_string(files.size()) +
                               (files.size() == 1 ? " file" : " files") + " looked at)");
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

char axisLetter(const glm::dvec3& direction) {
  // DICOM's patient frame (LPS): +x toward the patient's Left, +y Posterior, +z Superior.
  const glm::dvec3 a = glm::abs(direction);
  if (a.x >= a.y && a.x >= a.z) return direction.x > 0 ? 'L' : 'R';
  if (a.y >= a.z) return direction.y > 0 ? 'P' : 'A';
  return direction.z > 0 ? 'S' : 'I';
}

}  // namespace

Volume readDicomSeries(const std::string& path, const LoadOptions& options) {
  const std::filesystem::path given(path);
  const bool folderGiven = std::filesystem::is_directory(given);
  if (!folderGiven) regularFileSize(path);
  const std::string folder =
      folderGiven ? path : (given.has_parent_path() ? given.parent_path().string() : ".");

  // GDCM's messages would go to stderr; vsil's errors say what is wrong in one line.
  GdcmWarnings gdcmWarnings;
  gdcm::Scanner scanner;
  const std::vector<Series> all = scanSeries(path, folder, scanner);
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
      for (const Series& s : all) known += (known.empty() ? "" : ", ") + s.uid;
      throwInputError(path, "has no series " + quote(wanted) + " (series: " + known + ")");
    }
    chosen = &*it;
  }
  auto describe = [&](const Series& s) {
    const char* first = s.files.front().c_str();
    const std::string description = trimmed(scanner.GetValue(first, kSeriesDescription));
    return s.uid + " (" + std::to_string(s.files.size()) + " slices" +
           (description.empty() ? "" : ", " + quote(description)) + ")";
  };
  std::vector<std::string> warnings;
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
  const std::vector<double> iop = parseNumbers(scanner.GetValue(firstFile, kImageOrientation), 6);
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
  std::vector<Slice> slices;
  for (const std::string& file : chosen->files) {
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
      if (gap <= spacingZ * kSpacingTolerance) {
        throwInputError(path, "slices " + fileLabel(slices[i - 1].file) + " and " +
                                  fileLabel(slices[i].file) + " lie at the same position " +
                                  formatNumber(slices[i].position) + " along the normal");
      }
      if (std::abs(gap - spacingZ) > spacingZ * kSpacingTolerance) {
        throwInputError(path, "slices are unevenly spaced: " + formatNumber(gap) +
                                  " between positions " + formatNumber(slices[i - 1].position) +
                                  " and " + formatNumber(slices[i].position) + " (" +
                                  fileLabel(slices[i - 1].file) + ", " + fileLabel(slices[i].file) +
                                  "), " + formatNumber(spacingZ) +
                                  " between most: a missing slice?");
      }
    }
    // Exact for evenly spaced slices, averaging the positions' rounding.
    spacingZ = (slices.back().position - slices.front().position) / double(slices.size() - 1);
  }

  // The first slice's full header: pixel format, spacing, rescale, transfer syntax.
  gdcm::ImageReader first;
  first.SetFileName(slices.front().file.c_str());
  if (!withinGdcm(path, [&] { return first.Read(); })) {
    throwInputError(path, "GDCM cannot read slice " + fileLabel(slices.front().file));
  }
  const gdcm::Image& firstImage = first.GetImage();
  const std::string firstWhere = path + ": slice " + fileLabel(slices.front().file);
  if (firstImage.GetNumberOfDimensions() == 3 && firstImage.GetDimension(2) > 1) {
    throwInputError(path, "slice " + fileLabel(slices.front().file) + " holds " +
                              std::to_string(firstImage.GetDimension(2)) +
                              " frames: multi-frame DICOM is not supported");
  }
  const StoredType type = storedTypeOfPixels(firstWhere, firstImage.GetPixelFormat());
  const glm::ivec3 dims =
      parseDims(path, "Columns, Rows, slices",
                std::to_string(firstImage.GetColumns()) + " " +
                    std::to_string(firstImage.GetRows()) + " " + std::to_string(slices.size()));
  Rescale rescale{firstImage.GetSlope(), firstImage.GetIntercept()};
  if (!std::isfinite(rescale.slope) || !std::isfinite(rescale.intercept) || rescale.slope == 0) {
    throwInputError(path, "slice " + fileLabel(slices.front().file) + " has Rescale Slope " +
                              formatNumber(rescale.slope) + " and Intercept " +
                              formatNumber(rescale.intercept));
  }
  planVolume(path, dims, keptSampleType(type, rescale), options.limits, options.region);
  const glm::dvec3 spacing(firstImage.GetSpacing(0), firstImage.GetSpacing(1), spacingZ);
  if (!std::isfinite(spacing.x) || !std::isfinite(spacing.y) || spacing.x <= 0 || spacing.y <= 0) {
    throwInputError(path, "slice " + fileLabel(slices.front().file) + " has Pixel Spacing " +
                              formatNumber(spacing.y) + "\\" + formatNumber(spacing.x) +
                              ": not positive");
  }

  Volume volume = startVolume(path, dims, type, spacing, options, rescale);
  const std::string modality = trimmed(scanner.GetValue(firstFile, kModality));
  volume.format = "DICOM series (" + (modality.empty() ? std::string() : modality + ", ") +
                  std::to_string(slices.size()) + " slices, " +
                  transferSyntaxName(firstImage.GetTransferSyntax()) + ")";
  volume.name = folderGiven ? given.filename().string() : given.parent_path().filename().string();
  if (volume.name.empty()) volume.name = "dicom";
  volume.warnings = warnings;
  const VolumeSubset subset = subsetOf(volume);
  const glm::dmat4 worldFromFile(
      glm::dvec4(rowDir * spacing.x, 0), glm::dvec4(columnDir * spacing.y, 0),
      glm::dvec4(normal * spacingZ, 0), glm::dvec4(slices.front().origin, 1));
  volume.orientations.push_back({"patient",
                                 "LPS",
                                 worldFromFile * fileFromKept(subset),
                                 {axisLetter(rowDir), axisLetter(columnDir), axisLetter(normal)}});

  // Decode the kept slices in order; each must match the first's size, format and rescale.
  SampleSink sink(path, volume, subset, type, /*bigEndian=*/false, rescale);
  const std::uint64_t sliceSamples = std::uint64_t(dims.x) * std::uint64_t(dims.y);
  const std::uint64_t sliceBytes = sliceSamples * storedSize(type);
  std::vector<char> buffer;
  std::uint64_t done = 0;
  for (int z = subset.lo.z; z < subset.hi.z; z += subset.stride) {
    const Slice& slice = slices[std::size_t(z)];
    const std::string where = "slice " + fileLabel(slice.file);
    gdcm::ImageReader reader;
    reader.SetFileName(slice.file.c_str());
    gdcmWarnings.incompletePixelData();  // forget what came before this slice
    if (!withinGdcm(path, [&] { return reader.Read(); })) {
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
    if (image.GetBufferLength() != sliceBytes) {
      throwInputError(path, where + " decodes to " + std::to_string(image.GetBufferLength()) +
                                " bytes, " + std::to_string(sliceBytes) + " expected");
    }
    if (gdcmWarnings.incompletePixelData()) {
      throwInputError(path, where + ": the file ends inside its pixel data (truncated)");
    }
    buffer.resize(std::size_t(sliceBytes));
    if (!withinGdcm(path, [&] { return image.GetBuffer(buffer.data()); })) {
      throwInputError(path, "GDCM cannot decode the pixel data of " + where + " (" +
                                transferSyntaxName(image.GetTransferSyntax()) + ")");
    }
    sink.put(std::uint64_t(z) * sliceSamples,
             std::span(reinterpret_cast<const std::uint8_t*>(buffer.data()), buffer.size()));
    done += sliceBytes;
    if (options.progress) options.progress(done, sliceBytes * std::uint64_t(volume.dims.z));
  }
  sink.finish();
  return volume;
}

}  // namespace vsil::io
