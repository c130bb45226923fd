#include "slicing/techniques/mip/colour_sphere.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/image_file.h"
#include "core/limits.h"
#include "core/number_pair.h"

namespace vsil {

namespace {

const SphereMap* findBuiltin(const std::string& name) {
  for (const auto& map : sphereMaps()) {
    if (map.name == name) return &map;
  }
  return nullptr;
}

// Errors about the file say which flag named it: "map.png: no such file (--sphere-map)".
template <typename Read>
auto readingMapFile(Read read) {
  try {
    return read();
  } catch (const InputError& error) {
    throw InputError(std::string(error.what()) + " (--sphere-map)");
  }
}

// The size a map file declares, within the limits; InputError naming the file otherwise.
cv::Size checkedMapSize(const std::string& file) {
  const cv::Size size = readPngSize(file);
  if (size.width > limits::kMaxSphereMapSide || size.height > limits::kMaxSphereMapSide ||
      std::int64_t(size.width) * size.height > limits::kMaxSphereMapPixels) {
    throwInputError(file, std::to_string(size.width) + "x" + std::to_string(size.height) +
                              " pixels is over the limit for a sphere map (" +
                              std::to_string(limits::kMaxSphereMapSide) + " per side, " +
                              std::to_string(limits::kMaxSphereMapPixels) + " in all)");
  }
  return size;
}

SphereMapImage readMapImage(const std::string& file) {
  checkedMapSize(file);
  const cv::Mat image = readPng(file);
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throwInputError(file, "sphere maps must have 8 or 16 bits per channel");
  }
  cv::Mat rgb;
  switch (image.channels()) {
    case 1:
      cv::cvtColor(image, rgb, cv::COLOR_GRAY2RGB);
      break;
    case 3:
      cv::cvtColor(image, rgb, cv::COLOR_BGR2RGB);
      break;
    case 4:
      cv::cvtColor(image, rgb, cv::COLOR_BGRA2RGB);  // alpha has no meaning for a colour
      break;
    default:
      throwInputError(file, "sphere maps must be grey, RGB or RGBA");
  }
  cv::Mat3f floats;
  rgb.convertTo(floats, CV_32FC3, image.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0);
  SphereMapImage map;
  map.width = floats.cols;
  map.height = floats.rows;
  map.texels.reserve(std::size_t(map.width) * std::size_t(map.height));
  for (int y = 0; y < floats.rows; ++y) {
    for (int x = 0; x < floats.cols; ++x) {
      const cv::Vec3f& p = floats(y, x);
      map.texels.emplace_back(p[0], p[1], p[2]);
    }
  }
  return map;
}

// What GL_LINEAR reads from the map at (u, v): u wraps around (GL_REPEAT), v is clamped to the
// edge texels (GL_CLAMP_TO_EDGE).
glm::vec3 sampleBilinear(const SphereMapImage& map, glm::vec2 uv) {
  const float x = uv.x * float(map.width) - 0.5f, y = uv.y * float(map.height) - 0.5f;
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  const auto wrap = [&](int i) { return ((i % map.width) + map.width) % map.width; };
  const auto clampRow = [&](int j) { return std::clamp(j, 0, map.height - 1); };
  const int i0 = wrap(int(x0)), i1 = wrap(int(x0) + 1);
  const int j0 = clampRow(int(y0)), j1 = clampRow(int(y0) + 1);
  const glm::vec3 top = glm::mix(map.at(i0, j0), map.at(i1, j0), fx);
  const glm::vec3 bottom = glm::mix(map.at(i0, j1), map.at(i1, j1), fx);
  return glm::mix(top, bottom, fy);
}

}  // namespace

const std::vector<SphereMap>& sphereMaps() {
  static const std::vector<SphereMap> maps{
      {"red-blue", {1, 0, 0}, {0, 0, 1}},
      {"green-red", {0, 1, 0}, {1, 0, 0}},
      {"green-blue", {0, 1, 0}, {0, 0, 1}},
  };
  return maps;
}

