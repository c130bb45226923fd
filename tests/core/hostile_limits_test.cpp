// Bounds that keep hostile input from the memory and the stack (issue 33): the slice bound
// against the slices a plan really takes, the JSON nesting limit, the bounded value quotes.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/json_input.h"
#include "core/limits.h"
#include "slicing/slicer.h"

namespace vsil {
namespace {

// The bound holds for every camera: the plan's own count, from many views of anisotropic
// boxes, never exceeds it (and the finest axis seen end on comes close to it).
TEST(HostileLimits, SliceBoundHoldsForEveryViewAndSpacing) {
  const glm::ivec3 dims(40, 30, 20);
  for (const glm::dvec3 spacing : {glm::dvec3(1, 1, 1), glm::dvec3(1, 1, 0.01),
                                   glm::dvec3(0.5, 3, 1), glm::dvec3(100, 1, 1)}) {
    const std::int64_t bound = limits::sliceCountBound(dims, spacing, 1.5);
    std::size_t most = 0;
    for (double az = 0; az < 360; az += 30) {
      for (double el = -90; el <= 90; el += 22.5) {
        for (bool ortho : {false, true}) {
          CameraSpec camera;
          camera.azimuthDeg = az;
          camera.elevationDeg = el;
          camera.orthographic = ortho;
          const View view = makeView(camera, dims, spacing, {32, 32});
          const std::size_t count = planSlices(view, dims, spacing, 1.5).slices.size();
          EXPECT_LE(std::int64_t(count), bound) << az << "," << el << " " << spacing.z;
          most = std::max(most, count);
        }
      }
    }
    EXPECT_GT(double(most), 0.25 * double(bound)) << "the bound is within 4 times the most";
  }
}

// A spacing ratio of 10^7 (it was an out-of-memory kill) is past the limit from the header's
// numbers alone; the same samples evenly spaced are far within it.
TEST(HostileLimits, ExtremeSpacingRatioIsPastTheSliceLimit) {
  EXPECT_GT(limits::sliceCountBound({4, 4, 4}, {1, 1, 1e-7}, 1.0), limits::kMaxSlices);
  EXPECT_LT(limits::sliceCountBound({4, 4, 4}, {1, 1, 1}, 1.0), 10);
  EXPECT_EQ(limits::sliceCountBound({4, 4, 4}, {1, 1, 1e-300}, 1.0), std::int64_t(1e15));
}

// planSlices refuses such a view itself (it cast the count to int: undefined, then bad_alloc).
TEST(HostileLimits, PlanSlicesRefusesACountPastTheLimit) {
  CameraSpec camera;
  camera.azimuthDeg = 20;
  camera.elevationDeg = 30;
  const View view = makeView(camera, {4, 4, 4}, {1, 1, 1e-9}, {16, 16});
  EXPECT_THROW(planSlices(view, {4, 4, 4}, {1, 1, 1e-9}, 1.0), InputError);
}

TEST(HostileLimits, JsonNestedPastTheLimitIsRefusedWhileParsed) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  try {
    parseJsonText(deep, "deep.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "deep.json: not valid JSON (nested more than 64 levels deep)");
  }
  // At the limit it parses.
  const std::string atLimit = std::string(64, '[') + std::string(64, ']');
  EXPECT_NO_THROW(parseJsonText(atLimit, "ok.json"));
  std::string objects;
  for (int i = 0; i < 65; ++i) objects += "{\"a\":";
  objects += "1" + std::string(65, '}');
  EXPECT_THROW(parseJsonText(objects, "objects.json"), InputError);
}

// A message quotes the start of a value: a large one is never serialised whole.
TEST(HostileLimits, JsonSnippetQuotesTheStartOnly) {
  nlohmann::json big = nlohmann::json::array();
  for (int i = 0; i < 100000; ++i) big.push_back(i);
  EXPECT_EQ(jsonSnippet(big), "[0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,1...");
  EXPECT_EQ(jsonSnippet(nlohmann::json(std::string(1 << 20, 'x'))),
            "\"" + std::string(39, 'x') + "...");
  EXPECT_EQ(jsonSnippet(nlohmann::json::parse(R"({"k": [1, "a\nb"], "z": null})")),
            R"({"k":[1,"a\nb"],"z":null})");
  EXPECT_EQ(jsonSnippet(nlohmann::json(3.5)), "3.5");
}

// A message is one line (control bytes become '?'); what it quotes from a file's contents is
// valid UTF-8 too (bytes of no UTF-8 sequence: binary data, a truncated or overlong sequence, a
// surrogate, become '?'), UTF-8 stays; a file name that is not UTF-8 is named as it is.
TEST(HostileLimits, MessagesAreOneLineAndQuotesValidUtf8) {
  EXPECT_EQ(oneLine("a\nb\x1b[31m\x7f"), "a?b?[31m?");
  EXPECT_EQ(oneLine("cut\xfe.nrrd"), "cut\xfe.nrrd");
  EXPECT_EQ(printableText("a\nb\x1b[31m\x7f"), "a?b?[31m?");
  const std::string names =
      "Sch\xc3\xa4"
      "del \xe2\x86\x92 \xf0\x9f\x98\x80";  // Schädel → 😀
  EXPECT_EQ(printableText(names), names);
  EXPECT_EQ(printableText("\xff\xfe\x80"), "???");
  EXPECT_EQ(printableText("cut \xe2\x86"), "cut ??");           // a sequence cut short
  EXPECT_EQ(printableText("\xc0\xaf \xe0\x80\xaf"), "?? ???");  // overlong '/'
  EXPECT_EQ(printableText("\xed\xa0\x80"), "???");              // a surrogate
  EXPECT_EQ(printableText("\xf4\x90\x80\x80"), "????");         // past U+10FFFF
  EXPECT_EQ(printableText(std::string("a\0b", 3)), "a?b");
}

}  // namespace
}  // namespace vsil
