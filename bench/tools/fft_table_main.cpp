// vsil_fft_table [--threads N] [--json FILE]: the FFT-vs-spatial blur table
// (bench/tables/fft_table.h) as Markdown on stdout, and as JSON in FILE.
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
  const auto rows = vsil::bench::measureFftTable(spec);
  std::cout << vsil::bench::formatFftTable(rows);
  if (json) std::ofstream(json) << vsil::bench::fftTableJson(rows).dump(2) << "\n";
  return 0;
}
