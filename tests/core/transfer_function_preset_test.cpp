// Transfer-function presets (`--tf ct-bone`; core/transfer_function.h): every preset parses,
// HU presets keep their values on data in Hounsfield units and map onto the default window
// otherwise, window presets span Otsu's threshold to the window's top, an unknown name is one
// line listing the names, and the suggestion follows the units. Also the default window itself
// (core/volume.h derivedDefaults) against a histogram built by hand.
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/transfer_function.h"
#include "core/volume.h"

namespace vsil {
namespace {

// 8-bit CT like engine or bonsai: air at 0, the object above Otsu's threshold.
constexpr DerivedDefaults kEightBit{
    .iso = 78.0, .valueRangeWidth = 255.0, .valueMin = 0.0, .windowHigh = 230.0};
// A CT in HU (a DICOM series with its rescale).
constexpr DerivedDefaults kHounsfield{
    .iso = -420.0, .valueRangeWidth = 4095.0, .valueMin = -1024.0, .windowHigh = 1800.0};

TEST(TransferFunctionPresets, EveryPresetParsesAndHasItsName) {
  const std::vector<std::string> expected{"ct-angio", "ct-bone", "ct-soft-tissue", "mr-default",
                                          "ramp"};
  EXPECT_EQ(transferFunctionPresetNames(), expected);
  for (const std::string& name : expected) {
    for (const DerivedDefaults& volume : {kEightBit, kHounsfield}) {
      const TransferFunction tf = transferFunctionPreset(name, volume);
      ASSERT_GE(tf.points.size(), 2u) << name;
      EXPECT_EQ(tf.source, "preset " + name);
      double most = 0;
      for (std::size_t i = 0; i < tf.points.size(); ++i) {
        if (i > 0) {
          EXPECT_GE(tf.points[i].value, tf.points[i - 1].value) << name;
        }
        most = std::max(most, tf.points[i].opacity);
      }
      EXPECT_GT(most, 0.2) << name << " shows something";
      // Transparent at and below Otsu's threshold: the air and noise stay background.
      EXPECT_EQ(tf.at(volume.iso).a, 0.0) << name;
    }
    EXPECT_NO_THROW(checkTransferFunctionOption(name));
  }
}

TEST(TransferFunctionPresets, HounsfieldUnitsAsTheyAreOnHuDataAndOnTheWindowOtherwise) {
  EXPECT_TRUE(inHounsfieldUnits(kHounsfield));
  EXPECT_FALSE(inHounsfieldUnits(kEightBit));
  // ct-bone's opacity starts rising at −16.4 HU and reaches 0.72 at 641 HU.
  const TransferFunction hu = transferFunctionPreset("ct-bone", kHounsfield);
  EXPECT_DOUBLE_EQ(hu.points[1].value, -16.4);
  EXPECT_DOUBLE_EQ(hu.points[2].value, 641.0);
  EXPECT_NEAR(hu.at(641.0).a, 0.72, 1e-12);
  // 8-bit: −500 HU at Otsu's threshold (78), +3000 HU at the window's top (230).
  const TransferFunction byte = transferFunctionPreset("ct-bone", kEightBit);
  const auto mapped = [](double hu) { return 78.0 + (hu + 500.0) * (230.0 - 78.0) / 3500.0; };
  EXPECT_NEAR(byte.points[1].value, mapped(-16.4), 1e-9);
  EXPECT_NEAR(byte.points[2].value, mapped(641.0), 1e-9);
  EXPECT_NEAR(byte.at(mapped(641.0)).a, 0.72, 1e-12);
  EXPECT_NEAR(mapped(kHounsfieldAtOtsu), 78.0, 1e-12);
  // The same colours and opacities either way: only the values move.
  for (std::size_t i = 0; i < hu.points.size(); ++i) {
    EXPECT_EQ(hu.points[i].opacity, byte.points[i].opacity);
    EXPECT_EQ(hu.points[i].color, byte.points[i].color);
  }
}

TEST(TransferFunctionPresets, RampSpansOtsusThresholdToTheWindowsTop) {
  const TransferFunction ramp = transferFunctionPreset("ramp", kEightBit);
  EXPECT_EQ(ramp.at(78.0).a, 0.0);
  EXPECT_NEAR(ramp.at(154.0).a, 0.5, 1e-12);
  EXPECT_EQ(ramp.at(230.0).a, 1.0);
  EXPECT_EQ(ramp.at(255.0).a, 1.0);
  // On HU data too ("window" units know no HU).
  const TransferFunction huRamp = transferFunctionPreset("ramp", kHounsfield);
  EXPECT_EQ(huRamp.at(-420.0).a, 0.0);
  EXPECT_EQ(huRamp.at(1800.0).a, 1.0);
}

TEST(TransferFunctionPresets, AnUnknownNameIsOneLineListingThePresets) {
  for (const auto& check :
       {std::function<void()>([] { checkTransferFunctionOption("bone"); }),
        std::function<void()>([] { transferFunctionOption("bone", kEightBit); })}) {
    try {
      check();
      ADD_FAILURE() << "no error";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_EQ(message,
                "--tf: unknown preset \"bone\" (presets: ct-angio, ct-bone, ct-soft-tissue, "
                "mr-default, ramp; or a .json file)");
    }
  }
  // A name with a '/' or ending in .json is a file: the error names the file.
  try {
    checkTransferFunctionOption("/nonexistent/ct-bone.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/ct-bone.json"), std::string::npos)
        << error.what();
  }
}

TEST(TransferFunctionPresets, SuggestsCtBoneForHuAndTheRampOtherwise) {
  EXPECT_EQ(suggestedTransferFunction(kHounsfield), "ct-bone");
  EXPECT_EQ(suggestedTransferFunction(kEightBit), "ramp");
}

// Illustrate's power opacity and semantic's default rule base end at the default window's top
// (a nucleus does not leave the rest near transparent), HU data at the range's top (a CT's
// soft tissue under a top in bone was an opaque barrel, round 21), never beyond the range.
TEST(TransferFunctionPresets, TheDefaultClassificationEndsAtTheWindowsTopButForHu) {
  EXPECT_EQ(defaultClassificationTop(
                {.iso = 15.6, .valueRangeWidth = 250, .valueMin = 0, .windowHigh = 75.2}),
            75.2);
  EXPECT_EQ(defaultClassificationTop(
                {.iso = -480, .valueRangeWidth = 4095, .valueMin = -1024, .windowHigh = 1119}),
            3071);
  EXPECT_EQ(
      defaultClassificationTop({.iso = 7, .valueRangeWidth = 0, .valueMin = 7, .windowHigh = 8}), 7)
      << "a constant volume: its one value";
}

// The default window of the MIP family: Otsu's threshold to the 99.5th percentile of the values
// above it, so a few outliers do not set the top.
TEST(DefaultWindow, RunsFromOtsuToTheHighPercentileAboveIt) {
  Volume ct;
  ct.dims = {64, 64, 64};
  ct.allocate(SampleType::UInt8);
  std::mt19937 random(5);
  std::uniform_int_distribution<int> air(0, 12), object(100, 199);
  const auto samples = ct.samples<std::uint8_t>();
  std::size_t objectCount = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const bool inObject = i % 5 == 0;
    samples[i] = std::uint8_t(inObject ? object(random) : air(random));
    objectCount += inObject;
  }
  for (std::size_t i = 1; i < 200; i += 2) samples[i] = 255;  // 100 outliers (0.2 %)
  const DerivedDefaults derived = derivedDefaults(ct);
  EXPECT_EQ(derived.iso, double(defaultIso(ct)));
  EXPECT_GT(derived.iso, 12.0);
  EXPECT_LT(derived.iso, 100.0);
  EXPECT_EQ(derived.valueMin, 0.0);
  EXPECT_EQ(derived.valueRangeWidth, 255.0);
  // Above the threshold: the object's values uniform over 100..199 and 100 outliers at 255.
  // Their 99.5th percentile lies in the object's top levels, 1 % of a level wide each.
  const double above = double(objectCount + 100);
  const double wanted = 0.995 * above;
  const double perLevel = double(objectCount) / 100.0;
  const double level = 100.0 + std::ceil(wanted / perLevel) - 1.0;  // the level holding it
  EXPECT_NEAR(derived.windowHigh, level + 1.0, 1.0);
  EXPECT_LT(derived.windowHigh, 201.0) << "the outliers at 255 do not set the top";
  // A constant volume: the window starts at its value and ends one data unit above, a window
  // --window takes (LO < HI: the metadata replays), showing nothing as the value is LO.
  Volume flat;
  flat.dims = {2, 2, 2};
  flat.allocate(SampleType::Float32);
  for (float& v : flat.samples<float>()) v = 3.5f;
  const DerivedDefaults constant = derivedDefaults(flat);
  EXPECT_EQ(constant.iso, 3.5);
  EXPECT_EQ(constant.windowHigh, 4.5);
  for (float& v : flat.samples<float>()) v = 1e9f;  // one unit is below a float's step there
  const DerivedDefaults large = derivedDefaults(flat);
  EXPECT_EQ(large.windowHigh, std::nextafter(1e9f, INFINITY));
}

