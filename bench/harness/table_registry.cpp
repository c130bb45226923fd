#include "harness/table_registry.h"

#include "core/error.h"
#include "tables/animate_table.h"
#include "tables/dv1_table.h"
#include "tables/fft_table.h"
#include "tables/illustrate_table.h"
#include "tables/large_table.h"
#include "tables/nk3_table.h"
#include "tables/scaling_table.h"
#include "tables/semantic_table.h"
#include "tables/startup_table.h"

namespace vsil::bench {
namespace {

// The classic datasets' files as Table 3 lists them (the animate and startup tables read those).
std::optional<std::string> classicDatasetFile(const std::string& name) {
  const auto file = nk3DatasetFile(name);
  return file ? std::optional<std::string>(file->file) : std::nullopt;
}

std::vector<TableDefinition> makeRegistry() {
  return {
      {"nk3", "Nagy–Klein Table 3: RA, OPS and BS frame rates per dataset and window",
       nk3DatasetNames(), runNk3Table, "", false, classicDatasetFile},
      {"fft", "broadening cost against sigma: FFT vs OpenCV GaussianBlur", {}, runFftTable, ""},
      {"animate", "one vsil animate against 36 vsil render processes (a 36-frame orbit)",
       animateDatasetNames(), runAnimateTable, "", false, classicDatasetFile},
      {"dv1", "Díaz–Vázquez Table 1: MIP, DEMIP and DEMIP with colour sphere frame rates",
       dv1DatasetNames(), runDv1Table, "", false, dv1DatasetFile},
      {"illustrate",
       "Ebert–Rheingans volume illustration: plain composite, each effect, all, and RA",
       illustrateDatasetNames(), runIllustrateTable, "", false, illustrateDatasetFile},
      {"semantic",
       "Rautek et al. semantic rendering: rule bases of 1 to 32 rules against the plain "
       "composite, a membership change against a rule change",
       semanticDatasetNames(), runSemanticTable, "", false, semanticDatasetFile},
      {"startup",
       "a default vsil render from exec to exit, stage by stage, with Mesa's shader cache on "
       "and off",
       startupDatasetNames(), runStartupTable, "", false, classicDatasetFile},
      {"large",
       "volumes beyond one 3D texture (512³, 1024³, 2048²·1024 uint8): load + upload, "
       "silhouette frame, peak memory",
       largeDatasetNames(), runLargeTable, "", /*onlyWhenNamed=*/true},
      {"scaling",
       "mpirun -np N vsil render for N = 1..4 over a volume beyond one rank's --max-memory: "
       "frame, reduction share, memory per rank (--only: techniques)",
       scalingTechniqueNames(), runScalingTable, "", /*onlyWhenNamed=*/true},
  };
}

}  // namespace

const std::vector<TableDefinition>& tableRegistry() {
  static const std::vector<TableDefinition> registry = makeRegistry();
  return registry;
}

const TableDefinition& implementedTable(const std::string& name) {
  std::string known;
  for (const auto& table : tableRegistry()) {
    known += (known.empty() ? "" : ", ") + table.name;
    if (table.name != name) continue;
    if (!table.run) {
      throw InputError("--table " + name + ": not implemented yet (" + table.missingTechnique +
                       ")");
    }
    return table;
  }
  throw InputError("--table " + name + ": unknown table (known: " + known + ")");
}

}  // namespace vsil::bench
