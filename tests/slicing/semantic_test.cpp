// The semantic technique (slicing/techniques/semantic/): random rule bases on analytic volumes
// against the CPU reference (tests/reference/semantic_frame_reference.h), in the artistic
// template and in the flat rendering mode; flatness 0 is the ordinary composite; flatness 1
// shows the top priority through an occluder (gen:cube with the fig6-cube preset); moving the
// cursor changes only what the focus rules reach; a membership-function change re-renders
// without compiling a program, a rule change compiles one; a .png strip of spheres gives a style
// its colours; --plane-show draws the data on the plane in grey.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "frame_compare.h"
#include "generators/generators.h"
#include "gl_harness.h"
#include "semantic_frame_reference.h"
#include "slice_sampler.h"
#include "slicing/renderer.h"
#include "slicing/shader_program.h"
#include "slicing/techniques/semantic/rule_compiler.h"

namespace vsil {
namespace {

std::string writeRulesFile(const std::string& name, const std::string& text) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("vsil_semantic_" + std::to_string(::getpid()) + "_" + name + ".rules");
  std::ofstream(file) << text;
  return file.string();
}

RenderSettings semanticSettings(const std::string& rules, glm::ivec2 size = {96, 80}) {
  RenderSettings settings;
  settings.technique = "semantic";
  if (!rules.empty()) settings.options["rules"] = rules;
  settings.size = size;
  settings.camera.azimuthDeg = 30;
  settings.camera.elevationDeg = 20;
  settings.camera.zoom = 1.4;
  return settings;
}

// A random rule base: a data attribute that keeps the air empty, up to two attributes of other
// sources, one to three styles of random priorities, rules that combine the data term with
// others under and/or/not; with `flatness`, a flatness block and a rule that sets it.
std::string randomRules(unsigned seed, bool flatness) {
  std::mt19937 random(seed);
  const auto uniform = [&](double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random);
  };
  const auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(random); };
  // Edges at least 0.1 wide: the membership tables (1024 entries) then hold them within 0.6/255.
  const auto trapezoid = [&](double start) {
    const double a = start, b = a + uniform(0.1, 0.25), c = b + uniform(0.0, 0.3),
                 d = std::min(1.0, c + uniform(0.1, 0.3));
    std::ostringstream out;
    out << "trapezoid(" << a << ", " << b << ", " << std::min(c, d) << ", " << d << ")";
    return out.str();
  };
  const auto shape = [&] {
    if (pick(3) == 0) {
      std::ostringstream out;
      out << "gauss(" << uniform(0.1, 0.9) << ", " << uniform(0.08, 0.25) << ")";
      return out.str();
    }
    return trapezoid(uniform(0.0, 0.5));
  };
  const char* sources[] = {"gradient",       "cursor_distance", "plane_distance",
                           "image_distance", "view_angle",      "time"};
  const char* spheres[] = {"gray", "ivory", "skin", "red", "green", "blue"};
  std::ostringstream text;
  text << "attribute density from data { a = " << trapezoid(uniform(0.1, 0.3))
       << "  b = " << trapezoid(uniform(0.3, 0.6)) << " }\n";
  const int others = 1 + pick(2);
  for (int i = 0; i < others; ++i) {
    text << "attribute x" << i << " from " << sources[pick(6)] << " { p = " << shape()
         << "  q = " << shape() << " }\n";
  }
  const int styles = 1 + pick(3);
  for (int s = 0; s < styles; ++s) {
    text << "style s" << s << " priority " << pick(4) << " { spheres = \"" << spheres[pick(6)]
         << "\"  lo = triangle(0, 0, " << uniform(0.3, 0.6) << ")  hi = trapezoid("
         << uniform(0.3, 0.6) << ", 0.8, 1, 1) }\n";
  }
  if (flatness)
    text << "flatness { some = triangle(0.2, 0.5, 0.8)  full = trapezoid(0.6, 0.9, 1, 1) }\n";
  const auto term = [&] {
    const int attribute = pick(others);
    std::string t = "x" + std::to_string(attribute) + " is " + (pick(2) ? "p" : "q");
    return pick(3) == 0 ? "not " + t : t;
  };
  const int rules = 2 + pick(5);
  for (int r = 0; r < rules; ++r) {
    text << "rule if density is " << (pick(2) ? "a" : "b");
    const int extra = pick(3);
    for (int e = 0; e < extra; ++e) {
      if (pick(3) == 0) {
        text << " and (" << term() << " or " << term() << ")";
      } else {
        text << " and " << term();
      }
    }
    text << " then s" << pick(styles) << " is " << (pick(2) ? "lo" : "hi") << "\n";
  }
  // Every style reached (else a warning, and a style that adds nothing).
  for (int s = 0; s < styles; ++s) text << "rule if density is b then s" << s << " is hi\n";
  if (flatness)
    text << "rule if " << term() << " then flatness is " << (pick(2) ? "some" : "full") << "\n";
  return text.str();
}

