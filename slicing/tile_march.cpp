#include "slicing/tile_march.h"

#include <algorithm>

#include "slicing/gl_state.h"
#include "slicing/texture_units.h"

namespace vsil {

gl::Program& marchProgram(const FrameContext& frame, const std::vector<std::string>& shared,
                          const std::string& computeFile, const MarchShape& shape,
                          std::vector<std::string> defines) {
  std::vector<std::string> sources = shared;
  sources.push_back("shaders/tile_march.glsl");
  defines.insert(defines.end(),
                 {"MARCH_GROUP_X " + std::to_string(shape.group.x),
                  "MARCH_GROUP_Y " + std::to_string(shape.group.y),
                  "MARCH_TILE_X " + std::to_string(shape.tile.x),
                  "MARCH_TILE_Y " + std::to_string(shape.tile.y),
                  "MARCH_RANGE_SLICES " + std::to_string(frame.uniforms->slicesPerRange()),
                  "SLICE_STRIDE_VEC4 " + std::to_string(frame.uniforms->sliceStrideVec4())});
  return frame.programs->get(gl::computeProgram(sources, computeFile, defines));
}

void runMarch(const FrameContext& frame, gl::Program& program, const MarchShape& shape,
              const gl::RenderTarget& record) {
  {
    gl::Capability noDepthTest(GL_DEPTH_TEST, false);
    frame.emptySpace->drawEntryDepthImage(glm::mat4(frame.view->clipFromVoxel()));
  }
  gl::bindTexture(gl::TextureUnit::EntryDepth, GL_TEXTURE_2D,
                  frame.emptySpace->entryDepthTexture());
  gl::bindTexture(gl::TextureUnit::ExitDepth, GL_TEXTURE_2D, frame.emptySpace->exitDepthTexture());
  gl::bindImage(gl::ImageUnit::Record, record);
  program.use();
  const int sliceCount = int(frame.plan->slices.size());
  program.set("sliceCount", sliceCount);
  const glm::ivec2 viewport = frame.view->viewport;
  const glm::ivec2 tiles = (viewport + shape.tile - 1) / shape.tile;
  const int perDispatch = std::clamp(shape.slicesPerDispatch, 1, frame.uniforms->slicesPerRange());
  // At least one dispatch: with no slices it still writes every record (EMPTY).
  for (int first = 0; first == 0 || first < sliceCount; first += perDispatch) {
    const int end = std::min(first + perDispatch, sliceCount);
    frame.uniforms->bindSliceRange(first);
    program.set("rangeFirstSlice", first);
    program.set("rangeEndSlice", end);
    VSIL_GL(glDispatchCompute(GLuint(tiles.x), GLuint(tiles.y), 1));
    // The next dispatch reads the records through the image, the finishing pass as a texture.
    VSIL_GL(glMemoryBarrier(end < sliceCount ? GL_SHADER_IMAGE_ACCESS_BARRIER_BIT
                                             : GL_TEXTURE_FETCH_BARRIER_BIT));
  }
}

}  // namespace vsil
