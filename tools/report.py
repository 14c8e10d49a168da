#!/usr/bin/python3
"""Plots of a viqu run folder or sweep folder (`viqu report DIR`), headless, from the folder alone.

A run folder (complete: run_complete.json) gives DIR/plots/
  trajectory_top.png   top view: ground truth, SLAM estimate, leg odometry (when present), the
                       obstacles' paths, lost and relocalised frames marked;
  error_time.png       position error of the aligned estimate over time, with the moving
                       obstacles' share of the image on a second axis (blank while the camera
                       was dark: the scenario's sensors.camera.dropouts, shaded);
  dynamic_timeline.png per object: when it truly moved and when it was judged dynamic.
A folder may lack what its run did not make (a --no-slam run: no estimate, leg odometry or
dynamic.csv; a replay: no scenario.yaml, no truth of the objects' motion, perhaps no ground
truth): each plot or series left out is one warning line on stderr, exit code 0.
A sweep folder (sweep.yaml, results.csv) gives DIR/plots/
  heatmap_<metric>.png  mean of a metric over two grid keys (--x, --y);
  line_<metric>.png     mean and seed spread of a metric over one grid key (--x).

Uses Debian's python3-matplotlib, numpy and yaml. Exit code 2 on bad input (the message names the
file), as the viqu program does.
"""
import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")  # headless
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402

FIGSIZE = (8, 6)  # inches
DPI = 100         # 800 x 600 px images
MAX_ASSOC_S = 0.02  # association window of TUM's evaluate_ate.py (s)


class BadInput(Exception):
    pass


def warn(run_dir, text):
    """One line on stderr for a plot or series left out, and why (the report still succeeds)."""
    print(f"viqu report: warning: {run_dir}: {text}", file=sys.stderr)


def read_tum(path):
    """(t, xyz) arrays of a TUM trajectory file; None when the file is absent."""
    if not os.path.exists(path):
        return None
    rows = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            s = line.strip()
            if not s or s.startswith("#"):
                continue
            parts = s.split()
            try:
                if len(parts) != 8:
                    raise ValueError
                values = [float(x) for x in parts]
            except ValueError:
                raise BadInput(f"{path}:{n}: expected 8 numbers 't tx ty tz qx qy qz qw'") from None
            if not all(math.isfinite(v) for v in values):  # as viqu eval: nan, inf
                raise BadInput(f"{path}:{n}: value is not a finite number")
            rows.append(values[:4])
    a = np.array(rows, dtype=float).reshape(-1, 4)
    return a[:, 0], a[:, 1:4]


