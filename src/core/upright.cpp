#include "core/upright.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace vsil {
namespace {

std::string axisText(const glm::dvec3& axis) {
  for (int a = 0; a < 3; ++a) {
    if (axis[a] != 0) return std::string(axis[a] > 0 ? "+" : "-") + char('x' + a);
  }
  return "?";
}

ResolvedUpright make(glm::dvec3 up, glm::dvec3 front, std::string from) {
  return {{up, front}, axisText(up), axisText(front), std::move(from)};
}

// The opposite anatomical direction's letter.
char opposite(char letter) {
  switch (letter) {
    case 'R':
      return 'L';
    case 'L':
      return 'R';
    case 'A':
      return 'P';
    case 'P':
      return 'A';
    case 'S':
      return 'I';
    case 'I':
      return 'S';
  }
  return '?';
}

// The index axis (as a signed unit world axis) whose letters in `axes` run toward `letter`, or
// 0 where none does.
glm::dvec3 indexAxisToward(const std::string& axes, char letter) {
  for (int a = 0; a < 3 && a < int(axes.size()); ++a) {
    glm::dvec3 axis(0.0);
    if (axes[a] == letter) axis[a] = 1;
    if (axes[a] == opposite(letter)) axis[a] = -1;
    if (axis != glm::dvec3(0.0)) return axis;
  }
  return glm::dvec3(0.0);
}

// Whether each index axis runs toward its own anatomical direction (an oblique placement can
// name one twice: "SSA").
bool namesEachDirectionOnce(const std::string& axes) {
  if (axes.size() != 3) return false;
  for (const char* pair : {"RL", "AP", "SI"}) {
    if (std::count_if(axes.begin(), axes.end(),
                      [&](char c) { return c == pair[0] || c == pair[1]; }) != 1) {
      return false;
    }
  }
  return true;
}

// The placement medical tools go by: NIfTI's sform where it has one (as nibabel's affine),
// else the first (qform, DICOM's patient frame, NRRD's space).
const Orientation* anatomicalPlacement(const std::vector<Orientation>& placements) {
  const Orientation* chosen = nullptr;
  for (const Orientation& o : placements) {
    if (!chosen || o.name == "sform") chosen = &o;
  }
  return chosen;
}

}  // namespace

std::string anatomicalAxes(const glm::dmat3& directions, std::string_view spaceAxes) {
  static constexpr int kPermutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                              {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const auto cosine = [&](int axis, int space) {
    const double length = glm::length(directions[axis]);
    return length > 0 ? std::abs(directions[axis][space]) / length : 0.0;
  };
  const int* best = kPermutations[0];
  double bestScore = -1;
  for (const auto& permutation : kPermutations) {
    const double score =
        cosine(0, permutation[0]) + cosine(1, permutation[1]) + cosine(2, permutation[2]);
    if (score > bestScore) best = permutation, bestScore = score;
  }
  std::string axes;
  for (int axis = 0; axis < 3; ++axis) {
    const char positive = spaceAxes[std::size_t(best[axis])];
    axes += directions[axis][best[axis]] >= 0 ? positive : opposite(positive);
  }
  return axes;
}

ResolvedUpright resolveUpright(const std::string& flag,
                               const std::vector<Orientation>& placements) {
  if (flag == "auto") {
    if (const Orientation* o = anatomicalPlacement(placements)) {
      const glm::dvec3 superior = indexAxisToward(o->axes, 'S');
      const glm::dvec3 anterior = indexAxisToward(o->axes, 'A');
      if (namesEachDirectionOnce(o->axes)) {
        // Right-handed index axes show the patient as seen; a mirror image (LAS) stays one.
        const glm::dvec3 right = indexAxisToward(o->axes, 'R');
        const bool mirrored = glm::dot(glm::cross(right, anterior), superior) < 0;
        return make(
            superior, anterior,
            "the file's " + o->name + " (" + o->axes + "): superior up, anterior front" +
                (mirrored ? "; its axes store the patient mirrored, and so is the picture" : ""));
      }
    }
    return make({0, 1, 0}, {0, 0, 1}, "the default (no anatomical placement in the file)");
  }
  std::string text = flag;
  if (text.size() == 1) text = "+" + text;
  if (text.size() != 2 || (text[0] != '+' && text[0] != '-') || text[1] < 'x' || text[1] > 'z') {
    throwInputError(
        "--up", "'" + printableText(flag) + "' is not auto or an axis (+x, -x, +y, -y, +z, -z)");
  }
  const double sign = text[0] == '+' ? 1.0 : -1.0;
  glm::dvec3 up(0.0), front(0.0);
  up[text[1] - 'x'] = sign;
  if (text[1] == 'y') front = {0, 0, sign};
  if (text[1] == 'z') front = {0, -sign, 0};
  if (text[1] == 'x') front = {0, 0, 1};
  return make(up, front, "--up " + text);
}

}  // namespace vsil
