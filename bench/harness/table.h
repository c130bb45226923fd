#pragma once
// What every benchmark table hands back to the harness, and what it gets to run with. A table
// is one function (TableRun) registered by name in table_registry.cpp.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/bench_options.h"
#include "harness/progress.h"

namespace vsil::bench {

// A grouped bar chart: one group per row of a table, one bar per series in each group. NaN
// values are drawn as "n/a".
struct PlotSpec {
  std::string title;
  std::string valueLabel;  // e.g. "fps (log scale)"
  bool logScale = true;
  struct Series {
    std::string name;
    bool reference = false;  // drawn hatched: numbers quoted from a paper, not measured here
    int color = -1;          // palette index; -1: the series' own index
  };
  std::vector<Series> series;
  std::vector<std::string> groups;
  std::vector<std::vector<double>> values;  // [group][series]
};

struct TableResult {
  std::string name;   // e.g. "nk3"
  std::string title;  // one line
  std::string text;   // aligned plain-text table for stdout
  std::string markdown;
  nlohmann::json rows = nlohmann::json::array();  // each carries "table"
  std::vector<std::string> notes;     // printed under the table (missing data, iso values, ...)
  std::vector<std::string> failures;  // failed self-checks, "bonsai 512² ops: reason"
  PlotSpec plot;                      // empty series: nothing to plot
};

using TableRun = std::function<TableResult(const BenchOptions& options, Progress& progress)>;

}  // namespace vsil::bench
