#pragma once
// A sequence of frames as `vsil animate` renders it: a base request (the render flags), a frame
// count, and what changes from frame to frame — an orbit of the camera, a view moving from one
// position to another, and sweeps of numeric parameters, all linear in the frame index.
//
// Frame i of N (i = 0 .. N − 1):
//  - sweeps and the view from `viewFrom` to `viewTo` at t = i / (N − 1): the first frame shows
//    A, the last B (a single frame: t = 0);
//  - the orbit adds orbitDeg · i / N to the azimuth: 360° ends one step before the start, so a
//    sequence played in a loop shows no frame twice.
//
// A sweep NAME=A:B names what it changes; sweepTargets() resolves names in one place:
//   1. the technique's Number and Integer options (its entry in slicing/technique_table.h;
//      Integer values are rounded to the nearest whole number at each frame),
//   2. the technique's Text options declared to hold numbers (OptionSpec::holdsNumbers, e.g. a
//      position "X,Y,Z"), componentwise: cursor=10,20,30:40,20,30,
//   3. the shared numeric flags: zoom, sampling, and for techniques whose lines are broadened
//      width, width-near, width-far.
// Each value is checked as the flag would be, at both ends before any frame is rendered (every
// rule on these values is an interval, which holds in between when it holds at the ends).
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "io/volume_loader.h"
#include "job/render_job.h"

namespace vsil {

struct Sweep {
  std::string text;  // as given ("iso=30:50"), for messages
  std::string name;
  std::vector<double> from, to;  // one number, or the components of a list
};

// Parses "NAME=A:B", each end a number or numbers separated by commas. InputError naming
// "--sweep TEXT" otherwise.
Sweep parseSweep(const std::string& text);

// What a sweep name changes in a request.
struct SweepTarget {
  std::string name;
  int components = 1;    // numbers at each end
  bool integer = false;  // rounded to the nearest whole number at each frame
  bool text = false;     // a Text option: its value is the numbers as "X,Y,Z"
  std::function<void(RenderRequest&, const std::vector<double>&)> apply;
};

// Everything that can be swept with `request`'s technique, in lookup order (above). A new kind
// of sweepable parameter (a technique's list of NAME=VALUE parameters, say) is one more step in
// this function.
std::vector<SweepTarget> sweepTargets(const RenderRequest& request);

struct AnimationSpec {
  std::int64_t frames = 1;
  double orbitDeg = 0;
  std::optional<glm::dvec2> viewFrom, viewTo;  // AZ,EL in degrees; both or neither
  std::vector<Sweep> sweeps;
};

class AnimationPlan {
 public:
  // Resolves the sweeps and checks everything that needs no volume: the frame count
  // (1 .. limits::kMaxFrames), the orbit, the sweep names (an unknown one: InputError listing
  // what can be swept), and the requests of the first and the last frame, each sweep's ends
  // alone first so that an error names its sweep. Throws InputError naming the flag.
  AnimationPlan(RenderRequest base, AnimationSpec spec, const VolumeLimits& limits);

  int frames() const { return int(spec_.frames); }
  // Where frame `frame` lies between the first (0) and the last (1) for sweeps and views.
  double t(int frame) const;
  // The request of frame `frame`: the base with its view and the swept values.
  RenderRequest request(int frame) const;
  // The swept values of a frame by name: a number, or a list for a Text option.
  nlohmann::json sweptValues(int frame) const;
  // The sequence as asked: frames, orbit, views, sweeps with their ends.
  nlohmann::json describe() const;

 private:
  struct Resolved {
    Sweep sweep;
    SweepTarget target;
  };
  // Refuses width flags given beside a sweep of the line width (`where` names the sweep).
  void checkWidthSweep(const std::string& where, const std::string& name) const;
  std::vector<double> valueAt(const Resolved& sweep, double t) const;
  glm::dvec2 viewAt(int frame) const;

  RenderRequest base_;
  AnimationSpec spec_;
  std::vector<Resolved> sweeps_;
};

// The warnings of an animation's frames, each said once. A warning that an option is ignored
// ("...; ignored") holds for the animation only where every frame had it: a sweep may turn on in
// later frames what frame 0 ignores (the colour sphere's weight from 0).
class AnimationWarnings {
 public:
  // The frame's warnings to say now, those not said before; "ignored" ones wait for finish().
  std::vector<std::string> add(const std::vector<std::string>& frameWarnings);
  // The "ignored" warnings that every one of `frames` frames had.
  std::vector<std::string> finish(int frames) const;

 private:
  std::set<std::string> said_;
  std::map<std::string, int> ignoredIn_;
};

}  // namespace vsil
