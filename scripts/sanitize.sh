#!/usr/bin/env bash
# Sanitizer builds and runs (issue 11):
#   scripts/sanitize.sh asan   ASan + UBSan build in build-asan/, runs the fast tests (label unit)
#   scripts/sanitize.sh tsan   TSan build in build-tsan/, runs the realtime-mapping tests
# Any report fails the run (halt_on_error). Extra arguments go to ctest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" >/dev/null   # packages (the normal build is reused by nothing here)
jobs=${VIQU_JOBS:-$(nproc)}
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
  *) echo "usage: scripts/sanitize.sh asan|tsan [ctest args]" >&2; exit 2 ;;
esac
