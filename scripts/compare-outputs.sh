#!/usr/bin/env bash
# Renders a fixed set of commands with two vsil binaries and compares every output byte for
# byte (image, state, depth): the check that a refactoring or a speed-up changed no pixel.
#   scripts/compare-outputs.sh OLD_VSIL NEW_VSIL
# Keep a copy of the old binary first (cp build/vsil /tmp/vsil-before). Needs the classic
# datasets in ../shared/datasets (VSIL_SHARED_DIR overrides). Exit 0: all identical.
set -euo pipefail
[[ $# -eq 2 ]] || { echo "usage: $0 OLD_VSIL NEW_VSIL" >&2; exit 2; }
old=$(readlink -f "$1"); new=$(readlink -f "$2")
cd "$(dirname "$0")/.."
data=${VSIL_SHARED_DIR:-../shared}/datasets
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
commands=(
  "default|"
  "spheres_fill|gen:spheres:96 --fill shaded --width 5 --view 10,30"
  "torus_ra|gen:torus:96 --technique rightangle --ortho --size 300x200"
  "torus_ra_k|gen:torus:96 --technique rightangle --ra-exponent 4 --ra-threshold 0.5 --size 256x256"
  "bonsai|$data/bonsai.vti --iso 40 --view 30,10 --size 256x256"
  "engine_law|$data/engine.vti --iso 80 --view 40,25 --width-near 8 --width-far 2 --size 320x240"
  "neghip_paper|$data/neghip_64x64x64_uint8.nhdr --iso 64 --pipeline paper --size 200x300 --zoom 1.3"
  "tooth_noess|$data/tooth.nrrd --iso 100 --no-empty-space-skipping --fill flat --background #102030"
  "teddy_sampling|$data/teddybear_128x128x62_uint8.nhdr --iso 60 --sampling 1.7 --width 1 --ortho"
  "hydrogen_ra|$data/hydrogen_atom_128x128x128_uint8.nhdr --technique rightangle --iso 20 --view 200,-40"
)
differ=0
for entry in "${commands[@]}"; do
  name=${entry%%|*}; args=${entry#*|}
  for side in old new; do
    binary=$old; [[ $side == new ]] && binary=$new
    mkdir -p "$work/$side"
    # shellcheck disable=SC2086
    "$binary" render $args --out "$work/$side/$name.png" --state-out "$work/$side/$name.state.png" \
      --depth-out "$work/$side/$name.depth.png" >/dev/null 2>"$work/$side/$name.err" ||
      { echo "$name: $side failed: $(cat "$work/$side/$name.err")"; differ=1; }
  done
  for kind in png state.png depth.png; do
    if ! cmp -s "$work/old/$name.$kind" "$work/new/$name.$kind"; then
      echo "$name.$kind differs"; differ=1
    fi
  done
done
((differ == 0)) && echo "all ${#commands[@]} commands: image, state and depth identical"
exit $differ
