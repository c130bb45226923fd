#pragma once
// Procedural volumes with known geometry, for the demo, tests and analytic ground truth.
// Spec: gen:NAME[:N], N the edge length in samples (default 64). All are float32 volumes in
// [0, 1] with spacing 1, except where noted.
#include <string>
#include <vector>

#include "core/volume.h"

namespace vsil {

std::vector<std::string> generatorNames();
// `spec` without the "gen:" prefix, e.g. "sphere:128".
Volume generateVolume(const std::string& spec, const VolumeLimits& limits = {});

}  // namespace vsil
