#pragma once
// What every GL table's JSON rows must share, for the bench tests.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace vsil::test {

// Each measured row ran on the back end the machine block reports (the one `--gl` or $VSIL_GL
// chose; ctest runs the bench tests once per back end): a table that made its own context with
// other options would render on one back end and report another.
inline void expectRowsRanOnTheReportedBackEnd(const nlohmann::json& document) {
  const std::string machine = document["machine"]["gl_backend"];
  const std::string backend = machine.substr(0, machine.find(' '));  // "egl (egl device 0 ...)"
  if (const char* chosen = std::getenv("VSIL_GL"); chosen && *chosen) {
    EXPECT_EQ(backend, chosen);
  }
  int measured = 0;
  for (const auto& row : document["rows"]) {
    if (row.value("fps", nlohmann::json()).is_null()) continue;  // a dataset reported missing
    ++measured;
    EXPECT_EQ(row.value("gl_backend", ""), backend) << row.dump();
  }
  EXPECT_GT(measured, 0);
}

}  // namespace vsil::test