def read_csv(path, numeric=(), optional=()):
    """Rows of a CSV file as dicts ([] when absent); the `numeric` columns must be finite numbers,
    the `optional` ones finite numbers or blank (not known: dynamic.csv's truth columns in a
    replay, or for an object reported but not truly in view)."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for n, r in enumerate(rows, 2):
        for c in tuple(numeric) + tuple(optional):
            try:
                if c in optional and r[c] == "":
                    continue
                if not math.isfinite(float(r[c])):
                    raise ValueError
            except (KeyError, TypeError, ValueError):
                raise BadInput(f"{path}:{n}: column '{c}' is not a number") from None
    return rows


def known(rows, column):
    """Whether any row has a value in `column` (dynamic.csv's truth columns are blank throughout
    in a replay, which has no truth of the objects' motion)."""
    return any(r.get(column) not in ("", None) for r in rows)


DYNAMIC_TRUTH = ("visible_px", "truly_moving")  # dynamic.csv's columns that may be blank


def read_scenario(run_dir):
    """scenario.yaml as a dict; {} for a replay's folder, which has none."""
    path = os.path.join(run_dir, "scenario.yaml")
    if not os.path.exists(path):
        return {}
    try:
        with open(path) as f:
            scenario = yaml.safe_load(f) or {}
    except yaml.YAMLError as e:
        raise BadInput(f"{path}: {e}") from None
    if not isinstance(scenario, dict):
        raise BadInput(f"{path}: not a scenario (a mapping of keys)")
    return scenario


def camera_config(run_dir):
    """The scenario's sensors.camera block ({} without one)."""
    sensors = read_scenario(run_dir).get("sensors") or {}
    cam = (sensors.get("camera") or {}) if isinstance(sensors, dict) else None
    if not isinstance(cam, dict):
        raise BadInput(f"{os.path.join(run_dir, 'scenario.yaml')}: sensors.camera: expected a mapping")
    return cam


def camera_dropouts(run_dir):
    """The camera's outages [(t0, t1), ...] in s, from the scenario's sensors.camera.dropouts: both
    images black for t0 <= t < t1, nothing in view ([] without any, or without scenario.yaml)."""
    raw = camera_config(run_dir).get("dropouts") or []
    try:
        if not isinstance(raw, list) or not all(isinstance(d, list) and len(d) == 2 for d in raw):
            raise ValueError
        out = [(float(t0), float(t1)) for t0, t1 in raw]
        if not all(0 <= t0 < t1 < math.inf for t0, t1 in out):
            raise ValueError
    except (TypeError, ValueError):
        raise BadInput(f"{os.path.join(run_dir, 'scenario.yaml')}: sensors.camera.dropouts: expected "
                       "[[t0_s, t1_s], ...] with 0 <= t0_s < t1_s") from None
    return out


def in_dropout(t, dropouts):
    """Whether the camera was dark at t (s), to the nanosecond, as the run decided it."""
    t_ns = round(t * 1e9)
    return any(round(t0 * 1e9) <= t_ns < round(t1 * 1e9) for t0, t1 in dropouts)


def shade_dropouts(ax, dropouts, t_min, t_max):
    """The camera's dark intervals within [t_min, t_max], shaded and labelled "camera dark"."""
    first = True
    for t0, t1 in dropouts:
        a, b = max(t0, t_min), min(t1, t_max)
        if a >= b:
            continue
        ax.axvspan(a, b, color="0.5", alpha=0.25, lw=0, label="camera dark" if first else None, gid="camera_dark")
        ax.text((a + b) / 2, 0.98, "camera dark", transform=ax.get_xaxis_transform(), ha="center", va="top",
                fontsize=8, color="0.3")
        first = False


def associate(t_est, t_gt):
    """Index pairs (i, j): each estimate stamp with the nearest ground-truth stamp within 0.02 s."""
    pairs = []
    if len(t_gt) == 0:
        return pairs
    for i, t in enumerate(t_est):
        j = int(np.argmin(np.abs(t_gt - t)))
        if abs(t_gt[j] - t) <= MAX_ASSOC_S:
            pairs.append((i, j))
    return pairs


def umeyama_se3(src, dst):
    """R, t minimising |dst - (R src + t)|^2 (Umeyama 1991, no scale)."""
    mu_s, mu_d = src.mean(axis=0), dst.mean(axis=0)
    cov = (dst - mu_d).T @ (src - mu_s) / len(src)
    u, _, vt = np.linalg.svd(cov)
    s = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        s[2, 2] = -1
    r = u @ s @ vt
    return r, mu_d - r @ mu_s


def aligned_errors(est, gt):
    """(t, error) of an estimate against the ground truth after SE(3) alignment, as viqu eval."""
    (t_e, p_e), (t_g, p_g) = est, gt
    pairs = associate(t_e, t_g)
    if len(pairs) < 3:
        return np.zeros(0), np.zeros(0)
    i, j = np.array(pairs).T
    r, t = umeyama_se3(p_e[i], p_g[j])
    err = np.linalg.norm(p_g[j] - (p_e[i] @ r.T + t), axis=1)
    return t_e[i], err


def require_complete_run(run_dir):
    """As viqu's readers: the completion marker, and every file it lists with its size."""
    marker = os.path.join(run_dir, "run_complete.json")
    try:
        if not os.path.exists(marker):
            why = "no completion marker run_complete.json"
            inc = os.path.join(run_dir, "run_incomplete.json")
            if os.path.exists(inc):
                with open(inc) as f:
                    why = "interrupted: " + json.load(f).get("reason", "")
            raise BadInput(f"{run_dir}: not a complete run folder: {why}")
        with open(marker) as f:
            files = json.load(f)["files"]
        for entry in files:
            p = os.path.join(run_dir, entry["path"])
            if not os.path.isfile(p):
                raise BadInput(f"{run_dir}: not a complete run folder: {entry['path']} is missing")
            if os.path.getsize(p) != entry["bytes"]:
                raise BadInput(f"{run_dir}: not a complete run folder: {entry['path']} has changed since the run")
    except (ValueError, KeyError, TypeError) as e:
        raise BadInput(f"{marker}: unreadable ({e})") from None


def read_trajectories(run_dir):
    """Ground truth, SLAM estimate and leg odometry of a run folder (None for each one absent)."""
    return tuple(read_tum(os.path.join(run_dir, f"trajectory_{k}.txt")) for k in ("gt", "est", "lo"))


def plot_trajectory_top(run_dir):
    """The top-view figure (returned for tests; the caller saves it)."""
    gt, est, lo = read_trajectories(run_dir)
    if gt is None and est is None:
        raise BadInput(f"{run_dir}: no trajectory_gt.txt and no trajectory_est.txt")
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    scenario = read_scenario(run_dir)
    for k, ob in enumerate(scenario.get("obstacles") or []):
        path = np.array(ob.get("path") or [], dtype=float).reshape(-1, 2)
        if len(path) == 0:
            continue
        ax.plot(path[:, 0], path[:, 1], "--", color="0.6", lw=1, label="obstacle paths" if k == 0 else None)
        ax.plot(path[0, 0], path[0, 1], "s", color="0.6", ms=4)
        ax.annotate(ob.get("name", ""), path[0], fontsize=8, color="0.4")
    if gt is not None:
        ax.plot(gt[1][:, 0], gt[1][:, 1], "k-", lw=2, label="ground truth", gid="gt")
    if est is not None:
        ax.plot(est[1][:, 0], est[1][:, 1], "-", color="tab:blue", lw=1.2, label="SLAM estimate", gid="est")
        status = {round(float(r["t_s"]), 6): r["status"]
                  for r in read_csv(os.path.join(run_dir, "tracking.csv"), numeric=("t_s",))}
        for name, style, label in (("lost", "rx", "lost"), ("relocalised", "go", "relocalised")):
            idx = [i for i, t in enumerate(est[0]) if status.get(round(float(t), 6)) == name]
            if idx:
                ax.plot(est[1][idx, 0], est[1][idx, 1], style, ms=5, label=f"{label} ({len(idx)} frames)")
    if lo is not None:
        ax.plot(lo[1][:, 0], lo[1][:, 1], "-", color="tab:orange", lw=1, label="leg odometry + IMU", gid="lo")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{scenario.get('name', os.path.basename(run_dir))}: top view (left camera)")
    ax.grid(True, alpha=0.3)
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        # Below the axes, so that it covers none of the obstacles' names drawn in the plot.
        leg = fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
        height = leg.get_window_extent(fig.canvas.get_renderer()).height / fig.bbox.height
        fig.tight_layout(rect=(0, height + 0.01, 1, 1))
    else:
        fig.tight_layout()
    return fig


def moving_share(run_dir):
    """(t, share) of the left image covered by truly moving obstacles, from dynamic.csv; None when
    that is not known (visible_px blank throughout: a replay has no truth of the objects). A blank
    row in a live run is an object reported but not truly in view: no share. While the camera was
    dark (sensors.camera.dropouts) nothing was in view: NaN there, one at each outage's start at
    least, so that a curve breaks."""
    cam = camera_config(run_dir)
    try:
        pixels = float(cam.get("width", 640)) * float(cam.get("height", 480))
    except (TypeError, ValueError):
        raise BadInput(f"{os.path.join(run_dir, 'scenario.yaml')}: sensors.camera: width and height "
                       "must be numbers") from None
    rows = read_csv(os.path.join(run_dir, "dynamic.csv"), numeric=("t_s",), optional=DYNAMIC_TRUTH)
    if rows and not known(rows, "visible_px"):
        return None
    share = {}
    for r in rows:
        t = float(r["t_s"])
        share.setdefault(t, 0.0)
        if r.get("truly_moving") == "1" and r["visible_px"] != "":
            share[t] += float(r["visible_px"]) / pixels
    dropouts = camera_dropouts(run_dir)
    if share:
        for t0, _ in dropouts:
            if min(share) < t0 < max(share):
                share.setdefault(t0, math.nan)
    for t in share:
        if in_dropout(t, dropouts):
            share[t] = math.nan
    ts = np.array(sorted(share))
    return ts, np.array([share[t] for t in ts])


def plot_error_time(run_dir):
    gt, est, lo = read_trajectories(run_dir)
    if gt is None or est is None:
        raise BadInput(f"{run_dir}: error_time.png needs trajectory_gt.txt and trajectory_est.txt")
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    t, e = aligned_errors(est, gt)
    if len(t) == 0:
        warn(run_dir, f"error_time.png leaves out the SLAM estimate's error: fewer than 3 of its poses "
                      f"have a ground-truth stamp within {MAX_ASSOC_S} s")
    ax.plot(t, e * 1000, "-", color="tab:blue", label="SLAM estimate", gid="est_error")
    if lo is not None:
        tl, el = aligned_errors(lo, gt)
        if len(tl) == 0:
            warn(run_dir, f"error_time.png leaves out the leg odometry's error: fewer than 3 of its poses "
                          f"have a ground-truth stamp within {MAX_ASSOC_S} s")
        ax.plot(tl, el * 1000, "-", color="tab:orange", lw=1, label="leg odometry + IMU", gid="lo_error")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("position error after SE(3) alignment (mm)")
    ax.grid(True, alpha=0.3)
    stamps = np.concatenate([est[0], gt[0]])
    shade_dropouts(ax, camera_dropouts(run_dir), stamps.min(initial=0), stamps.max(initial=0))
    moving = moving_share(run_dir)
    if moving is None:
        warn(run_dir, "dynamic.csv's visible_px is blank throughout (a replay: no truth of the objects): "
                      "error_time.png leaves out the moving obstacles' share of the image")
        moving = (np.zeros(0), np.zeros(0))
    ts, share = moving
    if len(ts):
        ax2 = ax.twinx()
        ax2.fill_between(ts, share * 100, step="mid", color="tab:red", alpha=0.15)
        ax2.plot(ts, share * 100, "-", color="tab:red", lw=0.8, label="moving obstacles in view", gid="share")
        ax2.set_ylabel("moving obstacles' share of the left image (%)", color="tab:red")
        ax2.set_ylim(bottom=0)
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = ax2.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, loc="upper left", fontsize=8)
    else:
        ax.legend(loc="upper left", fontsize=8)
    ax.set_title("position error over time")
    fig.tight_layout()
    return fig


