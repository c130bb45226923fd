// Analytic truth: silhouettes of spheres whose outlines are known exactly; the right-angle
// line against the exact silhouettes of the analytic torus and sphere.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "analytic_volumes.h"
#include "generators/generators.h"
#include "gl_harness.h"
#include "slicing/renderer.h"

namespace vsil {
namespace {

// Projected centre (pixels, top-left origin) and radius (pixels) of a ball in an orthographic
// view: the silhouette of a sphere is a circle of the sphere's radius around its projection.
struct Circle {
  glm::dvec2 centre;
  double radius;
};

Circle projectBall(const test::Ball& ball, const View& view) {
  const glm::dvec4 clip = view.clipFromVoxel() * glm::dvec4(ball.centreVoxel, 1.0);
  const glm::dvec2 pixel((clip.x / clip.w + 1) * 0.5 * view.viewport.x,
                         (1 - clip.y / clip.w) * 0.5 * view.viewport.y);
  // World units per voxel (spacing 1) is worldFromVoxel's scale; pixels per world unit from
  // the orthographic half extent.
  const double worldPerVoxel = view.worldFromVoxel[0][0];
  const double pixelsPerWorld = view.viewport.y / (2.0 * view.halfExtent.y);
  return {pixel, ball.radiusVoxels * worldPerVoxel * pixelsPerWorld};
}

RenderResult renderOrthographic(const Volume& volume, glm::ivec2 size, double azimuth = 0,
                                double elevation = 0) {
  RenderSettings settings;
  settings.size = size;
  settings.options["iso"] = 0.5;
  settings.camera.orthographic = true;
  settings.camera.azimuthDeg = azimuth;
  settings.camera.elevationDeg = elevation;
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  return renderer.render(settings);
}

using SilhouetteAnalytic = test::GlTest;

TEST_F(SilhouetteAnalytic, SeparatedSpheresGiveOnePixelCirclesAtTheProjectedRadius) {
  const std::vector<test::Ball> balls = {
      {{24, 40, 30}, 14.0}, {{72, 40, 50}, 10.0}, {{50, 76, 40}, 7.5}};
  const Volume volume = test::ballsVolume({96, 96, 80}, balls);
  const RenderResult result = renderOrthographic(volume, {320, 320});
  std::vector<Circle> circles;
  for (const auto& ball : balls) circles.push_back(projectBall(ball, result.view));

  std::vector<int> onCircle(balls.size(), 0);
  for (int y = 0; y < result.frame.height(); ++y) {
    for (int x = 0; x < result.frame.width(); ++x) {
      if (PixelState(result.frame.state(y, x)) != PixelState::Silhouette) continue;
      const glm::dvec2 p(x + 0.5, y + 0.5);
      // Which circle's outline is nearest, and how far off.
      std::size_t best = 0;
      double bestOff = 1e9;
      for (std::size_t i = 0; i < circles.size(); ++i) {
        const double off = glm::length(p - circles[i].centre) - circles[i].radius;
        if (std::abs(off) < std::abs(bestOff)) {
          bestOff = off;
          best = i;
        }
      }
      // Silhouette pixels are filled pixels at the rim: centres within one pixel inside the
      // exact circle (plus the trilinear reconstruction's sub-pixel error).
      EXPECT_LE(bestOff, 0.25) << "at (" << x << "," << y << ")";
      EXPECT_GE(bestOff, -1.5) << "at (" << x << "," << y << ")";
      ++onCircle[best];
    }
  }
  for (std::size_t i = 0; i < circles.size(); ++i) {
    // Thinness: a one-pixel 8-connected digital circle has between 1 and sqrt(2)·... pixels
    // per unit length (about 1.27 on average over orientations for an inner boundary);
    // a doubled line would be near 2.
    const double perLength = onCircle[i] / (2 * std::numbers::pi * circles[i].radius);
    EXPECT_GE(perLength, 0.8) << "circle " << i;
    EXPECT_LE(perLength, 1.4) << "circle " << i;
  }
}

TEST_F(SilhouetteAnalytic, OverlappingSpheresShowOnlyTheVisibleOutline) {
  // Front ball (nearer the eye at azimuth 0: larger z) overlaps a back ball in projection.
  const test::Ball front{{44, 48, 62}, 18.0};
  const test::Ball back{{66, 48, 30}, 20.0};
  const Volume volume = test::ballsVolume({112, 96, 96}, {front, back});
  const RenderResult result = renderOrthographic(volume, {320, 300});
  const Circle f = projectBall(front, result.view), b = projectBall(back, result.view);
  ASSERT_LT(glm::length(f.centre - b.centre), f.radius + b.radius) << "they must overlap";

  int frontRim = 0, backRim = 0, hidden = 0, interior = 0;
  for (int y = 0; y < result.frame.height(); ++y) {
    for (int x = 0; x < result.frame.width(); ++x) {
      if (PixelState(result.frame.state(y, x)) != PixelState::Silhouette) continue;
      const glm::dvec2 p(x + 0.5, y + 0.5);
      const double offFront = glm::length(p - f.centre) - f.radius;
      const double offBack = glm::length(p - b.centre) - b.radius;
      if (offFront <= 0.25 && offFront >= -1.5) {
        ++frontRim;  // the front sphere's whole outline is visible
      } else if (offBack <= 0.25 && offBack >= -1.5) {
        // The back sphere's outline is visible only outside the front disc.
        if (offFront < 0)
          ++hidden;
        else
          ++backRim;
      } else {
        ++interior;
      }
    }
  }
  EXPECT_EQ(hidden, 0) << "silhouette of the back sphere drawn through the front one";
  EXPECT_EQ(interior, 0) << "silhouette pixels away from both outlines (double lines?)";
  EXPECT_GT(frontRim, int(2 * std::numbers::pi * f.radius * 0.8));
  EXPECT_GT(backRim, int(std::numbers::pi * b.radius * 0.5));
}

// A view that clips the object: the sphere crosses the right and bottom borders of the frame.
// Its silhouette is the visible arc of its circle and nothing else: off-screen neighbours are
// not known, so the rows and columns along the border hold no line (they once did, wherever
// the surface crossed the border). Every pipeline, and precision and recall against the
// exact circle (a rim pixel: centre within 1.5 px inside to 0.25 px outside of it, as above).
TEST_F(SilhouetteAnalytic, AViewThatClipsTheSphereDrawsNoLineAlongTheFrame) {
  const test::Ball ball{{58, 26, 40}, 20.0};
  const Volume volume = test::ballsVolume({80, 80, 80}, {ball});
  for (const char* pipeline : {"fast", "paper", "tiles"}) {
    SCOPED_TRACE(pipeline);
    RenderSettings settings;
    settings.size = {160, 140};
    settings.options["iso"] = 0.5;
    settings.options["pipeline"] = std::string(pipeline);
    settings.camera.orthographic = true;
    settings.camera.azimuthDeg = 0;
    settings.camera.elevationDeg = 0;
    settings.camera.zoom = 3.0;
    Renderer renderer(test::sharedGlContext());
    renderer.setVolume(volume);
    const RenderResult result = renderer.render(settings);
    const Circle circle = projectBall(ball, result.view);
    const int w = result.frame.width(), h = result.frame.height();
    ASSERT_GT(circle.centre.x + circle.radius, w + 10) << "the sphere must cross the right border";
    ASSERT_GT(circle.centre.y + circle.radius, h + 10) << "and the bottom one";
    int truePositives = 0, falsePositives = 0, onBorder = 0, rimPixels = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const glm::dvec2 p(x + 0.5, y + 0.5);
        const double off = glm::length(p - circle.centre) - circle.radius;
        const bool rim = off <= 0.25 && off >= -1.5;
        const bool line = PixelState(result.frame.state(y, x)) == PixelState::Silhouette;
        // Recall counts the rim pixels a one-pixel line must hold: inside by more than the
        // reconstruction's error (0.25 px), and within half a pixel, so that the neighbour
        // outward (at least 0.92 px further out) is outside.
        const bool mustHold = off <= -0.25 && off >= -0.5;
        rimPixels += mustHold;
        truePositives += line && mustHold;
        falsePositives += line && !rim;
        onBorder += line && (x == 0 || y == 0 || x == w - 1 || y == h - 1) && !rim;
      }
    }
    ASSERT_GT(rimPixels, 20);
    EXPECT_EQ(onBorder, 0) << "a line along the frame";
    int lines = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        lines += PixelState(result.frame.state(y, x)) == PixelState::Silhouette;
    const double precision = 1.0 - double(falsePositives) / std::max(lines, 1);
    const double recall = double(truePositives) / rimPixels;
    EXPECT_GE(precision, 0.99) << falsePositives << " of " << lines << " line pixels off the rim";
    EXPECT_GE(recall, 0.99) << truePositives << " of " << rimPixels << " rim pixels drawn";
  }
}

