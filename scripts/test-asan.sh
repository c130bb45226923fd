#!/usr/bin/env bash
# The test suite again, built with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DVSIL_SANITIZE=ON, into build-asan/), GL suites included, on the first back end built
# (OSMesa, or EGL where configured with -DVSIL_OSMESA=OFF as CI does): llvmpipe runs under ASan.
# LeakSanitizer ignores only the Mesa/LLVM allocations in tests/sanitizers/lsan.supp, and is off
# in the GL suites, where its tracer crashes at exit (tests/CMakeLists.txt says more).
# The Python module is left out: a sanitized extension loads only into an interpreter started
# with the sanitizer runtime preloaded; its C++ below is the library the other suites test, and
# its threads' GL lock (job/gl_turn.h) is driven from 8 threads on every back end here by
# tests/gl_backends/gl_turn_test.cpp (the Python thread test's C++ twin).
set -euo pipefail
cd "$(dirname "$0")/.."
VSIL_BUILD_DIR=build-asan \
  VSIL_CMAKE_ARGS="-DVSIL_SANITIZE=ON -DVSIL_BUILD_BENCH=OFF -DVSIL_PYTHON=OFF ${VSIL_CMAKE_ARGS:-}" \
  scripts/bootstrap.sh
cd build-asan
# A test that fails is run once more, so that one run disturbed by the sanitizers' timing does
# not hide the whole run; a real leak or sanitizer error fails both runs (and ctest names each
# test that needed a second).
# Left to the plain build (scripts/test.sh): the GL-vs-reference comparisons on the two large
# datasets (bonsai, engine), whose CPU references take 5-9 s each here and test float
# agreement, not memory; the analytic and small dataset scenes run the same code here.
ctest --output-on-failure --repeat until-pass:2 -j"$(nproc)" \
  -E 'GlMatchesReference\.PixelByPixel/(bonsai|engine)_dataset_' "$@"
