// libvsil_dicom.so: the DICOM reader (dicom_reader.cpp, GDCM) behind dicom_plugin.h, loaded by
// readDicomSeries (dicom_loader.cpp).
#include "io/dicom_plugin.h"

extern "C" __attribute__((visibility("default"))) void vsilReadDicomSeries(
    const std::string& path, const vsil::LoadOptions& options, vsil::Volume& out) {
  out = vsil::io::readDicomSeriesWithGdcm(path, options);
}
