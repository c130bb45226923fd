#pragma once
// demip's colour sphere (Díaz & Vázquez, Figure 7): a colour for each direction from the
// volume's centre to a pixel's first hit, read in the sphere's frame: x its right, y its up, z its
// front. Unturned in the view's frame (--sphere-rotate 0,0, --sphere-frame view) the front faces
// the viewer, up is the image's up and right the image's right (sphereFrameEye).
//
// --sphere-map names the map:
//  - red-blue, green-red, green-blue (built in): the first colour at the front, the second at
//    the back, blended linearly in the cosine between the direction and the front.
//  - FILE.png: an equirectangular map. Longitude λ = atan2(x, z) runs across the width, latitude
//    φ = atan2(y, √(x² + z²)) down the height:
//        u = 0.5 + λ/2π  (0 at the left edge),  v = 0.5 − φ/π  (0 at the top row),
//    so the image's centre is the front, facing the viewer (a PNG red in its centre and blue at
//    its edges behaves like red-blue), three quarters of its width the sphere's right (+x), its
//    left and right edges the back, its top row up. Read as OpenGL reads the texture: bilinear
//    between texel centres (GL_LINEAR, no mipmaps), wrapping around in u, clamped in v.
//    Grey, RGB or RGBA, 8 or 16 bits (alpha is ignored), at most limits::kMaxSphereMapSide
//    pixels per side and kMaxSphereMapPixels in all.
// A direction of length 0 (a hit at the centre itself) takes the built-in maps' middle colour
// and an image's centre.
//
// The GPU twin is sphereColour() in mip_finish.frag; the CPU reference
// (tests/reference/mip_reference.cpp) samples the map again on its own. What here reads colours
// serves --legend.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/options.h"

namespace vsil {

// The built-in maps: `front` toward the sphere's front, `back` away from it.
struct SphereMap {
  std::string name;
  glm::vec3 front;
  glm::vec3 back;
};
const std::vector<SphereMap>& sphereMaps();

// An equirectangular map's texels: straight RGB in [0, 1], rows top-down (row 0 is the
// latitude +90° edge), as uploaded to the texture.
struct SphereMapImage {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> texels;
  const glm::vec3& at(int x, int y) const {
    return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
  }
};

// --sphere-map as given: a built-in's name, or a file when it ends in .png.
bool isSphereMapFile(std::string_view text);

// What --sphere-map names, resolved: a built-in's colours, or a file's texels.
struct ColourSphere {
  std::string name;  // as given
  glm::vec3 front{0.0f}, back{0.0f};
  std::optional<SphereMapImage> image;

  // The colour toward `directionSphere` (in the sphere's frame, any length).
  glm::vec3 colourAt(glm::vec3 directionSphere) const;
};

// Checks --sphere-map without decoding an image: a known name, or a PNG file whose header
// declares a size within the limits. InputError naming --sphere-map for an unknown name
// ("unknown map 'x' (known: red-blue, green-red, green-blue, or FILE.png)"), naming the file for
// a missing, empty, non-PNG or oversized one.
void checkSphereMap(const std::string& nameOrFile);
// The same checks, then the built-in's colours or the file's texels (core/image_file.h readPng:
// InputError naming the file when it is truncated, corrupt or cannot be decoded). Errors about
// a file end in "(--sphere-map)".
ColourSphere colourSphere(const std::string& nameOrFile);

// The equirectangular texture coordinates (u, v) of a direction in the sphere's frame (length
// above 0): the convention above.
glm::vec2 sphereMapTexCoord(glm::vec3 directionSphere);

// The sphere's frame in eye space, columns right, up, front: +x, +y, +z eye turned by
// --sphere-rotate AZ,EL (AZ about +y, then EL towards +y, as --view orbits the camera), in the
// view's frame (`view`) or the volume's (`volume`: world axes, then seen through the camera, so
// colours stay on the structures while the view orbits).
glm::mat3 sphereFrameEye(const OptionReader& options, const View& view);
// Its third column: where the map's front points.
glm::vec3 sphereFrontEye(const OptionReader& options, const View& view);

}  // namespace vsil
