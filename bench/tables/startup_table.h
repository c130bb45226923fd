#pragma once
// startup: what a default `vsil render` costs from exec to exit, stage by stage. Each run is one
// child process rendering a dataset with no flags but the file, --out and --meta-out (the iso
// value from the histogram, each technique's default pipeline, 512²), timed from spawn to exit
// (wall, and the child's CPU time from getrusage), with the stages its --meta-out reports
// (timings_ms and cpu_ms: startup, context, read, upload, defaults, programs, render, readback,
// postfx, write). Runs alternate between Mesa's on-disk shader cache as it is and the same cache
// turned off (MESA_SHADER_CACHE_DISABLE=true), so that the cache's share is measured in the same
// run. Self-check: every run exits 0 and writes the same PNG bytes. Runs the vsil binary it is
// part of (/proc/self/exe).
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

// The dataset names --only accepts: bonsai (the default), engine, neghip (small: quick runs).
std::vector<std::string> startupDatasetNames();

// `vsil bench --table startup`: --frames runs per cache setting (default 10), --warmup untimed
// runs before them (default 2; they fill the shader and page caches), --sizes the window (512),
// --only the datasets.
TableResult runStartupTable(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
