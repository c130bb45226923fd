#!/usr/bin/env bash
# `mpirun -np N vsil render` (issue 35) against the single-process render:
#  - one rank: every technique's PNG, state and depth images are the single process's bytes
#    (odd view angles, perspective with the eye close);
#  - several ranks (2, 3, 4) for mip (silhouette: mpi_silhouette_test.sh): the same bytes,
#    on one texture, on a bricked volume, perspective close to the volume; a volume over one
#    rank's --max-memory renders across three; the --meta-out "mpi" object;
#  - several ranks (2, 3, 4) for the relay (rightangle, firsthit, demip, lmip): PNG, depth and
#    state images the same bytes at an odd view, orthographic, bricked and on the engine dataset;
#    a perspective view whose rays go both ways along z refuses in one line;
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
# The single process's pipeline to compare several ranks with: illustrate's default tiles march
# composites the slabs' samples, but its colours equal the slice passes' (which slabs run) only
# to float rounding, so the single process runs its fast pipeline.
single_pipeline() { [[ $1 == illustrate ]] && echo "--pipeline fast" || true; }
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

# The relay (Composition::Relay): firsthit, demip and lmip pass their targets from slab to slab
# in the view's depth order; PNG and depth image byte-identical to the single process.
relay_case() {  # $1: technique, $2: rank counts, then the render's arguments
  local technique=$1 counts=$2 kind
  shift 2
  local state=() depth=(--depth-out)
  [[ $technique == rightangle ]] && state=(--state-out)
  [[ $technique == illustrate || $technique == semantic ]] && depth=()  # no depth image
  # shellcheck disable=SC2046
  "$vsil" render "$@" --technique "$technique" $(single_pipeline "$technique") \
    --out "$work/single.png" \
    ${depth[@]+"${depth[@]}" "$work/single.depth.png"} \
    ${state[@]+"${state[@]}" "$work/single.state.png"} >/dev/null
  for n in $counts; do
    "$mpiexec" --oversubscribe -np "$n" "$vsil" render "$@" --technique "$technique" \
      --out "$work/many.png" ${depth[@]+"${depth[@]}" "$work/many.depth.png"} \
      --meta-out "$work/many.json" ${state[@]+"${state[@]}" "$work/many.state.png"} >/dev/null ||
      fail "$technique $*: -np $n failed"
    for kind in "" .depth .state; do
      [[ -e $work/single$kind.png ]] || continue
      cmp -s "$work/single$kind.png" "$work/many$kind.png" ||
        fail "$technique $*: -np $n differs in $kind.png"
    done
    grep -q '"compose": "relay"' "$work/many.json" || fail "$technique: no mpi compose relay"
    rm -f "$work"/many*.png
  done
  rm -f "$work"/single*.png
}
for technique in rightangle firsthit demip lmip; do
  relay_case "$technique" "2 3 4" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6
  relay_case "$technique" "3" gen:spheres:64 --size 128x128 --view 200,55 --zoom 1.3 --ortho
  relay_case "$technique" "4" gen:spheres:128 --size 128x128 --view 200,55 --zoom 2.5 \
    --max-texture-mib 1
done
engine=${VSIL_DATASETS:-/work/shared/datasets}/engine.vti
if [[ -e $engine ]]; then
  relay_case demip "3" "$engine" --size 256x256 --view 30,20
  relay_case lmip "2" "$engine" --size 256x256 --view 30,20
  relay_case rightangle "4" "$engine" --size 256x256 --view 30,20 --fill tone
fi
# rightangle's default tiles runs fast in a slab (as the metadata says); paper stays paper.
relay_case rightangle "2" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6
grep -q '"pipeline": "fast"' "$work/many.json" || fail "rightangle -np 2: meta pipeline not fast"
relay_case rightangle "2" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6 --pipeline paper
grep -q '"pipeline": "paper"' "$work/many.json" || fail "rightangle paper -np 2: meta pipeline"
# The last passes that shade at a hit's own point, in whichever slab it lies (relayScreenPass).
relay_case rightangle "3" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6 --fill shaded
echo "relay (rightangle, firsthit, demip, lmip): -np 2, 3, 4 byte-identical, PNG, depth, state"