TEST_F(SilhouetteAnalytic, SilhouetteDepthIsWhereTheViewRayGrazesTheSphere) {
  const test::Ball ball{{40, 40, 40}, 20.0};
  const Volume volume = test::ballsVolume({80, 80, 80}, {ball});
  const RenderResult result = renderOrthographic(volume, {200, 200}, 25, 15);
  const double centreDistance = -(result.view.eyeFromVoxel * glm::dvec4(ball.centreVoxel, 1)).z;
  const double expected = result.view.normalizedDepth(centreDistance);
  int count = 0;
  double sum = 0;
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 200; ++x) {
      if (PixelState(result.frame.state(y, x)) != PixelState::Silhouette) continue;
      sum += result.frame.depth(y, x);
      ++count;
      // Each rim pixel's ray grazes the sphere over a chord centred on the centre's depth;
      // half a slice of quantization either way.
      EXPECT_NEAR(result.frame.depth(y, x), expected, 1.0 / result.sliceCount + 1e-6);
    }
  }
  ASSERT_GT(count, 50);
  EXPECT_NEAR(sum / count, expected, 0.5 / result.sliceCount);
}

TEST_F(SilhouetteAnalytic, RenderingIsDeterministic) {
  const Volume volume = test::ballsVolume({64, 64, 64}, {{{30, 34, 32}, 17.0}});
  RenderSettings settings;
  settings.size = {150, 130};
  settings.options["iso"] = 0.5;
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  for (const char* technique : {"silhouette", "rightangle"}) {
    settings.technique = technique;
    const RenderResult a = renderer.render(settings);
    const RenderResult b = renderer.render(settings);
    EXPECT_EQ(cv::norm(a.frame.state, b.frame.state, cv::NORM_INF), 0) << technique;
    cv::Mat depthA = a.frame.depth.clone(), depthB = b.frame.depth.clone();
    cv::patchNaNs(depthA, -1);
    cv::patchNaNs(depthB, -1);
    EXPECT_EQ(cv::norm(depthA, depthB, cv::NORM_INF), 0) << technique;
  }
}

