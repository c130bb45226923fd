#include "job/animation.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/limits.h"
#include "core/options.h"
#include "slicing/technique_table.h"

namespace vsil {

namespace {

nlohmann::json valueJson(const SweepTarget& target, const std::vector<double>& value) {
  if (target.text) return value;
  return value.front();
}

// ---- The steps of sweepTargets(), in lookup order ------------------------------------------

// 1. The technique's Number and Integer options.
void addNumberOptions(const TechniqueInfo& technique, std::vector<SweepTarget>& targets) {
  for (const OptionSpec& spec : technique.options) {
    if (spec.kind != OptionKind::Number && spec.kind != OptionKind::Integer) continue;
    targets.push_back({spec.name, 1, spec.kind == OptionKind::Integer, false,
                       [name = spec.name](RenderRequest& request, const std::vector<double>& v) {
                         request.settings.options[name] = v.front();
                       }});
  }
}

// 2. The technique's Text options that hold numbers ("X,Y,Z"), componentwise.
void addNumberListOptions(const TechniqueInfo& technique, std::vector<SweepTarget>& targets) {
  for (const OptionSpec& spec : technique.options) {
    if (spec.kind != OptionKind::Text || spec.numberCount < 1) continue;
    targets.push_back({spec.name, spec.numberCount, false, true,
                       [name = spec.name](RenderRequest& request, const std::vector<double>& v) {
                         request.settings.options[name] = formatNumberList(v);
                       }});
  }
}

// 3. The shared numeric flags; the widths only where lines are broadened.
void addSharedFlags(const TechniqueInfo& technique, std::vector<SweepTarget>& targets) {
  using Apply = std::function<void(RenderRequest&, const std::vector<double>&)>;
  const auto shared = [&](std::string name, Apply apply) {
    targets.push_back({std::move(name), 1, false, false, std::move(apply)});
  };
  shared("zoom", [](RenderRequest& r, const std::vector<double>& v) {
    r.settings.camera.zoom = v.front();
  });
  shared("sampling", [](RenderRequest& r, const std::vector<double>& v) {
    r.settings.samplesPerVoxel = v.front();
  });
  if (!technique.outputs.state) return;
  shared("width", [](RenderRequest& r, const std::vector<double>& v) {
    r.postfx.width = WidthLaw::fixed(v.front());
  });
  shared("width-near",
         [](RenderRequest& r, const std::vector<double>& v) { r.postfx.width.near = v.front(); });
  shared("width-far",
         [](RenderRequest& r, const std::vector<double>& v) { r.postfx.width.far = v.front(); });
}

}  // namespace

Sweep parseSweep(const std::string& text) {
  const std::string where = "--sweep " + text;
  Sweep sweep;
  sweep.text = text;
  const std::size_t equals = text.find('=');
  const std::size_t colon = text.find(':', equals == std::string::npos ? 0 : equals);
  if (equals == std::string::npos || equals == 0 || colon == std::string::npos ||
      text.find(':', colon + 1) != std::string::npos) {
    throwInputError(where, "expected NAME=A:B (e.g. iso=30:50)");
  }
  sweep.name = text.substr(0, equals);
  // Python's spelling (sphere_weight) names the flag as the command line's does.
  std::replace(sweep.name.begin(), sweep.name.end(), '_', '-');
  const auto from = parseNumberList(std::string_view(text).substr(equals + 1, colon - equals - 1));
  const auto to = parseNumberList(std::string_view(text).substr(colon + 1));
  if (!from || !to) {
    throwInputError(where, "each end must be a number or numbers separated by commas");
  }
  if (from->size() != to->size()) {
    throwInputError(where, "both ends need the same number of components");
  }
  sweep.from = *from;
  sweep.to = *to;
  return sweep;
}

std::vector<SweepTarget> sweepTargets(const RenderRequest& request) {
  const TechniqueInfo& technique = findTechnique(request.settings.technique);
  std::vector<SweepTarget> targets;
  addNumberOptions(technique, targets);
  addNumberListOptions(technique, targets);
  addSharedFlags(technique, targets);
  return targets;
}

// The line width is one law, fixed (--width) or between two ends (--width-near, --width-far,
// given together): a sweep sets its part of it on every frame, so a width flag given beside it
// would be lost or mixed in unsaid.
void AnimationPlan::checkWidthSweep(const std::string& where, const std::string& name) const {
  if (name != "width" && name != "width-near" && name != "width-far") return;
  for (const std::string& flag : base_.lineFlagsGiven) {
    if (flag == "--width" || flag == "--width-near" || flag == "--width-far") {
      throwInputError(where, flag +
                                 " is given too, and the sweep sets the line width on every "
                                 "frame: give one of them");
    }
  }
}

AnimationPlan::AnimationPlan(RenderRequest base, AnimationSpec spec, const VolumeLimits& limits)
    : base_(std::move(base)), spec_(std::move(spec)) {
  if (spec_.frames < 1 || spec_.frames > limits::kMaxFrames) {
    throw InputError("--frames: " + std::to_string(spec_.frames) + " is outside 1.." +
                     std::to_string(limits::kMaxFrames));
  }
  if (!std::isfinite(spec_.orbitDeg)) throw InputError("--orbit: must be a finite angle");
  if (spec_.viewFrom.has_value() != spec_.viewTo.has_value()) {
    throw InputError(spec_.viewFrom ? "--view-from: needs --view-to"
                                    : "--view-to: needs --view-from");
  }
  RenderJob::checkRequest(base_, limits);

  const std::vector<SweepTarget> targets = sweepTargets(base_);
  for (const Sweep& sweep : spec_.sweeps) {
    const std::string where = "--sweep " + sweep.text;
    const auto target = std::find_if(targets.begin(), targets.end(),
                                     [&](const SweepTarget& t) { return t.name == sweep.name; });
    if (target == targets.end()) {
      std::vector<std::string> names;
      for (const auto& t : targets) names.push_back(t.name);
      throwInputError(where, "'" + sweep.name + "' cannot be swept with technique '" +
                                 base_.settings.technique + "' (can be swept: " + joined(names) +
                                 ")");
    }
    if (int(sweep.from.size()) != target->components) {
      throwInputError(where, "'" + sweep.name + "' takes " + std::to_string(target->components) +
                                 (target->components == 1 ? " number" : " numbers") +
                                 " at each end");
    }
    for (const Resolved& earlier : sweeps_) {
      const std::string& other = earlier.sweep.name;
      const bool widths = (other == "width" && sweep.name.starts_with("width-")) ||
                          (sweep.name == "width" && other.starts_with("width-"));
      if (other == sweep.name || widths) {
        throwInputError(where,
                        "'" + sweep.name + "' is already swept by --sweep " + earlier.sweep.text);
      }
    }
    checkWidthSweep(where, sweep.name);
    sweeps_.push_back({sweep, *target});
    // Each end alone over the base, so that an error names this sweep. A number's checks are
    // ranges, which hold between ends that pass; a vector's need not (a plane's normal passes
    // through 0 between 1,0,0 and -1,0,0): every frame of it is checked, before any renders.
    const int checked = target->components == 1 ? 2 : frames();
    for (int i = 0; i < checked; ++i) {
      const int frame = target->components == 1 ? i * (frames() - 1) : i;
      RenderRequest request = base_;
      target->apply(request, valueAt(sweeps_.back(), t(frame)));
      try {
        RenderJob::checkRequest(request, limits);
      } catch (const InputError& e) {
        throwInputError(where, (frame == 0              ? std::string("first frame")
                                : frame == frames() - 1 ? std::string("last frame")
                                                        : "frame " + std::to_string(frame + 1)) +
                                   ": " + e.what());
      }
    }
  }
  // A sweep of one end of a width law needs the other swept too (as render's --width-near
  // needs --width-far): it would take the default's 3 unsaid.
  for (const auto& [end, other] : {std::pair<const char*, const char*>{"width-near", "width-far"},
                                   {"width-far", "width-near"}}) {
    const auto swept = [&](const char* name) {
      return std::any_of(sweeps_.begin(), sweeps_.end(),
                         [&](const Resolved& r) { return r.sweep.name == name; });
    };
    if (swept(end) && !swept(other)) {
      throwInputError(std::string("--sweep ") + end,
                      std::string("needs --sweep ") + other + " too: a width law has two ends");
    }
  }
  if (spec_.viewFrom) {
    for (const glm::dvec2 view : {*spec_.viewFrom, *spec_.viewTo}) {
      if (!std::isfinite(view.x) || !std::isfinite(view.y)) {
        throw InputError("--view-from, --view-to: angles must be finite");
      }
    }
  }
  RenderJob::checkRequest(request(0), limits);
  RenderJob::checkRequest(request(frames() - 1), limits);
}

double AnimationPlan::t(int frame) const {
  return frames() > 1 ? double(frame) / double(frames() - 1) : 0.0;
}

std::vector<double> AnimationPlan::valueAt(const Resolved& resolved, double t) const {
  std::vector<double> value(resolved.sweep.from.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    // (1 − t)·A + t·B: exactly A at t = 0 and exactly B at t = 1.
    value[i] = (1.0 - t) * resolved.sweep.from[i] + t * resolved.sweep.to[i];
    if (resolved.target.integer) value[i] = std::round(value[i]);
  }
  return value;
}

glm::dvec2 AnimationPlan::viewAt(int frame) const {
  const CameraSpec& camera = base_.settings.camera;
  glm::dvec2 view{camera.azimuthDeg, camera.elevationDeg};
  if (spec_.viewFrom) {
    const double s = t(frame);
    view = (1.0 - s) * *spec_.viewFrom + s * *spec_.viewTo;
  }
  // The fraction first: --orbit 1e308 times the frame number overflowed to infinity.
  view.x += spec_.orbitDeg * (double(frame) / double(frames()));
  return view;
}

RenderRequest AnimationPlan::request(int frame) const {
  RenderRequest request = base_;
  const glm::dvec2 view = viewAt(frame);
  request.settings.camera.azimuthDeg = view.x;
  request.settings.camera.elevationDeg = view.y;
  for (const Resolved& sweep : sweeps_) sweep.target.apply(request, valueAt(sweep, t(frame)));
  return request;
}

nlohmann::json AnimationPlan::sweptValues(int frame) const {
  nlohmann::json values = nlohmann::json::object();
  for (const Resolved& sweep : sweeps_) {
    values[sweep.sweep.name] = valueJson(sweep.target, valueAt(sweep, t(frame)));
  }
  return values;
}

nlohmann::json AnimationPlan::describe() const {
  nlohmann::json sweeps = nlohmann::json::array();
  for (const Resolved& sweep : sweeps_) {
    sweeps.push_back({{"name", sweep.sweep.name},
                      {"from", valueJson(sweep.target, sweep.sweep.from)},
                      {"to", valueJson(sweep.target, sweep.sweep.to)}});
  }
  nlohmann::json description = {{"frames", spec_.frames},
                                {"orbit_deg", spec_.orbitDeg},
                                {"view_from", nullptr},
                                {"view_to", nullptr},
                                {"sweeps", sweeps}};
  if (spec_.viewFrom) {
    description["view_from"] = {spec_.viewFrom->x, spec_.viewFrom->y};
    description["view_to"] = {spec_.viewTo->x, spec_.viewTo->y};
  }
  return description;
}

std::vector<std::string> AnimationWarnings::add(const std::vector<std::string>& frameWarnings) {
  std::vector<std::string> now;
  for (const std::string& warning : frameWarnings) {
    if (warning.ends_with("; ignored")) {
      ++ignoredIn_[warning];
    } else if (said_.insert(warning).second) {
      now.push_back(warning);
    }
  }
  return now;
}

std::vector<std::string> AnimationWarnings::finish(int frames) const {
  std::vector<std::string> held;
  for (const auto& [warning, count] : ignoredIn_) {
    if (count == frames) held.push_back(warning);
  }
  return held;
}

}  // namespace vsil