struct RandomCase {
  std::string name;
  unsigned seed;
  std::string volume;
  bool flatness;
  bool orthographic;
};

std::ostream& operator<<(std::ostream& out, const RandomCase& c) {
  return out << c.name;
}

const RandomCase kRandomCases[] = {
    {"sphere_1", 1, "sphere:48", false, false},  {"torus_2", 2, "torus:48", false, false},
    {"spheres_3", 3, "spheres:48", false, true}, {"sphere_4", 4, "sphere:48", false, true},
    {"cube_5", 5, "cube:40", false, false},      {"flat_sphere_6", 6, "sphere:48", true, false},
    {"flat_torus_7", 7, "torus:48", true, true}, {"flat_spheres_8", 8, "spheres:48", true, false},
};

class SemanticMatchesReference : public test::GlTest,
                                 public ::testing::WithParamInterface<RandomCase> {};

// The rule base's name goes into the generated GLSL's comments only as text a comment holds: a
// newline in a file's name started shader code there ("#error", or worse, a "#define").
TEST(RuleCompiler, AFileNameCannotStartShaderCode) {
  const RuleBase base = parseRulesText(
      "attribute a from gradient { x = triangle(0, 0.5, 1) }\n"
      "style s { spheres = \"blue\" v = points((0, 0), (1, 1)) }\n"
      "rule if a is x then s is v\n",
      "in\n#define semanticData 1.0\r\n#error injected\\\n\xff.rules");
  const std::string glsl = compileRules(base).glsl;
  std::istringstream lines(glsl);
  int comments = 0;
  for (std::string line; std::getline(lines, line);) {
    EXPECT_FALSE(line.starts_with("#error") || line.starts_with("#define semanticData")) << line;
    if (line.find("//") != std::string::npos) {
      ++comments;
      EXPECT_EQ(line.find_first_of("\\\r"), std::string::npos) << line;
    }
  }
  EXPECT_GE(comments, 2);  // the header and the rule's line
  EXPECT_NE(glsl.find("in?#define semanticData 1.0??#error injected???.rules"), std::string::npos);
}

TEST_P(SemanticMatchesReference, EveryChannelWithin2Of255) {
  const RandomCase& c = GetParam();
  const std::string text = randomRules(c.seed, c.flatness);
  SCOPED_TRACE(text);
  const Volume volume = generateVolume(c.volume);
  RenderSettings settings = semanticSettings(writeRulesFile(c.name, text));
  settings.camera.orthographic = c.orthographic;
  settings.options["cursor"] = std::string("20,26,30");
  settings.options["cursor-pixel"] = std::string("30,50");
  settings.options["plane"] = std::string("24,24,24,1,2,0.5");
  settings.options["time"] = 0.4;
  const reference::ReferenceFrame cpu = reference::renderSemantic(volume, settings, 0.0f);
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  const RenderResult gl = renderer.render(settings);
  ASSERT_EQ(gl.sliceCount, cpu.sliceCount);
  double maxError = 0;
  int over = 0, ambiguous = 0;
  std::ostringstream first;
  for (int y = 0; y < settings.size.y; ++y) {
    for (int x = 0; x < settings.size.x; ++x) {
      const double pixelError = test::maxChannelDifference(gl.frame.color, cpu.frame.color, y, x);
      if (cpu.ambiguous(y, x)) {
        ambiguous += pixelError > 2.0 / 255.0;
        continue;
      }
      maxError = std::max(maxError, pixelError);
      if (pixelError > 2.0 / 255.0 && ++over <= 3) {
        first << " (" << x << "," << y << ") gl " << gl.frame.color(y, x) << " cpu "
              << cpu.frame.color(y, x) << ";";
      }
    }
  }
  const int shown = test::shownPixels(cpu.frame);
  std::cout << "[ info ] " << c.name << ": " << shown << " pixels shown, max channel error "
            << maxError * 255.0 << "/255, " << over << " over 2/255, " << ambiguous
            << " ambiguous regions differing\n";
  EXPECT_GT(shown, 300);
  // Both composite in float from the same texels and tables; 2/255 covers early ray
  // termination (<= 1/255) and trilinear weights rounded in a different order (as illustrate).
  EXPECT_EQ(over, 0) << "pixels off by more than 2/255:" << first.str();
  // Flat mode: where a sample's region is decided within kRegionEpsilon, GL may enter the other.
  EXPECT_LE(ambiguous, std::max(2, shown / 100));
}

