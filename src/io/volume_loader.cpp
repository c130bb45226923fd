#include "io/volume_loader.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "generators/generators.h"
#include "io/file_access.h"
#include "io/readers.h"
#include "io/text_fields.h"

namespace vsil {

Volume loadVolume(const std::string& spec, const LoadOptions& options) {
  // --series chooses among a DICOM folder's series; anything else would ignore it silently.
  const auto refuseSeries = [&] {
    if (options.series.empty()) return;
    throwInputError("--series " + io::quote(options.series),
                    "chooses a DICOM series, but " + spec + " is not DICOM");
  };
  if (spec.starts_with("gen:")) {
    refuseSeries();
    // The raw layout describes a headerless file; a generated volume would ignore it silently.
    if (options.raw) {
      throw InputError("--dims and --type describe a headerless raw file, not " + spec);
    }
    return generateVolume(spec.substr(4), options.limits, options.region);
  }
  if (spec.empty()) throw InputError("no volume given (a file path or gen:NAME[:N])");
  if (options.raw) {
    refuseSeries();
    return io::readRaw(spec, *options.raw, options);
  }

  std::string extension = io::toLower(std::filesystem::path(spec).extension().string());
  if (extension == ".gz") {  // name.nii.gz: the extension before .gz says the format
    extension = io::toLower(std::filesystem::path(spec).stem().extension().string()) + ".gz";
  }
  using Reader = Volume (*)(const std::string&, const LoadOptions&);
  const auto read = [&](Reader reader) {
    refuseSeries();
    return reader(spec, options);
  };
  if (extension == ".nrrd" || extension == ".nhdr") return read(io::readNrrd);
  if (extension == ".vti") return read(io::readVti);
  if (extension == ".vtk") return read(io::readLegacyVtk);
  if (extension == ".slc") return read(io::readSlc);
  if (extension == ".mhd" || extension == ".mha") return read(io::readMetaImage);
  for (const char* nifti : {".nii", ".nii.gz", ".hdr", ".hdr.gz", ".img", ".img.gz"}) {
    if (extension == nifti) return read(io::readNifti);
  }

  // A folder is a DICOM series (one named like a volume file was refused above: "is a
  // directory").
  std::error_code error;
  if (extension == ".dcm" || extension == ".dicom" || std::filesystem::is_directory(spec, error)) {
    return io::readDicomSeries(spec, options);
  }
  // DICOM files often have no extension: "DICM" after the 128-byte preamble says it.
  if (io::regularFileSize(spec) >= 132) {  // a missing file says so first
    std::uint8_t magic[4] = {};
    io::FileReader(spec).readAt(128, magic);
    if (std::equal(magic, magic + 4, "DICM")) return io::readDicomSeries(spec, options);
  }
  throwInputError(spec, "unknown volume format" +
                            (extension.empty() ? std::string() : " " + io::quote(extension)) +
                            " (known: " + kVolumeFileKinds +
                            ", gen:NAME[:N]; a headerless raw file needs --dims and --type)");
}

}  // namespace vsil