# Compositing across ranks (semantic): gradients divided by the whole volume's largest (agreed
# over the ranks), ghost layers for the central differences, and the early-ray-termination marks
# relayed with the colour (a slab marks only at slices whose sample it owns).
relay_case semantic "2 3 4" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6
relay_case semantic "3" gen:spheres:128 --size 128x128 --view 37,-23 --zoom 1.6 --max-texture-mib 1
echo "semantic (default rules): -np 2, 3, 4 byte-identical, one texture and bricked"
# illustrate: also its halo field (precomputed per volume, from the ghost layers, with the
# agreed gradient maximum).
every_effect=boundary,silhouette,fading,sketch,distance,halo,tone
relay_case illustrate "2 3 4" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6
relay_case illustrate "2 4" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6 \
  --effects "$every_effect"
relay_case illustrate "3" gen:spheres:64 --size 128x128 --view 37,-23 --zoom 1.6 \
  --style fig6-distance-halo
relay_case illustrate "3" gen:spheres:128 --size 128x128 --view 37,-23 --zoom 1.6 \
  --max-texture-mib 1 --effects "$every_effect"
if [[ -e $engine ]]; then
  relay_case illustrate "4" "$engine" --size 256x256 --effects "$every_effect"
fi
echo "illustrate (default, every effect, fig6 halo style): -np 2, 3, 4 byte-identical"
# Its tiles march asked for by name: a slab runs the slice passes (optionsForSlab), as the
# metadata says, not a refusal after reading on every rank.
"$mpiexec" --oversubscribe -np 2 "$vsil" render "${common[@]}" "$volume" --technique illustrate \
  --pipeline tiles --out "$work/many.png" --meta-out "$work/many.json" >/dev/null ||
  fail "illustrate --pipeline tiles -np 2 failed"
"$vsil" render "${common[@]}" "$volume" --technique illustrate --pipeline fast \
  --out "$work/single.png" >/dev/null
cmp -s "$work/single.png" "$work/many.png" || fail "illustrate --pipeline tiles -np 2 differs"
grep -q '"pipeline": "fast"' "$work/many.json" || fail "illustrate --pipeline tiles -np 2: meta"
rm -f "$work"/single.png "$work"/many.png
echo "illustrate --pipeline tiles: -np 2 runs fast, byte-identical, recorded in --meta-out"

# A perspective view whose rays leave the eye both ways along z: no slab order is every ray's.
if "$mpiexec" --oversubscribe -np 2 "$vsil" render "$volume" --technique firsthit \
  --size 64x64 --view 90,0 --zoom 4 --out "$work/many.png" >"$work/out" 2>"$work/err"; then
  fail "perspective both ways along z: expected a refusal"
fi
[[ ! -e $work/many.png ]] || fail "perspective both ways: an output file was written"
count=$(grep -c "rays that leave the eye both ways" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "perspective: the refusal printed $count times"; }
echo "perspective with rays both ways along z: one refusal line, no output"

# Options that need the volume in one texture (a slab is not): refused alike before reading.
if "$mpiexec" --oversubscribe -np 2 "$vsil" render "$volume" --technique rightangle \
  --pipeline tiles --size 64x64 --out "$work/many.png" >"$work/out" 2>"$work/err"; then
  fail "--pipeline tiles across ranks: expected a refusal"
fi
[[ ! -e $work/many.png ]] || fail "--pipeline tiles: an output file was written"
count=$(grep -c "need the volume in one texture" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "--pipeline tiles: the refusal printed $count times"; }

# illustrate's exact halos (taps in the slice plane) need the volume in one texture.
if "$mpiexec" --oversubscribe -np 2 "$vsil" render "$volume" --technique illustrate \
  --effects halo --halo-mode exact "${common[@]}" --out "$work/many.png" >"$work/out" \
  2>"$work/err"; then
  fail "illustrate --halo-mode exact -np 2: expected a refusal"
fi
[[ ! -e $work/many.png ]] || fail "illustrate --halo-mode exact -np 2: an output file was written"
count=$(grep -c "need the volume in one texture" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "--halo-mode exact: the refusal printed $count times"; }
echo "illustrate --halo-mode exact across ranks: one refusal line, no output"

# Ranks that run different commands (MPMD's ':'): another technique, another command (which
# never joined the render's collectives: a hang), another view. Refused on every rank at start
# (exit 2, one line from rank 0), within the timeout, no output.
mpmd_case() {  # $1: label; the rest: rank 1's arguments after "vsil"
  local label=$1
  shift
  if timeout 120 "$mpiexec" --oversubscribe -np 1 "$vsil" render "$volume" --technique mip \
    --size 64x64 --out "$work/many.png" : -np 1 "$vsil" "$@" >"$work/out" 2>"$work/err"; then
    fail "$label: expected a refusal"
  fi
  [[ ! -e $work/many.png ]] || fail "$label: an output file was written"
  count=$(grep -c "runs another command line than rank 0" "$work/err" || true)
  [[ $count == 1 ]] || { cat "$work/err" >&2; fail "$label: the refusal printed $count times"; }
}
mpmd_case "another technique" render "$volume" --technique silhouette --size 64x64 \
  --out "$work/many.png"
