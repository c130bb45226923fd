#pragma once
// Inside the DICOM plugin (io/dicom_plugin.h): GDCM run in a child process (dicom_child.cpp).
#include <csignal>
#include <string>

#include "core/volume.h"
#include "io/volume_loader.h"

namespace vsil::io {

// readDicomSeriesWithGdcm(path, options) in a forked child; the same volume, or the same
// InputError, and options.progress called in this process as the child reads. A child that
// GDCM aborts (one of its assert()s) or crashes (a signal) ends in an InputError naming `path`:
// "GDCM failed one of its internal checks reading it (a malformed DICOM file)", or "GDCM
// crashed reading it (signal SIGSEGV; ...)". Nothing of the child is left behind.
Volume readDicomSeriesInChild(const std::string& path, const LoadOptions& options);

// Nonzero while a call into GDCM runs (dicom_reader.cpp's GdcmCall): the child's SIGABRT handler
// tells GDCM's assert()s from other aborts with it.
extern volatile std::sig_atomic_t gdcmCallRunning;

}  // namespace vsil::io