def spans(ts, flags, period):
    """[start, width] of the runs of True in flags (each sample covers one frame period; a gap
    of more than 1.5 periods between samples, when the object was out of view, ends a run)."""
    out, start, prev = [], None, None
    for t, f in zip(ts, flags):
        if start is not None and (not f or t - prev > 1.5 * period):
            out.append((start, prev + period - start))
            start = None
        if f and start is None:
            start = t
        prev = t
    if start is not None:
        out.append((start, prev + period - start))
    return out


def plot_dynamic_timeline(run_dir):
    rows = read_csv(os.path.join(run_dir, "dynamic.csv"), numeric=("t_s",), optional=DYNAMIC_TRUTH)
    truth = known(rows, "truly_moving")
    if rows and not truth:
        warn(run_dir, "dynamic.csv's truly_moving is blank throughout (a replay: no truth of the objects): "
                      "dynamic_timeline.png leaves out when they truly moved")
    objects = []
    for r in rows:
        if r["object"] not in objects:
            objects.append(r["object"])
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    all_t = sorted({float(r["t_s"]) for r in rows})
    period = (all_t[1] - all_t[0]) if len(all_t) > 1 else 0.05
    for k, name in enumerate(objects):
        mine = [r for r in rows if r["object"] == name]
        ts = [float(r["t_s"]) for r in mine]
        moving = [r.get("truly_moving") == "1" for r in mine]
        decided = [r.get("decided_dynamic") == "1" for r in mine]
        ax.broken_barh(spans(ts, [True] * len(ts), period), (k - 0.4, 0.8), color="0.9")
        if truth:  # drawn where known: a blank is not known
            ax.broken_barh(spans(ts, moving, period), (k - 0.35, 0.3), color="tab:orange",
                           label="truly moving" if k == 0 else None)
        ax.broken_barh(spans(ts, decided, period), (k + 0.05, 0.3), color="tab:red",
                       label="judged dynamic" if k == 0 else None)
    ax.set_yticks(range(len(objects)))
    ax.set_yticklabels(objects)
    ax.set_xlabel("time (s)")
    if truth:
        ax.set_title("dynamic objects: truth (orange) and decision (red); grey: in view")
    else:
        ax.set_title("dynamic objects: decision (red); grey: reported; truth not known")
    if all_t:
        shade_dropouts(ax, camera_dropouts(run_dir), all_t[0], all_t[-1] + period)
    ax.grid(True, axis="x", alpha=0.3)
    if objects:
        ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    return fig


