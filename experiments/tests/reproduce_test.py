#!/usr/bin/python3
"""End to end: experiments/reproduce.py on the sphere writes Table 1 with the paper's Sphere row
reproduced exactly (M2 1344 vertices, 2684 faces), the report saying so, and fails cleanly on an
unknown model."""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(os.path.dirname(HERE), "reproduce.py")
BUILD = sys.argv.pop(1)


class Reproduce(unittest.TestCase):
    def test_sphere_row(self):
        with tempfile.TemporaryDirectory() as out:
            r = subprocess.run(["/usr/bin/python3", SCRIPT, "--build", BUILD, "--models", "sphere",
                                "--results", out], capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            rows = list(csv.DictReader(open(os.path.join(out, "table1.csv"))))
            ours = [x for x in rows if x["source"] == "ours"]
            self.assertEqual(len(ours), 1)
            self.assertEqual((ours[0]["m2_v"], ours[0]["m2_f"]), ("1344", "2684"))
            self.assertLess(float(ours[0]["h"]), 0.13)  # the paper's 0.13% on its own sphere
            report = open(os.path.join(out, "REPORT.md")).read()
            self.assertIn("exactly the paper's 1344 / 2684", report)
            for f in ("table2.md", "smoothness.md", "atoms.md"):
                self.assertTrue(os.path.exists(os.path.join(out, f)), f)

    def test_unknown_model(self):
        with tempfile.TemporaryDirectory() as out:
            r = subprocess.run(["/usr/bin/python3", SCRIPT, "--build", BUILD, "--models", "teapot",
                                "--results", out], capture_output=True, text=True)
            self.assertEqual(r.returncode, 1)
            self.assertIn("unknown model(s): teapot", r.stderr)
            self.assertEqual(os.listdir(out), [])


if __name__ == "__main__":
    unittest.main()
