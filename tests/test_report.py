#!/usr/bin/python3
"""viqu report (tools/report.py) on the stored run folder tests/data/report_run and on a small
sweep folder made here: PNGs of the expected size, plotted series equal to the files' data,
incomplete folders refused with exit 2, what a folder lacks named on stderr. Run by CTest with
Debian's python3."""
import contextlib
import csv
import io
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import report  # noqa: E402

VIQU = os.environ.get("VIQU_BINARY", "")
STORED = os.path.join(ROOT, "tests", "data", "report_run")


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", path
    return struct.unpack(">II", head[16:24])


def line(fig, gid):
    for ax in fig.axes:
        for ln in ax.get_lines():
            if ln.get_gid() == gid:
                return ln
    raise AssertionError(f"no line {gid}")


def has_line(fig, gid):
    return any(ln.get_gid() == gid for ax in fig.axes for ln in ax.get_lines())


def report_py(*args):
    """tools/report.py run as `viqu report` runs it: (exit code, stdout, stderr)."""
    r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "report.py"), *args],
                       capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def quietly(make, run_dir):
    """make(run_dir) with its stderr (the warnings) captured: (figure, stderr text)."""
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        fig = make(run_dir)
    return fig, err.getvalue()


def marker_files(run):
    with open(os.path.join(run, "run_complete.json")) as f:
        return json.load(f)


def write_marker(run, marker):
    with open(os.path.join(run, "run_complete.json"), "w") as f:
        json.dump(marker, f, indent=2)


def rewrite(run, name, text):
    """Replaces a file of a run folder, its size in run_complete.json with it (the folder stays
    complete, as if the run had written it so)."""
    path = os.path.join(run, name)
    with open(path, "w") as f:
        f.write(text)
    marker = marker_files(run)
    for entry in marker["files"]:
        if entry["path"] == name:
            entry["bytes"] = os.path.getsize(path)
    write_marker(run, marker)


def drop(run, name):
    """Removes a file of a run folder and its entry in run_complete.json (a run that did not make it)."""
    os.remove(os.path.join(run, name))
    marker = marker_files(run)
    marker["files"] = [e for e in marker["files"] if e["path"] != name]
    write_marker(run, marker)


def read_text(run, name):
    with open(os.path.join(run, name)) as f:
        return f.read()


