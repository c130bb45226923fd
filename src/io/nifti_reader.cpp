// NIfTI-1 and NIfTI-2 (and their ANALYZE 7.5 ancestor): `.nii`, `.hdr` + `.img`, each gzipped
// or not, through Debian's nifticlib (libnifti2: nifti2_io reads both versions, znzlib the
// gzip layer). nifticlib parses the header and finds the data; vsil checks the dims and type
// against its limits before any sample is read, then streams the samples through zlib (or,
// uncompressed, reads only the rows --crop/--stride keep) into the volume: no second copy.
// scl_slope/scl_inter are applied as the standard says (slope 0: none; not finite: refused); the
// qform and sform are recorded as the volume's orientations, not applied.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/options.h"
#include "io/file_access.h"
#include "io/inflate.h"
#include "io/readers.h"
#include "io/text_fields.h"

#include <zlib.h>

extern "C" {
#include <nifti2_io.h>
}

namespace vsil::io {
namespace {

// Extensions (the bytes between the header and vox_offset) beyond this are not an image
// header's: refused before nifticlib allocates them.
constexpr std::uint64_t kMaxExtensionBytes = std::uint64_t(64) << 20;
// nifti_image::byteorder of big-endian data (nifti2_io.c's MSB_FIRST, not in its public API).
constexpr int kMsbFirst = 2;

struct NiftiImageFree {
  void operator()(nifti_image* image) const { nifti_image_free(image); }
};
struct GzipClose {
  void operator()(gzFile file) const { gzclose(file); }
};

StoredType storedTypeOfNifti(const std::string& path, int datatype) {
  switch (datatype) {
    case NIFTI_TYPE_UINT8:
      return StoredType::UInt8;
    case NIFTI_TYPE_INT8:
      return StoredType::Int8;
    case NIFTI_TYPE_UINT16:
      return StoredType::UInt16;
    case NIFTI_TYPE_INT16:
      return StoredType::Int16;
    case NIFTI_TYPE_UINT32:
      return StoredType::UInt32;
    case NIFTI_TYPE_INT32:
      return StoredType::Int32;
    case NIFTI_TYPE_UINT64:
      return StoredType::UInt64;
    case NIFTI_TYPE_INT64:
      return StoredType::Int64;
    case NIFTI_TYPE_FLOAT32:
      return StoredType::Float32;
    case NIFTI_TYPE_FLOAT64:
      return StoredType::Float64;
    default:
      throwInputError(path, "datatype " + std::to_string(datatype) + " (" +
                                nifti_datatype_string(datatype) +
                                ") is not supported: vsil reads scalar integer and float "
                                "samples (UINT8 .. UINT64, INT8 .. INT64, FLOAT32, FLOAT64)");
  }
}

// The header fields vsil checks itself before nifticlib acts on them, from either version.
struct RawHeader {
  int version = 0;  // 1 or 2
  std::int64_t dim[8] = {};
  int datatype = 0;
  double voxOffset = 0;  // NIfTI-1 stores a float (any value, 1e25 too), NIfTI-2 an int64
  double pixdim[4] = {};
  double sclSlope = 0, sclInter = 0;  // as written (nifticlib reads a non-finite one as 0)
  std::string magic;                  // "n+1", "ni1", "n+2", "ni2"; anything else: ANALYZE 7.5
};

// Whether the gzip file at `path` fails to inflate (a broken stream, a CRC that does not match)
// within its first 64 MiB: what to blame when nifticlib reads no header from a .nii.gz.
bool gzipStreamFails(const std::string& path) {
  const gzFile file = gzopen(path.c_str(), "rb");
  if (!file) return false;
  std::vector<char> piece(std::size_t(1) << 16);
  int got = 0;
  for (int pieces = 0; pieces < 1024; ++pieces) {
    got = gzread(file, piece.data(), unsigned(piece.size()));
    if (got <= 0) break;
  }
  gzclose(file);
  return got < 0;
}

RawHeader readRawHeader(const std::string& path) {
  int version = 0;
  // check = 0: vsil says what is wrong with the fields below; nifticlib's own check follows.
  void* raw = nifti_read_header(path.c_str(), &version, 0);
  if (!raw) {
    if (nifti_is_gzfile(path.c_str()) && gzipStreamFails(path)) {
      throwInputError(path, "is not a whole gzip stream (cut short, or its CRC check fails)");
    }
    throwInputError(path,
                    "is not a NIfTI-1 or NIfTI-2 file (no 348- or 540-byte header "
                    "nifticlib can read)");
  }
  const std::unique_ptr<void, decltype(&std::free)> owner(raw, &std::free);
  RawHeader header;
  header.version = version;
  // Without the check nifticlib hands back any 348 or 540 bytes, in the file's byte order;
  // sizeof_hdr says whether they are a header, and its byte order whether to swap.
  const int expectedSize = version == 2 ? 540 : 348;
  int sizeofHdr = version == 2 ? static_cast<const nifti_2_header*>(raw)->sizeof_hdr
                               : static_cast<const nifti_1_header*>(raw)->sizeof_hdr;
  if (int(__builtin_bswap32(std::uint32_t(sizeofHdr))) == expectedSize) {
    if (version == 2) {
      nifti_swap_as_nifti2(static_cast<nifti_2_header*>(raw));
    } else {
      nifti_swap_as_nifti1(static_cast<nifti_1_header*>(raw));
    }
    sizeofHdr = expectedSize;
  }
  if (sizeofHdr != expectedSize) {
    throwInputError(path, "is not a NIfTI-1 or NIfTI-2 file (sizeof_hdr is " +
                              std::to_string(sizeofHdr) + ", neither 348 nor 540)");
  }
  if (version == 2) {
    const auto* h = static_cast<const nifti_2_header*>(raw);
    for (int i = 0; i < 8; ++i) header.dim[i] = h->dim[i];
    header.datatype = h->datatype;
    header.voxOffset = double(h->vox_offset);
    for (int i = 0; i < 4; ++i) header.pixdim[i] = h->pixdim[i];
    header.sclSlope = h->scl_slope;
    header.sclInter = h->scl_inter;
    header.magic.assign(h->magic, strnlen(h->magic, 4));
    if (!nifti_hdr2_looks_good(h)) header.version = -2;
  } else {
    const auto* h = static_cast<const nifti_1_header*>(raw);
    for (int i = 0; i < 8; ++i) header.dim[i] = h->dim[i];
    header.datatype = h->datatype;
    header.voxOffset = h->vox_offset;
    for (int i = 0; i < 4; ++i) header.pixdim[i] = h->pixdim[i];
    header.sclSlope = h->scl_slope;
    header.sclInter = h->scl_inter;
    header.magic.assign(h->magic, strnlen(h->magic, 4));
    if (!nifti_hdr1_looks_good(h)) header.version = -1;
  }
  return header;
}

void checkRawHeader(const std::string& path, const RawHeader& header) {
  const std::int64_t* dim = header.dim;
  if (dim[0] < 1 || dim[0] > 7) {
    throwInputError(path, "dim[0] " + std::to_string(dim[0]) + " is not a dimension count (1..7)");
  }
  for (int i = 1; i <= dim[0]; ++i) {
    if (dim[i] < 1) {
      throwInputError(path, "dim[" + std::to_string(i) + "] " + std::to_string(dim[i]) +
                                " is not a positive size");
    }
  }
  for (int i = 4; i <= dim[0]; ++i) {
    if (dim[i] > 1) {
      throwInputError(path, "holds " + std::to_string(dim[i]) + " volumes along dim[" +
                                std::to_string(i) +
                                "] (a 4D or 5D image): vsil reads one 3D volume; extract one, "
                                "e.g. with fslroi or nibabel");
    }
  }
  if (!(header.voxOffset >= 0) || std::isinf(header.voxOffset)) {
    throwInputError(path, "vox_offset is negative or not finite");
  }
  if (header.voxOffset > double(kMaxExtensionBytes)) {
    std::ostringstream offset;  // the file's number: 999999995904, 1.79827990282068e+25
    offset << std::setprecision(15) << header.voxOffset;
    throwInputError(path, "vox_offset " + offset.str() + " is beyond " +
                              std::to_string(kMaxExtensionBytes >> 20) +
                              " MiB: not the header of an image");
  }
  storedTypeOfNifti(path, header.datatype);
  // Without NIfTI's magic the header is ANALYZE 7.5's, whose image is a .hdr/.img pair: a .nii
  // without it is a damaged file (nifticlib would read it as NIfTI-1 all the same).
  std::string name = std::filesystem::path(path).filename().string();
  for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool oneFile = name.ends_with(".nii") || name.ends_with(".nii.gz");
  const bool niftiMagic = header.magic == "n+1" || header.magic == "n+2" || header.magic == "ni1" ||
                          header.magic == "ni2";
  if (oneFile && !niftiMagic) {
    throwInputError(path, "magic " + quote(header.magic) +
                              " is not NIfTI's (n+1 or n+2): a damaged file, or an ANALYZE 7.5 "
                              "header, whose image is a .hdr/.img pair");
  }
  if (header.version < 0) {
    throwInputError(path, "nifticlib rejects its NIfTI-" + std::to_string(-header.version) +
                              " header (inconsistent fields)");
  }
  // One file holds the header and 4 extension bytes before the image (the standard's rule for
  // vox_offset); below that, nifticlib would read the image from inside the header.
  const int dataStart = header.version == 2 ? 540 + 4 : 348 + 4;
  if (oneFile && header.voxOffset < dataStart) {
    throwInputError(path, "vox_offset " + std::to_string(std::int64_t(header.voxOffset)) +
                              " lies inside the header (a single-file image starts at " +
                              std::to_string(dataStart) + " or later)");
  }
}

glm::dmat4 toGlm(const nifti_dmat44& m) {
  glm::dmat4 result(1.0);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) result[c][r] = m.m[r][c];
  }
  return result;
}