// The right-angle line with its default (k, ε) on smooth analytic surfaces: continuous and
// thin. The exact one-pixel silhouettes (technique `silhouette`) are the truth: every one of
// them should have a line pixel within one pixel (a gap in the line leaves silhouette pixels
// without one), and the line's pixels should number at most three per silhouette pixel (a band
// ~3 px wide on average). The defaults draw |n·v| < 0.33, a band about r·0.33²/2 px wide where
// the outline's radial curvature radius is r px (rightangle_technique.cpp): the cases span r
// from ~9 px (the torus tube at 256²) to ~55 px (the sphere at 256²). The old defaults
// (8, 0.3: |n·v| < 0.14) leave 30–50 % of the torus's silhouette pixels without a line pixel.
struct RightAngleCase {
  std::string name;
  std::string volume;
  int size;
  double azimuth, elevation;
  bool orthographic;
};

std::ostream& operator<<(std::ostream& out, const RightAngleCase& c) {
  return out << c.name;
}

class RightAngleLine : public test::GlTest, public ::testing::WithParamInterface<RightAngleCase> {};

TEST_P(RightAngleLine, DefaultsGiveAContinuousThinLineOnSmoothSurfaces) {
  const RightAngleCase& c = GetParam();
  const Volume volume = generateVolume(c.volume);
  RenderSettings settings;
  settings.size = {c.size, c.size};
  settings.camera.orthographic = c.orthographic;
  settings.camera.azimuthDeg = c.azimuth;
  settings.camera.elevationDeg = c.elevation;
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  settings.technique = "silhouette";
  const RenderResult exact = renderer.render(settings);
  settings.technique = "rightangle";
  const RenderResult ra = renderer.render(settings);
  const auto isLine = [](const FrameBuffers& f, int y, int x) {
    return PixelState(f.state(y, x)) == PixelState::Silhouette;
  };
  int silhouettePixels = 0, covered = 0, linePixels = 0;
  std::string firstGaps;
  for (int y = 0; y < c.size; ++y) {
    for (int x = 0; x < c.size; ++x) {
      linePixels += isLine(ra.frame, y, x);
      if (!isLine(exact.frame, y, x)) continue;
      ++silhouettePixels;
      bool near = false;
      for (int dy = -1; dy <= 1 && !near; ++dy) {
        for (int dx = -1; dx <= 1 && !near; ++dx) {
          const int yy = y + dy, xx = x + dx;
          near = yy >= 0 && xx >= 0 && yy < c.size && xx < c.size && isLine(ra.frame, yy, xx);
        }
      }
      covered += near;
      if (!near && firstGaps.size() < 60)
        firstGaps += " (" + std::to_string(x) + "," + std::to_string(y) + ")";
    }
  }
  ASSERT_GT(silhouettePixels, 200);
  const double recall = double(covered) / silhouettePixels;
  const double width = double(linePixels) / silhouettePixels;
  std::cout << "[ info ] " << c.name << ": " << silhouettePixels << " silhouette pixels, recall "
            << recall << ", line pixels per silhouette pixel " << width << "\n";
  EXPECT_GE(recall, 0.98) << "silhouette pixels with no line pixel within 1 px:" << firstGaps;
  EXPECT_LE(width, 3.0);
}

INSTANTIATE_TEST_SUITE_P(
    AnalyticSurfaces, RightAngleLine,
    ::testing::Values(RightAngleCase{"torus128_256_top", "torus:128", 256, 0, 90, false},
                      RightAngleCase{"torus128_256_ortho", "torus:128", 256, 30, 20, true},
                      RightAngleCase{"torus128_256_low_ortho", "torus:128", 256, 60, 10, true},
                      RightAngleCase{"torus64_256_top", "torus:64", 256, 0, 90, false},
                      RightAngleCase{"torus128_384", "torus:128", 384, 30, 20, false},
                      RightAngleCase{"sphere64_256_ortho", "sphere:64", 256, 30, 20, true},
                      RightAngleCase{"sphere128_256", "sphere:128", 256, 45, 45, false}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace vsil
