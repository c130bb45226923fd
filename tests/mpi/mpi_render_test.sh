#!/usr/bin/env bash
# `mpirun -np N vsil render` (issue 35) against the single-process render:
#  - one rank: every technique's PNG, state and depth images are the single process's bytes
#    (odd view angles, perspective with the eye close);
#  - several ranks: until the slab renderer is wired in (slicing/slab.h), every technique refuses
#    with one line, printed once, a non-zero exit and no output file.
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

for n in 2 3; do
  if "$mpiexec" --oversubscribe -np "$n" "$vsil" render "$volume" --technique mip \
    "${common[@]}" --out "$work/many.png" >"$work/out" 2>"$work/err"; then
    fail "-np $n: expected a refusal"
  fi
  [[ ! -e $work/many.png ]] || fail "-np $n: an output file was written"
  count=$(grep -c "rendering across $n MPI ranks is not available yet" "$work/err" || true)
  [[ $count == 1 ]] || { cat "$work/err" >&2; fail "-np $n: the refusal printed $count times"; }
done
echo "several ranks: one refusal line, no output"
