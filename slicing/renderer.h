#pragma once
// The slicing engine's front door: upload a volume once, render frames with any technique.
//
//   vsil::gl::GlContext context;
//   vsil::Renderer renderer(context);
//   renderer.setVolume(volume);
//   vsil::RenderResult result = renderer.render(settings);   // result.frame.state, .depth ...
#include <memory>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/frame.h"
#include "core/volume.h"

namespace vsil {
namespace gl {
class GlContext;
}

// How the silhouette technique runs its per-slice passes. Both give the same pixels.
//  Fast:  footprint, then contour and decision table fused, updating the intermediate record in
//         place (image load/store); final pixels (Filled, Silhouette) are skipped.
//  Paper: Nagy–Klein's three passes (footprint, contour, decision) over ping-pong targets.
enum class SilhouettePipeline { Fast, Paper };

struct RenderSettings {
  std::string technique = "silhouette";  // silhouette | rightangle
  glm::ivec2 size{512, 512};
  float iso = 0.5f;  // in the data's own units
  CameraSpec camera;
  double samplesPerVoxel = 1.0;  // slices per voxel along the view direction
  SilhouettePipeline silhouettePipeline = SilhouettePipeline::Fast;
  // Skip pixels whose samples cannot reach the iso value (slicing/empty_space.h); the pixels
  // are the same either way. Off: every slice samples its whole polygon, as in the papers.
  bool emptySpaceSkipping = true;
  // rightangle: a first hit is a line pixel where (1 - |n·v|)^exponent > threshold.
  double rightAngleExponent = 8.0;
  double rightAngleThreshold = 0.3;
};

struct RenderTimings {
  double renderMs = 0;    // slicing, ended by glFinish
  double readbackMs = 0;  // GPU targets to CPU images
};

struct RenderResult {
  FrameBuffers frame;
  View view;
  int sliceCount = 0;  // slices drawn, not counting the extra empty one
  double sliceStepEye = 0;
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

  // Uploads the volume as a 3D texture (replacing any previous one).
  void setVolume(const Volume& volume);
  RenderResult render(const RenderSettings& settings);

  static std::vector<std::string> techniqueNames();
  // The checks render() makes first (size, sampling, zoom, angles, ...; core/limits.h), callable
  // before any GL work. Throws InputError naming the flag.
  static void validateSettings(const RenderSettings& settings);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vsil
