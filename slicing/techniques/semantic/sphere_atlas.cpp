#include "slicing/techniques/semantic/sphere_atlas.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/image_file.h"
#include "core/limits.h"

namespace vsil {

namespace {

// One built-in sphere: Lambert from the upper left and a little from the viewer, a soft
// highlight, opacity `alpha`. Texels beyond the disc take the rim's normal (the shader's normals
// reach the rim and linear filtering reads one texel beyond).
glm::vec4 shadedSphereTexel(glm::vec3 base, float u, float v, float alpha) {
  glm::vec2 xy(u * 2.0f - 1.0f, v * 2.0f - 1.0f);
  const float length = glm::length(xy);
  if (length > 1.0f) xy /= length;
  const glm::vec3 n(xy, std::sqrt(std::max(0.0f, 1.0f - glm::dot(xy, xy))));
  const glm::vec3 light = glm::normalize(glm::vec3(-0.45f, 0.55f, 0.7f));
  const glm::vec3 half = glm::normalize(light + glm::vec3(0, 0, 1));
  const float diffuse = std::max(glm::dot(n, light), 0.0f);
  const float specular = std::pow(std::max(glm::dot(n, half), 0.0f), 24.0f);
  const glm::vec3 color = base * (0.3f + 0.7f * diffuse) + glm::vec3(0.25f * specular);
  return glm::vec4(glm::clamp(color, 0.0f, 1.0f), alpha);
}

std::string quoted(const std::string& text) {
  return "\"" + text + "\"";
}

}  // namespace

glm::vec3 builtinSphereColor(const std::string& name) {
  if (name == "gray") return {0.62f, 0.62f, 0.62f};
  if (name == "ivory") return {1.0f, 0.95f, 0.82f};
  if (name == "skin") return {0.94f, 0.71f, 0.58f};
  if (name == "red") return {0.86f, 0.22f, 0.16f};
  if (name == "green") return {0.27f, 0.70f, 0.32f};
  if (name == "blue") return {0.22f, 0.42f, 0.86f};
  throw std::out_of_range("no built-in sphere ramp '" + name + "'");
}

std::vector<std::vector<glm::vec4>> sphereRamp(const Spheres& spheres, const std::string& where,
                                               int cell) {
  std::vector<std::vector<glm::vec4>> ramp;
  if (!spheres.builtin.empty()) {
    const glm::vec3 base = builtinSphereColor(spheres.builtin);
    for (int k = 0; k < kBuiltinSpheres; ++k) {
      const float alpha = float(k) / float(kBuiltinSpheres - 1);
      std::vector<glm::vec4> sphere(std::size_t(cell) * std::size_t(cell));
      for (int y = 0; y < cell; ++y) {
        for (int x = 0; x < cell; ++x) {
          sphere[std::size_t(y) * std::size_t(cell) + std::size_t(x)] = shadedSphereTexel(
              base, (float(x) + 0.5f) / float(cell), (float(y) + 0.5f) / float(cell), alpha);
        }
      }
      ramp.push_back(std::move(sphere));
    }
    return ramp;
  }
  const std::string file = spheres.file.string();
  const std::string context = " (spheres " + quoted(spheres.text) + " at " + where + ")";
  // OpenCV warns on stderr about a file it cannot open: only files that exist reach it.
  std::error_code error;
  if (!std::filesystem::is_regular_file(spheres.file, error)) {
    throwInputError(file, "no such sphere image" + context);
  }
  // The checks of every PNG input (core/image_file.h readPng), and a size from the header
  // before anything is decoded: the strip is kept as floats, as a sphere map is.
  const cv::Mat image = [&] {
    try {
      const cv::Size size = readPngSize(spheres.file);
      if (std::int64_t(size.width) * size.height > limits::kMaxSphereMapPixels) {
        throwInputError(file, std::to_string(size.width) + "x" + std::to_string(size.height) +
                                  " pixels is over the limit of " +
                                  std::to_string(limits::kMaxSphereMapPixels) +
                                  " for a sphere image");
      }
      return readPng(spheres.file);
    } catch (const InputError& e) {
      throw InputError(e.what() + context);
    }
  }();
  const int height = image.rows, width = image.cols;
  if (height < 2 || width % height != 0 || width / height > kMaxSpheresPerStrip) {
    throwInputError(file, "a strip of spheres must be 1 to " + std::to_string(kMaxSpheresPerStrip) +
                              " square images side by side, not " + std::to_string(width) + "x" +
                              std::to_string(height) + " pixels" + context);
  }
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throwInputError(file, "sphere images must have 8 or 16 bits per channel" + context);
  }
  cv::Mat rgba;
  switch (image.channels()) {
    case 1:
      cv::cvtColor(image, rgba, cv::COLOR_GRAY2RGBA);
      break;
    case 3:
      cv::cvtColor(image, rgba, cv::COLOR_BGR2RGBA);
      break;
    case 4:
      cv::cvtColor(image, rgba, cv::COLOR_BGRA2RGBA);
      break;
    default:
      throwInputError(file, "sphere images must be grey, RGB or RGBA" + context);
  }
  cv::Mat4f floats;
  rgba.convertTo(floats, CV_32FC4, image.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0);
  for (int k = 0; k < width / height; ++k) {
    cv::Mat4f resized;
    cv::resize(floats(cv::Rect(k * height, 0, height, height)), resized, cv::Size(cell, cell), 0, 0,
               height > cell ? cv::INTER_AREA : cv::INTER_LINEAR);
    std::vector<glm::vec4> sphere(std::size_t(cell) * std::size_t(cell));
    for (int y = 0; y < cell; ++y) {
      for (int x = 0; x < cell; ++x) {
        const cv::Vec4f& p = resized(cell - 1 - y, x);  // rows bottom-up
        sphere[std::size_t(y) * std::size_t(cell) + std::size_t(x)] =
            glm::clamp(glm::vec4(p[0], p[1], p[2], p[3]), 0.0f, 1.0f);
      }
    }
    ramp.push_back(std::move(sphere));
  }
  return ramp;
}

SphereAtlas buildSphereAtlas(const RuleBase& rules, int cell) {
  SphereAtlas atlas;
  atlas.cell = cell;
  for (const Style& style : rules.styles) {
    const std::string where = rules.source + ":" + std::to_string(style.position.line) + ":" +
                              std::to_string(style.position.column);
    const auto ramp = sphereRamp(style.spheres, where, cell);
    atlas.firstLayer.push_back(atlas.depth);
    atlas.sphereCount.push_back(int(ramp.size()));
    atlas.depth += int(ramp.size());
    for (const auto& sphere : ramp)
      atlas.texels.insert(atlas.texels.end(), sphere.begin(), sphere.end());
  }
  if (atlas.depth == 0) {  // no styles: one transparent layer keeps the texture valid
    atlas.depth = 1;
    atlas.texels.assign(std::size_t(cell) * std::size_t(cell), glm::vec4(0.0f));
  }
  return atlas;
}

}  // namespace vsil
