#pragma once
// `vsil bench`: runs the asked tables and reports them. The CLI subcommand
// (src/cli/bench_command.cpp) only parses flags into BenchOptions and calls runBench.
#include <ostream>
#include <string>
#include <vector>

#include "harness/bench_options.h"

namespace vsil::bench {

// Checks the options before anything runs (unknown or unimplemented tables, --only names no
// selected table knows, sizes, frame counts, output folders) and fills defaults: no --table
// means every implemented table; a default datasets folder that does not exist falls back to
// the one beside the source tree. Throws InputError naming the flag.
BenchOptions validateOptions(BenchOptions options);

struct BenchReport {
  std::vector<std::string> failures;  // failed self-checks, one line each
};

// Prints the machine header and each table to `out`, progress to `progress` (rewritten in
// place when `progressIsTerminal`), and writes the --json, --markdown and --plot files
// atomically. Failed self-checks do not stop the run; they are returned. Before any table runs,
// a dataset --only names whose file is missing or unreadable, or an output naming a file the
// run reads, throws InputError.
BenchReport runBench(const BenchOptions& options, std::ostream& out, std::ostream& progress,
                     bool progressIsTerminal);

}  // namespace vsil::bench
