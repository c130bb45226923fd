#pragma once
// What `vsil bench` was asked to do. Checked by validateOptions() before anything runs.
#include <filesystem>
#include <string>
#include <vector>

#include "slicing/gl_context.h"

namespace vsil::bench {

struct BenchOptions {
  std::vector<std::string> tables;    // empty: every implemented table
  std::filesystem::path datasetsDir;  // empty: ../shared/datasets, else the one beside the source
  std::vector<std::string> only;      // dataset names; empty: all of a table's datasets
  std::vector<int> sizes;             // square window sides; empty: each table's own sizes
  int frames = 10;                    // timed frames per case
  int warmup = 2;                     // untimed frames before them
  std::filesystem::path json, markdown, plot;  // optional outputs
  gl::ContextOptions gl;                       // --gl, --gl-device: the back end every table uses
};

}  // namespace vsil::bench
