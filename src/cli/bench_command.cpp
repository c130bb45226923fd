// vsil bench: the papers' benchmark tables, reproduced on this machine (bench/harness).
#include <unistd.h>

#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "cli/cli_gl_options.h"
#include "cli/cli_parse.h"
#include "cli/cli_report.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/options.h"
#include "harness/run_bench.h"
#include "harness/table_registry.h"

namespace vsil::cli {
namespace {

struct BenchFlags {
  bench::BenchOptions options;
  std::string datasets;
  GlOptions gl;
};

void run(BenchFlags flags) {
  if (!flags.datasets.empty()) flags.options.datasetsDir = flags.datasets;
  flags.options.gl = toContextOptions(flags.gl);
  // Every flag: tables, --only names, sizes, frame counts, the datasets folder, output folders.
  const bench::BenchOptions options = bench::validateOptions(flags.options);
  if (validateOnly()) return;

  // The tables reach stdout once every output is written: a bench that fails (an output that
  // cannot be written) prints no part of its report. Progress goes to stderr meanwhile.
  std::ostringstream tables;
  const bench::BenchReport report =
      bench::runBench(options, tables, std::cerr, isatty(STDERR_FILENO) == 1);
  reportStream({options.json, options.markdown, options.plot}) << tables.str() << std::flush;
  if (!report.failures.empty()) {
    throw CheckFailed(
        "bench: " + std::to_string(report.failures.size()) +
        " self-check(s) failed (their rows say FAILED), first: " + report.failures.front());
  }
}

// --table's help, from the registry: every table, and those a run without --table leaves out.
std::string tableHelp() {
  std::vector<std::string> all, named;
  for (const auto& table : bench::tableRegistry()) {
    all.push_back(table.name);
    if (table.onlyWhenNamed) named.push_back(table.name);
  }
  return "Table(s) to run: " + joined(all, ", ") + "; default: all but " + joined(named, ", ");
}

const CommandRegistration registerBenchCommand(40, [](CLI::App& app) {
  auto flags = std::make_shared<BenchFlags>();
  auto& o = flags->options;
  CLI::App* command = app.add_subcommand(
      "bench", "Reproduce the papers' benchmark tables and vsil's own on this machine");
  command->add_option("--table", o.tables, tableHelp())->delimiter(',');
  nonEmpty(command->add_option("--datasets", flags->datasets,
                               "Folder with the classic datasets (default ../shared/datasets)"));
  command->add_option("--only", o.only, "Datasets to run, e.g. bonsai,neghip")->delimiter(',');
  command
      ->add_option("--sizes", o.sizes,
                   "Square window sides, e.g. 256,512 (default: each table's own)")
      ->delimiter(',');
  command->add_option("--frames", o.frames, "Timed frames per case")->capture_default_str();
  command->add_option("--warmup", o.warmup, "Untimed frames before them")->capture_default_str();
  nonEmpty(command->add_option("--json", o.json, "Write the rows and the machine as JSON"));
  nonEmpty(command->add_option("--markdown", o.markdown, "Write the tables as Markdown"));
  nonEmpty(command->add_option("--plot", o.plot, "Write a bar chart (PNG)"));
  addGlOptions(*command, flags->gl);
  command->callback([flags] { run(*flags); });
});

}  // namespace
}  // namespace vsil::cli
