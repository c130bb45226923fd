#pragma once
// The OpenGL flags every command that makes a GL context shares: --gl auto|osmesa|egl and
// --gl-device N (slicing/gl_context.h). Without them, $VSIL_GL and $VSIL_GL_DEVICE choose, then
// auto. Usage in a command's setup:
//
//   auto gl = std::make_shared<GlOptions>();
//   addGlOptions(*command, *gl);
//   command->callback([gl, ...] { gl::GlContext context(toContextOptions(*gl)); ... });
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "slicing/gl_context.h"

namespace vsil::cli {

struct GlOptions {
  std::string backend;        // --gl; empty: not given
  std::optional<int> device;  // --gl-device
  bool given = false;         // --gl appeared (for `vsil info --gl`, whose value is optional)
};

// Adds --gl and --gl-device (group "OpenGL"). With `valueOptional`, `--gl` may come bare: it sets
// `given` and leaves the choice to $VSIL_GL, else auto.
void addGlOptions(CLI::App& command, GlOptions& options, bool valueOptional = false);

// The flags over the environment (contextOptionsFromEnvironment). Throws InputError naming the
// flag or variable.
gl::ContextOptions toContextOptions(const GlOptions& options);

}  // namespace vsil::cli
