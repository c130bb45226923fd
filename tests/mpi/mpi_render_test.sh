#!/usr/bin/env bash
# `mpirun -np N vsil render` (issue 35) against the single-process render:
#  - one rank: every technique's PNG, state and depth images are the single process's bytes
#    (odd view angles, perspective with the eye close);
#  - several ranks (2, 3, 4) for mip (silhouette: mpi_silhouette_test.sh): the same bytes,
#    on one texture, on a bricked volume, perspective close to the volume; a volume over one
#    rank's --max-memory renders across three; the --meta-out "mpi" object;
#  - several ranks for the other techniques: one refusal line, printed once, a non-zero exit and
#    no output file.
# Usage: mpi_render_test.sh VSIL MPIEXEC
set -euo pipefail
vsil=$1
mpiexec=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

volume=gen:spheres:64
common=(--size 128x128 --view 37,-23 --zoom 1.6)
for technique in silhouette rightangle firsthit illustrate mip demip lmip semantic; do
  extra=()
  case $technique in
    silhouette | rightangle) extra=(--state-out STATE --depth-out DEPTH) ;;
    firsthit | demip | lmip) extra=(--depth-out DEPTH) ;;
  esac
  outputs() {  # $1: prefix
    local args=()
    for a in "${extra[@]}"; do
      case $a in
        STATE) args+=("$1.state.png") ;;
        DEPTH) args+=("$1.depth.png") ;;
        *) args+=("$a") ;;
      esac
    done
    echo "${args[@]}"
  }
  # shellcheck disable=SC2046
  "$vsil" render "$volume" --technique "$technique" "${common[@]}" --out "$work/single.png" \
    $(outputs "$work/single") >/dev/null
  # shellcheck disable=SC2046
  "$mpiexec" --oversubscribe -np 1 "$vsil" render "$volume" --technique "$technique" \
    "${common[@]}" --out "$work/one.png" $(outputs "$work/one") >/dev/null
  for kind in "" .state .depth; do
    [[ -e $work/single$kind.png ]] || continue
    cmp -s "$work/single$kind.png" "$work/one$kind.png" ||
      fail "$technique: mpirun -np 1 differs from the single process in $kind.png"
  done
  rm -f "$work"/*.png
done
echo "one rank: 8 techniques byte-identical"

for args in "gen:spheres:64 --view 37,-23 --zoom 1.6" \
  "gen:spheres:128 --view 200,55 --zoom 2.5 --max-texture-mib 1"; do
  # shellcheck disable=SC2086
  "$vsil" render $args --technique mip --size 128x128 --out "$work/single.png" >/dev/null
  for n in 2 3 4; do
    # shellcheck disable=SC2086
    "$mpiexec" --oversubscribe -np "$n" "$vsil" render $args --technique mip --size 128x128 \
      --out "$work/many.png" --meta-out "$work/many.json" >/dev/null
    cmp -s "$work/single.png" "$work/many.png" || fail "mip $args: -np $n differs"
    grep -q '"compose": "max-reduce"' "$work/many.json" || fail "mip: no mpi metadata"
    grep -q "\"ranks\": $n" "$work/many.json" || fail "mip: mpi.ranks is not $n"
    rm -f "$work/many.png"
  done
done
echo "mip: -np 2, 3, 4 byte-identical, one texture and bricked"

big=(gen:spheres:128 --technique mip --size 128x128 --max-memory 30)
if "$vsil" render "${big[@]}" --out "$work/big1.png" 2>/dev/null; then
  fail "the volume should be over one process's --max-memory 30"
fi
"$mpiexec" --oversubscribe -np 3 "$vsil" render "${big[@]}" --out "$work/big3.png" >/dev/null ||
  fail "three ranks should each fit --max-memory 30"
"$vsil" render gen:spheres:128 --technique mip --size 128x128 --out "$work/big.png" >/dev/null
cmp -s "$work/big.png" "$work/big3.png" || fail "--max-memory across 3 ranks differs"
echo "over one rank's --max-memory: renders across 3"

for n in 2 3; do
  if "$mpiexec" --oversubscribe -np "$n" "$vsil" render "$volume" --technique rightangle \
    "${common[@]}" --out "$work/many.png" >"$work/out" 2>"$work/err"; then
    fail "-np $n: expected a refusal"
  fi
  [[ ! -e $work/many.png ]] || fail "-np $n: an output file was written"
  count=$(grep -c "rendering across $n MPI ranks is not available yet" "$work/err" || true)
  [[ $count == 1 ]] || { cat "$work/err" >&2; fail "-np $n: the refusal printed $count times"; }
done
echo "several ranks: one refusal line, no output"