INSTANTIATE_TEST_SUITE_P(RandomRuleBases, SemanticMatchesReference,
                         ::testing::ValuesIn(kRandomCases),
                         [](const auto& info) { return info.param.name; });

class SemanticTest : public test::GlTest {};

TEST_F(SemanticTest, FlatnessZeroGivesTheOrdinaryComposite) {
  const Volume volume = generateVolume("cube:40");
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  // fig6-cube without its flatness rule: the artistic template, blended.
  const std::string text = R"(attribute density from data {
      low = trapezoid(0, 0, 0.3, 0.6)  high = trapezoid(0.4, 0.7, 1, 1) }
    style shell priority 1 { spheres = "gray"  faint = triangle(0, 0, 0.4)  strong = trapezoid(0.5, 0.8, 1, 1) }
    style core priority 2 { spheres = "red"  low = triangle(0, 0, 0.4)  high = trapezoid(0.5, 0.8, 1, 1) }
    rule if density is low then shell is faint
    rule if density is high then core is high)";
  RenderSettings settings = semanticSettings(writeRulesFile("flat0", text));
  const RenderResult ordinary = renderer.render(settings);
  settings.options["flatness"] = 0.0;  // the flat mode's program, p_f = 0
  const RenderResult flat = renderer.render(settings);
  EXPECT_GT(test::shownPixels(ordinary.frame), 500);
  EXPECT_EQ(ordinary.options["semantic"]["flat_mode"], false);
  EXPECT_EQ(flat.options["semantic"]["flat_mode"], true);
  // Early ray termination differs (flat mode retires a pixel only when nothing higher is
  // left): at most 1/255 per channel; otherwise the same operations.
  EXPECT_LE(test::maxChannelDifference(ordinary.frame.color, flat.frame.color), 1.0 / 255.0 + 1e-6);
}

// The straight colour's red minus its blue, averaged over the centre block: the core is red,
// the shell grey.
double centreRedness(const cv::Mat4f& color) {
  double sum = 0;
  int count = 0;
  for (int y = color.rows / 2 - 4; y < color.rows / 2 + 4; ++y) {
    for (int x = color.cols / 2 - 4; x < color.cols / 2 + 4; ++x) {
      const cv::Vec4f c = color(y, x);
      if (c[3] <= 0.05f) continue;
      sum += (c[0] - c[2]) / c[3];
      ++count;
    }
  }
  EXPECT_GT(count, 30);
  return count ? sum / count : 0;
}

TEST_F(SemanticTest, FlatnessOneShowsTheTopPriorityThroughTheOccluder) {
  const Volume volume = generateVolume("cube:48");
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  RenderSettings settings = semanticSettings("fig6-cube", {80, 80});
  settings.options["flatness"] = 0.0;
  const double hidden = centreRedness(renderer.render(settings).frame.color);
  settings.options["flatness"] = 0.5;
  const double half = centreRedness(renderer.render(settings).frame.color);
  settings.options["flatness"] = 1.0;
  const double shown = centreRedness(renderer.render(settings).frame.color);
  std::cout << "[ info ] centre redness at flatness 0, 0.5, 1: " << hidden << ", " << half << ", "
            << shown << "\n";
  // Red minus blue of the shaded red ramp is about 0.4 where it is all that shows.
  EXPECT_LT(hidden, 0.12) << "the grey shell hides the core";
  EXPECT_GT(half, hidden + 0.1);
  EXPECT_GT(shown, half + 0.1);
  EXPECT_GT(shown, 0.3) << "the red core shows through";
}

