#!/usr/bin/python3
"""experiments/propose_bounds.py on the sphere: without --write it prints the current bound, the
measurement, the proposal (measured x 1.05 + 0.02, rounded up to 3 decimals) and the difference
for both metrics and leaves the bounds file byte for byte; with --write (into a copy) it rewrites
the sphere's entry alone; an unknown model is bad usage.

Usage: propose_bounds_test.py BUILD
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
EXPERIMENTS = os.path.dirname(HERE)
SCRIPT = os.path.join(EXPERIMENTS, "propose_bounds.py")
BOUNDS = os.path.join(EXPERIMENTS, "regression_thresholds.json")
BUILD = sys.argv.pop(1)
METRICS = ("hausdorff_pct", "rms_pct")


def propose(*args):
    return subprocess.run(["/usr/bin/python3", SCRIPT, BUILD, *args], capture_output=True, text=True,
                          stdin=subprocess.DEVNULL)


def proposal_rows(stdout):
    """{(model, metric): (bound, measured, proposed, difference)} of the printed table."""
    rows = {}
    for line in stdout.splitlines():
        cells = line.split()
        if len(cells) == 6 and cells[1] in METRICS:
            rows[cells[0], cells[1]] = tuple(cells[2:])
    return rows


def read(path):
    with open(path, "rb") as f:
        return f.read()


class ProposeBounds(unittest.TestCase):
    def test_dry_run_prints_the_proposal_and_leaves_the_file(self):
        before = read(BOUNDS)
        current = json.loads(before)["models"]["sphere"]
        r = propose("--models", "sphere")
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = proposal_rows(r.stdout)
        self.assertEqual(sorted(rows), [("sphere", m) for m in METRICS], r.stdout)
        for metric in METRICS:
            bound, measured, proposed, difference = rows["sphere", metric]
            self.assertEqual(float(bound), current[metric])
            # The measurement is printed to 4 decimals, the proposal from the full value.
            self.assertAlmostEqual(float(proposed), float(measured) * 1.05 + 0.02, delta=0.00101)
            self.assertGreaterEqual(float(proposed), float(measured) * 1.05 + 0.02 - 0.0001)
            self.assertAlmostEqual(float(difference), float(proposed) - float(bound), places=6)
        self.assertIn("not written", r.stdout)
        self.assertEqual(read(BOUNDS), before)
        self.assertFalse([f for f in os.listdir(EXPERIMENTS) if "partial" in f])

    def test_write_rewrites_the_measured_model_alone(self):
        with tempfile.TemporaryDirectory() as tmp:
            copy = os.path.join(tmp, "bounds.json")
            shutil.copy(BOUNDS, copy)
            old = json.loads(read(copy))
            r = propose("--models", "sphere", "--write", "--bounds", copy)
            self.assertEqual(r.returncode, 0, r.stderr)
            new = json.loads(read(copy))
            self.assertEqual(list(new["models"]), list(old["models"]))
            for name in old["models"]:
                if name != "sphere":
                    self.assertEqual(new["models"][name], old["models"][name], name)
            sphere = new["models"]["sphere"]
            rows = proposal_rows(r.stdout)
            for metric in METRICS:
                self.assertEqual(sphere[metric], float(rows["sphere", metric][2]))
                self.assertEqual("%.4f" % sphere["measured_" + metric], rows["sphere", metric][1])
            self.assertIn("by experiments/propose_bounds.py at ", sphere["why"])
            self.assertIn("measured x 1.05 + 0.02", new["about"])
            self.assertEqual(os.listdir(tmp), ["bounds.json"])

    def test_unknown_model_is_bad_usage(self):
        before = read(BOUNDS)
        r = propose("--models", "teapot", "--write")
        self.assertEqual(r.returncode, 2)
        self.assertIn("unknown model(s): teapot", r.stderr)
        self.assertEqual(read(BOUNDS), before)


if __name__ == "__main__":
    unittest.main()