// "RAS"-style letters for the positive direction of each index axis (nifti's L2R is +x = R).
std::string axesOf(const nifti_dmat44& m) {
  // The letter each of nifticlib's codes names, by code (NIFTI_L2R = 1 .. NIFTI_S2I = 6).
  static_assert(NIFTI_L2R == 1 && NIFTI_R2L == 2 && NIFTI_P2A == 3 && NIFTI_A2P == 4 &&
                NIFTI_I2S == 5 && NIFTI_S2I == 6);
  constexpr std::string_view kLetters = "?RLAPSI";
  int codes[3] = {0, 0, 0};
  nifti_dmat44_to_orientation(m, &codes[0], &codes[1], &codes[2]);
  std::string axes;
  for (int code : codes) axes += code >= 1 && code <= 6 ? kLetters[std::size_t(code)] : '?';
  return axes;
}

// The image's qform and sform, for the samples the volume keeps (index 0 is the subset's first).
std::vector<Orientation> orientationsOf(const nifti_image& image, const VolumeSubset& subset) {
  std::vector<Orientation> result;
  auto add = [&](const char* name, int code, const nifti_dmat44& m) {
    if (code <= 0) return;
    result.push_back({name, nifti_xform_string(code), toGlm(m) * fileFromKept(subset), axesOf(m)});
  };
  add("qform", image.qform_code, image.qto_xyz);
  add("sform", image.sform_code, image.sto_xyz);
  return result;
}