LEGS = ("FL", "FR", "BL", "BR")


def feet_timeline_inputs(run_dir):
    """lo.csv and slip.csv as the feet timeline needs them, or None with why not (a run before
    issue 55's scoring has neither the debounced truth nor slip.csv's crossed_s)."""
    lo_path, slip_path = os.path.join(run_dir, "lo.csv"), os.path.join(run_dir, "slip.csv")
    if not os.path.exists(lo_path) or not os.path.exists(slip_path):
        return None, "no lo.csv or slip.csv (leg odometry runs live with SLAM in slam.mode full only)"
    with open(lo_path) as f:
        header = f.readline().strip().split(",")
    with open(slip_path) as f:
        slip_header = f.readline().strip().split(",")
    if "FL_true_travel" not in header or "crossed_s" not in slip_header:
        return None, "lo.csv and slip.csv are of an older viqu (no stance truth)"
    return (lo_path, slip_path), None


def plot_feet_timeline(run_dir):
    """Per foot: its true (debounced) contact and the estimator's, the true slip events (a stance
    whose sole travelled over the scoring threshold) and the reported detections."""
    (lo_path, slip_path), _ = feet_timeline_inputs(run_dir)
    numeric = ["t_s"] + [f"{leg}_{c}" for leg in LEGS for c in ("contact", "true_contact")]
    rows = read_csv(lo_path, numeric=numeric)
    events = read_csv(slip_path, numeric=("start_s", "end_s"))
    ts = [float(r["t_s"]) for r in rows]
    period = (ts[1] - ts[0]) if len(ts) > 1 else 0.005
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    for k, leg in enumerate(LEGS):
        y = 3 - k  # FL on top
        true_c = [r[f"{leg}_true_contact"] == "1" for r in rows]
        est_c = [r[f"{leg}_contact"] == "1" for r in rows]
        ax.broken_barh(spans(ts, true_c, period), (y - 0.4, 0.18), color="0.6",
                       label="true contact" if k == 0 else None, gid=f"{leg}_true_contact")
        ax.broken_barh(spans(ts, est_c, period), (y - 0.2, 0.18), color="tab:blue", alpha=0.5,
                       label="estimated contact" if k == 0 else None, gid=f"{leg}_contact")
        mine = [e for e in events if e["leg"] == leg]
        truth = [(float(e["start_s"]), float(e["end_s"]) - float(e["start_s"])) for e in mine if e["kind"] == "truth"]
        found = [(float(e["start_s"]), float(e["end_s"]) - float(e["start_s"])) for e in mine if e["kind"] == "detected"]
        ax.broken_barh(truth, (y + 0.02, 0.18), color="tab:orange", label="true slip (stance)" if k == 0 else None,
                       gid=f"{leg}_true_slip")
        ax.broken_barh(found, (y + 0.22, 0.18), color="tab:red", label="slip detected" if k == 0 else None,
                       gid=f"{leg}_slip")
    ax.set_yticks(range(4))
    ax.set_yticklabels(list(reversed(LEGS)))
    ax.set_xlabel("time (s)")
    ax.set_title("feet: contact (grey true, blue estimated) and slip (orange true, red detected)")
    ax.grid(True, axis="x", alpha=0.3)
    ax.legend(loc="upper right", fontsize=7, ncol=4)
    fig.tight_layout()
    return fig


