#!/usr/bin/env bash
# The whole test suite again, built with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DVSIL_SANITIZE=ON, into build-asan/), GL suites included: OSMesa/llvmpipe runs under ASan.
# LeakSanitizer ignores only the Mesa/LLVM allocations in tests/sanitizers/lsan.supp.
set -euo pipefail
cd "$(dirname "$0")/.."
VSIL_BUILD_DIR=build-asan VSIL_CMAKE_ARGS="-DVSIL_SANITIZE=ON -DVSIL_BUILD_BENCH=OFF ${VSIL_CMAKE_ARGS:-}" \
  scripts/bootstrap.sh
cd build-asan
ctest --output-on-failure -j"$(nproc)" "$@"
