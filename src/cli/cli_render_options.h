#pragma once
// The flags every command that renders takes, by the same names (vsil render, vsil animate):
// INPUT, --technique and the technique options (cli_technique_options.h), --size, --view,
// --ortho, --zoom, --sampling, --no-empty-space-skipping, the volume flags
// (cli_volume_options.h), the postfx flags (cli_postfx_options.h) and --gl, --gl-device
// (cli_gl_options.h; RenderJob job(toContextOptions(flags.gl))). One registration and one
// conversion into a RenderRequest, so the commands cannot drift apart.
//
//   auto flags = std::make_shared<RenderFlags>();
//   addRenderOptions(*command, *flags);
//   command->callback([flags] { RenderRequest request = toRenderRequest(*flags); ... });
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/cli_gl_options.h"
#include "cli/cli_volume_options.h"
#include "core/options.h"
#include "job/render_job.h"
#include "postfx/compose.h"

namespace vsil::cli {

// The embedded default volume rendered when no INPUT is given (the paper's Figure 3).
inline constexpr const char* kDefaultInput = "gen:spheres:128";

struct RenderFlags {
  std::string input = kDefaultInput;
  std::string technique = "silhouette";
  OptionValues techniqueOptions;
  std::string size = "512x512";
  std::string view = "30,20";
  std::string up = "auto";
  bool orthographic = false;
  double zoom = 1.0;
  double sampling = 1.0;
  bool noEmptySpaceSkipping = false;
  VolumeOptions volume;
  PostfxOptions postfx;
  std::vector<std::string> lineFlagsGiven;  // cli_postfx_options.h addPostfxOptions
  GlOptions gl;
};

// Adds the positional INPUT and every flag above to `command`; `flags` must outlive the parse.
void addRenderOptions(CLI::App& command, RenderFlags& flags);

// The request the flags describe. Throws InputError naming the flag (--size, --view); the
// checks that need the table of techniques are RenderJob::checkRequest's.
RenderRequest toRenderRequest(const RenderFlags& flags);

}  // namespace vsil::cli