mpmd_case "another command" info "$volume"
mpmd_case "another view" render "$volume" --technique mip --size 64x64 --out "$work/many.png" \
  --view 180,0
# A volume of 4 slices or fewer (one brick of its own size along z, which slabs could not cut:
# an internal error on every rank) is one brick layer: refused once (exit 2: run fewer ranks), no
# output.
for thin in gen:sphere:4 gen:sphere:2; do
  status=0
  timeout 120 "$mpiexec" --oversubscribe -np 2 "$vsil" render "$thin" --size 32x32 \
    --out "$work/thin.png" >"$work/out" 2>"$work/err" || status=$?
  [[ $status == 2 ]] || { cat "$work/err" >&2; fail "$thin -np 2: exit $status, expected 2"; }
  [[ ! -e $work/thin.png ]] || fail "$thin -np 2: an output file was written"
  count=$(grep -c "make 1 brick layer, fewer than the 2 ranks; run fewer ranks" "$work/err" || true)
  [[ $count == 1 ]] || { cat "$work/err" >&2; fail "$thin -np 2: the refusal printed $count times"; }
done
echo "volumes of 2 and 4 slices across 2 ranks: one refusal line, exit 2, no output"

# One path naming different files on different ranks (another working directory): refused on
# every rank before any frame (exit 2, one line from rank 0), no output.
for dir in a b; do
  mkdir -p "$work/wd_$dir"
  { printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: raw\n\n'
    head -c 4096 /dev/urandom; } >"$work/wd_$dir/vol.nrrd"
done
if timeout 120 "$mpiexec" --oversubscribe -np 1 -wdir "$work/wd_a" "$vsil" render vol.nrrd \
  --size 32x32 --out "$work/wd.png" : -np 1 -wdir "$work/wd_b" "$vsil" render vol.nrrd \
  --size 32x32 --out "$work/wd.png" >"$work/out" 2>"$work/err"; then
  fail "different files behind one path: expected a refusal"
fi
[[ ! -e $work/wd.png ]] || fail "different files behind one path: an output file was written"
count=$(grep -c "rank 1 reads another volume from vol.nrrd than rank 0" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "different files: the refusal printed $count times"; }
echo "one path, different files on two ranks: one refusal line, no output"

# Commands that run in one process (all but render and sweep) ran once per rank (two servers,
# every frame twice): refused once, exit 2, before any work.
for command in "info $volume" "animate $volume --frames 2 --size 32x32 --out-dir $work/frames"; do
  status=0
  # shellcheck disable=SC2086 # the command's words
  timeout 120 "$mpiexec" --oversubscribe -np 2 "$vsil" $command >"$work/out" 2>"$work/err" ||
    status=$?
  [[ $status == 2 ]] || { cat "$work/err" >&2; fail "$command -np 2: exit $status, expected 2"; }
  count=$(grep -c "runs in one process: run it without mpirun" "$work/err" || true)
  [[ $count == 1 ]] || { cat "$work/err" >&2; fail "$command -np 2: refused $count times"; }
  [[ ! -s $work/out && ! -e $work/frames ]] || fail "$command -np 2: it ran"
done
echo "info and animate under mpirun -np 2: one refusal line, exit 2, nothing run"

# A refused flag is the same on every rank: said once.
if "$mpiexec" --oversubscribe -np 2 "$vsil" render "$volume" --bogus >"$work/out" \
  2>"$work/err"; then
  fail "--bogus -np 2: expected a refusal"
fi
count=$(grep -c "not expected: --bogus" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "--bogus: the refusal printed $count times"; }
echo "ranks with different command lines, a refused flag: one line from rank 0, no output"

