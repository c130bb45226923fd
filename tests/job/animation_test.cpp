// The frames of an animation (job/animation.h): where each frame looks from and what each sweep
// sets, which names can be swept with which technique, and the checks made before any frame is
// rendered. No GL: a plan is requests, not images.
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/limits.h"
#include "job/animation.h"

namespace vsil {
namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

RenderRequest baseRequest(const std::string& technique = "silhouette") {
  RenderRequest request;
  request.settings.technique = technique;
  request.settings.size = {64, 64};
  request.settings.camera.azimuthDeg = 30;
  request.settings.camera.elevationDeg = 20;
  return request;
}

AnimationSpec specWith(int frames, std::vector<std::string> sweeps = {}) {
  AnimationSpec spec;
  spec.frames = frames;
  for (const auto& text : sweeps) spec.sweeps.push_back(parseSweep(text));
  return spec;
}

std::vector<std::string> namesFor(const std::string& technique) {
  std::vector<std::string> names;
  for (const auto& target : sweepTargets(baseRequest(technique))) names.push_back(target.name);
  return names;
}

TEST(Animation, AnOrbitStepsDegreesOverFramesAndDoesNotRepeatItsStart) {
  AnimationSpec spec = specWith(4);
  spec.orbitDeg = 360;
  const AnimationPlan plan(baseRequest(), spec, {});
  for (int i = 0; i < 4; ++i) {
    const CameraSpec camera = plan.request(i).settings.camera;
    EXPECT_DOUBLE_EQ(camera.azimuthDeg, 30 + 90 * i) << "frame " << i;
    EXPECT_EQ(camera.elevationDeg, 20);
  }
}

// The largest finite orbit gives finite views (frame × orbit overflowed to infinity, and the
// renderer then blamed --view).
TEST(Animation, TheLargestOrbitGivesFiniteViews) {
  AnimationSpec spec = specWith(3);
  spec.orbitDeg = 1e308;
  const AnimationPlan plan(baseRequest(), spec, {});
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(std::isfinite(plan.request(i).settings.camera.azimuthDeg)) << "frame " << i;
  }
}

TEST(Animation, ViewsAndSweepsRunFromTheFirstFrameToTheLast) {
  AnimationSpec spec = specWith(5, {"iso=0.3:0.6", "width=2:10", "zoom=1:3"});
  spec.viewFrom = glm::dvec2(10, -30);
  spec.viewTo = glm::dvec2(70, 50);
  const AnimationPlan plan(baseRequest(), spec, {});
  EXPECT_EQ(plan.t(0), 0.0);
  EXPECT_EQ(plan.t(4), 1.0);
  EXPECT_EQ(plan.t(2), 0.5);
  // The ends are exactly A and B, whatever their rounding in between.
  const RenderRequest first = plan.request(0), middle = plan.request(2), last = plan.request(4);
  EXPECT_EQ(std::get<double>(first.settings.options.at("iso")), 0.3);
  EXPECT_EQ(std::get<double>(last.settings.options.at("iso")), 0.6);
  EXPECT_DOUBLE_EQ(std::get<double>(middle.settings.options.at("iso")), 0.45);
  EXPECT_EQ(first.postfx.width.near, 2);
  EXPECT_EQ(first.postfx.width.far, 2);
  EXPECT_EQ(middle.postfx.width.near, 6);
  EXPECT_EQ(last.postfx.width.far, 10);
  EXPECT_EQ(first.settings.camera.zoom, 1);
  EXPECT_EQ(last.settings.camera.zoom, 3);
  EXPECT_EQ(first.settings.camera.azimuthDeg, 10);
  EXPECT_EQ(first.settings.camera.elevationDeg, -30);
  EXPECT_EQ(middle.settings.camera.azimuthDeg, 40);
  EXPECT_EQ(middle.settings.camera.elevationDeg, 10);
  EXPECT_EQ(last.settings.camera.azimuthDeg, 70);
  EXPECT_EQ(last.settings.camera.elevationDeg, 50);

  EXPECT_EQ(plan.sweptValues(4), (nlohmann::json{{"iso", 0.6}, {"width", 10.0}, {"zoom", 3.0}}));
  const nlohmann::json described = plan.describe();
  EXPECT_EQ(described["frames"], 5);
  EXPECT_EQ(described["view_from"], nlohmann::json({10.0, -30.0}));
  EXPECT_EQ(described["sweeps"][0], (nlohmann::json{{"name", "iso"}, {"from", 0.3}, {"to", 0.6}}));
}

TEST(Animation, OneFrameShowsTheStart) {
  AnimationSpec spec = specWith(1, {"iso=0.3:0.6"});
  spec.orbitDeg = 360;
  const AnimationPlan plan(baseRequest(), spec, {});
  EXPECT_EQ(std::get<double>(plan.request(0).settings.options.at("iso")), 0.3);
  EXPECT_EQ(plan.request(0).settings.camera.azimuthDeg, 30);
}

