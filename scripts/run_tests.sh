#!/usr/bin/env bash
# Set up (install missing packages, build) and run the whole test suite through CTest.
# Extra arguments go to ctest, e.g. -L scenario or -LE scenario.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
cd "$root/build"
exec ctest --output-on-failure --timeout 900 "$@"