// How far the edge between the cube's top face and its front face (gen:cube:64, fig6-cube at
// flatness 1, 256², view 30, 20, zoom 1) strays from a straight line: per column, the edge's
// position (the row below the cube's top row plus the summed fraction of the top face's tone over
// the front face's, from the top row to 6 rows past where the front face's tone begins), then the
// RMS residual from a least-squares line, in pixels. The faces are flat in tone (one normal
// each), so a straight edge gives the staircase of its pixels only, ~0.25 px; samples on the
// slice planes give a rope of top-face samples under the edge whose period follows the planes.
double cubeEdgeWaviness(const cv::Mat4f& color) {
  // Over white, as `vsil render` writes it.
  const auto luminance = [&](int y, int x) {
    const cv::Vec4f c = color(y, x);
    return (c[0] + c[1] + c[2]) / 3.0 + (1.0 - c[3]);
  };
  const double frontTone = luminance(150, 60);  // well inside the front face
  std::vector<double> xs, ys;
  for (int x = 30; x <= 90; ++x) {  // the edge's columns away from its ends and the red core
    int top = 0;
    while (top < color.rows && color(top, x)[3] < 0.5f) ++top;
    if (top + 40 >= color.rows) continue;
    const double topTone = luminance(top + 2, x);
    if (!(topTone > frontTone + 0.02)) continue;
    int front = top + 3;
    while (front < top + 40 && luminance(front, x) > frontTone + 0.1 * (topTone - frontTone)) {
      ++front;
    }
    // From the row below the outline's (partly transparent) row.
    double position = top + 1;
    for (int y = top + 1; y < front + 6; ++y) {
      position += (luminance(y, x) - frontTone) / (topTone - frontTone);
    }
    xs.push_back(x);
    ys.push_back(position);
  }
  EXPECT_GT(xs.size(), 50u) << "the top-front edge was not found";
  if (xs.size() < 3) return 1e9;
  const double n = double(xs.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) mx += xs[i] / n, my += ys[i] / n;
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    sxy += (xs[i] - mx) * (ys[i] - my);
    sxx += (xs[i] - mx) * (xs[i] - mx);
  }
  const double slope = sxy / sxx;
  double squares = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double r = ys[i] - (my + slope * (xs[i] - mx));
    squares += r * r;
  }
  return std::sqrt(squares / n);
}

TEST_F(SemanticTest, TheCubesEdgeIsStraightAtTheDefaultSampling) {
  const Volume volume = generateVolume("cube:64");
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  RenderSettings settings = semanticSettings("fig6-cube", {256, 256});
  settings.camera.zoom = 1.0;
  settings.options["flatness"] = 1.0;
  const double atOne = cubeEdgeWaviness(renderer.render(settings).frame.color);
  settings.samplesPerVoxel = 4;
  const double atFour = cubeEdgeWaviness(renderer.render(settings).frame.color);
  std::cout << "[ info ] RMS of the edge from a straight line at sampling 1, 4: " << atOne << ", "
            << atFour << " px\n";
  // Samples on the slice planes: 1.8 px at sampling 1, 0.25 at 4. Aligned to the box entry:
  // 0.25 and 0.20.
  EXPECT_LT(atOne, 0.5);
  EXPECT_LT(atFour, 0.5);
}

