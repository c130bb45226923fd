// readDicomSeries: the DICOM reader in its plugin (io/dicom_plugin.h), loaded at the first
// DICOM file a process reads.
#include "core/plugin.h"
#include "io/dicom_plugin.h"
#include "io/readers.h"

namespace vsil::io {

Volume readDicomSeries(const std::string& path, const LoadOptions& options) {
#ifdef VSIL_DICOM_PLUGIN_BUILT
  const std::string built = VSIL_DICOM_PLUGIN_BUILT;
#else
  const std::string built;
#endif
  const auto read = reinterpret_cast<dicom::ReadSeries>(
      pluginSymbol("DICOM", dicom::kPluginFile, dicom::kReadSeriesSymbol, built));
  Volume volume;
  read(path, options, volume);
  return volume;
}

}  // namespace vsil::io
