#pragma once
// The benchmark tables `vsil bench --table NAME` knows. Adding a table is one entry in
// table_registry.cpp: its name, a description, the datasets --only may name, and its run
// function (left empty while the technique it measures does not exist yet).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "harness/table.h"

namespace vsil::bench {

struct TableDefinition {
  std::string name;
  std::string description;
  std::vector<std::string> datasets;  // names --only accepts for this table (may be empty)
  TableRun run;                       // empty: not implemented yet
  std::string
      missingTechnique;  // when run is empty: why, e.g. "the x technique does not exist yet"
  // Runs only when --table names it (minutes and gigabytes of disk: the large table).
  bool onlyWhenNamed = false;
  // The file in the datasets folder a dataset of this table is read from; none for a name it
  // does not read from a file (generated volumes, the paper's Skull, the scaling techniques).
  std::function<std::optional<std::string>(const std::string& name)> datasetFile = nullptr;
};

const std::vector<TableDefinition>& tableRegistry();

// Throws InputError "--table NAME: ..." for unknown names and for tables not implemented yet.
const TableDefinition& implementedTable(const std::string& name);

}  // namespace vsil::bench
