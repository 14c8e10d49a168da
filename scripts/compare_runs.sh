#!/usr/bin/env bash
# Compares two run folders of the same scenario and seed: every output must be the same bytes,
# except what measures wall time (the timing columns of tracking.csv, timing and wall-time keys
# in metrics.json, the command in run_complete.json, the video's encoder). Exit 1 on a difference.
# Usage: scripts/compare_runs.sh RUN_A RUN_B
set -euo pipefail
a=$1 b=$2
status=0
strip_metrics() { grep -v -E '"(render_ms_|wall_time_s|real_time_factor|track_ms_|local_ba_ms_|dynamic_ms_|update_ms_mean)' "$1"; }
strip_tracking() { cut -d, -f1-6,8,10- "$1"; }  # all but track_ms and dynamic_ms
while IFS= read -r -d '' f; do
  rel=${f#"$a"/}
  case "$rel" in
    run_complete.json|video.mp4) continue ;;
  esac
  if [[ ! -e "$b/$rel" ]]; then echo "only in $a: $rel"; status=1; continue; fi
  case "$rel" in
    metrics.json) cmp -s <(strip_metrics "$f") <(strip_metrics "$b/$rel") || { echo "differs: $rel"; diff <(strip_metrics "$f") <(strip_metrics "$b/$rel") | head -5 || true; status=1; } ;;
    tracking.csv) cmp -s <(strip_tracking "$f") <(strip_tracking "$b/$rel") || { echo "differs: $rel"; status=1; } ;;
    *) cmp -s "$f" "$b/$rel" || { echo "differs: $rel"; status=1; } ;;
  esac
done < <(find "$a" -type f -print0 | sort -z)
while IFS= read -r -d '' f; do
  rel=${f#"$b"/}
  [[ -e "$a/$rel" ]] || { echo "only in $b: $rel"; status=1; }
done < <(find "$b" -type f -print0 | sort -z)
[[ $status == 0 ]] && echo "same outputs: $a $b"
exit $status