// "NIfTI-2 (.nii, gzip)": the version from the header's size (nifticlib's nifti_type says
// NIFTI1 for NIfTI-2 files too), one file or a pair from nifti_type.
std::string formatOf(const nifti_image& image, int version, bool gzipped) {
  const bool analyze = image.nifti_type == NIFTI_FTYPE_ANALYZE;
  const bool oneFile =
      image.nifti_type == NIFTI_FTYPE_NIFTI1_1 || image.nifti_type == NIFTI_FTYPE_NIFTI2_1;
  return std::string(analyze        ? "ANALYZE 7.5"
                     : version == 2 ? "NIfTI-2"
                                    : "NIfTI-1") +
         (oneFile ? " (.nii" : " (.hdr/.img") + (gzipped ? ", gzip)" : ")");
}

}  // namespace

Volume readNifti(const std::string& path, const LoadOptions& options) {
  regularFileSize(path);
  nifti_set_debug_level(0);  // nifticlib would print to stderr; vsil's errors say it in a line
  const RawHeader raw = readRawHeader(path);
  checkRawHeader(path, raw);

  const std::unique_ptr<nifti_image, NiftiImageFree> image(nifti_image_read(path.c_str(), 0));
  if (!image) throwInputError(path, "nifticlib cannot read its header or extensions");
  if (image->nifti_type == NIFTI_FTYPE_ASCII) {
    throwInputError(path, "NIfTI-ASCII files are not supported (binary NIfTI only)");
  }
  if (!image->iname) throwInputError(path, "its image data file (.img) is missing");
  const StoredType type = storedTypeOfNifti(path, image->datatype);
  const glm::ivec3 dims = parseDims(path, "dim[1..3]",
                                    std::to_string(image->nx) + " " + std::to_string(image->ny) +
                                        " " + std::to_string(image->nz));
  // The standard's rule: a slope of 0 means none; any other applies with its intercept. A
  // slope or intercept that is not a number (nifticlib would read it as 0) is refused.
  if (!std::isfinite(raw.sclSlope)) {
    throwInputError(path, "scl_slope " + formatNumber(raw.sclSlope) +
                              " is not a finite number (0 means no scaling)");
  }
  Rescale rescale;
  if (raw.sclSlope != 0.0) {
    if (!std::isfinite(raw.sclInter)) {
      throwInputError(path, "scl_inter " + formatNumber(raw.sclInter) + " is not a finite number");
    }
    rescale.slope = raw.sclSlope;
    rescale.intercept = raw.sclInter;
  }
  planVolume(path, dims, keptSampleType(type, rescale), options.limits, options.region);
  glm::dvec3 spacing(image->dx, image->dy, image->dz);
  for (int axis = 0; axis < 3; ++axis) {
    // NIfTI's sign of a spacing lives in qfac and the transforms; pixdim itself is a size.
    spacing[axis] = std::abs(spacing[axis]);
    if (!std::isfinite(spacing[axis]) || spacing[axis] <= 0.0) {
      throwInputError(path, "pixdim[" + std::to_string(axis + 1) + "] " +
                                formatNumber(image->pixdim[axis + 1]) +
                                " is not a positive spacing");
    }
  }

  // nifticlib looks for a .hdr's image as .img (and a .hdr.gz's as .img.gz); an uncompressed
  // .hdr beside a gzipped .img.gz is read too.
  std::string dataPath = image->iname;
  if (dataPath != path && fileTypeAt(dataPath, dataPath) == std::filesystem::file_type::not_found &&
      fileTypeAt(dataPath + ".gz", dataPath + ".gz") != std::filesystem::file_type::not_found) {
    dataPath += ".gz";
  }
  const std::string dataLabel =
      dataPath == path ? "its data"
                       : "data file " + quote(std::filesystem::path(dataPath).filename().string());
  const bool gzipped = nifti_is_gzfile(dataPath.c_str()) != 0;
  const std::uint64_t expected = payloadBytes(dims, type);
  const auto offset = std::uint64_t(image->iname_offset);
  const bool bigEndian = image->byteorder == kMsbFirst;

  if (dataPath != path && fileTypeAt(dataPath, dataPath) == std::filesystem::file_type::not_found) {
    throwInputError(path, "its image file " +
                              quote(std::filesystem::path(dataPath).filename().string()) +
                              " is missing");
  }
  if (gzipped) {
    // Before the volume is allocated: a few KiB of gzip cannot hold a 2048³ volume (deflate
    // packs at most 1032:1), as NRRD and MetaImage check their compressed payloads.
    checkInflatable(path, dataLabel + " (gzip)", regularFileSize(dataPath), offset + expected);
  } else {
    const std::uint64_t available = regularFileSize(dataPath);
    if (available < offset || available - offset < expected) {
      throwInputError(path, dataLabel + " holds " +
                                std::to_string(available > offset ? available - offset : 0) +
                                " bytes after offset " + std::to_string(offset) + ", " +
                                std::to_string(expected) + " expected (" +
                                describeLayout(dims, type) + ")");
    }
  }
  Volume volume = startVolume(path, dims, type, spacing, options, rescale);
  volume.format = formatOf(*image, raw.version, gzipped);
  for (int axis = 1; axis <= 3; ++axis) {
    if (!std::isfinite(raw.pixdim[axis]) || raw.pixdim[axis] == 0) {
      volume.warnings.push_back(path + ": pixdim[" + std::to_string(axis) + "] " +
                                formatNumber(raw.pixdim[axis]) +
                                " is no spacing; read as 1 (nifticlib's rule)");
    }
  }
  volume.orientations = orientationsOf(*image, subsetOf(volume));
  SampleSink sink(path, volume, subsetOf(volume), type, bigEndian, rescale);
  if (!gzipped) {
    readUncompressed(FileReader(dataPath), offset, sink, options);
    return volume;
  }
  // gzip: read in order through zlib (a gzip stream cannot seek backward cheaply); the sink
  // keeps the samples of --crop/--stride. zlib directly, not znzlib: the end of the stream (its
  // length and CRC) is checked only by its error state, which znzlib does not pass on.
  const std::unique_ptr<gzFile_s, GzipClose> file(gzopen(dataPath.c_str(), "rb"));
  if (!file) throwInputError(path, "cannot open " + dataLabel);
  if (gzseek(file.get(), z_off_t(offset), SEEK_SET) < 0) {
    throwInputError(path, dataLabel + " ends before its offset " + std::to_string(offset));
  }
  const std::string corrupt =
      dataLabel + " is not a whole gzip stream (cut short, or its CRC check fails)";
  std::vector<std::uint8_t> piece(std::size_t(1) << 20);
  std::uint64_t read = 0;
  while (read < expected) {
    const auto want = unsigned(std::min<std::uint64_t>(piece.size(), expected - read));
    const int got = gzread(file.get(), piece.data(), want);
    if (got < 0) throwInputError(path, corrupt);
    if (unsigned(got) != want) {
      throwInputError(path, dataLabel + " ends after " + std::to_string(read + unsigned(got)) +
                                " of " + std::to_string(expected) + " bytes (" +
                                describeLayout(dims, type) + "; truncated or corrupt gzip)");
    }
    sink.append(std::span(piece.data(), std::size_t(got)));
    read += unsigned(got);
    if (options.progress) options.progress(read, expected);
  }
  // One byte more reaches the stream's end, where zlib checks its length and CRC; a stream cut
  // before its trailer reads as an end with Z_BUF_ERROR. Both refused, as the NRRD reader does.
  std::uint8_t beyond = 0;
  int error = Z_OK;
  if (gzread(file.get(), &beyond, 1) < 0 || (gzerror(file.get(), &error), error != Z_OK)) {
    throwInputError(path, corrupt);
  }
  sink.finishAppending();
  return volume;
}

}  // namespace vsil::io
