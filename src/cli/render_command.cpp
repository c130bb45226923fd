// vsil render: one frame of a technique to PNG, with optional state, depth and metadata files.
// The work is the library's render job (job/render_job.h); this file reads flags and writes files.
#include <chrono>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli/cli_gl_options.h"
#include "cli/cli_parse.h"
#include "cli/cli_postfx_options.h"
#include "cli/cli_technique_options.h"
#include "cli/cli_volume_options.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_file.h"
#include "core/number_pair.h"
#include "job/render_job.h"
#include "slicing/technique_table.h"

namespace vsil::cli {
namespace {

// The embedded default volume the demo renders when no INPUT is given.
constexpr const char* kDefaultInput = "gen:spheres:128";

struct RenderFlags {
  std::string input = kDefaultInput;
  std::string technique = "silhouette";
  OptionValues techniqueOptions;
  std::string size = "512x512";
  std::string view = "30,20";
  bool orthographic = false;
  double zoom = 1.0;
  double sampling = 1.0;
  bool noEmptySpaceSkipping = false;
  std::string out = "vsil.png";
  std::string stateOut, depthOut, metaOut;
};

RenderRequest requestFrom(const RenderFlags& flags, const PostfxOptions& postfx) {
  RenderRequest request;
  RenderSettings& settings = request.settings;
  settings.technique = flags.technique;
  settings.options = flags.techniqueOptions;
  settings.size = parseSize("--size", flags.size);
  const glm::dvec2 view = parseNumberPair("--view", flags.view);
  settings.camera.azimuthDeg = view.x;
  settings.camera.elevationDeg = view.y;
  settings.camera.orthographic = flags.orthographic;
  settings.camera.zoom = flags.zoom;
  settings.samplesPerVoxel = flags.sampling;
  settings.emptySpaceSkipping = !flags.noEmptySpaceSkipping;
  request.postfx = postfx;
  return request;
}

// Outputs the technique cannot make are refused before any work.
void checkOutputs(const RenderFlags& flags) {
  const TechniqueInfo& technique = findTechnique(flags.technique);
  if (!flags.stateOut.empty() && !technique.outputs.state) {
    throw InputError("--state-out: technique '" + technique.name + "' makes no state image");
  }
  if (!flags.depthOut.empty() && !technique.outputs.depth) {
    throw InputError("--depth-out: technique '" + technique.name + "' makes no depth image");
  }
}

void run(const RenderFlags& flags, const LoadOptions& loadOptions, const PostfxOptions& postfx,
         const gl::ContextOptions& glOptions) {
  const auto start = std::chrono::steady_clock::now();
  const RenderRequest request = requestFrom(flags, postfx);
  RenderJob::checkRequest(request, loadOptions.limits);
  checkOutputs(flags);
  if (validateOnly()) return;

  RenderJob job(glOptions);
  job.load(flags.input, loadOptions);
  RenderOutput output = job.render(request, loadOptions.limits);
  for (const auto& warning : output.warnings) std::cerr << "vsil: warning: " << warning << "\n";

  writePng(flags.out, output.image);
  if (!flags.stateOut.empty()) writePng(flags.stateOut, stateImage(output.result.frame));
  if (!flags.depthOut.empty()) writePng(flags.depthOut, depthImage(output.result.frame));
  if (!flags.metaOut.empty()) {
    nlohmann::json& meta = output.metadata;
    meta["parameters"]["out"] = flags.out;
    meta["timings_ms"]["total"] =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count();
    writeFileAtomically(flags.metaOut, meta.dump(2) + "\n");
  }
  std::cout << flags.out << "\n";
}

const CommandRegistration registration(10, [](CLI::App& app) {
  auto flags = std::make_shared<RenderFlags>();
  auto load = std::make_shared<VolumeOptions>();
  auto postfx = std::make_shared<PostfxOptions>();
  auto glFlags = std::make_shared<GlOptions>();
  CLI::App* command = app.add_subcommand("render", "Render one frame of a technique to PNG");
  command->add_option("input", flags->input,
                      "Volume file (.nrrd .nhdr .vti .vtk, raw with --dims/--type) or "
                      "gen:NAME[:N]; default " +
                          std::string(kDefaultInput));
  addTechniqueOptions(*command, flags->technique, flags->techniqueOptions);
  command->add_flag("--no-empty-space-skipping", flags->noEmptySpaceSkipping,
                    "sample every pixel of every slice (slower; the same pixels)");
  command->add_option("--size", flags->size, "Image size WxH")->capture_default_str();
  command->add_option("--view", flags->view, "Orbit angles AZ,EL in degrees")
      ->capture_default_str();
  command->add_flag("--ortho", flags->orthographic, "Orthographic instead of perspective");
  command->add_option("--zoom", flags->zoom, "Magnification (> 0)")->capture_default_str();
  command->add_option("--sampling", flags->sampling, "Slices per voxel along the view")
      ->capture_default_str();
  command->add_option("--out", flags->out, "Output PNG")->capture_default_str();
  command->add_option("--state-out", flags->stateOut,
                      "8-bit PNG of pixel states: 0 Empty, 85 Filled, 170 Contour, 255 Silhouette");
  command->add_option("--depth-out", flags->depthOut,
                      "16-bit PNG of normalized depth d: 1 + round(d*65534), 0 where none "
                      "(for line techniques: the line pixels)");
  command->add_option("--meta-out", flags->metaOut, "JSON with parameters, camera, timings");
  addVolumeOptions(*command, *load);
  addPostfxOptions(*command, *postfx);
  addGlOptions(*command, *glFlags);
  command->callback([flags, load, postfx, glFlags] {
    run(*flags, toLoadOptions(*load), *postfx, toContextOptions(*glFlags));
  });
});

}  // namespace
}  // namespace vsil::cli
