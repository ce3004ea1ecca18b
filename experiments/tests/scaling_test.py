#!/usr/bin/python3
"""experiments/scaling.py at its smallest size, into a temporary results folder: the table's row
holds the atoms skeletonize kept (one per vertex, about), an M2 and an OpenVDB mesh within 5 % of
each other's vertex count, positive times and memory; the plot is written; an unknown size is
refused with a message and no output.

Usage: scaling_test.py BUILD
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(os.path.dirname(HERE), "scaling.py")
BUILD = sys.argv.pop(1)


def scaling(results, *args):
    return subprocess.run(["/usr/bin/python3", SCRIPT, "--build", BUILD, "--results", results,
                           *args], capture_output=True, text=True, stdin=subprocess.DEVNULL)


class Scaling(unittest.TestCase):
    def test_smallest_size(self):
        with tempfile.TemporaryDirectory() as results:
            r = scaling(results, "--sizes", "10k")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(results, "scaling.csv")) as f:
                rows = list(csv.DictReader(f))
            self.assertEqual(len(rows), 1)
            row = rows[0]
            self.assertEqual(row["size"], "10k")
            vertices, atoms = int(row["vertices"]), int(row["atoms"])
            self.assertEqual(vertices, 126 * 80)
            self.assertGreater(atoms, 0.9 * vertices)  # --merge-tol 0: about a pole per vertex
            self.assertLessEqual(atoms, vertices)
            m2_v, vdb_v = int(row["m2_v"]), int(row["vdb_v"])
            self.assertLess(abs(vdb_v - m2_v), 0.05 * m2_v)
            for key in ("garbing_s", "octree_s", "peak_mb", "vdb_s", "vdb_peak_mb"):
                self.assertGreater(float(row[key]), 0, key)
            # High-water marks at the end of each phase: rising, up to the program's peak.
            marks = [float(row["peak_mb_" + p]) for p in ("cones", "octree", "m1", "m2")]
            self.assertGreater(marks[0], 0)
            self.assertEqual(marks, sorted(marks))
            self.assertLessEqual(marks[-1], float(row["peak_mb"]))
            # The thinned atoms: fewer kept, M2 as close to the generated mesh (10k atoms: within
            # 5 % of the exact G's Hausdorff distance; measured 0.38 % against 0.67 %).
            for key in ("c4", "c8", "k16"):
                self.assertLess(int(row[key + "_atoms"]), atoms)
                self.assertGreater(float(row[key + "_garbing_s"]), 0)
                self.assertLess(float(row[key + "_h_pct"]), 1.05 * float(row["h_pct"]))
            self.assertTrue(os.path.getsize(os.path.join(results, "scaling.png")) > 0)
            with open(os.path.join(results, "scaling.md")) as f:
                self.assertIn("| 10k | 10080 |", f.read())

    def test_unknown_size(self):
        with tempfile.TemporaryDirectory() as results:
            r = scaling(results, "--sizes", "3m")
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("unknown size(s) 3m", r.stderr)
            self.assertEqual(os.listdir(results), [])


if __name__ == "__main__":
    unittest.main()
