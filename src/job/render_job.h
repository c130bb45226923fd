#pragma once
// One render as its callers make it — the `vsil render` command, `vsil animate`, the Python
// module: load a volume once, render frames of any technique, broaden and compose them, and say
// what was done (the metadata `--meta-out` writes). One GL context and one Renderer per job, so
// a sequence of frames pays the set-up once.
//
//   vsil::RenderJob job;
//   job.load("../shared/datasets/bonsai.vti", {});
//   vsil::RenderRequest request;                     // technique, options, camera, postfx
//   request.settings.options["iso"] = 40.0;
//   vsil::RenderOutput out = job.render(request);    // out.image, out.result.frame, out.metadata
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "core/volume.h"
#include "io/volume_loader.h"
#include "postfx/compose.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"

namespace vsil {

struct RenderRequest {
  RenderSettings settings;
  PostfxOptions postfx;
  // The line flags the caller was given (--width, --line-color, --fill, ...: cli_postfx_options.h).
  // A technique that draws no lines ignores `postfx` but the background, and warns that it did.
  std::vector<std::string> lineFlagsGiven;
  // --up (core/upright.h): "auto" or an axis, resolved per volume into settings.camera.upright.
  std::string up = "auto";
};

// The request's camera for a volume: --up resolved by the volume's anatomical placement.
CameraSpec cameraFor(const RenderRequest& request, const Volume& volume);

struct RenderOutput {
  RenderResult result;
  cv::Mat image;     // the illustration, 8-bit BGR or BGRA (compose.h)
  StageTime postfx;  // broadening and composition
  // What `--meta-out` writes: parameters (the shared ones, the technique's options, postfx),
  // dataset, slices, camera, pixel counts, timings, the GL context (back end, renderer). The caller
  // adds its own (output paths, total time).
  nlohmann::json metadata;
  // What the user should hear about although the frame was made (e.g. an iso value outside the
  // data's range): one line each, for stderr or Python warnings.
  std::vector<std::string> warnings;
};

class RenderJob {
 public:
  // Creates the GL context (current on the calling thread; gl_context.h says how `gl` chooses
  // the back end) and the renderer.
  explicit RenderJob(const gl::ContextOptions& gl = {});
  ~RenderJob();
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  // Reads or generates the volume (io/volume_loader.h) and uploads it, replacing the last one.
  const Volume& load(const std::string& spec, const LoadOptions& options);
  // Uploads a volume made elsewhere; `input` is the spec it was loaded from, for the metadata
  // (default: the volume's source).
  // `maxTextureBytes`: the largest brick texture (--max-texture-mib; VolumeLimits).
  const Volume& setVolume(Volume volume, const std::string& input = "",
                          std::uint64_t maxTextureBytes = limits::kMaxTextureBytes);
  const Volume& volume() const;
  // One process's slab of a volume split across processes (slicing/slab.h Renderer::setSlab):
  // `slabVolume` holds the whole volume's z from part.voxelZ0 on; memory checks count it alone.
  const Volume& setSlab(Volume slabVolume, const SlabPart& part, const std::string& input);

  // Renders, broadens and composes one frame. Checks the request first (checkRequest) and the
  // work the volume needs (slices per frame, memory) against `limits`.
  RenderOutput render(const RenderRequest& request, const VolumeLimits& limits = VolumeLimits{});

  gl::GlContext& context();
  Renderer& renderer();

  // The checks that need no volume and no GL (technique, options, size, camera, widths, the
  // image's memory): callers run them before reading any file. Throws InputError naming the flag.
  static void checkRequest(const RenderRequest& request, const VolumeLimits& limits);
  // `load` with limits for rendering `request`: the loader checks the whole render's memory
  // (samples in the file's type, texture, brick ranges and images; limits::renderVolumeBytes)
  // and that the texture can exist, from the file's header, before reading any payload.
  // The memory the checks count for rendering `request` from a volume of `dims` samples of
  // `type` (textures, the structures beside them, the images).
  static std::uint64_t memoryBytes(const RenderRequest& request, glm::ivec3 dims, SampleType type,
                                   std::uint64_t maxTextureBytes);
  static LoadOptions loadOptionsFor(const RenderRequest& request, LoadOptions load);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The images `render` writes beside the illustration: pixel states as 8-bit grey
// (core/frame.h stateGrey), and the depth image (core/depth_image.h) of what the technique's
// depth means for broadening: the line (Silhouette) pixels of a state technique, every pixel
// with a depth otherwise.
cv::Mat1b stateImage(const FrameBuffers& frame);
cv::Mat1w depthImage(const FrameBuffers& frame);

}  // namespace vsil