TEST_F(SemanticTest, MovingTheCursorChangesOnlyTheRegionTheFocusRulesName) {
  const Volume volume = generateVolume("sphere:48");
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  // The focus: within 0.1 of the box diagonal (8.3 voxels) of the cursor.
  const std::string text = R"(attribute density from data { some = trapezoid(0.1, 0.3, 1, 1) }
    attribute focus from cursor_distance { near = trapezoid(0, 0, 0.06, 0.1) }
    style tissue { spheres = "skin"  faint = triangle(0, 0, 0.3)  opaque = trapezoid(0.5, 0.8, 1, 1) }
    rule if density is some and not focus is near then tissue is faint
    rule if density is some and focus is near then tissue is opaque)";
  RenderSettings settings = semanticSettings(writeRulesFile("cursor", text), {96, 96});
  settings.camera.orthographic = true;
  settings.camera.azimuthDeg = 0;
  settings.camera.elevationDeg = 0;
  const glm::dvec3 a(16, 24, 24), b(32, 24, 24);
  settings.options["cursor"] = std::string("16,24,24");
  const RenderResult first = renderer.render(settings);
  settings.options["cursor"] = std::string("32,24,24");
  const RenderResult second = renderer.render(settings);
  // The options record the interaction as used: the cursor given, its pixel and the plane
  // resolved (round 18: the defaults were recorded as "" alone).
  const nlohmann::json& used = second.options["semantic"];
  EXPECT_EQ(used["cursor"], nlohmann::json({32.0, 24.0, 24.0}));
  EXPECT_EQ(used["plane"], nlohmann::json({23.5, 23.5, 23.5, 0.0, 0.0, 1.0}));
  EXPECT_EQ(used["cursor_pixel"].size(), 2u);
  settings.options.erase("cursor");
  EXPECT_EQ(renderer.render(settings).options["semantic"]["cursor"],
            nlohmann::json({23.5, 23.5, 23.5}))
      << "the default: the volume's centre";
  // Where the focus balls (radius 0.1 of the diagonal) around either cursor project, with a
  // pixel to spare.
  const double radius = 0.1 * glm::length(glm::dvec3(volume.dims));
  const auto nearCursor = [&](const View& view, glm::dvec3 cursor, int x, int y) {
    glm::dvec2 low(1e30), high(-1e30);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 offset(corner & 1 ? radius : -radius, corner & 2 ? radius : -radius,
                              corner & 4 ? radius : -radius);
      const glm::dvec4 clip = view.clipFromVoxel() * glm::dvec4(cursor + offset, 1.0);
      const glm::dvec2 pixel((clip.x / clip.w + 1) * 48.0, (1 - clip.y / clip.w) * 48.0);
      low = glm::min(low, pixel);
      high = glm::max(high, pixel);
    }
    const glm::dvec2 centre(x + 0.5, y + 0.5);
    return centre.x >= low.x - 1.5 && centre.x <= high.x + 1.5 && centre.y >= low.y - 1.5 &&
           centre.y <= high.y + 1.5;
  };
  int changedInside = 0, changedOutside = 0;
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 96; ++x) {
      const cv::Vec4f p = first.frame.color(y, x), q = second.frame.color(y, x);
      const bool changed = cv::norm(p - q, cv::NORM_INF) > 0;
      const bool inside = nearCursor(first.view, a, x, y) || nearCursor(first.view, b, x, y);
      (inside ? changedInside : changedOutside) += changed;
    }
  }
  std::cout << "[ info ] pixels changed near the cursors " << changedInside << ", elsewhere "
            << changedOutside << "\n";
  EXPECT_GT(changedInside, 100);
  EXPECT_EQ(changedOutside, 0);
}

TEST_F(SemanticTest, AMembershipChangeReRendersWithoutCompilingARuleChangeCompiles) {
  const Volume volume = generateVolume("sphere:40");
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  const std::string head = "attribute density from data { some = ";
  const std::string tail = R"( }
    style tissue priority 1 { spheres = "skin"  opaque = trapezoid(0.5, 0.8, 1, 1) }
    rule if density is some then tissue is opaque
)";
  const std::string path = writeRulesFile("change", head + "trapezoid(0.1, 0.3, 1, 1)" + tail);
  const RenderSettings settings = semanticSettings(path);
  const RenderResult before = renderer.render(settings);
  const int builds = renderer.programs().builds();
  // Another shape and other numbers: data, not code.
  std::ofstream(path) << head + "gauss(0.7, 0.1)" + tail;
  const RenderResult changed = renderer.render(settings);
  EXPECT_EQ(renderer.programs().builds(), builds) << "a membership change must not recompile";
  EXPECT_EQ(changed.options["semantic"]["program_compiled"], false);
  EXPECT_GT(test::differingPixels(before.frame, changed.frame), 100);
  // A rule more: new code.
  std::ofstream(path) << head + "gauss(0.7, 0.1)" + tail +
                             "rule if not density is some then tissue is opaque\n";
  renderer.render(settings);
  EXPECT_EQ(renderer.programs().builds(), builds + 1);
}

