// --up: the axes the camera's orbit is laid out by (core/upright.h) and what makeView does with
// them: the up axis shows upward on screen, the front faces the viewer at --view 0,0, and the
// orbit turns about the up axis.
#include "core/upright.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "core/error.h"

namespace vsil {
namespace {

Orientation placement(const std::string& name, const std::string& axes) {
  return {name, "LPS", glm::dmat4(1.0), axes};
}

// Where a world direction points on screen: eye-space x (right), y (up), z (towards the viewer).
glm::dvec3 eyeDirection(const View& view, glm::dvec3 world) {
  return glm::dmat3(view.eyeFromWorld) * world;
}

TEST(Upright, AutoStandsAnAnatomicalPlacementSuperiorUpSeenFromAnterior) {
  // DICOM's and the tooth's LPS index axes: i Left, j Posterior, k Superior.
  const ResolvedUpright lps = resolveUpright("auto", {placement("space", "LPS")});
  EXPECT_EQ(lps.up, "+z");
  EXPECT_EQ(lps.front, "-y");
  EXPECT_EQ(lps.from, "the file's space (LPS): superior up, anterior front");
  // NIfTI: the sform rules where there are both; letters flipped per axis.
  const ResolvedUpright nifti =
      resolveUpright("auto", {placement("sform", "RIA"), placement("qform", "LPS")});
  EXPECT_EQ(nifti.up, "-y");
  EXPECT_EQ(nifti.front, "+z");
  // Index axes that store the patient mirrored (NIfTI's radiological LAS): said so.
  EXPECT_EQ(resolveUpright("auto", {placement("sform", "LAS")}).from,
            "the file's sform (LAS): superior up, anterior front; its axes store the patient "
            "mirrored, and so is the picture");
  // Without a placement, or one that does not name superior and anterior on their own axes:
  // +y up, +z front.
  for (const std::vector<Orientation>& none :
       {std::vector<Orientation>{}, {placement("qform", "L??")}, {placement("qform", "SSA")}}) {
    const ResolvedUpright r = resolveUpright("auto", none);
    EXPECT_EQ(r.up, "+y");
    EXPECT_EQ(r.front, "+z");
    EXPECT_EQ(r.from, "the default (no anatomical placement in the file)");
  }
}

// Letters are chosen for the three axes together: a double-oblique acquisition (rows 45°
// between x and y, then tilted 40° about x) names each direction once, as nibabel's
// io_orientation does (each axis by its largest cosine alone gave "LRS", round 20).
TEST(Upright, AnObliquePlacementNamesEachDirectionOnce) {
  const glm::dvec3 row(0.707, 0.542, 0.455), column(-0.707, 0.542, 0.455);
  const glm::dmat3 directions(row, column, glm::cross(row, column));
  EXPECT_EQ(anatomicalAxes(directions, "LPS"), "LPS");
  EXPECT_EQ(anatomicalAxes(directions, "RAS"), "RAS");
  EXPECT_EQ(anatomicalAxes(glm::dmat3(-row, column, -glm::cross(row, column)), "LPS"), "RPI");
  // Permuted axes: i along z, j along -x, k along y.
  EXPECT_EQ(
      anatomicalAxes(glm::dmat3(glm::dvec3(0, 0.1, 2), glm::dvec3(-3, 0, 0), glm::dvec3(0, 1, 0)),
                     "LPS"),
      "SRP");
  EXPECT_EQ(resolveUpright("auto", {placement("patient", anatomicalAxes(directions, "LPS"))}).up,
            "+z");
}

TEST(Upright, AnAxisGivenFixesItsFrontAndOverridesThePlacement) {
  const std::vector<Orientation> lps{placement("space", "LPS")};
  const std::pair<const char*, const char*> cases[][2] = {
      {{"+y", "+z"}, {"+y", "+z"}}, {{"y", "+z"}, {"+y", "+z"}},  {{"-y", "-z"}, {"-y", "-z"}},
      {{"+z", "-y"}, {"+z", "-y"}}, {{"-z", "+y"}, {"-z", "+y"}}, {{"+x", "+z"}, {"+x", "+z"}},
      {{"-x", "+z"}, {"-x", "+z"}}};
  for (const auto& c : cases) {
    const ResolvedUpright r = resolveUpright(c[0].first, lps);
    EXPECT_EQ(r.up, c[1].first) << c[0].first;
    EXPECT_EQ(r.front, c[0].second) << c[0].first;
    // A rotation: right = up × front is a unit axis.
    EXPECT_DOUBLE_EQ(glm::length(glm::cross(r.upright.up, r.upright.front)), 1.0);
  }
  for (const char* bad : {"", "up", "+w", "z+", "++z", "auto "}) {
    try {
      resolveUpright(bad, {});
      ADD_FAILURE() << "'" << bad << "' was taken";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()),
                "--up: '" + std::string(bad) + "' is not auto or an axis (+x, -x, +y, -y, +z, -z)");
    }
  }
}

TEST(Upright, TheViewShowsUpUpwardAndFrontTowardTheViewerAndOrbitsAboutUp) {
  const glm::ivec3 dims{40, 30, 20};
  const glm::dvec3 spacing{1, 2, 0.5};
  const glm::ivec2 viewport{64, 48};
  for (const char* flag : {"+y", "-y", "+z", "-z", "+x", "-x"}) {
    const Upright upright = resolveUpright(flag, {}).upright;
    CameraSpec camera{.azimuthDeg = 0, .elevationDeg = 0, .upright = upright};
    const View front = makeView(camera, dims, spacing, viewport);
    EXPECT_NEAR(glm::distance(eyeDirection(front, upright.up), glm::dvec3(0, 1, 0)), 0, 1e-12)
        << flag;
    EXPECT_NEAR(glm::distance(eyeDirection(front, upright.front), glm::dvec3(0, 0, 1)), 0, 1e-12)
        << flag;
    // Azimuth 90 turns about up: up stays up, and the right side (up × front) comes to face
    // the viewer.
    camera.azimuthDeg = 90;
    const View side = makeView(camera, dims, spacing, viewport);
    const glm::dvec3 right = glm::cross(upright.up, upright.front);
    EXPECT_NEAR(glm::distance(eyeDirection(side, upright.up), glm::dvec3(0, 1, 0)), 0, 1e-12);
    EXPECT_NEAR(glm::distance(eyeDirection(side, right), glm::dvec3(0, 0, 1)), 0, 1e-12) << flag;
    // Elevation 90 looks straight down the up axis.
    camera.azimuthDeg = 0;
    camera.elevationDeg = 90;
    const View above = makeView(camera, dims, spacing, viewport);
    EXPECT_NEAR(glm::distance(eyeDirection(above, upright.up), glm::dvec3(0, 0, 1)), 0, 1e-12);
  }
}

}  // namespace
}  // namespace vsil
