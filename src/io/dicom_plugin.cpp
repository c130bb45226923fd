// libvsil_dicom.so: the DICOM reader (dicom_reader.cpp, GDCM) behind dicom_plugin.h, loaded by
// readDicomSeries (dicom_loader.cpp). GDCM reads in a child process unless the options say
// otherwise (io/dicom_child.h).
#include "io/dicom_plugin.h"
#include "io/dicom_child.h"

extern "C" __attribute__((visibility("default"))) void vsilReadDicomSeries(
    const std::string& path, const vsil::LoadOptions& options, vsil::Volume& out) {
  out = options.dicomInChildProcess ? vsil::io::readDicomSeriesInChild(path, options)
                                    : vsil::io::readDicomSeriesWithGdcm(path, options);
}
