#pragma once
// The slicing engine's front door: upload a volume once, render frames with any technique.
//
//   vsil::gl::GlContext context(vsil::gl::contextOptionsFromEnvironment());  // or --gl
//   vsil::Renderer renderer(context);
//   renderer.setVolume(volume);
//   vsil::RenderResult result = renderer.render(settings);   // result.frame.state, .depth ...
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "core/clock.h"
#include "core/color.h"
#include "core/frame.h"
#include "core/limits.h"
#include "core/options.h"
#include "core/volume.h"

namespace vsil {
struct SlabPart;
namespace gl {
class GlContext;
class ProgramCache;
}  // namespace gl

// What a frame is made of: the technique (technique_table.h) and its options, and what every
// technique shares (image, camera, sampling, empty-space skipping).
struct RenderSettings {
  std::string technique = "silhouette";
  glm::ivec2 size{512, 512};
  CameraSpec camera;
  double samplesPerVoxel = 1.0;  // slices per voxel along the view direction
  // Skip what cannot change a pixel (slicing/empty_space.h); the pixels are the same either
  // way. Off: every slice samples its whole polygon, as in the papers.
  bool emptySpaceSkipping = true;
  // Colour techniques retire a pixel once its accumulated opacity passed 1 − 1/255 (early ray
  // termination, slicing/compositing.h): no channel changes by more than 1/255. Off: every
  // sample in occupied space is composited.
  bool earlyRayTermination = true;
  // Whether FrameBuffers::depth is wanted where a colour technique makes it beside its colour
  // (demip's first hit, lmip's local maximum): reading it back costs 5-10 ms per 512² frame, so
  // callers that write no depth (`vsil render` without --depth-out, `vsil animate`, the bench)
  // turn it off and get no depth. Techniques with pixel states and firsthit always return theirs
  // (broadening and their colour are made from it).
  bool readDepth = true;
  // The colour the frame will be composed over (`--background`) when the caller chose one;
  // techniques that blend towards it read FrameContext::background (distance colour blending's
  // c_b: illustrate's, the tone fill's). Unset: the technique's own choice (a style's), else white.
  std::optional<Rgba> background;
  // `--fill tone` (postfx/compose.h): the object colour c_o (`--fill-color`) in which the
  // techniques that return pixel states tone-shade each first hit (slicing/tone_fill.h), into
  // FrameBuffers::tone. Unset: they do not.
  std::optional<Rgba> toneFill;
  // The technique's options by name (its entry in technique_table.h declares them); options
  // not given take their declared defaults, the iso value the volume's default.
  OptionValues options;
};

// Where a frame's time went, in wall and process CPU time (core/clock.h).
struct RenderTimings {
  // The volume's default iso value (Otsu's threshold of a histogram of every sample), computed
  // on the first frame that leaves an iso option unset and kept; zero for the others.
  StageTime defaults;
  StageTime programs;  // building the shader programs the frame was the first to use
  StageTime render;    // slicing, ended by glFinish; program builds and `combine` excluded
  StageTime readback;  // GPU targets to CPU images
  // Across processes (setSlab): combining this process's slab with the others' (wall time in
  // Technique::combineSlabs and in the relay's calls elsewhere in the frame: the MPI calls, the
  // waits for the other processes, the read-backs they need). Zero for a whole volume.
  StageTime combine;
};

struct RenderResult {
  FrameBuffers frame;
  View view;
  // Every option of the technique with the value used, and what the technique resolved them
  // to (e.g. illustrate's "illustration": effects, every parameter, lights).
  nlohmann::json options;
  Rgba background = kDefaultBackground;  // what the frame was made for and is composed over
  int sliceCount = 0;                    // slices drawn, not counting the extra empty one
  double sliceStepEye = 0;
  // How the frame held the volume (slicing/volume_texture.h): "R16F" or "R32F", and the bricks
  // along x, y and z ({1, 1, 1}: one texture).
  std::string textureFormat;
  glm::ivec3 textureBricks{0};
  RenderTimings timings;
};

class Technique;

class Renderer {
 public:
  // The context must be current on the calling thread and outlive the renderer.
  explicit Renderer(gl::GlContext& context);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads the volume as 3D textures (replacing any previous ones): one brick when it fits
  // one texture of at most `maxTextureBytes` (--max-texture-mib) with little padding, else the
  // bricks of BrickLayout::choose (core/brick_layout.h). Frames are the same bytes either way.
  // The volume must stay alive and unchanged until the next setVolume: a frame that needs one
  // texture (TechniqueInfo::needsOneTexture: the tiles march, illustrate's halos) uploads it
  // again in one texture when it fits.
  void setVolume(const Volume& volume, std::uint64_t maxTextureBytes = limits::kMaxTextureBytes);
  // One process's slab of a volume split along z across processes (slab.h): uploads only the
  // bricks `part` holds from `slabVolume`; frames draw only the pieces of the bricks it owns and
  // combine with the other processes' before their last passes (Technique::combineSlabs, or for
  // Composition::Relay each sweep's Technique::relayTargets in the view's depth order). The
  // value range and derived defaults are the whole volume's, from `part`.
  void setSlab(const Volume& slabVolume, const SlabPart& part);
  // Bricks of the current volume's texture (0 before setVolume).
  std::size_t brickCount() const;
  // The current volume's value range (valueRange, computed once in setVolume).
  ValueRange valueRange() const;
  RenderResult render(const RenderSettings& settings);

  // The programs built so far (tests count recompiles).
  const gl::ProgramCache& programs() const;

  // The checks render() makes first (technique and options, size, sampling, zoom, angles;
  // core/limits.h), callable before any GL work. Throws InputError naming the flag.
  static void validateSettings(const RenderSettings& settings);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vsil
