#!/usr/bin/env bash
# `mpirun -np N vsil render --technique silhouette` (issue 35: the pair reduce, slab.h) against
# the single process: PNG, --state-out and --depth-out byte-identical for N = 1..4, on one
# texture and bricked, perspective (also rays running both ways along z, and close) and
# orthographic, zoomed out so far that a pixel spans several voxels (there a slab without its
# ghost layers must differ: the contour test reads neighbours in the next slab), spheres that
# cross the slab borders, and a classic dataset. The single process runs the default tiles
# pipeline; a slab runs the fast one (and --pipeline paper or tiles turns into it).
# Usage: mpi_silhouette_test.sh VSIL MPIEXEC [DATASETS]
set -euo pipefail
vsil=$1
mpiexec=$2
datasets=${3:-/work/shared/datasets}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
outs() { echo --out "$1.png" --state-out "$1.state.png" --depth-out "$1.depth.png"; }

# same "CASE" "RANKS" ARGS...: the single process, then mpirun -np each of RANKS, compared.
same() {
  local name=$1 ranks=$2
  shift 2
  # shellcheck disable=SC2046
  "$vsil" render "$@" --technique silhouette $(outs "$work/single") >/dev/null
  for n in $ranks; do
    # shellcheck disable=SC2046
    "$mpiexec" --oversubscribe -np "$n" "$vsil" render "$@" --technique silhouette \
      $(outs "$work/many") --meta-out "$work/many.json" >/dev/null
    for kind in "" .state .depth; do
      cmp -s "$work/single$kind.png" "$work/many$kind.png" ||
        fail "$name: -np $n differs from the single process in $kind.png"
    done
    if ((n > 1)); then
      grep -q '"compose": "pair-reduce"' "$work/many.json" || fail "$name: no mpi metadata"
    fi
  done
  echo "$name: -np $ranks byte-identical"
}

same "spheres, perspective" "1 2 3 4" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6
same "spheres, bricked, orthographic" "2 3 4" gen:spheres:128 --size 128x128 --view 200,55 \
  --zoom 2.5 --ortho --max-texture-mib 1
# The eye level with the middle of z: the left half's rays run up z, the right half's down.
same "spheres, rays both ways, close" "2 3 4" gen:spheres:64 --size 128x128 --view 90,0 --zoom 2.2
zoomed=(gen:spheres:128 --size 64x64 --zoom 0.6 --view 80,15)
same "spheres, zoomed out (a pixel spans 6-7 voxels)" "2 4" "${zoomed[@]}"
if [[ -e $datasets/bonsai.vti ]]; then
  same "bonsai" "3" "$datasets/bonsai.vti" --size 256x256 --view 30,20
else
  echo "bonsai: $datasets/bonsai.vti absent, skipped"
fi

# Without ghost layers the contour test misses the neighbours' footprints beyond the slab.
VSIL_SLAB_GHOST_VOXELS=0 "$mpiexec" -x VSIL_SLAB_GHOST_VOXELS --oversubscribe -np 4 "$vsil" \
  render "${zoomed[@]}" --technique silhouette --out "$work/noghost.png" \
  --state-out "$work/noghost.state.png" >/dev/null
"$vsil" render "${zoomed[@]}" --technique silhouette --out "$work/single.png" \
  --state-out "$work/single.state.png" >/dev/null
if cmp -s "$work/single.state.png" "$work/noghost.state.png"; then
  fail "zoomed out without ghost layers: expected false contours at the slab borders"
fi
echo "without ghost layers: differs (as it must)"

# --pipeline paper or tiles across ranks runs the fast pipeline: the single process's bytes,
# and the metadata says fast.
for pipeline in paper tiles; do
  "$vsil" render gen:spheres:64 --size 96x96 --view 37,-23 --technique silhouette \
    --pipeline "$pipeline" --out "$work/one.png" >/dev/null
  "$mpiexec" --oversubscribe -np 2 "$vsil" render gen:spheres:64 --size 96x96 --view 37,-23 \
    --technique silhouette --pipeline "$pipeline" --out "$work/two.png" \
    --meta-out "$work/two.json" >/dev/null
  cmp -s "$work/one.png" "$work/two.png" || fail "--pipeline $pipeline: -np 2 differs"
  grep -q '"pipeline": "fast"' "$work/two.json" || fail "--pipeline $pipeline: meta not fast"
done
echo "--pipeline paper, tiles: -np 2 byte-identical, recorded as fast"

# --fill tone shades with the volume at every hit: refused in one line across ranks.
if "$mpiexec" --oversubscribe -np 2 "$vsil" render gen:spheres:64 --size 64x64 \
  --technique silhouette --fill tone --out "$work/tone.png" >/dev/null 2>"$work/err"; then
  fail "--fill tone across ranks: expected a refusal"
fi
[[ ! -e $work/tone.png ]] || fail "--fill tone: an output file was written"
count=$(grep -c -- "--fill tone: not across MPI ranks yet" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "--fill tone: the refusal printed $count times"; }
echo "--fill tone across ranks: one refusal line"

# A volume over one process's --max-memory renders across three ranks, each holding its slab and
# thin ghost layers (more, smaller brick layers where a technique reads ghosts): the same bytes.
big=(gen:spheres:128 --technique silhouette --size 128x128 --view 37,-23)
if "$vsil" render "${big[@]}" --max-memory 30 --out "$work/big1.png" 2>/dev/null; then
  fail "silhouette: the volume should be over one process's --max-memory 30"
fi
"$mpiexec" --oversubscribe -np 3 "$vsil" render "${big[@]}" --max-memory 30 \
  --out "$work/big3.png" >/dev/null || fail "silhouette: three ranks should each fit --max-memory 30"
"$vsil" render "${big[@]}" --out "$work/big.png" >/dev/null
cmp -s "$work/big.png" "$work/big3.png" || fail "silhouette: --max-memory across 3 ranks differs"
echo "silhouette over one rank's --max-memory: renders across 3"
