#!/usr/bin/env bash
# Fuzzes every target in tests/fuzz (or those named) for a bounded time each, with libFuzzer,
# ASan and UBSan (clang; build-fuzz/). New findings (crash-*, leak-*, timeout-*, oom-*) are
# copied to tests/fuzz/regressions/<target>/, where the normal test suite replays them; the
# script then exits 1. The growing corpus stays in build-fuzz/corpus/<target>/.
#
#   scripts/fuzz.sh                 # 60 s per target
#   VSIL_FUZZ_SECONDS=300 scripts/fuzz.sh nrrd vti
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${VSIL_FUZZ_SECONDS:-60}

VSIL_CONFIGURE_ONLY=1 VSIL_BUILD_DIR=build-fuzz VSIL_EXTRA_PACKAGES="clang libclang-rt-14-dev" \
  VSIL_CMAKE_ARGS="-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DVSIL_FUZZ=ON \
                   -DVSIL_BUILD_TESTS=OFF -DVSIL_BUILD_BENCH=OFF ${VSIL_CMAKE_ARGS:-}" \
  scripts/bootstrap.sh

if (($#)); then targets=("$@"); else
  targets=(); for f in tests/fuzz/fuzz_*.cpp; do n=${f##*/fuzz_}; targets+=("${n%.cpp}"); done
fi
found=0
for target in "${targets[@]}"; do
  # Each binary alone: one that does not build (see its log) is reported and skipped.
  if ! cmake --build build-fuzz -j"$(nproc)" --target fuzz_"$target" > "build-fuzz/build-$target.log" 2>&1; then
    echo "fuzz: fuzz_$target does not build with clang, skipped (build-fuzz/build-$target.log)" >&2
    grep -m3 "error:" "build-fuzz/build-$target.log" >&2 || true
    found=1
    continue
  fi
  corpus=build-fuzz/corpus/$target artifacts=build-fuzz/artifacts/$target
  mkdir -p "$corpus" "$artifacts"
  echo "fuzz: $target for ${seconds}s" >&2
  # -rss_limit_mb: the targets load with a 64 MiB limit; more than 2 GiB is a finding.
  # -timeout: one input taking 10 s is a finding (a hang). -max_len: headers and small volumes.
  status=0
  ASAN_OPTIONS=detect_leaks=1 ./build-fuzz/fuzz/fuzz_"$target" "$corpus" tests/fuzz/seeds/"$target" \
    -dict=tests/fuzz/dicts/"$target".dict -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="$artifacts/" -print_final_stats=1 \
    2> "build-fuzz/$target.log" || status=$?
  grep -E "^(stat::number_of_executed_units|stat::new_units_added|Done)" "build-fuzz/$target.log" >&2 || true
  if ((status)); then
    tail -40 "build-fuzz/$target.log" >&2
    mkdir -p tests/fuzz/regressions/"$target"
    for f in "$artifacts"/*; do
      [[ -f $f ]] && cp "$f" tests/fuzz/regressions/"$target"/ && echo "fuzz: new finding $f" >&2
    done
    found=1
  fi
done
exit $found