bool isSphereMapFile(std::string_view text) {
  if (text.size() < 4) return false;
  std::string tail(text.substr(text.size() - 4));
  std::transform(tail.begin(), tail.end(), tail.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return tail == ".png";
}

void checkSphereMap(const std::string& nameOrFile) {
  if (findBuiltin(nameOrFile)) return;
  if (isSphereMapFile(nameOrFile)) {
    readingMapFile([&] { return checkedMapSize(nameOrFile); });
    return;
  }
  std::string known;
  for (const auto& map : sphereMaps()) known += map.name + ", ";
  // Something of that name exists (a folder, a FIFO, a file not named .png): it was meant as
  // a file, and calling it an unknown map name would mislead.
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(nameOrFile, error);
  if (!error && std::filesystem::exists(status)) {
    const std::string what = std::filesystem::is_directory(status)      ? "is a directory"
                             : std::filesystem::is_regular_file(status) ? "is a file not named .png"
                                                                        : "is not a regular file";
    throwInputError(nameOrFile, what + " (--sphere-map takes a map name, " + known +
                                    "or an equirectangular FILE.png)");
  }
  throwInputError("--sphere-map", "unknown map '" + nameOrFile + "' (known: " + known +
                                      "or an equirectangular FILE.png)");
}

ColourSphere colourSphere(const std::string& nameOrFile) {
  checkSphereMap(nameOrFile);
  ColourSphere sphere;
  sphere.name = nameOrFile;
  if (const SphereMap* builtin = findBuiltin(nameOrFile)) {
    sphere.front = builtin->front;
    sphere.back = builtin->back;
  } else {
    sphere.image = readingMapFile([&] { return readMapImage(nameOrFile); });
  }
  return sphere;
}

glm::vec2 sphereMapTexCoord(glm::vec3 d) {
  // Straight up or down the longitude is arbitrary: 0 (as mip_finish.frag takes it).
  const float longitude = d.x != 0 || d.z != 0 ? std::atan2(d.x, d.z) : 0.0f;
  const float latitude = std::atan2(d.y, std::sqrt(d.x * d.x + d.z * d.z));
  return {0.5f + longitude / (2.0f * std::numbers::pi_v<float>),
          0.5f - latitude / std::numbers::pi_v<float>};
}

glm::vec3 ColourSphere::colourAt(glm::vec3 directionSphere) const {
  const float length2 = glm::dot(directionSphere, directionSphere);
  if (image) {
    return sampleBilinear(*image,
                          length2 > 0 ? sphereMapTexCoord(directionSphere) : glm::vec2(0.5f));
  }
  const float facing = length2 > 0 ? directionSphere.z / std::sqrt(length2) : 0.0f;
  return glm::mix(back, front, 0.5f + 0.5f * facing);
}

glm::mat3 sphereFrameEye(const OptionReader& options, const View& view) {
  const glm::dvec2 turn = parseNumberPair("--sphere-rotate", options.text("sphere-rotate"));
  const double az = glm::radians(turn.x), el = glm::radians(turn.y);
  // +x, +y, +z turned by EL about −x (z towards +y), then by AZ about +y.
  const glm::dvec3 right(std::cos(az), 0.0, -std::sin(az));
  const glm::dvec3 up(-std::sin(el) * std::sin(az), std::cos(el), -std::sin(el) * std::cos(az));
  const glm::dvec3 front(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  if (options.text("sphere-frame") == "view") return glm::mat3(glm::dmat3(right, up, front));
  // The volume's frame is world space (camera.h: worldFromVoxel scales by the spacing only).
  const glm::dmat3 eyeFromWorld(view.eyeFromWorld);
  return glm::mat3(glm::dmat3(glm::normalize(eyeFromWorld * right),
                              glm::normalize(eyeFromWorld * up),
                              glm::normalize(eyeFromWorld * front)));
}

glm::vec3 sphereFrontEye(const OptionReader& options, const View& view) {
  return sphereFrameEye(options, view)[2];
}

}  // namespace vsil
