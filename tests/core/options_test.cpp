// Declared options (core/options.h): parsing, ranges, unknown names, defaults.
#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/options.h"

namespace vsil {
namespace {

std::vector<OptionSpec> specs() {
  OptionSpec iso;
  iso.name = "iso";
  iso.derived = OptionSpec::Derived::VolumeIso;
  return {OptionSpec::number("ra-exponent", 8.0, "").above(0),
          OptionSpec::number("depth-weight", 0.15, "").atLeast(0).atMost(1),
          OptionSpec::choice("pipeline", "fast", {"fast", "paper"}, ""), iso,
          OptionSpec::list("light", "")};
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Options, ParseChecksKindAndRangeNamingTheFlag) {
  const auto s = specs();
  EXPECT_EQ(std::get<double>(s[0].parse("2.5")), 2.5);
  EXPECT_EQ(errorOf([&] { s[0].parse("0"); }), "--ra-exponent: must be > 0 (got 0)");
  EXPECT_EQ(errorOf([&] { s[0].parse("x"); }), "--ra-exponent: 'x' is not a number");
  EXPECT_EQ(errorOf([&] { s[0].parse("nan"); }), "--ra-exponent: must be a finite number");
  EXPECT_EQ(errorOf([&] { s[0].parse("1e999"); }), "--ra-exponent: '1e999' is out of range");
  EXPECT_EQ(errorOf([&] { s[1].parse("1.5"); }), "--depth-weight: must be in [0, 1] (got 1.5)");
  EXPECT_EQ(errorOf([&] { s[2].parse("slow"); }),
            "--pipeline: unknown value 'slow' (known: fast, paper)");
  EXPECT_EQ(std::get<std::vector<std::string>>(s[4].parse("30,40")),
            std::vector<std::string>{"30,40"});
  // Values of any origin (Python, style files) are checked the same way.
  EXPECT_EQ(errorOf([&] { s[1].check(std::string("high")); }), "--depth-weight: must be a number");
}

TEST(Options, UnknownNamesAreReportedWithTheOwnersOptions) {
  const auto s = specs();
  EXPECT_EQ(errorOf([&] {
              checkOptions(s, {{"k-os", 1.0}}, "technique 'x'");
            }),
            "--k-os: not an option of technique 'x' (its options: --ra-exponent, "
            "--depth-weight, --pipeline, --iso, --light)");
  EXPECT_EQ(errorOf([&] {
              checkOptions(s, {{"depth-weight", 2.0}}, "technique 'x'");
            }),
            "--depth-weight: must be in [0, 1] (got 2)");
  EXPECT_NO_THROW(checkOptions(s, {{"depth-weight", 1.0}, {"pipeline", std::string("paper")}},
                               "technique 'x'"));
}

TEST(Options, RangeFractionDefaultsScaleWithTheValueRange) {
  OptionSpec eps = OptionSpec::number("material-eps", 0, "tolerance").above(0);
  eps.defaultValue.reset();
  eps.derived = OptionSpec::Derived::RangeFraction;
  eps.rangeFraction = 0.05;
  const std::vector<OptionSpec> s{eps};
  EXPECT_DOUBLE_EQ(OptionReader(s, {}, {.valueRangeWidth = 255.0}).number("material-eps"), 12.75);
  EXPECT_DOUBLE_EQ(OptionReader(s, {}, {.valueRangeWidth = 1.0}).number("material-eps"), 0.05);
  EXPECT_EQ(OptionReader(s, {{"material-eps", 3.0}}, {.valueRangeWidth = 255.0})
                .number("material-eps"),
            3.0);
}

TEST(Options, ReaderResolvesGivenDeclaredAndDerivedValues) {
  const auto s = specs();
  const OptionReader reader(s, {{"depth-weight", 0.5}}, {.iso = 42.0});
  EXPECT_EQ(reader.number("depth-weight"), 0.5);
  EXPECT_TRUE(reader.given("depth-weight"));
  EXPECT_EQ(reader.number("ra-exponent"), 8.0);
  EXPECT_FALSE(reader.given("ra-exponent"));
  EXPECT_EQ(reader.number("iso"), 42.0);
  EXPECT_EQ(reader.text("pipeline"), "fast");
  EXPECT_TRUE(reader.list("light").empty());
  EXPECT_THROW(reader.number("k-os"), std::logic_error);
  const nlohmann::json json = reader.toJson();
  EXPECT_EQ(json["ra_exponent"], 8.0);
  EXPECT_EQ(json["depth_weight"], 0.5);
  EXPECT_EQ(json["pipeline"], "fast");
  EXPECT_EQ(json.size(), 5u);
}

TEST(Options, DescribeSaysDefaultChoicesAndRange) {
  const auto s = specs();
  EXPECT_EQ(s[0].describe(), "default 8, > 0");
  EXPECT_EQ(s[1].describe(), "default 0.15, in [0, 1]");
  EXPECT_EQ(s[2].describe(), "default fast, fast | paper");
  EXPECT_EQ(s[0].key(), "ra_exponent");
}

// Text options that hold numbers (a position "X,Y,Z"): checked like a range, and written back
// exactly (animate's componentwise sweeps pass them as text).
TEST(Options, NumberListsAreCheckedAndRoundTrip) {
  const OptionSpec cursor = OptionSpec::text("cursor", "").holdsNumbers(3);
  EXPECT_EQ(std::get<std::string>(cursor.parse("10,-2.5,3e2")), "10,-2.5,3e2");
  EXPECT_EQ(errorOf([&] { cursor.parse("10,20"); }),
            "--cursor: '10,20' is not 3 numbers separated by commas");
  EXPECT_EQ(errorOf([&] { cursor.parse("1,x,3"); }),
            "--cursor: '1,x,3' is not 3 numbers separated by commas");
  EXPECT_NO_THROW(cursor.check(std::string())) << "empty: not given";

  EXPECT_EQ(parseNumberList("1,2,3"), (std::vector<double>{1, 2, 3}));
  EXPECT_FALSE(parseNumberList("1,,3"));
  EXPECT_FALSE(parseNumberList(""));
  EXPECT_FALSE(parseNumberList("1,inf"));
  EXPECT_FALSE(parseNumberList("1,2", 3));
  const std::vector<double> values{0.1 + 0.2, -1e-300, 12345.678901234567, 40};
  EXPECT_EQ(parseNumberList(formatNumberList(values)), values);
  EXPECT_EQ(formatNumberList({10, 20.5}), "10,20.5");
}

}  // namespace
}  // namespace vsil
