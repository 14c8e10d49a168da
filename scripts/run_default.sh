#!/usr/bin/env bash
# Set up (install missing packages, build) and run the default scenario headless.
# Extra arguments go to `viqu run`, e.g. --out DIR or --set duration_s=10.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
out="$root/runs/default"
exec "$root/build/apps/viqu" run "$root/scenarios/walking_people.yaml" --out "$out" "$@"
