#!/usr/bin/python3
"""viqu report (tools/report.py) on the stored run folder tests/data/report_run and on a small
sweep folder made here: PNGs of the expected size, plotted series equal to the files' data,
incomplete folders refused with exit 2. Run by CTest with Debian's python3."""
import csv
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

    def test_incomplete_folder_is_refused(self):
        os.remove(os.path.join(self.run, "run_complete.json"))
        r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "report.py"), self.run],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith(f"viqu: {self.run}: not a complete run folder"), r.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.run, "plots")))


class SweepReport(unittest.TestCase):
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
