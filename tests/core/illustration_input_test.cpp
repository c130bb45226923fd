// What users write for illustrations: transfer functions (core/transfer_function.h), effect and
// parameter lists, lights and style files (core/illustration.h). Values against hand-computed
// ones; every bad input an InputError whose one line names the source and the place.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/illustration.h"
#include "core/transfer_function.h"

namespace vsil {
namespace {

// The message of the InputError `body` throws ("" if it throws none).
template <typename Body>
std::string inputError(Body body) {
  try {
    body();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(TransferFunction, InterpolatesLinearlyAndHoldsBeyondTheEnds) {
  const TransferFunction tf = parseTransferFunctionText(
      R"([{"value": 10, "color": "#000000", "opacity": 0},
          {"value": 20, "color": "#ff0000", "opacity": 0.5},
          {"value": 20, "color": "#0000ff", "opacity": 1}])",
      "tf.json");
  EXPECT_EQ(tf.at(0.0), glm::dvec4(0, 0, 0, 0));
  const glm::dvec4 mid = tf.at(15.0);
  EXPECT_DOUBLE_EQ(mid.r, 0.5);
  EXPECT_DOUBLE_EQ(mid.a, 0.25);
  // A step (two equal values): the later point wins at and beyond it.
  EXPECT_EQ(tf.at(20.0), glm::dvec4(0, 0, 1, 1));
  EXPECT_EQ(tf.at(1e6), glm::dvec4(0, 0, 1, 1));
  // The table spans the range end to end.
  const auto table = tf.table(ValueRange{10.0f, 20.0f}, 3);
  ASSERT_EQ(table.size(), 3u);
  EXPECT_FLOAT_EQ(table[1].a, 0.25f);

  // Points near the ends of the doubles: their span overflows a double, the halves do not (the
  // span overflowed to infinity once, and every value between them took the first point's).
  const TransferFunction wide = parseTransferFunctionText(
      R"([{"value": -1e308, "color": "#000000", "opacity": 0},
          {"value": 1e308, "color": "#ffffff", "opacity": 1}])",
      "tf.json");
  EXPECT_DOUBLE_EQ(wide.at(0.0).a, 0.5);
  EXPECT_DOUBLE_EQ(wide.at(5e307).r, 0.75);
}