def left_out(run_dir):
    """Warning lines for what a complete folder lacks: each plot or series left out, and why."""
    def have(name):
        return os.path.exists(os.path.join(run_dir, name))
    notes = []
    gt, est, lo = have("trajectory_gt.txt"), have("trajectory_est.txt"), have("trajectory_lo.txt")
    if not gt and not est:
        return notes  # plot_trajectory_top refuses it
    why_est = "no trajectory_est.txt (a --no-slam run?)"
    why_gt = "no trajectory_gt.txt (a replay of a dataset without ground truth?)"
    if not est:
        notes.append(f"{why_est}: trajectory_top.png leaves out the SLAM estimate (and its lost and relocalised frames)")
        notes.append(f"{why_est}: no error_time.png (the SLAM estimate's error)")
    elif not have("tracking.csv"):
        notes.append("no tracking.csv: trajectory_top.png leaves out the lost and relocalised frames")
    if not gt:
        notes.append(f"{why_gt}: trajectory_top.png leaves out the ground truth")
        notes.append(f"{why_gt}: no error_time.png (the error needs the ground truth)")
    if not lo:
        where = "trajectory_top.png and error_time.png leave" if gt and est else "trajectory_top.png leaves"
        notes.append(f"no trajectory_lo.txt (leg odometry runs live with SLAM in slam.mode full only): "
                     f"{where} out the leg odometry")
    if not have("scenario.yaml"):
        notes.append("no scenario.yaml (a replay?): trajectory_top.png leaves out the obstacles' paths")
    if lo:
        _, why = feet_timeline_inputs(run_dir)
        if why:
            notes.append(f"{why}: no feet_timeline.png")
    if not have("dynamic.csv"):
        notes.append("no dynamic.csv (a --no-slam run?): no dynamic_timeline.png")
    elif not read_csv(os.path.join(run_dir, "dynamic.csv")):
        notes.append("dynamic.csv has no rows (no movable object was seen or reported): no dynamic_timeline.png")
    return notes


