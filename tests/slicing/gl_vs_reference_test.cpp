// Every technique against its CPU reference (tests/reference/reference_table.h), pixel by pixel,
// on analytic scenes and classic datasets, with every value of each of its choice options (the
// three pipelines of silhouette and rightangle). The references sample the same positions;
// disagreement is allowed only where a sample lies within kIsoEpsilon of a decision threshold
// (float rounding in the rasteriser may decide such a sample either way), and the count of those is
// reported and bounded.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "frame_compare.h"
#include "generators/generators.h"
#include "gl_harness.h"
#include "io/volume_loader.h"
#include "reference_table.h"
#include "slicing/renderer.h"
#include "slicing/technique_table.h"
#include "test_support.h"

namespace vsil {
namespace {

// Samples are floats in data units; GL and CPU interpolate in float with differently ordered
// operations, so values agree to a few ulps of the data range. 1e-4 of the range is far above
// that and far below any real feature.
constexpr float kIsoEpsilonRelative = 1e-4f;

struct Scene {
  std::string name;
  std::string volume;  // gen:... or a dataset file name
  float iso;
  double azimuth, elevation;
  bool orthographic;
  // False for the large scenes: of the choice options that change only the finishing pass (all
  // but --pipeline: demip's --depth-mode and --sphere-frame), only the first value, which the
  // small scenes cover in full; hundreds of slices per pixel make each case seconds here and
  // tens under the sanitizers.
  bool everyFinishingVariant = true;
};

const Scene kScenes[] = {
    {"sphere_perspective", "gen:sphere:64", 0.5f, 30, 20, false},
    {"sphere_orthographic", "gen:sphere:48", 0.3f, 0, 0, true},
    {"spheres_perspective", "gen:spheres:64", 0.5f, 10, 60, false},
    {"spheres_orthographic", "gen:spheres:64", 0.5f, 90, 0, true},
    {"torus_perspective", "gen:torus:64", 0.5f, 20, 35, false},
    {"torus_edge_on", "gen:torus:64", 0.5f, 0, 80, true},
    // Iso-surfaces that meet the box's faces, seen obliquely and along an axis: where a pixel
    // samples at the box's edge, the shaders' inside test must decide, as the reference's does
    // (slicer.h kPieceMargin: with the slice polygons cut at the box they disagree here).
    {"marschner_lobb_faces", "gen:marschner-lobb:41", 0.5f, 25, 15, false},
    {"marschner_lobb_axis", "gen:marschner-lobb:40", 0.3f, 0, 0, false},
    {"nucleon_dataset", "nucleon_41x41x41_uint8.nhdr", 100.0f, 40, 25, false},
    {"neghip_dataset", "neghip_64x64x64_uint8.nhdr", 60.0f, -50, 10, true},
    // Larger volumes (the nk3 table's iso values): hundreds of slices, tiles that start and stop
    // far apart.
    {"bonsai_dataset", "bonsai.vti", 40.0f, 30, 10, false, false},
    {"engine_dataset", "engine.vti", 90.0f, 40, 25, false, false},
};

struct Case {
  std::string name;
  Scene scene;
  std::string technique;
  OptionValues variant;  // one value of each choice option
};

std::ostream& operator<<(std::ostream& out, const Case& c) {
  return out << c.name;
}

Volume loadScene(const Scene& scene) {
  if (scene.volume.rfind("gen:", 0) == 0) return generateVolume(scene.volume.substr(4));
  return loadVolume(test::datasetPath(scene.volume).string());
}

// Every scene for every technique that has a reference, once per value of its choice options.
std::vector<Case> cases() {
  std::vector<Case> all;
  for (const auto& reference : reference::referenceTable()) {
    const TechniqueInfo& technique = findTechnique(reference.technique);
    std::vector<OptionValues> variants{{}};
    std::map<std::string, std::string> firstChoice;
    for (const auto& option : technique.options) {
      if (option.kind != OptionKind::Choice) continue;
      firstChoice[option.name] = option.choices.front();
      std::vector<OptionValues> expanded;
      for (const auto& variant : variants) {
        for (const auto& choice : option.choices) {
          OptionValues v = variant;
          v[option.name] = choice;
          expanded.push_back(v);
        }
      }
      variants = expanded;
    }
    for (const auto& scene : kScenes) {
      for (const auto& variant : variants) {
        const bool finishingOnly = std::any_of(variant.begin(), variant.end(), [&](const auto& v) {
          return v.first != "pipeline" && std::get<std::string>(v.second) != firstChoice[v.first];
        });
        if (finishingOnly && !scene.everyFinishingVariant) continue;
        std::string name = scene.name + "_" + technique.name;
        for (const auto& [key, value] : variant) name += "_" + std::get<std::string>(value);
        std::replace(name.begin(), name.end(), '-', '_');  // test names: letters, digits, _
        all.push_back({name, scene, technique.name, variant});
      }
    }
  }
  return all;
}

class GlMatchesReference : public test::GlTest, public ::testing::WithParamInterface<Case> {};

TEST_P(GlMatchesReference, PixelByPixel) {
  const Case& c = GetParam();
  if (c.scene.volume.rfind("gen:", 0) != 0) VSIL_REQUIRE_DATASETS();
  const Volume volume = loadScene(c.scene);
  const TechniqueInfo& technique = findTechnique(c.technique);
  const reference::ReferenceTechnique& reference = reference::findReference(c.technique);
  RenderSettings settings;
  settings.technique = c.technique;
  settings.options = test::isoOptions(technique, c.scene.iso);
  settings.options.insert(c.variant.begin(), c.variant.end());
  settings.options.insert(reference.caseOptions.begin(), reference.caseOptions.end());
  settings.size = {128, 112};
  settings.camera.azimuthDeg = c.scene.azimuth;
  settings.camera.elevationDeg = c.scene.elevation;
  settings.camera.orthographic = c.scene.orthographic;
  settings.camera.zoom = 1.5;
  // The state techniques tone-fill their first hits (--fill tone), in a colour that leaves room
  // for the warm and cool tones below white.
  if (technique.outputs.state) settings.toneFill = Rgba{110, 120, 100, 255};
  const ValueRange range = valueRange(volume);
  const float epsilon = kIsoEpsilonRelative * std::max(1.0f, range.max - range.min);
  const reference::ReferenceFrame cpu = reference.render(volume, settings, epsilon);
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  const RenderResult gl = renderer.render(settings);
  ASSERT_EQ(gl.sliceCount, cpu.sliceCount);
  if (technique.outputs.state) {
    ASSERT_FALSE(gl.frame.tone.empty()) << "the tone fill was asked for";
    ASSERT_FALSE(cpu.frame.tone.empty());
  }

  int unexplained = 0, ambiguous = 0, shown = test::shownPixels(cpu.frame), lines = 0, flagged = 0;
  std::ostringstream firstMismatches;
  double maxDepthError = 0, maxShadeError = 0, maxToneError = 0, maxColorError = 0;
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      bool same = true;
      flagged += cpu.ambiguous(y, x) != 0;
      if (technique.outputs.state) {
        const auto glState = PixelState(gl.frame.state(y, x));
        const auto cpuState = PixelState(cpu.frame.state(y, x));
        lines += cpuState == PixelState::Silhouette;
        same = glState == cpuState;
        if (same && glState != PixelState::Empty && !cpu.ambiguous(y, x)) {
          maxDepthError = std::max(maxDepthError,
                                   double(std::abs(gl.frame.depth(y, x) - cpu.frame.depth(y, x))));
          if (glState == PixelState::Filled) {
            maxShadeError = std::max(
                maxShadeError, double(std::abs(gl.frame.shade(y, x) - cpu.frame.shade(y, x))));
            for (int k = 0; k < 3; ++k) {
              maxToneError = std::max(
                  maxToneError, double(std::abs(gl.frame.tone(y, x)[k] - cpu.frame.tone(y, x)[k])));
            }
          }
        }
      }
      if (technique.outputs.depth && !technique.outputs.state) {
        const float a = gl.frame.depth(y, x), b = cpu.frame.depth(y, x);
        const bool bothNone = std::isnan(a) && std::isnan(b);
        const double error = bothNone ? 0.0 : std::abs(double(a) - double(b));
        same = same && (bothNone || error < 1e-5);
        if (!bothNone && !std::isnan(error) && !cpu.ambiguous(y, x)) {
          maxDepthError = std::max(maxDepthError, error);
        }
      }
      if (technique.outputs.color) {
        double error = 0;
        for (int k = 0; k < 4; ++k) {
          error =
              std::max(error, double(std::abs(gl.frame.color(y, x)[k] - cpu.frame.color(y, x)[k])));
        }
        same = same && error <= reference.colorTolerance;
        if (!cpu.ambiguous(y, x)) maxColorError = std::max(maxColorError, error);
      }
      if (same) continue;
      if (cpu.ambiguous(y, x)) {
        ++ambiguous;
      } else if (++unexplained <= 5) {
        firstMismatches << " (" << x << "," << y << ")";
        if (technique.outputs.state) {
          firstMismatches << " gl=" << int(gl.frame.state(y, x))
                          << " cpu=" << int(cpu.frame.state(y, x));
        }
        firstMismatches << ";";
      }
    }
  }
  RecordProperty("near_iso_mismatches", ambiguous);
  std::cout << "[ info ] " << c.name << ": " << shown << " pixels shown, " << lines
            << " line pixels; " << flagged << " pixels the reference calls ambiguous, " << ambiguous
            << " of them mismatched; max depth error " << maxDepthError << ", max shade error "
            << maxShadeError << ", max tone error " << maxToneError << ", max colour error "
            << maxColorError << "\n";
  EXPECT_GT(shown, 10) << "the scene should show something";
  if (technique.outputs.state) {
    EXPECT_GT(lines, 10) << "the scene should show lines";
  }
  EXPECT_EQ(unexplained, 0) << "mismatches away from decision thresholds:" << firstMismatches.str();
  // Near-threshold disagreements are rare: at most 1 % of the pixels shown (the line pixels
  // where a technique draws lines) unless the technique's reference says why more.
  EXPECT_LE(ambiguous, std::max(2, int((lines > 0 ? lines : shown) * reference.ambiguousShare)));
  // Depths are slice depths (or the mean of two), computed identically: float rounding only.
  EXPECT_LT(maxDepthError, 1e-5);
  // Shades come from 6 trilinear samples each, differences of nearly equal floats.
  EXPECT_LT(maxShadeError, 2e-3);
  // Tone colours come from the same normal (the shade's error times k_d, k_td and the lights)
  // and pow(d, k_de) of equal depths: as small, and far below one 8-bit step (0.004).
  EXPECT_LT(maxToneError, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GlMatchesReference, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

// Every technique of the table has a CPU reference: a new one cannot join untested.
TEST(ReferenceTable, CoversEveryTechnique) {
  for (const auto& technique : techniqueTable()) {
    EXPECT_NO_THROW(reference::findReference(technique.name)) << technique.name;
  }
}

}  // namespace
}  // namespace vsil