TEST_F(SemanticTest, SphereFilesThatDoNotReadAreNamedInTheError) {
  const std::string path =
      writeRulesFile("badpng",
                     "attribute d from data { v = trapezoid(0.1, 0.2, 1, 1) }\n"
                     "style s { spheres = \"missing-spheres.png\"  v = triangle(0, 1, 1) }\n"
                     "rule if d is v then s is v\n");
  Renderer renderer(test::sharedGlContext());
  const Volume volume = generateVolume("sphere:16");  // alive while rendered (setVolume)
  renderer.setVolume(volume);
  try {
    renderer.render(semanticSettings(path));
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("missing-spheres.png"), std::string::npos)
        << error.what();
  }
}

// A .png strip of spheres: a red sphere, then a blue one, written with OpenCV (BGR, 8 bit, no
// alpha: opaque). A style whose value is near 0 shows the first sphere's colour, one near 1 the
// last's: the colours come from the file, channel order included, and nothing of a built-in
// ramp's shading is left (green stays 0).
TEST_F(SemanticTest, APngSphereStripGivesTheStyleItsColours) {
  const std::string stem = "vsil_semantic_" + std::to_string(::getpid()) + "_strip.png";
  const auto strip = std::filesystem::temp_directory_path() / stem;
  cv::Mat3b image(16, 32, cv::Vec3b(0, 0, 0));
  image(cv::Rect(0, 0, 16, 16)).setTo(cv::Vec3b(0, 0, 255));   // red (BGR)
  image(cv::Rect(16, 0, 16, 16)).setTo(cv::Vec3b(255, 0, 0));  // blue
  ASSERT_TRUE(cv::imwrite(strip.string(), image));
  const Volume volume = generateVolume("sphere:40");
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  const auto renderWith = [&](const std::string& value) {
    const std::string text =
        "attribute density from data { some = trapezoid(0.1, 0.3, 1, 1) }\n"
        "style painted { spheres = \"" +
        stem +
        "\"  low = triangle(0, 0, 0.1)  high = trapezoid(0.9, 1, 1, 1) }\n"
        "rule if density is some then painted is " +
        value + "\n";
    return renderer.render(semanticSettings(writeRulesFile("strip_" + value, text))).frame.color;
  };
  // The mean straight colour of the pixels that show something.
  const auto meanColour = [](const cv::Mat4f& color) {
    cv::Vec3d sum(0, 0, 0);
    int count = 0;
    for (auto it = color.begin(); it != color.end(); ++it) {
      const cv::Vec4f c = *it;
      if (c[3] < 0.2f) continue;
      sum += cv::Vec3d(c[0] / c[3], c[1] / c[3], c[2] / c[3]);
      ++count;
    }
    EXPECT_GT(count, 500);
    return count ? sum / double(count) : sum;
  };
  const cv::Vec3d low = meanColour(renderWith("low"));
  const cv::Vec3d high = meanColour(renderWith("high"));
  std::filesystem::remove(strip);
  std::cout << "[ info ] straight colour near the first sphere " << low << ", near the last "
            << high << "\n";
  // `low`'s centroid is about 0.03 of the way along the strip, `high`'s about 0.95.
  EXPECT_GT(low[0], 0.9);
  EXPECT_LT(low[2], 0.1);
  EXPECT_GT(high[2], 0.9);
  EXPECT_LT(high[0], 0.1);
  EXPECT_LT(low[1], 1e-4);
  EXPECT_LT(high[1], 1e-4);
  EXPECT_NEAR(low[0] + low[2], 1.0, 1e-3) << "a mix of the two spheres' colours";
  EXPECT_NEAR(high[0] + high[2], 1.0, 1e-3);
}

