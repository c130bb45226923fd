// vsil_fft_table [--json FILE]: the FFT-vs-spatial blur table (bench/tables/fft_table.h) as
// Markdown on stdout, and as JSON in FILE.
#include <cstring>
#include <fstream>
#include <iostream>

#include "tables/fft_table.h"

int main(int argc, char** argv) {
  const auto rows = vsil::bench::measureFftTable();
  std::cout << vsil::bench::formatFftTable(rows);
  if (argc == 3 && std::strcmp(argv[1], "--json") == 0) {
    std::ofstream(argv[2]) << vsil::bench::fftTableJson(rows).dump(2) << "\n";
  }
  return 0;
}
