#!/usr/bin/python3
"""Memory and per-frame cost over a long run (issue 10's bounded-memory check).

Runs `viqu run SCENARIO --set duration_s=D [--set ...]`, samples the process's resident set size
(VmRSS) twice a second while it runs, and afterwards reads tracking.csv of the run folder. Prints:
  - RSS when the first minute of simulated time is done and at the end, and the growth between;
  - the median tracking time of the second minute and of the last minute, and their ratio.
Simulated time during the run is read from the progress of trajectory_gt.txt, which the run
writes as it goes (in DIR.partial-PID until the run ends), so no guess from wall time is made.

Usage: tools/memory_growth.py VIQU SCENARIO.yaml OUT_DIR [--duration 600] [--set K=V ...]
"""
import argparse
import glob
import os
import statistics
import subprocess
import sys
import time


def rss_mb(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        return None
    return None


def sim_time_s(out_dir, pid):
    """Last stamp written to trajectory_gt.txt of the run in progress (s), or None."""
    for path in glob.glob(f"{out_dir}.partial-{pid}/trajectory_gt.txt*") + glob.glob(f"{out_dir}.partial-{pid}/.*trajectory_gt*"):
        try:
            with open(path, "rb") as f:
                f.seek(0, os.SEEK_END)
                size = f.tell()
                f.seek(max(0, size - 400))
                lines = f.read().decode(errors="replace").strip().splitlines()
            if len(lines) >= 2:
                return float(lines[-2].split()[0])
        except (OSError, ValueError, IndexError):
            continue
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("viqu")
    ap.add_argument("scenario")
    ap.add_argument("out")
    ap.add_argument("--duration", type=float, default=600.0)
    ap.add_argument("--set", action="append", default=[])
    a = ap.parse_args()
    cmd = [a.viqu, "run", a.scenario, "--out", a.out, "--force", "--set", f"duration_s={a.duration}"]
    for s in a.set:
        cmd += ["--set", s]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    samples = []  # (wall_s, sim_s or None, rss_mb)
    t0 = time.monotonic()
    while proc.poll() is None:
        r = rss_mb(proc.pid)
        if r is not None:
            samples.append((time.monotonic() - t0, sim_time_s(a.out, proc.pid), r))
        time.sleep(0.5)
    out = proc.stdout.read()
    if proc.returncode != 0:
        sys.stderr.write(out)
        sys.exit(f"the run failed with exit code {proc.returncode}")
    print(out.strip())
    with_sim = [(s, r) for _, s, r in samples if s is not None]
    if not with_sim:
        sys.exit("no simulated time could be read during the run")
    after_first_minute = [r for s, r in with_sim if s >= 60.0]
    rss_1min = after_first_minute[0] if after_first_minute else float("nan")
    rss_end = max(r for _, _, r in samples[-6:])
    peak = max(r for _, _, r in samples)
    print(f"RSS after the first minute {rss_1min:.1f} MB, at the end {rss_end:.1f} MB "
          f"(growth {100.0 * (rss_end / rss_1min - 1):.1f}%), peak {peak:.1f} MB")
    track = []
    with open(os.path.join(a.out, "tracking.csv")) as f:
        next(f)
        for line in f:
            fields = line.split(",")
            track.append((float(fields[0]), float(fields[6])))
    end = track[-1][0]
    second = [ms for t, ms in track if 60.0 <= t < 120.0]
    last = [ms for t, ms in track if t >= end - 60.0]
    if second and last:
        m2, ml = statistics.median(second), statistics.median(last)
        print(f"tracking median: second minute {m2:.2f} ms, last minute {ml:.2f} ms (ratio {ml / m2:.3f})")
    with open(os.path.join(a.out, "memory_growth.csv.tmp"), "w") as f:
        f.write("wall_s,sim_s,rss_mb\n")
        for w, s, r in samples:
            f.write(f"{w:.2f},{'' if s is None else f'{s:.3f}'},{r:.1f}\n")
    os.replace(os.path.join(a.out, "memory_growth.csv.tmp"), os.path.join(a.out, "memory_growth.csv"))


if __name__ == "__main__":
    main()
