#!/usr/bin/python3
"""The skeletonize program at its edges: output, stats, exit codes, messages, no partial output."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SKELETONIZE = sys.argv.pop(1)
MODELS = sys.argv.pop(1)


def run(*args):
    return subprocess.run([SKELETONIZE, *args], capture_output=True, text=True)


class SkeletonizeCli(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def write(self, name, text):
        with open(self.path(name), "w") as f:
            f.write(text)
        return self.path(name)

    def assert_refused(self, r, code, message):
        self.assertEqual(r.returncode, code, r.stderr)
        self.assertIn(message, r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertFalse(os.path.exists(self.path("out.ma")))
        self.assertFalse([f for f in os.listdir(self.dir) if "partial" in f])

    def test_torus_gives_sixty_atoms_and_stats(self):
        mesh = self.path("torus.off")
        subprocess.run([MODELS, "generate", "torus", "-o", mesh], check=True)
        r = run(mesh, "-o", self.path("out.ma"), "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        stats = json.load(open(self.path("s.json")))
        self.assertEqual(stats["atoms"], 60)
        self.assertEqual(stats["union"], {"components": 1, "euler": 0})
        self.assertTrue(stats["union_matches_mesh"])
        with open(self.path("out.ma")) as f:
            self.assertEqual(f.readline().split(), ["60", "0", "0"])

    def test_same_file_at_one_and_two_threads(self):
        mesh = self.path("b.off")
        subprocess.run([MODELS, "generate", "bumpy-torus", "--ring", "40", "--tube", "30",
                        "-o", mesh], check=True)
        for t in ("1", "2"):
            r = run(mesh, "-o", self.path("t%s.ma" % t), "--samples", "3000", "--threads", t)
            self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(open(self.path("t1.ma"), "rb").read(), open(self.path("t2.ma"), "rb").read())

    def test_open_mesh(self):
        mesh = self.write("open.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n")
        r = run(mesh, "-o", self.path("out.ma"))
        self.assert_refused(r, 2, "open.off: open mesh (3 boundary edges)")

    def test_non_manifold_mesh(self):
        # Two tetrahedra sharing one vertex.
        mesh = self.write("bow.off", "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n"
                          "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 5\n3 0 6 4\n3 0 5 6\n3 4 6 5\n")
        r = run(mesh, "-o", self.path("out.ma"))
        self.assert_refused(r, 2, "bow.off: non-manifold mesh: vertex 0")

    def test_empty_and_missing_mesh(self):
        r = run(self.write("e.off", "OFF\n0 0 0\n"), "-o", self.path("out.ma"))
        self.assert_refused(r, 2, "e.off: no faces")
        r = run(self.path("none.off"), "-o", self.path("out.ma"))
        self.assert_refused(r, 3, "none.off: cannot open for reading")

    def test_flat_mesh(self):
        mesh = self.write("flat.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n")
        r = run(mesh, "-o", self.path("out.ma"))
        self.assert_refused(r, 2, "flat.off: fewer than 4 non-coplanar samples")

    def test_bad_sample_option(self):
        mesh = self.path("torus.off")
        subprocess.run([MODELS, "generate", "torus", "-o", mesh], check=True)
        r = run(mesh, "-o", self.path("out.ma"), "--samples", "lots")
        self.assert_refused(r, 2, "--samples: expected vertices, midpoints or a count, got 'lots'")


if __name__ == "__main__":
    unittest.main()
