#include "slicing/texture_units.h"

#include <utility>

namespace vsil::gl {

void bindTexture(TextureUnit unit, GLenum target, GLuint texture) {
  glActiveTexture(GL_TEXTURE0 + GLenum(unit));
  glBindTexture(target, texture);
  glActiveTexture(GL_TEXTURE0);
}

void bindImage(ImageUnit unit, const RenderTarget& target) {
  VSIL_GL(glBindImageTexture(GLuint(unit), target.texture(), 0, GL_FALSE, 0, GL_READ_WRITE,
                             target.internalFormat()));
}

std::string glslUnitDefines() {
  static const std::pair<const char*, TextureUnit> textures[] = {
      {"VOLUME", TextureUnit::Volume},
      {"GRADIENT", TextureUnit::Gradient},
      {"TRANSFER_FUNCTION", TextureUnit::TransferFunction},
      {"EXIT_DEPTH", TextureUnit::ExitDepth},
      {"FOOTPRINT", TextureUnit::Footprint},
      {"CONTOUR", TextureUnit::Contour},
      {"RECORD", TextureUnit::Record},
      {"AUXILIARY0", TextureUnit::Auxiliary0},
      {"AUXILIARY1", TextureUnit::Auxiliary1},
      {"AUXILIARY2", TextureUnit::Auxiliary2},
      {"ENTRY_DEPTH", TextureUnit::EntryDepth},
      {"AUXILIARY3", TextureUnit::Auxiliary3},
  };
  static const std::pair<const char*, ImageUnit> images[] = {
      {"RECORD", ImageUnit::Record},
      {"AUXILIARY0", ImageUnit::Auxiliary0},
  };
  std::string text;
  for (const auto& [name, unit] : textures) {
    text += "#define UNIT_" + std::string(name) + " " + std::to_string(GLuint(unit)) + "\n";
  }
  for (const auto& [name, unit] : images) {
    text += "#define IMAGE_" + std::string(name) + " " + std::to_string(GLuint(unit)) + "\n";
  }
  return text;
}

}  // namespace vsil::gl
