#!/usr/bin/env bash
# Installs, builds and runs the whole test suite (ctest; GL suites carry the label `gl`).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/bootstrap.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