TEST(Animation, WhatCanBeSweptFollowsTheTechnique) {
  EXPECT_EQ(namesFor("silhouette"), (std::vector<std::string>{"iso", "zoom", "sampling", "width",
                                                              "width-near", "width-far"}));
  EXPECT_EQ(namesFor("rightangle"),
            (std::vector<std::string>{"iso", "ra-exponent", "ra-threshold", "zoom", "sampling",
                                      "width", "width-near", "width-far"}));
  // firsthit's frames are colour, composed without lines: no widths to sweep.
  EXPECT_EQ(namesFor("firsthit"), (std::vector<std::string>{"iso", "zoom", "sampling"}));
}

TEST(Animation, UnknownNamesAreRefusedListingWhatCanBeSwept) {
  EXPECT_EQ(errorOf([] { AnimationPlan(baseRequest(), specWith(3, {"ra-exponent=1:8"}), {}); }),
            "--sweep ra-exponent=1:8: 'ra-exponent' cannot be swept with technique 'silhouette' "
            "(can be swept: iso, zoom, sampling, width, width-near, width-far)");
  EXPECT_NO_THROW(AnimationPlan(baseRequest("rightangle"), specWith(3, {"ra-exponent=1:8"}), {}));
  EXPECT_EQ(errorOf([] { AnimationPlan(baseRequest(), specWith(3, {"pipeline=1:2"}), {}); }),
            "--sweep pipeline=1:2: 'pipeline' cannot be swept with technique 'silhouette' "
            "(can be swept: iso, zoom, sampling, width, width-near, width-far)")
      << "a Choice option is not numeric";
}

TEST(Animation, BothEndsAreCheckedNamingTheSweep) {
  EXPECT_EQ(errorOf([] {
              AnimationPlan(baseRequest("rightangle"), specWith(3, {"ra-exponent=0:8"}), {});
            }),
            "--sweep ra-exponent=0:8: first frame: --ra-exponent: must be in (0, 1000] (got 0)");
  EXPECT_EQ(errorOf([] { AnimationPlan(baseRequest(), specWith(3, {"sampling=1:65"}), {}); }),
            "--sweep sampling=1:65: last frame: --sampling: must be in (0, 64] slices per voxel");
  EXPECT_EQ(
      errorOf([] { AnimationPlan(baseRequest(), specWith(3, {"width=0.5:4"}), {}); }),
      "--sweep width=0.5:4: first frame: --width: line width must be a number >= 1 pixel, got 0.5");
  EXPECT_EQ(errorOf([] { AnimationPlan(baseRequest(), specWith(3, {"zoom=2:-1"}), {}); }),
            "--sweep zoom=2:-1: last frame: --zoom: must be in [0.001, 1000]");
}

TEST(Animation, MalformedAndConflictingSweepsAreRefused) {
  EXPECT_EQ(errorOf([] { parseSweep("iso"); }), "--sweep iso: expected NAME=A:B (e.g. iso=30:50)");
  EXPECT_EQ(errorOf([] { parseSweep("iso=1:2:3"); }),
            "--sweep iso=1:2:3: expected NAME=A:B (e.g. iso=30:50)");
  EXPECT_EQ(errorOf([] { parseSweep("=1:2"); }),
            "--sweep =1:2: expected NAME=A:B (e.g. iso=30:50)");
  EXPECT_EQ(errorOf([] { parseSweep("iso=a:2"); }),
            "--sweep iso=a:2: each end must be a number or numbers separated by commas");
  EXPECT_EQ(errorOf([] { parseSweep("cursor=1,2:3"); }),
            "--sweep cursor=1,2:3: both ends need the same number of components");
  const Sweep negative = parseSweep("iso=-5:-1.5");
  EXPECT_EQ(negative.from, std::vector<double>{-5});
  EXPECT_EQ(negative.to, std::vector<double>{-1.5});

  EXPECT_EQ(errorOf([] { AnimationPlan(baseRequest(), specWith(3, {"iso=1,2:3,4"}), {}); }),
            "--sweep iso=1,2:3,4: 'iso' takes 1 number at each end");
  EXPECT_EQ(errorOf([] {
              AnimationPlan(baseRequest(), specWith(3, {"iso=1:2", "iso=3:4"}), {});
            }),
            "--sweep iso=3:4: 'iso' is already swept by --sweep iso=1:2");
  EXPECT_EQ(errorOf([] {
              AnimationPlan(baseRequest(), specWith(3, {"width=2:4", "width-near=3:4"}), {});
            }),
            "--sweep width-near=3:4: 'width-near' is already swept by --sweep width=2:4");
  EXPECT_NO_THROW(
      AnimationPlan(baseRequest(), specWith(3, {"width-near=2:4", "width-far=8:3"}), {}));
}

TEST(Animation, FrameCountsOutsideTheLimitAreRefused) {
  EXPECT_EQ(errorOf([] { AnimationPlan(baseRequest(), specWith(0), {}); }),
            "--frames: 0 is outside 1..100000");
  AnimationSpec absurd;
  absurd.frames = 5'000'000'000;
  EXPECT_EQ(errorOf([&] { AnimationPlan(baseRequest(), absurd, {}); }),
            "--frames: 5000000000 is outside 1..100000");
  EXPECT_NO_THROW(AnimationPlan(baseRequest(), specWith(limits::kMaxFrames), {}));
}

}  // namespace
}  // namespace vsil
