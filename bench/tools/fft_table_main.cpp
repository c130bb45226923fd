// vsil_fft_table [--threads N] [--json FILE]: the FFT-vs-spatial blur table
// (bench/tables/fft_table.h) at its default sizes, as `vsil bench --table fft` reports it:
// Markdown on stdout, the JSON rows in FILE. Here the FFT's threads can be set.
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>

#include "tables/fft_table.h"

int main(int argc, char** argv) {
  vsil::bench::FftTableSpec spec;
  const char* json = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--json") == 0) {
      json = argv[i + 1];
    } else if (std::strcmp(argv[i], "--threads") == 0) {
      spec.threads = std::atoi(argv[i + 1]);
    } else {
      std::cerr << "usage: vsil_fft_table [--threads N] [--json FILE]\n";
      return 2;
    }
  }
  const vsil::bench::TableResult table =
      vsil::bench::fftTableResult(vsil::bench::measureFftTable(spec), spec);
  std::cout << table.markdown;
  for (const auto& failure : table.failures) std::cerr << "check FAILED: " << failure << "\n";
  if (json) std::ofstream(json) << table.rows.dump(2) << "\n";
  return table.failures.empty() ? 0 : 1;
}