def report_run(run_dir):
    require_complete_run(run_dir)
    plots = [("trajectory_top.png", plot_trajectory_top)]
    if all(os.path.exists(os.path.join(run_dir, f)) for f in ("trajectory_est.txt", "trajectory_gt.txt")):
        plots.append(("error_time.png", plot_error_time))
    if read_csv(os.path.join(run_dir, "dynamic.csv")):
        plots.append(("dynamic_timeline.png", plot_dynamic_timeline))
    if feet_timeline_inputs(run_dir)[0]:
        plots.append(("feet_timeline.png", plot_feet_timeline))
    for note in left_out(run_dir):
        warn(run_dir, note)
    figures = []
    try:
        for name, make in plots:  # all drawn before any is written: bad input leaves no plots
            figures.append((name, make(run_dir)))
    except BadInput:
        plt.close("all")
        raise
    out = os.path.join(run_dir, "plots")
    os.makedirs(out, exist_ok=True)
    for name, fig in figures:
        save(fig, os.path.join(out, name))
    return out, [name for name, _ in figures]


def save(fig, path):
    tmp = path + ".tmp.png"  # written whole, then renamed
    fig.savefig(tmp)
    plt.close(fig)
    os.replace(tmp, path)


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def grid_values(results, key):
    """The values a grid key takes, numbers in numeric order before any text."""
    return sorted({r[key] for r in results}, key=lambda v: (number(v) is None, number(v) or 0, v))


RESULT_COLUMNS = ("id", "seed", "exit_code", "status", "wall_s")  # results.csv's own, no grid keys


def read_sweep_spec(sweep_dir):
    """(grid keys or None when sweep.yaml lists none, metrics) of sweep.yaml, as viqu sweep resolved
    it; an unreadable file gives (None, []) (results.csv is what the report reads)."""
    try:
        with open(os.path.join(sweep_dir, "sweep.yaml")) as f:
            spec = yaml.safe_load(f) or {}
        grid = spec.get("grid")
        metrics = spec.get("metrics") or []
    except (OSError, yaml.YAMLError, AttributeError):
        return None, []
    grid = [str(k) for k in grid] if isinstance(grid, dict) else None
    return grid, [str(m) for m in metrics] if isinstance(metrics, list) else []