class RunReport(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="viqu_report_")
        self.run = os.path.join(self.tmp, "run")
        shutil.copytree(STORED, self.run)

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def test_plots_of_a_copied_run_folder(self):
        cmd = [VIQU, "report", self.run] if VIQU else [sys.executable, os.path.join(ROOT, "tools", "report.py"), self.run]
        r = subprocess.run(cmd, capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        for name in ("trajectory_top.png", "error_time.png", "dynamic_timeline.png"):
            path = os.path.join(self.run, "plots", name)
            self.assertGreater(os.path.getsize(path), 10000, name)
            self.assertEqual(png_size(path), (800, 600), name)

    def test_series_equal_the_files(self):
        gt = np.loadtxt(os.path.join(self.run, "trajectory_gt.txt"))
        fig = report.plot_trajectory_top(self.run)
        x, y = line(fig, "gt").get_data()
        self.assertEqual(len(x), len(gt))
        self.assertEqual(x[40], gt[40, 1])
        self.assertEqual(y[40], gt[40, 2])
        lo = np.loadtxt(os.path.join(self.run, "trajectory_lo.txt"))
        self.assertEqual(line(fig, "lo").get_data()[0][-1], lo[-1, 1])
        # The error curve: the aligned error of frame 0, computed here independently (a rotation
        # fitted by least squares over every associated pose, as viqu eval does).
        est = np.loadtxt(os.path.join(self.run, "trajectory_est.txt"))
        fig2 = report.plot_error_time(self.run)
        t, e_mm = line(fig2, "est_error").get_data()
        a, b = est[:, 1:4], gt[:, 1:4]  # same stamps in a live run
        ma, mb = a.mean(0), b.mean(0)
        u, _, vt = np.linalg.svd((b - mb).T @ (a - ma))
        d = np.diag([1, 1, np.sign(np.linalg.det(u @ vt))])
        rot = u @ d @ vt
        err0 = np.linalg.norm(b[0] - (rot @ (a[0] - ma) + mb))
        self.assertAlmostEqual(e_mm[0], err0 * 1000, places=6)
        # ... and the curve's RMS is the run's own ATE (viqu's C++ evaluation, metrics.json).
        with open(os.path.join(self.run, "metrics.json")) as f:
            ate = json.load(f)["ate"]["rmse_m"]
        self.assertAlmostEqual(np.sqrt(np.mean(np.square(e_mm))) / 1000, ate, delta=1e-8)
        # The moving share: frame at 3 s, from dynamic.csv by hand.
        with open(os.path.join(self.run, "dynamic.csv")) as f:
            rows = [r for r in csv.DictReader(f) if abs(float(r["t_s"]) - 3.0) < 1e-9]
        want = sum(float(r["visible_px"]) for r in rows if r["truly_moving"] == "1") / (640 * 480)
        ts, share = line(fig2, "share").get_data()
        self.assertAlmostEqual(share[list(np.round(ts, 6)).index(3.0)], want * 100, places=9)
        self.assertGreater(want, 0)

    def test_sweep_options_on_a_run_folder_are_refused(self):
        r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "report.py"), self.run, "--x", "seed"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertIn("--x, --y and --metric are for a sweep folder", r.stderr)

    def fresh(self, name):
        """Another copy of the stored folder, in this test's temporary folder."""
        path = os.path.join(self.tmp, name)
        shutil.copytree(STORED, path)
        return path

    def test_replay_dynamic_csv_without_truth(self):
        # A replay (viqu slam) leaves dynamic.csv's truth columns blank: no truth of the objects.
        with open(os.path.join(self.run, "dynamic.csv")) as f:
            rows = list(csv.DictReader(f))
            fields = list(rows[0].keys())
        for r in rows:
            r["visible_px"] = r["truly_moving"] = ""
        text = io.StringIO()
        w = csv.DictWriter(text, fields, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
        rewrite(self.run, "dynamic.csv", text.getvalue())
        rc, out, err = report_py(self.run)
        self.assertEqual(rc, 0, err)
        for name in ("trajectory_top.png", "error_time.png", "dynamic_timeline.png"):
            self.assertEqual(png_size(os.path.join(self.run, "plots", name)), (800, 600), name)
        self.assertIn("error_time.png leaves out the moving obstacles' share", err)
        self.assertIn("dynamic_timeline.png leaves out when they truly moved", err)
        fig, _ = quietly(report.plot_error_time, self.run)
        self.assertFalse(has_line(fig, "share"))
        self.assertTrue(has_line(fig, "est_error"))
        # The timeline: "judged dynamic" for every object as in a live run, no "truly moving".
        fig, _ = quietly(report.plot_dynamic_timeline, self.run)
        ax = fig.axes[0]
        labels = ax.get_legend_handles_labels()[1]
        self.assertIn("judged dynamic", labels)
        self.assertNotIn("truly moving", labels)
        objects = [t.get_text() for t in ax.get_yticklabels()]
        self.assertEqual(sorted(objects), sorted({r["object"] for r in rows}))
        red = [c for c in ax.collections if c.get_label() == "judged dynamic"]
        self.assertTrue(red)
        # Non-blank garbage is still refused, naming the file and line.
        rows[3]["visible_px"] = "abc"
        text = io.StringIO()
        w = csv.DictWriter(text, fields, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
        rewrite(self.run, "dynamic.csv", text.getvalue())
        shutil.rmtree(os.path.join(self.run, "plots"))
        rc, out, err = report_py(self.run)
        self.assertEqual(rc, 2)
        self.assertIn("dynamic.csv:5: column 'visible_px' is not a number", err)
        self.assertFalse(os.path.exists(os.path.join(self.run, "plots")))
        # A live run's blank row (an object reported, not truly in view) adds no share.
        run = self.fresh("live")
        with open(os.path.join(run, "dynamic.csv")) as f:
            rows = list(csv.DictReader(f))
        at3 = [r for r in rows if abs(float(r["t_s"]) - 3.0) < 1e-9]
        want = sum(float(r["visible_px"]) for r in at3 if r["truly_moving"] == "1") / (640 * 480)
        rows.append(dict(at3[0], object="ghost", visible_px="", truly_moving=""))
        text = io.StringIO()
        w = csv.DictWriter(text, fields, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
        rewrite(run, "dynamic.csv", text.getvalue())
        ts, share = report.moving_share(run)
        self.assertAlmostEqual(share[list(np.round(ts, 6)).index(3.0)], want, places=12)

    def test_non_finite_pose_is_refused(self):
        for name, bad in (("trajectory_est.txt", "nan"), ("trajectory_gt.txt", "inf"), ("trajectory_gt.txt", "-inf")):
            with self.subTest(name=name, bad=bad):
                run = self.fresh(f"{bad}_{name}")
                lines = read_text(run, name).splitlines(keepends=True)
                parts = lines[3].split()  # line 4 of the file: its third pose
                parts[2] = bad
                lines[3] = " ".join(parts) + "\n"
                rewrite(run, name, "".join(lines))
                rc, out, err = report_py(run)
                self.assertEqual(rc, 2, err)
                self.assertIn(f"{name}:4: value is not a finite number", err)
                self.assertNotIn("Traceback", err)

    def test_what_a_folder_lacks_is_named(self):
        # The stored live run lacks nothing: no warning.
        rc, out, err = report_py(self.run)
        self.assertEqual((rc, err), (0, ""))
        # A --no-slam run: no estimate (nor its tracking, leg odometry, dynamic.csv).
        run = self.fresh("no_slam")
        for name in ("trajectory_est.txt", "tracking.csv", "trajectory_lo.txt", "lo.csv", "slip.csv",
                     "dynamic.csv", "slam_settings.yaml"):
            drop(run, name)
        rc, out, err = report_py(run)
        self.assertEqual(rc, 0, err)
        warnings = err.splitlines()
        self.assertTrue(all(w.startswith(f"viqu report: warning: {run}: ") for w in warnings), err)
        self.assertIn("no trajectory_est.txt (a --no-slam run?): trajectory_top.png leaves out the SLAM estimate", err)
        self.assertIn("no trajectory_est.txt (a --no-slam run?): no error_time.png", err)
        self.assertIn("no trajectory_lo.txt", err)
        self.assertIn("no dynamic.csv (a --no-slam run?): no dynamic_timeline.png", err)
        self.assertEqual(len(warnings), 4, err)
        self.assertEqual(sorted(os.listdir(os.path.join(run, "plots"))), ["trajectory_top.png"])
        # Only the estimate missing.
        run = self.fresh("no_est")
        drop(run, "trajectory_est.txt")
        rc, out, err = report_py(run)
        self.assertEqual(rc, 0, err)
        self.assertIn("no trajectory_est.txt (a --no-slam run?): no error_time.png", err)
        self.assertFalse(os.path.exists(os.path.join(run, "plots", "error_time.png")))
        # A replay: no scenario.yaml (the obstacles' paths are left out).
        run = self.fresh("no_scenario")
        drop(run, "scenario.yaml")
        rc, out, err = report_py(run)
        self.assertEqual(rc, 0, err)
        self.assertEqual(err.splitlines(), [f"viqu report: warning: {run}: no scenario.yaml (a replay?): "
                                            "trajectory_top.png leaves out the obstacles' paths"])
        # A replay of a dataset without ground truth: no error_time.png, said so.
        run = self.fresh("no_gt")
        drop(run, "trajectory_gt.txt")
        rc, out, err = report_py(run)
        self.assertEqual(rc, 0, err)
        self.assertIn("no trajectory_gt.txt (a replay of a dataset without ground truth?): no error_time.png "
                      "(the error needs the ground truth)", err)
        self.assertIn("no trajectory_gt.txt (a replay of a dataset without ground truth?): trajectory_top.png "
                      "leaves out the ground truth", err)
        self.assertEqual(sorted(os.listdir(os.path.join(run, "plots"))),
                         ["dynamic_timeline.png", "feet_timeline.png", "trajectory_top.png"])

    def test_feet_timeline_draws_the_files(self):
        # The stored run's contact spans and slip events, bar for bar: a synthetic slip.csv with one
        # true event and one detection of FR, and FL's estimated contact turned off over 1.0-1.5 s.
        with open(os.path.join(self.run, "lo.csv")) as f:
            rows = list(csv.DictReader(f))
        header = list(rows[0].keys())
        for r in rows:
            if 1.0 <= float(r["t_s"]) < 1.5:
                r["FL_contact"] = "0"
        text = io.StringIO()
        w = csv.DictWriter(text, fieldnames=header, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
        rewrite(self.run, "lo.csv", text.getvalue())
        rewrite(self.run, "slip.csv", "kind,leg,start_s,end_s,crossed_s,size,matched\n"
                                      "truth,FR,2.000,2.200,2.050,0.004,1\n"
                                      "detected,FR,2.060,2.100,,0.0035,1\n")
        fig = report.plot_feet_timeline(self.run)
        ax = fig.axes[0]
        bars = {c.get_gid(): c for c in ax.collections}
        self.assertEqual(len(bars), 16)  # four series of four feet
        self.assertEqual(len(bars["FL_true_slip"].get_paths()), 0)
        truth = bars["FR_true_slip"].get_paths()
        self.assertEqual(len(truth), 1)
        x0, x1 = truth[0].vertices[:, 0].min(), truth[0].vertices[:, 0].max()
        self.assertAlmostEqual(x0, 2.0)
        self.assertAlmostEqual(x1, 2.2)
        y = truth[0].vertices[:, 1].min()
        self.assertAlmostEqual(y, 2 + 0.02)  # FR is the second row from the top (y = 2)
        found = bars["FR_slip"].get_paths()
        self.assertAlmostEqual(found[0].vertices[:, 0].min(), 2.06)
        # FL's estimated contact has a gap over 1.0-1.5 s: no span covers 1.2 s on its row (y = 3).
        spans_fl = bars["FL_contact"].get_paths()
        self.assertAlmostEqual(spans_fl[0].vertices[:, 1].min(), 3 - 0.2)
        self.assertTrue(spans_fl)
        self.assertFalse(any(p.vertices[:, 0].min() <= 1.2 <= p.vertices[:, 0].max() for p in spans_fl))
        # lo.csv of an older viqu (no stance truth): the plot is left out, and said so.
        old = [c for c in header if not c.endswith(("_true_travel", "_normal_n", "_travel", "_slipped"))]
        text = io.StringIO()
        w = csv.DictWriter(text, fieldnames=old, lineterminator="\n", extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
        rewrite(self.run, "lo.csv", text.getvalue())
        rc, out, err = report_py(self.run)
        self.assertEqual(rc, 0, err)
        self.assertIn("lo.csv and slip.csv are of an older viqu (no stance truth): no feet_timeline.png", err)
        self.assertNotIn("feet_timeline.png", os.listdir(os.path.join(self.run, "plots")))

    def test_legend_clear_of_the_plot(self):
        # The legend lies outside the axes (where the obstacles' names are drawn), within the figure.
        fig = report.plot_trajectory_top(self.run)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        ax = fig.axes[0]
        legends = list(fig.legends) + [a.get_legend() for a in fig.axes if a.get_legend()]
        self.assertEqual(len(legends), 1)
        box = legends[0].get_window_extent(renderer)
        self.assertFalse(box.overlaps(ax.get_window_extent(renderer)))
        self.assertFalse(box.overlaps(ax.xaxis.label.get_window_extent(renderer)))
        names = [t for t in ax.texts if t.get_text()]
        self.assertEqual(len(names), 5)
        for t in names:
            self.assertFalse(box.overlaps(t.get_window_extent(renderer)), t.get_text())
        self.assertTrue(fig.bbox.contains(box.x0, box.y0) and fig.bbox.contains(box.x1, box.y1))
        self.assertEqual(tuple(fig.get_size_inches() * fig.dpi), (800, 600))

    def test_camera_dark_is_blank(self):
        # A camera outage from 3 s to 4 s: nothing is in view, though the truth still lists the
        # obstacles (it comes from the ideal image); the moving share is blank there, shaded.
        text = read_text(self.run, "scenario.yaml")
        old = "segmentation: true}"
        self.assertEqual(text.count(old), 1)
        rewrite(self.run, "scenario.yaml", text.replace(old, "segmentation: true, dropouts: [[3, 4]]}"))
        fig, err = quietly(report.plot_error_time, self.run)
        self.assertEqual(err, "")
        ts, share = line(fig, "share").get_data()
        ts, share = np.asarray(ts), np.asarray(share)
        dark = (ts >= 3.0 - 1e-9) & (ts < 4.0 - 1e-9)
        self.assertGreater(dark.sum(), 10)
        self.assertTrue(np.all(np.isnan(share[dark])))
        self.assertFalse(np.any(np.isnan(share[~dark])))
        self.assertGreater(share[list(np.round(ts, 6)).index(4.0)], 0)
        ax = fig.axes[0]
        shaded = [p for p in ax.patches if p.get_gid() == "camera_dark"]
        self.assertEqual(len(shaded), 1)
        self.assertIn("camera dark", [t.get_text() for t in ax.texts])
        self.assertIn("camera dark", [t.get_text() for t in ax.get_legend().get_texts()])
        rc, out, err = report_py(self.run)
        self.assertEqual((rc, err), (0, ""))
        # A malformed outage list is bad input, naming scenario.yaml.
        text = read_text(self.run, "scenario.yaml").replace("dropouts: [[3, 4]]", "dropouts: [[4, 3]]")
        rewrite(self.run, "scenario.yaml", text)
        rc, out, err = report_py(self.run)
        self.assertEqual(rc, 2)
        self.assertIn("scenario.yaml: sensors.camera.dropouts", err)

    def test_incomplete_folder_is_refused(self):
        os.remove(os.path.join(self.run, "run_complete.json"))
        r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "report.py"), self.run],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith(f"viqu: {self.run}: not a complete run folder"), r.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.run, "plots")))


