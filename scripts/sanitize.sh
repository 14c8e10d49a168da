#!/usr/bin/env bash
# Sanitizer builds and runs (issue 11):
#   scripts/sanitize.sh asan   ASan + UBSan build in build-asan/, runs the fast tests (label unit)
#   scripts/sanitize.sh tsan   TSan build in build-tsan/, runs the realtime-mapping tests
#   scripts/sanitize.sh ci     CI's stage (.ci/run): GCC ASan + UBSan in build-ci-asan/ on the core
#                              tests (the estimator, its readers and the loaders: VIQU_CORE_TESTS
#                              in tests/CMakeLists.txt; leaks checked), then on the other fast
#                              tests (label unit: simulator, run loop, program); clang libFuzzer
#                              in build-ci-fuzz/, each target for FUZZ_SECONDS (default 20) on
#                              its corpus; GCC TSan in
#                              build-ci-tsan/ on the realtime-mapping test of test_slam_system
# Any report fails the run (halt_on_error). Extra arguments go to ctest (asan, tsan).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" >/dev/null   # packages (the normal build is reused by nothing here)
jobs=${VIQU_JOBS:-$(nproc)}
# ccache hashes the build folder's path into every -g compilation, so a fresh clone (as CI
# makes) would rebuild every sanitizer object: with paths taken relative to the checkout and the
# folder left out of the hash, clones on one machine share them (debug info then names the
# folder of whichever build compiled an object first).
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1
kind=${1:-asan}
shift || true
case "$kind" in
  asan)
    dir="$root/build-asan"
    cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIQU_SANITIZE=address,undefined \
      -DVIQU_BUILD_BENCH=OFF >/dev/null
    cmake --build "$dir" -j"$jobs"
    # detect_leaks: MuJoCo's and Mesa's one-time allocations at exit are reported by LSan as
    # leaks of the process, not of viqu; leaks are checked by the fuzzers' runs instead.
    export ASAN_OPTIONS=halt_on_error=1:detect_leaks=0:abort_on_error=1
    export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
    cd "$dir" && ctest -L unit --output-on-failure --timeout 1800 "$@"
    ;;
  tsan)
    dir="$root/build-tsan"
    cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIQU_SANITIZE=thread -DVIQU_BUILD_BENCH=OFF >/dev/null
    cmake --build "$dir" -j"$jobs" --target test_slam_system
    export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
    cd "$dir" && ctest -R "Realtime|realtime" --output-on-failure --timeout 3600 "$@"
    ;;
  ci)
    # Only the core tests (and the libraries they need) and the fuzz targets are built: the
    # simulator, the run loop and the program are left out. Line tables only (-g1): the reports
    # keep file and line, the builds stay lean.
    flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIQU_BUILD_BENCH=OFF -DVIQU_VIEWER=OFF)
    # 1. GCC, ASan + UBSan, -O2 (the optimisation the tests' bounds were measured near).
    start=$(date +%s)
    dir="$root/build-ci-asan"
    cmake -S "$root" -B "$dir" "${flags[@]}" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1" \
      -DVIQU_SANITIZE=address,undefined >/dev/null
    mapfile -t core < "$dir/core_tests.txt"
    cmake --build "$dir" -j"$jobs" --target "${core[@]}"
    echo "viqu sanitize ci: ASan + UBSan build $(( $(date +%s) - start )) s"
    # Leaks are checked here too: the core tests never load MuJoCo or Mesa.
    export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=1
    export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
    for t in "${core[@]}"; do
      (cd "$dir/tests" && "./$t" --gtest_brief=1) > "$dir/$t.log" 2>&1 || { cat "$dir/$t.log"; echo "$t: failed under ASan + UBSan" >&2; exit 1; }
      echo "  $t: $(grep -E '^\[  PASSED  \]' "$dir/$t.log")"
    done
    # 1b. The other fast tests (label unit): the simulator, the run loop and the program, built
    # the same way. Leaks are not checked here: MuJoCo's and Mesa's one-time allocations at exit
    # would be reported as leaks of the process (the core tests above and the fuzzers check them).
    start=$(date +%s)
    mapfile -t other < "$dir/other_unit_tests.txt"
    cmake --build "$dir" -j"$jobs" --target viqu "${other[@]}"
    echo "viqu sanitize ci: ASan + UBSan build of the other fast tests $(( $(date +%s) - start )) s"
    export ASAN_OPTIONS=halt_on_error=1:detect_leaks=0:abort_on_error=1
    for t in "${other[@]}"; do
      (cd "$dir/tests" && "./$t" --gtest_brief=1) > "$dir/$t.log" 2>&1 || { cat "$dir/$t.log"; echo "$t: failed under ASan + UBSan" >&2; exit 1; }
      echo "  $t: $(grep -E '^\[  PASSED  \]' "$dir/$t.log")"
    done
    (cd "$dir" && ctest -R '^Report\.PythonTool$' --output-on-failure) > "$dir/report_tool.log" 2>&1 || {
      cat "$dir/report_tool.log"; echo "Report.PythonTool: failed with the ASan + UBSan program" >&2; exit 1; }
    echo "  Report.PythonTool: passed"
    # 2. clang, libFuzzer + ASan + UBSan: each target for FUZZ_SECONDS on its corpus (leaks on).
    start=$(date +%s)
    dir="$root/build-ci-fuzz"
    CC=clang CXX=clang++ cmake -S "$root" -B "$dir" "${flags[@]}" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
      "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1" -DVIQU_FUZZ=ON -DVIQU_SANITIZE=address,undefined -DVIQU_WERROR=OFF \
      -DBUILD_TESTING=OFF >/dev/null
    fuzzers=(fuzz_scenario_loader fuzz_slam_settings fuzz_tum_trajectory fuzz_dataset_readers)
    cmake --build "$dir" -j"$jobs" --target "${fuzzers[@]}"
    echo "viqu sanitize ci: fuzz build $(( $(date +%s) - start )) s"
    export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1
    for t in "${fuzzers[@]}"; do
      mkdir -p "$dir/corpus/$t"
      (cd "$dir" && "./fuzz/$t" -max_total_time="${FUZZ_SECONDS:-20}" -timeout=10 -rss_limit_mb=2048 \
         -print_final_stats=1 "$dir/corpus/$t" "$root/fuzz/corpus/$t") > "$dir/$t.log" 2>&1 || {
        tail -40 "$dir/$t.log"; echo "$t: failed (reproducer in $dir)" >&2; exit 1; }
      echo "  $t: $(grep -E 'stat::number_of_executed_units' "$dir/$t.log" | awk '{print $2}') runs, no crash, leak or hang"
    done
    # 3. GCC, TSan: the realtime-mapping test (the mapper on its own thread).
    start=$(date +%s)
    dir="$root/build-ci-tsan"
    cmake -S "$root" -B "$dir" "${flags[@]}" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1" -DVIQU_SANITIZE=thread >/dev/null
    cmake --build "$dir" -j"$jobs" --target test_slam_system
    echo "viqu sanitize ci: TSan build $(( $(date +%s) - start )) s"
    export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
    (cd "$dir/tests" && ./test_slam_system --gtest_brief=1 --gtest_filter='*Realtime*') > "$dir/tsan.log" 2>&1 || {
      cat "$dir/tsan.log"; echo "test_slam_system: failed under TSan" >&2; exit 1; }
    grep -qE '^\[  PASSED  \] [1-9]' "$dir/tsan.log" || { cat "$dir/tsan.log"; echo "TSan: no realtime-mapping test ran" >&2; exit 1; }
    echo "  test_slam_system, realtime mapping: $(grep -E '^\[  PASSED  \]' "$dir/tsan.log")"
    ;;
  *) echo "usage: scripts/sanitize.sh asan|tsan|ci [ctest args]" >&2; exit 2 ;;
esac
