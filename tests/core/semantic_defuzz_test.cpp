// The paper's table-based defuzzification (core/rules.h: DefuzzTables, what the `semantic` slice
// shader does: two lookups per rule, sums, one division) against the CPU reference's direct
// centroid integration (tests/reference/semantic_reference.h), on random rule bases and random
// samples from a fixed seed; and the reference itself on cases computed by hand.
#include <cmath>
#include <iostream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/rules.h"
#include "semantic_reference.h"

namespace vsil {
namespace {

using reference::evaluateSemantic;
using reference::SemanticSample;

// The shader's arithmetic on the CPU: per consequent, the (row, degree) of each rule reaching it.
double tablesValue(const RuleBase& base, const DefuzzTables& tables, const SemanticSample& sample,
                   bool flatness, int style) {
  std::vector<RuleActivation> activations;
  for (std::size_t i = 0; i < base.rules.size(); ++i) {
    const Rule& rule = base.rules[i];
    if (rule.flatness != flatness || (!flatness && rule.style != style)) continue;
    activations.push_back({tables.row(rule), sample.ruleDegrees[i]});
  }
  return tableCentroid(tables, activations);
}

TEST(SemanticReference, HandComputedSample) {
  const RuleBase base = loadRules(std::string(VSIL_SOURCE_DIR) + "/src/core/rules/example.rules");
  AttributeInputs inputs{};
  inputs[int(AttributeSource::Data)] = 0.35;            // density: low 0, high 0.5
  inputs[int(AttributeSource::CursorDistance)] = 0.10;  // focus near: 0.5
  const SemanticSample sample = evaluateSemantic(base, inputs);
  ASSERT_EQ(sample.ruleDegrees.size(), 4u);
  EXPECT_DOUBLE_EQ(sample.ruleDegrees[0], 0.5);
  EXPECT_DOUBLE_EQ(sample.ruleDegrees[1], 0.0);  // min(low 0, 1 − 0.5)
  EXPECT_DOUBLE_EQ(sample.ruleDegrees[2], 0.5);
  EXPECT_DOUBLE_EQ(sample.ruleDegrees[3], 0.5);
  // bone: opaque = trapezoid(0.6, 0.9, 1, 1) truncated at 0.5 is trapezoid-shaped with corners
  // 0.6, 0.75, 1, 1 at height 0.5: area 0.5·(0.4 + 0.25)/2, moment 0.5·(∫ ramp + ∫ top).
  const double area = 0.5 * (0.15 / 2 + 0.25);
  const double moment =
      0.5 * ((0.75 * 0.75 * 0.75 - 0.6 * 0.6 * 0.6) / 3 - 0.6 * (0.75 * 0.75 - 0.6 * 0.6) / 2) /
          0.15 +
      0.5 * (1.0 - 0.75 * 0.75) / 2;
  // Midpoint integration on 20000 steps: the kinks cost well under 1e-6.
  EXPECT_NEAR(sample.styles[0].value, moment / area, 1e-6);
  EXPECT_DOUBLE_EQ(sample.styles[0].weight, 0.5);
  // skin: transparent = triangle(0, 0, 0.3) truncated at 0.5: a trapezoid with corners
  // 0, 0, 0.15, 0.3 at height 0.5: a box [0, 0.15] (centroid 0.075) and a falling triangle on
  // [0.15, 0.3] (centroid a third of the way in, 0.2).
  const double skinArea = 0.5 * 0.15 + 0.5 * 0.15 / 2;
  const double skinMoment = 0.5 * 0.15 * 0.15 / 2 + 0.5 * 0.15 / 2 * (0.15 + 0.15 / 3);
  EXPECT_NEAR(sample.styles[1].value, skinMoment / skinArea, 1e-6);
  EXPECT_DOUBLE_EQ(sample.styles[1].weight, 0.5);
  EXPECT_DOUBLE_EQ(sample.flatness.weight, 0.5);

  // No rule fires for bone (density 0): weight 0, value 0, whatever the tables would say.
  inputs[int(AttributeSource::Data)] = 0.0;
  const SemanticSample outside = evaluateSemantic(base, inputs);
  EXPECT_EQ(outside.styles[0].weight, 0.0);
  EXPECT_EQ(outside.styles[0].value, 0.0);
}

// A random rule base as text: 1-3 attributes over random sources, 1-4 styles, maybe a flatness
// block, 1-10 rules with random conditions of up to three levels; every shape kind.
class RandomRules {
 public:
  explicit RandomRules(std::uint32_t seed) : rng_(seed) {}

  std::string text() {
    std::ostringstream out;
    out.precision(17);
    const int attributes = uniformInt(1, 3);
    for (int a = 0; a < attributes; ++a) {
      attributeValues_.push_back(uniformInt(1, 4));
      out << "attribute a" << a << " from "
          << attributeSourceName(AttributeSource(uniformInt(0, 6))) << " {";
      for (int v = 0; v < attributeValues_.back(); ++v) out << " v" << v << " = " << shape();
      out << " }\n";
    }
    const int styles = uniformInt(1, 4);
    for (int s = 0; s < styles; ++s) {
      styleValues_.push_back(uniformInt(1, 4));
      out << "style s" << s << " priority " << s << " { spheres = \"gray\"";
      for (int v = 0; v < styleValues_.back(); ++v) out << " v" << v << " = " << shape();
      out << " }\n";
    }
    const int flatnessValues = uniformInt(0, 2);
    if (flatnessValues > 0) {
      out << "flatness {";
      for (int v = 0; v < flatnessValues; ++v) out << " v" << v << " = " << shape();
      out << " }\n";
    }
    const int rules = uniformInt(1, 10);
    for (int r = 0; r < rules; ++r) {
      out << "rule if " << condition(0) << " then ";
      const int target = uniformInt(0, styles - (flatnessValues > 0 ? 0 : 1));
      if (target == styles) {
        out << "flatness is v" << uniformInt(0, flatnessValues - 1) << "\n";
      } else {
        out << "s" << target << " is v" << uniformInt(0, styleValues_[target] - 1) << "\n";
      }
    }
    return out.str();
  }