class SweepReport(unittest.TestCase):
    def test_axes_must_be_two_grid_keys(self):
        tmp = tempfile.mkdtemp(prefix="viqu_report_sweep_")
        try:
            with open(os.path.join(tmp, "sweep.yaml"), "w") as f:
                f.write("scenarios: []\ngrid:\n  a: [1, 2]\n  b: [0.1, 0.2]\nmetrics: [ate.rmse_m]\n")
            with open(os.path.join(tmp, "results.csv"), "w") as f:
                f.write("id,scenario,seed,a,b,ate.rmse_m,exit_code,status,wall_s\n")
                n = 0
                for a in (1, 2):
                    for b in (0.1, 0.2):
                        f.write(f"p{n:04d},s,1,{a},{b},{a * b},0,ok,1\n")
                        n += 1
            rc, out, err = report_py(tmp, "--x", "a", "--y", "a")
            self.assertEqual(rc, 2, err)
            self.assertIn("--x and --y name the same key 'a'", err)
            for args in (["--x", "seed"], ["--x", "a", "--y", "ate.rmse_m"], ["--x", "wall_s", "--y", "b"]):
                with self.subTest(args=args):
                    rc, out, err = report_py(tmp, *args)
                    self.assertEqual(rc, 2, err)
                    self.assertIn("is not a grid key", err)
            self.assertFalse(os.path.exists(os.path.join(tmp, "plots")))
            rc, out, err = report_py(tmp, "--x", "b", "--y", "a")
            self.assertEqual(rc, 0, err)
        finally:
            shutil.rmtree(tmp)

    def test_heatmap_and_line(self):
        tmp = tempfile.mkdtemp(prefix="viqu_report_sweep_")
        try:
            with open(os.path.join(tmp, "sweep.yaml"), "w") as f:
                f.write("scenarios: []\n")
            with open(os.path.join(tmp, "results.csv"), "w") as f:
                f.write("id,scenario,seed,a,b,ate.rmse_m,exit_code,status,wall_s\n")
                n = 0
                for a in (1, 2, 4):
                    for b in (0.1, 0.2):
                        for seed in (1, 2):
                            f.write(f"p{n:04d},s,{seed},{a},{b},{a * b + seed * 0.01},0,ok,1\n")
                            n += 1
            py = [sys.executable, os.path.join(ROOT, "tools", "report.py"), tmp]
            self.assertEqual(subprocess.run(py + ["--x", "a", "--y", "b", "--metric", "ate.rmse_m"]).returncode, 0)
            self.assertEqual(png_size(os.path.join(tmp, "plots", "heatmap_ate.rmse_m.png")), (800, 600))
            self.assertEqual(subprocess.run(py + ["--x", "a", "--metric", "ate.rmse_m"]).returncode, 0)
            self.assertEqual(png_size(os.path.join(tmp, "plots", "line_ate.rmse_m.png")), (800, 600))
            r = subprocess.run(py + ["--x", "c"], capture_output=True, text=True)
            self.assertEqual(r.returncode, 2)
            self.assertIn("no column 'c'", r.stderr)
            # Without --metric: the sweep's first metric, as sweep.yaml lists it.
            with open(os.path.join(tmp, "results.csv"), "w") as f:
                f.write("id,scenario,seed,a,ate.rmse_m,tracking.lost_frames,exit_code,status,wall_s\n")
                for n, a in enumerate((1, 2, 4)):
                    f.write(f"p{n:04d},s,1,{a},{a * 0.1},{10 * a},0,ok,1\n")
            with open(os.path.join(tmp, "sweep.yaml"), "w") as f:
                f.write("scenarios: []\nmetrics: [ate.rmse_m, tracking.lost_frames]\n")
            shutil.rmtree(os.path.join(tmp, "plots"))
            r = subprocess.run(py + ["--x", "a"], capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertTrue(os.path.exists(os.path.join(tmp, "plots", "line_ate.rmse_m.png")), r.stdout)
        finally:
            shutil.rmtree(tmp)


if __name__ == "__main__":
    unittest.main()