// --plane-show: where the plane crosses the volume and no style shows along the ray, the pixel is
// the data at the plane in grey, opaque; without it the same pixels are empty. The plane goes
// through the centre of a ball whose only style is its core (data ≥ 0.75, within 6 voxels of the
// centre), tilted against the view so that every ray has a sample within half a voxel of it.
TEST_F(SemanticTest, PlaneShowDrawsTheDataOnThePlaneInGrey) {
  const Volume volume = generateVolume("sphere:48");
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  const std::string text = R"(attribute density from data { core = trapezoid(0.75, 0.85, 1, 1) }
    style core priority 1 { spheres = "red"  opaque = trapezoid(0.6, 0.9, 1, 1) }
    rule if density is core then core is opaque)";
  RenderSettings settings = semanticSettings(writeRulesFile("plane", text), {96, 96});
  settings.camera.orthographic = true;
  settings.camera.zoom = 1.0;
  const RenderResult without = renderer.render(settings);
  const View& view = without.view;
  const glm::dvec3 centre = (glm::dvec3(volume.dims) - 1.0) * 0.5;
  const glm::dvec3 forward = view.viewDirectionWorld();
  const glm::dvec3 side = glm::normalize(glm::cross(forward, glm::dvec3(0, 0, 1)));
  const glm::dvec3 normal = glm::normalize(forward + 0.6 * side);
  std::ostringstream plane;
  plane << centre.x << "," << centre.y << "," << centre.z << "," << normal.x << "," << normal.y
        << "," << normal.z;
  settings.options["plane"] = plane.str();
  settings.options["plane-show"] = true;
  const RenderResult shown = renderer.render(settings);
  EXPECT_EQ(shown.options["semantic"]["program_compiled"], true) << "another program";

  const reference::SliceSampler sampler(volume, view);
  const ValueRange range = valueRange(volume);
  int checked = 0, bright = 0;
  double worst = 0;
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 96; ++x) {
      // The pixel's ray in voxels, and where it meets the plane.
      const glm::dvec3 a(sampler.voxelFromEyePoint(sampler.eyePoint(x, y, float(view.nearEye))));
      const glm::dvec3 b(sampler.voxelFromEyePoint(sampler.eyePoint(x, y, float(view.farEye))));
      const glm::dvec3 direction = glm::normalize(b - a);
      const double along = glm::dot(centre - a, normal) / glm::dot(direction, normal);
      const glm::dvec3 hit = a + along * direction;
      // Only rays that stay 10 voxels from the centre (data ≤ 0.58: the core's style never
      // fires), with the hit a voxel inside the box.
      const glm::dvec3 offset = centre - a;
      const double fromCentre = glm::length(offset - glm::dot(offset, direction) * direction);
      const bool inside = glm::all(glm::greaterThan(hit, glm::dvec3(1.0))) &&
                          glm::all(glm::lessThan(hit, glm::dvec3(volume.dims) - 2.0));
      if (fromCentre < 10.0 || !inside) continue;
      const double expected =
          (double(sampler.sample(glm::vec3(hit))) - range.min) / (double(range.max) - range.min);
      const cv::Vec4f p = shown.frame.color(y, x);
      SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
      ASSERT_NEAR(p[3], 1.0f, 1e-5f) << "the plane is opaque";
      ASSERT_NEAR(p[0], p[1], 1e-5f) << "grey";
      ASSERT_NEAR(p[1], p[2], 1e-5f) << "grey";
      worst = std::max(worst, std::abs(double(p[0]) - expected));
      ASSERT_EQ(without.frame.color(y, x)[3], 0.0f) << "nothing there without the plane";
      ++checked;
      bright += expected > 0.2;
    }
  }
  std::cout << "[ info ] " << checked << " plane pixels checked (" << bright
            << " brighter than 0.2), largest difference from the data " << worst << "\n";
  EXPECT_GT(checked, 1000);
  EXPECT_GT(bright, 300);
  // Slices sample within half a voxel of the plane (along the ray up to 0.6 voxel): the data
  // changes by 1/24 per voxel here.
  EXPECT_LT(worst, 0.035);
}

}  // namespace
}  // namespace vsil
