#!/usr/bin/env bash
# libFuzzer targets (issue 11), built with clang + ASan + UBSan in build-fuzz/:
#   scripts/fuzz.sh [RUNS]     every target for RUNS executions (default 1000000), seeded from
#                              fuzz/corpus/<target>/ (read only; new inputs go to build-fuzz/corpus/)
# A crash, leak or timeout stops with the reproducer in build-fuzz/ and a non-zero exit.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-1000000}
jobs=${VIQU_JOBS:-$(nproc)}
dir="$root/build-fuzz"
CC=clang CXX=clang++ cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIQU_FUZZ=ON \
  -DVIQU_SANITIZE=address,undefined -DVIQU_WERROR=OFF -DVIQU_BUILD_BENCH=OFF -DBUILD_TESTING=OFF >/dev/null
targets=(fuzz_scenario_loader fuzz_slam_settings fuzz_tum_trajectory fuzz_dataset_readers)
cmake --build "$dir" -j"$jobs" --target "${targets[@]}"
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
for t in "${targets[@]}"; do
  mkdir -p "$dir/corpus/$t"
  echo "== $t: $runs runs"
  rc=0
  (cd "$dir" && "./fuzz/$t" -runs="$runs" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
     "$dir/corpus/$t" "$root/fuzz/corpus/$t") > "$dir/$t.log" 2>&1 || rc=$?
  grep -E "^#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss_mb|ERROR|SUMMARY" "$dir/$t.log" || true
  [ "$rc" -eq 0 ] || { echo "$t: failed (exit $rc), see $dir/$t.log" >&2; exit 1; }
done