def report_sweep(sweep_dir, x, y, metric):
    results = read_csv(os.path.join(sweep_dir, "results.csv"))
    if not results:
        raise BadInput(f"{sweep_dir}/results.csv: missing or empty (run the sweep or viqu sweep --collect)")
    columns = results[0].keys()
    grid, listed = read_sweep_spec(sweep_dir)
    if not metric:
        # The sweep's first metric (its `metrics:` list, as viqu sweep resolved it into sweep.yaml).
        metric = next((m for m in listed if m in columns), None) or \
            [c for c in columns if c not in ("id", "scenario", "seed", "exit_code", "status", "wall_s")][-1]
    for key, what in ((x, "--x"), (y, "--y"), (metric, "--metric")):
        if key and key not in columns:
            raise BadInput(f"{sweep_dir}/results.csv: no column '{key}' ({what}); columns: {', '.join(columns)}")
    if not x:
        raise BadInput("a sweep report needs --x KEY (a grid key), and --y KEY for a heatmap")
    # The axes: the grid's keys (sweep.yaml's; without a grid there, the columns that are neither
    # results.csv's own nor a metric) or the scenario; never a metric, the seed or the same key twice.
    if grid is not None:
        keys = [c for c in columns if c in grid or c == "scenario"]
    else:
        keys = [c for c in columns if c not in RESULT_COLUMNS and c not in listed and c != metric]
    for key, what in ((x, "--x"), (y, "--y")):
        if key and key not in keys:
            raise BadInput(f"{sweep_dir}/results.csv: '{key}' ({what}) is not a grid key; the grid keys: "
                           f"{', '.join(keys) or 'none'}")
    if y and x == y:
        raise BadInput(f"{sweep_dir}: --x and --y name the same key '{x}'; a heatmap needs two grid keys "
                       f"(or --x alone for a line)")
    out = os.path.join(sweep_dir, "plots")
    os.makedirs(out, exist_ok=True)
    safe = metric.replace("/", "_")
    if y:
        xs, ys = grid_values(results, x), grid_values(results, y)
        grid = np.full((len(ys), len(xs)), np.nan)
        for iy, vy in enumerate(ys):
            for ix, vx in enumerate(xs):
                vals = [number(r[metric]) for r in results if r[x] == vx and r[y] == vy]
                vals = [v for v in vals if v is not None]
                if vals:
                    grid[iy, ix] = np.mean(vals)
        fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
        im = ax.imshow(grid, origin="lower", cmap="viridis", aspect="auto")
        ax.set_xticks(range(len(xs)))
        ax.set_xticklabels(xs)
        ax.set_yticks(range(len(ys)))
        ax.set_yticklabels(ys)
        for iy in range(len(ys)):
            for ix in range(len(xs)):
                if not np.isnan(grid[iy, ix]):
                    ax.text(ix, iy, f"{grid[iy, ix]:.3g}", ha="center", va="center", color="w", fontsize=8)
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        fig.colorbar(im, ax=ax, label=f"{metric} (mean over seeds and other keys)")
        ax.set_title(f"{metric} over {x} and {y}")
        fig.tight_layout()
        name = f"heatmap_{safe}.png"
    else:
        xs = grid_values(results, x)
        pos = [number(v) if number(v) is not None else i for i, v in enumerate(xs)]
        fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
        means, lo, hi = [], [], []
        for vx, px in zip(xs, pos):
            vals = [number(r[metric]) for r in results if r[x] == vx]
            vals = [v for v in vals if v is not None]
            if vals:
                ax.plot([px] * len(vals), vals, "o", color="tab:blue", alpha=0.35, ms=4)
            means.append(np.mean(vals) if vals else np.nan)
            lo.append(min(vals) if vals else np.nan)
            hi.append(max(vals) if vals else np.nan)
        ax.fill_between(pos, lo, hi, color="tab:blue", alpha=0.15, label="min-max over seeds")
        ax.plot(pos, means, "-o", color="tab:blue", label="mean", gid="mean")
        if any(number(v) is None for v in xs):
            ax.set_xticks(pos)
            ax.set_xticklabels(xs)
        ax.set_xlabel(x)
        ax.set_ylabel(metric)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title(f"{metric} over {x}")
        fig.tight_layout()
        name = f"line_{safe}.png"
    save(fig, os.path.join(out, name))
    return out, [name]


def main(argv):
    p = argparse.ArgumentParser(prog="viqu report", description=__doc__.split("\n")[0])
    p.add_argument("dir", help="a run folder or a sweep folder")
    p.add_argument("--x", help="sweep: grid key on the x axis")
    p.add_argument("--y", help="sweep: grid key on the y axis (heatmap)")
    p.add_argument("--metric", help="sweep: the metric (default: the sweep's first metric)")
    a = p.parse_args(argv)
    try:
        if not os.path.isdir(a.dir):
            raise BadInput(f"{a.dir}: not a folder")
        if os.path.exists(os.path.join(a.dir, "sweep.yaml")):
            out, made = report_sweep(a.dir, a.x, a.y, a.metric)
        elif a.x or a.y or a.metric:
            raise BadInput(f"{a.dir}: a run folder; --x, --y and --metric are for a sweep folder")
        else:
            out, made = report_run(a.dir)
    except BadInput as e:
        print(f"viqu: {e}", file=sys.stderr)
        return 2
    print(f"viqu report: {out}/{{{','.join(made)}}}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
