#include "cli/cli_gl_options.h"

#include <limits>

namespace vsil::cli {

void addGlOptions(CLI::App& command, GlOptions& options, bool valueOptional) {
  const std::string group = "OpenGL";
  CLI::Option* gl =
      command
          .add_option_function<std::string>(
              "--gl",
              [&options](const std::string& value) {
                options.given = true;
                options.backend = value;  // a bare --gl (value optional): $VSIL_GL, else auto
              },
              "back end: auto (a GPU's EGL device, else OSMesa, else EGL on llvmpipe), osmesa, "
              "egl; default $VSIL_GL, else auto")
          ->group(group);
  if (valueOptional) {
    gl->expected(0, 1)->check(CLI::IsMember({"", "auto", "osmesa", "egl"}));
  } else {
    gl->check(CLI::IsMember({"auto", "osmesa", "egl"}));
  }
  command
      .add_option("--gl-device", options.device,
                  "this EGL device only (numbered as `vsil info --gl` lists them); default "
                  "$VSIL_GL_DEVICE, else each in turn")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()))
      ->group(group);
}

gl::ContextOptions toContextOptions(const GlOptions& options) {
  gl::ContextOptions context = gl::contextOptionsFromEnvironment();
  if (!options.backend.empty()) {
    context.backend = gl::parseBackend(options.backend, "--gl");
    // A back end given on the command line is not narrowed by a device from the environment.
    if (context.backend == gl::Backend::Osmesa) context.eglDevice.reset();
  }
  if (options.device) context.eglDevice = *options.device;
  if (!options.backend.empty()) context.backendFromEnvironment = false;
  if (options.device) context.deviceFromEnvironment = false;
  gl::checkContextOptions(context);
  return context;
}

}  // namespace vsil::cli
