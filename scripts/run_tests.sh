#!/usr/bin/env bash
# Set up (install missing packages, build) and run the whole test suite through CTest.
# Extra arguments go to ctest, e.g. -L scenario or -LE scenario (or -j1 for one test at a time).
# Tests run on every core (VIQU_JOBS to change): the scenario tests run in synchronous mode and
# are deterministic, the window tests share one lock (RESOURCE_LOCK xvfb), and nothing asserts
# on time, so running them side by side changes no figure.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
jobs=${VIQU_JOBS:-$(nproc)}
cd "$root/build"
exec ctest --output-on-failure --timeout 900 -j"$jobs" "$@"
