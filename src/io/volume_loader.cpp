#include "io/volume_loader.h"

#include <filesystem>

#include "core/error.h"
#include "generators/generators.h"
#include "io/file_access.h"
#include "io/readers.h"
#include "io/text_fields.h"

namespace vsil {

Volume loadVolume(const std::string& spec, const LoadOptions& options) {
  if (spec.starts_with("gen:")) {
    return generateVolume(spec.substr(4), options.limits, options.region);
  }
  if (spec.empty()) throw InputError("no volume given (a file path or gen:NAME[:N])");
  if (options.raw) return io::readRaw(spec, *options.raw, options);

  const std::string extension = io::toLower(std::filesystem::path(spec).extension().string());
  if (extension == ".nrrd" || extension == ".nhdr") return io::readNrrd(spec, options);
  if (extension == ".vti") return io::readVti(spec, options);
  if (extension == ".vtk") return io::readLegacyVtk(spec, options);
  if (extension == ".mhd" || extension == ".mha") return io::readMetaImage(spec, options);

  io::regularFileSize(spec);  // a missing file or a directory says so first
  throwInputError(spec, "unknown volume format" +
                            (extension.empty() ? std::string() : " " + io::quote(extension)) +
                            " (known: .nrrd, .nhdr, .vti, .vtk, .mhd, .mha, gen:NAME[:N]; a "
                            "headerless raw file needs --dims and --type)");
}

}  // namespace vsil
