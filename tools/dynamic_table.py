#!/usr/bin/env python3
"""Markdown table of the dynamic-object figures of viqu run folders (metrics.json).

    python3 tools/dynamic_table.py runs/walking_people_none runs/walking_people_adaptive ...

One row per run folder: scenario, method, ATE (mm and % of path), lost frames, detection
precision / recall / median latency against the simulator's truth, the share of features kept
on standing movable objects and dropped on moving ones, and the dynamic stage's median time.
"""
import json
import sys


def fmt(value, spec):
    return "-" if value is None else format(value, spec)


def row(run_dir):
    with open(run_dir + "/metrics.json") as f:
        m = json.load(f)
    d = m.get("dynamic", {})
    return "| {} | {} | {} ({}%) | {} | {} / {} | {} | {} / {} | {} |".format(
        m.get("scenario", "?"), m.get("slam", {}).get("dynamic_method", "?"),
        fmt(1000 * m["ate"]["rmse_m"], ".1f"), fmt(m["ate"].get("rmse_pct_path"), ".2f"),
        m["tracking"]["lost_frames"], fmt(d.get("precision"), ".3f"), fmt(d.get("recall"), ".3f"),
        fmt(d.get("latency_s_median"), ".2f"), fmt(d.get("kept_on_static_movables"), ".2f"),
        fmt(d.get("dropped_on_moving"), ".2f"), fmt(m["timing"].get("dynamic_ms_median"), ".2f"))


def main(argv):
    if len(argv) < 2:
        sys.stderr.write(__doc__)
        return 2
    print("| scenario | method | ATE mm (% path) | lost | precision / recall | latency median s |"
          " kept on static / dropped on moving | dynamic ms |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for d in argv[1:]:
        try:
            print(row(d))
        except (OSError, KeyError, ValueError) as e:
            sys.stderr.write("{}: {}\n".format(d, e))
            return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