TEST(TransferFunction, BadFilesNameTheFileAndThePoint) {
  const auto error = [](const std::string& text) {
    return inputError([&] { parseTransferFunctionText(text, "tf.json"); });
  };
  EXPECT_EQ(error("[]").rfind("tf.json: ", 0), 0u) << error("[]");
  EXPECT_NE(error("[]"), "");
  EXPECT_NE(error("{\"value\": 1}"), "");
  EXPECT_NE(error("[{\"value\": 1, \"color\": \"red\""), "");  // not JSON
  const std::string descending = error(
      R"([{"value": 5, "color": "red", "opacity": 0}, {"value": 4, "color": "red", "opacity": 0}])");
  EXPECT_NE(descending.find("point 2"), std::string::npos) << descending;
  EXPECT_NE(error(R"([{"value": 5, "color": "red", "opacity": 1.5}])").find("point 1"),
            std::string::npos);
  EXPECT_NE(error(R"([{"value": 5, "color": "reddish", "opacity": 1}])"), "");
  EXPECT_NE(error(R"([{"value": 5, "color": "red", "opacity": 1, "gamma": 2}])"), "");
  EXPECT_NE(error(R"([{"value": "5", "color": "red", "opacity": 1}])"), "");
  for (const std::string& message : {descending, error("[]")}) {
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

TEST(IllustrationInput, EffectsAndParametersByThePapersNames) {
  const EffectSet effects = parseEffects("tone, boundary,halo", "--effects");
  EXPECT_EQ(effects.names(), (std::vector<std::string>{"boundary", "halo", "tone"}));
  EXPECT_TRUE(parseEffects("none", "--effects").empty());
  EXPECT_NE(inputError([] { parseEffects("tone,glow", "--effects"); }).find("'glow'"),
            std::string::npos);

  // Silhouette: the paper's Figure 4 values; boundary: o_v·|∇f| (README, issue 32).
  const ParameterValues defaults = defaultParameters();
  EXPECT_EQ(defaults.at("k_gc"), 0.0);
  EXPECT_EQ(defaults.at("k_gs"), 1.0);
  EXPECT_EQ(defaults.at("k_ss"), 50.0);
  EXPECT_EQ(defaults.at("k_se"), 0.25);
  ParameterValues values;
  parseParameterList("k_gc=0.5, k_gs=2", "--param", {}, "", values);
  EXPECT_EQ(values.at("k_gc"), 0.5);
  EXPECT_EQ(values.at("k_gs"), 2.0);
  for (const char* bad : {"k_zz=1", "k_gc", "k_gc=abc", "k_gc=nan", "k_gc=inf", "k_se=0", "k_se=-1",
                          "k_ds=2", "k_hr=100"}) {
    const std::string message =
        inputError([&] { parseParameterList(bad, "--param", {}, "", values); });
    EXPECT_EQ(message.rfind("--param: ", 0), 0u) << bad << " -> " << message;
  }
}

TEST(IllustrationInput, LightsPointAsTheirAnglesSay) {
  const glm::dvec3 above = parseLight("0,90", "--light").directionEye();
  EXPECT_NEAR(above.y, 1.0, 1e-12);
  const glm::dvec3 viewer = parseLight("0,0", "--light").directionEye();
  EXPECT_NEAR(viewer.z, 1.0, 1e-12);
  const glm::dvec3 right = parseLight("90,0", "--light").directionEye();
  EXPECT_NEAR(right.x, 1.0, 1e-12);
  // A huge azimuth is whole turns and a rest, as the view's is (its radians overflowed: NaN).
  const glm::dvec3 far = parseLight("1.7e308,0", "--light").directionEye();
  const glm::dvec3 rest = Light{std::fmod(1.7e308, 360.0), 0.0}.directionEye();
  EXPECT_NEAR(far.x, rest.x, 1e-12);
  EXPECT_NEAR(far.z, rest.z, 1e-12);
  EXPECT_NE(inputError([] { parseLight("0,91", "--light"); }), "");
  EXPECT_NE(inputError([] { parseLight("0", "--light"); }), "");
  EXPECT_NE(inputError([] { parseLight("nan,0", "--light"); }), "");
}

TEST(IllustrationInput, StylesSetOnlyWhatTheyNameAndFlagsWin) {
  const IllustrationStyle style = parseStyleText(
      R"({"effects": ["boundary", "tone"], "parameters": {"k_gc": 0.7},
          "background": "#000026", "lights": ["10,20", [30, 45]]})",
      "s.json", ".");
  IllustrationStyle flags;
  flags.parameters["k_gc"] = 0.9;
  const Illustration resolved = resolveIllustration(style, flags, "s.json");
  EXPECT_TRUE(resolved.effects.has(Effect::Tone));
  EXPECT_FALSE(resolved.effects.has(Effect::Halo));
  EXPECT_EQ(resolved["k_gc"], 0.9);                             // the flag
  EXPECT_EQ(resolved["k_gs"], defaultParameters().at("k_gs"));  // the default
  ASSERT_EQ(resolved.lights.size(), 2u);
  EXPECT_EQ(resolved.lights[1].elevationDeg, 45.0);
  EXPECT_EQ(resolved.background, (Rgba{0, 0, 0x26, 255}));
  // The metadata holds every parameter.
  EXPECT_EQ(resolved.toJson().dump().find("k_hpe") != std::string::npos, true);

  for (const char* bad :
       {R"({"shininess": 3})", R"({"effects": ["glow"]})", R"({"parameters": {"k_gc": "high"}})",
        R"({"lights": ["0,100"]})", R"({"transfer_function": []})", R"([1, 2])", R"({)"}) {
    const std::string message = inputError([&] { parseStyleText(bad, "s.json", "."); });
    EXPECT_EQ(message.rfind("s.json: ", 0), 0u) << bad << " -> " << message;
  }
}

TEST(IllustrationInput, EveryPresetLoadsAndUsesItsFiguresValues) {
  const auto names = stylePresetNames();
  EXPECT_GE(names.size(), 7u);
  for (const auto& name : names) {
    EXPECT_NO_THROW(loadStyle(name)) << name;
  }
  const Illustration fig11 = resolveIllustration(loadStyle("fig11-gradient-silhouette"), {}, "");
  EXPECT_EQ(fig11["k_ss"], 500.0);
  EXPECT_EQ(fig11["k_ge"], 3.0);
  EXPECT_NE(inputError([] { loadStyle("fig99"); }).find("fig99"), std::string::npos);
}

}  // namespace
}  // namespace vsil
