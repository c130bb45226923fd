#pragma once
// The interface between vsil and its DICOM plugin, libvsil_dicom.so (dicom_plugin.cpp, with
// dicom_reader.cpp). The plugin alone links GDCM: loading GDCM's 21 shared libraries builds its
// DICOM dictionaries, about 20 ms at the start of every process (a program linking them and
// doing nothing, 2 cores), so readDicomSeries (dicom_loader.cpp) loads the plugin when a DICOM
// file is read. Both sides are built together from the same sources by the same compiler; the
// plugin keeps its own copy of the vsil code the reader needs, its symbols not exported, and
// what it throws (InputError naming the file) reaches the caller as from any other reader.
#include <string>

#include "core/volume.h"
#include "io/volume_loader.h"

namespace vsil::io {

// The reader itself (dicom_reader.cpp, inside the plugin): readDicomSeries's contract.
Volume readDicomSeriesWithGdcm(const std::string& path, const LoadOptions& options);

namespace dicom {
// The plugin's entry point: `out` = readDicomSeriesWithGdcm(path, options).
using ReadSeries = void (*)(const std::string& path, const LoadOptions& options, Volume& out);
inline constexpr const char* kReadSeriesSymbol = "vsilReadDicomSeries";
inline constexpr const char* kPluginFile = "libvsil_dicom.so";
}  // namespace dicom

}  // namespace vsil::io