# Refusals found after the flags are read (a value out of range, an output the technique does
# not make, a sweep with nothing to write) and the flags' warnings: said once, not per rank
# (each rank said them, and rank 0's exit aborted the others with Open MPI's banner).
refused_once() {  # $1: the refusal's text; the rest: the command after "vsil"
  local text=$1
  shift
  if timeout 120 "$mpiexec" --oversubscribe -np 2 "$vsil" "$@" >"$work/out" 2>"$work/err"; then
    fail "$*: expected a refusal"
  fi
  count=$(grep -c -- "$text" "$work/err" || true)
  [[ $count == 1 ]] || { cat "$work/err" >&2; fail "$*: '$text' printed $count times"; }
  ! grep -q "MPI_ABORT" "$work/err" || { cat "$work/err" >&2; fail "$*: MPI_Abort"; }
}
refused_once "vsil: --zoom: must be in" render "$volume" --size 32x32 --zoom 0 --out "$work/z.png"
refused_once "makes no state image" render "$volume" --technique illustrate --size 32x32 \
  --state-out "$work/s.png" --out "$work/z.png"
refused_once "sweep: nothing to write" sweep /dev/null
[[ ! -e $work/z.png ]] || fail "a refused render wrote its output"
timeout 120 "$mpiexec" --oversubscribe -np 2 "$vsil" render "$volume" --technique illustrate \
  --size 32x32 --halo-mode exact --out "$work/z.png" >"$work/out" 2>"$work/err" ||
  { cat "$work/err" >&2; fail "illustrate --halo-mode exact without halos -np 2 failed"; }
count=$(grep -c "the halo effect is off; ignored" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "a flag's warning printed $count times"; }
echo "refusals after the flags are read and the flags' warnings: said once by rank 0"

# The file's warnings (here int32 samples rounded to float32) reach the user once: across ranks
# they were dropped (each rank's slab held them, none said them).
{ printf 'NRRD0004\ntype: int32\ndimension: 3\nsizes: 16 16 16\nendian: little\nencoding: raw\n\n'
  head -c 16384 /dev/urandom; } >"$work/wide.nrrd"
timeout 120 "$mpiexec" --oversubscribe -np 2 "$vsil" render "$work/wide.nrrd" --technique mip \
  --size 32x32 --out "$work/w.png" >"$work/out" 2>"$work/err" ||
  { cat "$work/err" >&2; fail "an int32 file across 2 ranks failed"; }
count=$(grep -c "samples lost precision as float32" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "the file's warning printed $count times"; }
echo "the file's warnings across ranks: said once"

# A file's errors, met by every rank alike (a bad header) or by one rank alone (the gzip check
# at the stream's end, in the last slab): said once, by rank 0, with no MPI_Abort banner (each
# rank said its own, and the launcher its banner).
{ printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: gzip\n\n'
  head -c 4096 /dev/urandom | gzip -c; } >"$work/badcrc.nrrd"
size=$(stat -c %s "$work/badcrc.nrrd")
printf '\0\0\0\0' | dd of="$work/badcrc.nrrd" bs=1 seek=$((size - 8)) conv=notrunc status=none
refused_once "badcrc.nrrd: gzip payload after the header is corrupt" render "$work/badcrc.nrrd" \
  --size 32x32 --out "$work/c.png"
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16\nencoding: raw\n\n' >"$work/bad.nrrd"
refused_once "bad.nrrd: " render "$work/bad.nrrd" --size 32x32 --out "$work/c.png"
[[ ! -e $work/c.png ]] || fail "a render of a bad file wrote its output"
echo "a file's errors across ranks: said once"

# Options that read their files while parsed (--rules, --tf): refused once, also where only one
# rank lacks the file (another working directory): the ranks meet after parsing, none waits. An
# output into a missing folder: refused once, before the frame.
refused_once "missing.rules: no such file" render "$volume" --technique semantic \
  --rules "$work/missing.rules" --size 32x32 --out "$work/rf.png"
refused_once "does not exist" render "$volume" --size 32x32 --out "$work/no_such_folder/z.png"
cp "$(dirname "$0")/../../src/core/rules/example.rules" "$work/wd_a/my.rules"
if timeout 120 "$mpiexec" --oversubscribe -np 1 -wdir "$work/wd_a" "$vsil" render "$volume" \
  --technique semantic --rules my.rules --size 32x32 --out "$work/rf.png" : -np 1 \
  -wdir "$work/wd_b" "$vsil" render "$volume" --technique semantic --rules my.rules \
  --size 32x32 --out "$work/rf.png" >"$work/out" 2>"$work/err"; then
  fail "a rules file on one rank only: expected a refusal"
fi
count=$(grep -c "my.rules: no such file" "$work/err" || true)
[[ $count == 1 ]] || { cat "$work/err" >&2; fail "a rules file on one rank only: said $count times"; }
[[ ! -e $work/rf.png ]] || fail "a refused render wrote its output"
echo "files the options read, missing everywhere or on one rank, and a missing output folder: once"
