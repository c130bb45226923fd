#!/usr/bin/env bash
# Installs, builds and renders the demo: silhouettes of the embedded default volume.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/bootstrap.sh
mkdir -p out
./build/vsil render --fill shaded --zoom 2 --width 3 --out out/demo.png --meta-out out/demo.json
echo "demo image: $(pwd)/out/demo.png"
