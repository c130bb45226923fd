#pragma once
// Named texture and image units, one list for the whole engine: GL binds textures to units
// globally, so every pass and technique draws its units from here and none can collide. The
// shaders see the same names as `UNIT_<NAME>` / `IMAGE_<NAME>` defines (shader_program.h puts
// glslUnitDefines() in every prelude) and declare `layout(binding = UNIT_RECORD) uniform ...`.
#include <string>

#include "slicing/gl_objects.h"

namespace vsil::gl {

enum class TextureUnit : GLuint {
  Volume = 0,            // the volume (sampler3D, data units)
  Gradient = 1,          // per-voxel gradient direction and magnitude (sampler3D)
  TransferFunction = 2,  // colour and opacity over the value range (sampler1D)
  ExitDepth = 3,         // where rays leave occupied bricks for good (empty_space.h)
  Footprint = 4,         // silhouette: this slice's footprint
  Contour = 5,           // silhouette (paper pipeline): this slice's contour values
  Record = 6,            // first-hit techniques: the per-pixel record
  Auxiliary0 = 7,        // a technique's own inputs (halo neighbourhood, sphere map, ...)
  Auxiliary1 = 8,
  Auxiliary2 = 9,
  EntryDepth = 10,  // where rays enter occupied bricks, as an image (empty_space.h; tile march)
  Auxiliary3 = 11,
};

enum class ImageUnit : GLuint {
  Record = 0,  // the record updated in place (image load/store)
  Auxiliary0 = 1,
};

// Binds `texture` (of `target`, e.g. GL_TEXTURE_2D) to `unit`; leaves unit 0 active.
void bindTexture(TextureUnit unit, GLenum target, GLuint texture);

// Binds `target`'s texture to `unit` for read-write image load/store.
void bindImage(ImageUnit unit, const RenderTarget& target);

// "#define UNIT_VOLUME 0\n..." for the shader prelude.
std::string glslUnitDefines();

}  // namespace vsil::gl
