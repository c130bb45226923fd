#pragma once
// Plugins: shared objects vsil loads with dlopen when a feature needs them, so that the
// libraries behind that feature cost nothing at the start of every process that does not use it
// (video files: libvsil_video.so, OpenCV's videoio and FFmpeg; DICOM: libvsil_dicom.so, GDCM).
// A plugin is built with vsil, by the same compiler, and exports one entry point.
#include <string>

namespace vsil {

// The address of `symbol` in the plugin file `file` (e.g. "libvsil_video.so"), loaded once per
// process and kept. Looked for beside the executable (the build tree), in ../lib/vsil beside it
// (installed), beside the shared object holding vsil's code (the Python extension vsil/_vsil*.so,
// whose package ships the plugins), and at `builtPath` (where the build put it; may be empty).
// Throws std::runtime_error naming `what` (e.g. "video"), the file and each path tried.
void* pluginSymbol(const std::string& what, const std::string& file, const char* symbol,
                   const std::string& builtPath);

}  // namespace vsil