  AttributeInputs inputs() {
    AttributeInputs values;
    for (double& v : values) v = uniform(0.0, 1.0);
    return values;
  }

 private:
  int uniformInt(int low, int high) { return std::uniform_int_distribution<int>(low, high)(rng_); }
  double uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(rng_);
  }

  // A shape with enough of it inside [0, 1] for a style value (an integral above 0.001).
  std::string shape() {
    std::ostringstream out;
    out.precision(17);
    switch (uniformInt(0, 3)) {
      case 0: {
        std::vector<double> p = {uniform(-0.2, 0.9), 0, 0, 0};
        for (int i = 1; i < 4; ++i) p[i] = p[i - 1] + uniform(0.0, 0.4);
        p[3] = std::max(p[3], std::max(p[0], 0.0) + 0.05);
        out << "trapezoid(" << p[0] << ", " << p[1] << ", " << p[2] << ", " << p[3] << ")";
        break;
      }
      case 1: {
        const double a = uniform(-0.2, 0.9);
        const double b = a + uniform(0.0, 0.4);
        const double c = std::max(b + uniform(0.0, 0.4), std::max(a, 0.0) + 0.05);
        out << "triangle(" << a << ", " << b << ", " << c << ")";
        break;
      }
      case 2:
        out << "gauss(" << uniform(0.0, 1.0) << ", " << uniform(0.02, 0.4) << ")";
        break;
      default: {
        const int count = uniformInt(2, 6);
        double x = uniform(-0.1, 0.5);
        out << "points(";
        for (int i = 0; i < count; ++i) {
          out << (i ? ", (" : "(") << x << ", " << uniform(0.05, 1.0) << ")";
          x += uniform(0.05, 0.4);
        }
        out << ")";
      }
    }
    return out.str();
  }

  std::string condition(int depth) {
    const int kind = depth >= 2 ? 0 : uniformInt(0, 5);
    if (kind <= 2) {
      const int a = uniformInt(0, int(attributeValues_.size()) - 1);
      return "a" + std::to_string(a) + " is v" +
             std::to_string(uniformInt(0, attributeValues_[a] - 1));
    }
    if (kind == 3) return "not " + condition(depth + 1);
    return "(" + condition(depth + 1) + (kind == 4 ? " and " : " or ") + condition(depth + 1) + ")";
  }

  std::mt19937 rng_;
  std::vector<int> attributeValues_, styleValues_;
};

// The paper's claim made a test: the tables (256 entries, linear interpolation) give the centroid
// of the direct integration within one 8-bit step, 1/255, for every style and the flatness whose
// weight (its largest rule degree) is at least two table steps, 2/255.
//
// Below that the tables cannot follow: between degree 0 and the first entry, interpolation scales
// N and D alike, so a lone rule gets the centroid of its value truncated at 1/255 instead of at
// its own degree, and a Gaussian's tails (or a points() shape's low plateaus) move that centroid
// a long way within one step (measured: up to 83/255 below 1/255, 1.2/255 between 1/255 and
// 2/255, 0.23/255 above, over 400 random bases). Such a style carries under 2/255 of its
// colour when its weight scales it; the comparison counts and prints those samples.
TEST(SemanticDefuzz, TablesAgreeWithDirectIntegration) {
  constexpr int kBases = 60;
  constexpr int kSamplesPerBase = 40;
  constexpr double kTolerance = 1.0 / 255.0;
  constexpr double kMinWeight = 2.0 / 255.0;
  double worst = 0.0, worstFaint = 0.0;
  int compared = 0, faint = 0;
  for (int b = 0; b < kBases; ++b) {
    RandomRules random(std::uint32_t(1000 + b));
    const std::string text = random.text();
    SCOPED_TRACE("rule base " + std::to_string(b) + ":\n" + text);
    const RuleBase base = parseRulesText(text, "random.rules");
    const DefuzzTables tables = buildDefuzzTables(base);
    for (int s = 0; s < kSamplesPerBase; ++s) {
      const AttributeInputs inputs = random.inputs();
      const SemanticSample sample = evaluateSemantic(base, inputs);
      const auto check = [&](const reference::FuzzyOutput& expected, bool flatness, int style,
                             const std::string& name) {
        if (expected.weight <= 0.0) return;  // no rule fires: nothing to compare
        const double value = tablesValue(base, tables, sample, flatness, style);
        const double error = std::abs(value - expected.value);
        if (expected.weight < kMinWeight) {
          ++faint;
          worstFaint = std::max(worstFaint, error);
          return;
        }
        ++compared;
        worst = std::max(worst, error);
        EXPECT_LE(error, kTolerance)
            << name << " at sample " << s << ": tables " << value << ", direct " << expected.value
            << ", weight " << expected.weight;
      };
      for (std::size_t i = 0; i < base.styles.size(); ++i) {
        check(sample.styles[i], false, int(i), base.styles[i].name);
      }
      check(sample.flatness, true, -1, "flatness");
    }
  }
  EXPECT_GT(compared, 3000);  // the random bases fire often enough to mean something
  std::cout << compared << " centroids compared, largest difference " << worst * 255.0 << "/255; "
            << faint << " with weight below 2/255 (largest difference " << worstFaint * 255.0
            << "/255)\n";
}

}  // namespace
}  // namespace vsil