// --tf takes the JSON list itself too (what the Python package's tf=[{...}] becomes): the same
// points as the file, errors named after the flag; a preset name or a file is still that.
TEST(TransferFunctionPresets, TheOptionTakesTheJsonItself) {
  const std::string json =
      R"([{"value": 0, "color": "#000000", "opacity": 0}, {"value": 9, "color": "red", "opacity": 0.5}])";
  EXPECT_TRUE(isInlineSource(json));
  EXPECT_FALSE(isInlineSource("ct-bone"));
  EXPECT_FALSE(isInlineSource("dir/tf.json"));
  // A list without an object in it is still the JSON, refused for what it lacks (it was once
  // looked up as a preset named "[]").
  EXPECT_TRUE(isInlineSource(" [ ] "));
  try {
    checkTransferFunctionOption("[]");
    FAIL() << "an empty list was taken";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(), "--tf: has no control points");
  }
  const TransferFunction tf = transferFunctionOption(json, kEightBit);
  ASSERT_EQ(tf.points.size(), 2u);
  EXPECT_EQ(tf.points[1].value, 9.0);
  EXPECT_EQ(tf.points[1].opacity, 0.5);
  EXPECT_EQ(tf.source, "--tf");
  EXPECT_NO_THROW(checkTransferFunctionOption(json));
  try {
    checkTransferFunctionOption(R"([{"value": 0, "color": "#000000", "opacity": 2}])");
    FAIL() << "an opacity of 2 was taken";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("--tf: point 1: ", 0), 0u) << error.what();
  }
}

}  // namespace
}  // namespace vsil
