#!/usr/bin/python3
"""experiments/reproduce.py --quick on a local Dask cluster of two worker processes
(--scheduler) writes the same tables, byte for byte, as on the local process pool: every file
without a measured time or memory figure (atoms, smoothness, the baselines' table, Table 1
less its peak-memory column). An unreachable or malformed scheduler address is one line and
exit 1.

Usage: dask_test.py BUILD
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

import distributed

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(os.path.dirname(HERE), "reproduce.py")
BUILD = None  # set in __main__: the cluster's worker processes import this file too
SAME_BYTES = ["atoms.csv", "atoms.md", "smoothness.csv", "smoothness.md", "table1_baselines.csv"]
MEASURED = {"peak_mb"}  # Table 1's column measured at run time


def reproduce(out, *args):
    return subprocess.run(["/usr/bin/python3", SCRIPT, "--build", BUILD, "--quick", "--results",
                           out, *args], capture_output=True, text=True, stdin=subprocess.DEVNULL)


def table1(path):
    with open(path) as f:
        return [{k: v for k, v in row.items() if k not in MEASURED} for row in csv.DictReader(f)]


class Dask(unittest.TestCase):
    def test_same_tables_as_the_local_pool(self):
        with tempfile.TemporaryDirectory() as local, tempfile.TemporaryDirectory() as remote:
            r = reproduce(local, "--jobs", "2")
            self.assertEqual(r.returncode, 0, r.stderr)
            with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                          dashboard_address=None) as cluster:
                r = reproduce(remote, "--scheduler", cluster.scheduler_address)
            self.assertEqual(r.returncode, 0, r.stderr)
            for name in SAME_BYTES:
                with open(os.path.join(local, name), "rb") as a, \
                        open(os.path.join(remote, name), "rb") as b:
                    self.assertEqual(a.read(), b.read(), name)
            rows = table1(os.path.join(local, "table1.csv"))
            self.assertEqual(len([x for x in rows if x["source"] == "ours"]), 3)
            self.assertEqual(rows, table1(os.path.join(remote, "table1.csv")))

    def test_unreachable_or_malformed_scheduler(self):
        for address in ("tcp://127.0.0.1:9", "localhost"):  # nothing there; no port
            with tempfile.TemporaryDirectory() as out:
                r = reproduce(out, "--scheduler", address)
                self.assertEqual(r.returncode, 1)
                self.assertIn("cannot reach the Dask scheduler at %s" % address, r.stderr)
                self.assertNotIn("Traceback", r.stderr)


if __name__ == "__main__":
    BUILD = sys.argv.pop(1)
    unittest.main()
