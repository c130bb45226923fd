#include "cli/cli_render_options.h"

#include "cli/cli_parse.h"
#include "cli/cli_postfx_options.h"
#include "cli/cli_technique_options.h"
#include "core/number_pair.h"
#include "core/upright.h"

namespace vsil::cli {

void addRenderOptions(CLI::App& command, RenderFlags& flags) {
  command.add_option("input", flags.input,
                     "Volume file (" + std::string(kVolumeFileKinds) +
                         "; raw with --dims/--type) or gen:NAME[:N]; default " +
                         std::string(kDefaultInput));
  addTechniqueOptions(command, flags.technique, flags.techniqueOptions);
  command.add_flag("--no-empty-space-skipping", flags.noEmptySpaceSkipping,
                   "sample every pixel of every slice (slower; the same pixels)");
  command.add_option("--size", flags.size, "Image size WxH")->capture_default_str();
  command.add_option("--view", flags.view, "Orbit angles AZ,EL in degrees about the up axis")
      ->capture_default_str();
  command
      .add_option("--up", flags.up,
                  "The axis shown upward, which the orbit turns about: auto (a file's "
                  "anatomical placement stands superior up, seen from anterior; else +y), or "
                  "+x, -x, +y, -y, +z, -z")
      ->capture_default_str();
  command.add_flag("--ortho", flags.orthographic, "Orthographic instead of perspective");
  command.add_option("--zoom", flags.zoom, "Magnification (0.001 .. 1000)")->capture_default_str();
  command.add_option("--sampling", flags.sampling, "Slices per voxel along the view")
      ->capture_default_str();
  addVolumeOptions(command, flags.volume);
  addPostfxOptions(command, flags.postfx, flags.lineFlagsGiven);
  addGlOptions(command, flags.gl);
}

RenderRequest toRenderRequest(const RenderFlags& flags) {
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
  // Checked before the volume is read, and recorded as written out ("x" as "+x").
  request.up = flags.up == "auto" ? flags.up : resolveUpright(flags.up, {}).up;
  settings.samplesPerVoxel = flags.sampling;
  settings.emptySpaceSkipping = !flags.noEmptySpaceSkipping;
  request.postfx = flags.postfx;
  request.lineFlagsGiven = flags.lineFlagsGiven;
  return request;
}

}  // namespace vsil::cli
