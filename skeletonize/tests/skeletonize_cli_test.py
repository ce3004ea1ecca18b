#!/usr/bin/python3
"""The skeletonize program at its edges: output, stats, exit codes, messages, no partial output."""
import json
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "core", "tests", "support"))
import cli_test_util as U  # noqa: E402

SKELETONIZE, MODELS = U.programs_from_argv("skeletonize", "models")


def run(*args):
    return U.run(SKELETONIZE, *args)


TETRA = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"


class SkeletonizeCli(U.CliTestCase):
    def generate(self, name, *args):
        return U.generate(MODELS, self.path(name), *args)

    def load(self, name):
        with open(self.path(name), "rb") as f:
            return f.read()

    def stats(self, name):
        return json.loads(self.load(name))

    def read_ma(self, name):
        with open(self.path(name)) as f:
            lines = [l.split() for l in f if l.strip() and not l.startswith("#")]
        header = [int(x) for x in lines[0]]
        kinds = [l[0] for l in lines[1:]]
        self.assertEqual(header, [kinds.count("v"), kinds.count("e"), kinds.count("f")])
        return header, lines[1:]

    def assert_refused(self, r, code, message, inputs=()):
        """Refused cleanly, and the folder holds the `inputs` alone."""
        super().assert_refused(r, code, message)
        self.assertEqual(sorted(os.listdir(self.dir)), sorted(os.path.basename(i) for i in inputs))

    def test_torus_gives_sixty_atoms_and_stats(self):
        mesh = self.generate("torus.off", "torus")
        r = run(mesh, "-o", self.path("out.ma"), "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr, "")
        stats = self.stats("s.json")
        self.assertEqual(stats["atoms"], 60)
        self.assertEqual(stats["samples"], 1200)
        self.assertGreater(stats["exact_circumcentres"], 0)
        self.assertEqual(stats["union"], {"components": 1, "euler": 0})
        self.assertEqual(stats["mesh"], {"components": 1, "euler": 0, "genus": 1})
        self.assertTrue(stats["union_matches_mesh"])
        self.assertAlmostEqual(stats["merge_tol"], 1e-3 * stats["diagonal"])
        self.assertGreaterEqual(stats["rmin"], 0.3 * 0.98)
        self.assertLessEqual(stats["rmax"], 0.3 * 1.02)
        for phase in ("delaunay", "poles", "merge", "distances", "union_topology", "total"):
            self.assertGreaterEqual(stats["seconds"][phase], 0)
        header, _ = self.read_ma("out.ma")
        self.assertEqual(header, [60, 0, 0])

    def test_clamped_connectivity(self):
        mesh = self.generate("torus.off", "torus", "--ring", "24", "--tube", "12")
        r = run(mesh, "-o", self.path("out.ma"), "--clamp-radius", "--connectivity", "--samples", "midpoints",
                "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        stats = self.stats("s.json")
        self.assertEqual(stats["worst_overshoot"], 0)
        self.assertGreater(stats["pole_overshoot"], 0)
        header, lines = self.read_ma("out.ma")
        self.assertEqual(header, [stats["atoms"], stats["edges"], stats["triangles"]])
        self.assertGreater(stats["edges"], stats["atoms"])
        for line in lines:
            if line[0] in "ef":
                self.assertTrue(all(0 <= int(i) < stats["atoms"] for i in line[1:]), line)

    def test_coarse_sampling_warns(self):
        # An 8 x 3 grid torus: its vertex poles do not go round the ring.
        mesh = self.generate("coarse.off", "torus", "--ring", "8", "--tube", "3")
        r = run(mesh, "-o", self.path("out.ma"), "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        stats = self.stats("s.json")
        self.assertFalse(stats["union_matches_mesh"])
        self.assertEqual(r.stderr.strip(), "skeletonize: warning: %s: the union of the atoms has 1 component(s) and "
                         "Euler characteristic 2, the mesh 1 and 0 (sample more densely: --samples midpoints or N)"
                         % mesh)

    def test_same_file_at_one_and_two_threads(self):
        mesh = self.generate("b.off", "bumpy-torus", "--ring", "40", "--tube", "30")
        for t in ("1", "2"):
            r = run(mesh, "-o", self.path("t%s.ma" % t), "--samples", "3000", "--threads", t, "--connectivity")
            self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(self.load("t1.ma"), self.load("t2.ma"))

    def test_open_mesh(self):
        mesh = self.write("open.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n")
        self.assert_refused(run(mesh, "-o", self.path("out.ma"), "--stats", self.path("s.json")), 2,
                            "open.off: open mesh (3 boundary edges)", [mesh])

    def test_non_manifold_mesh(self):
        # Two tetrahedra sharing one vertex.
        mesh = self.write("bow.off", "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n"
                          "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 5\n3 0 6 4\n3 0 5 6\n3 4 6 5\n")
        self.assert_refused(run(mesh, "-o", self.path("out.ma")), 2, "bow.off: non-manifold mesh: vertex 0", [mesh])

    def test_empty_missing_and_malformed_mesh(self):
        empty = self.write("e.off", "OFF\n0 0 0\n")
        self.assert_refused(run(empty, "-o", self.path("out.ma")), 2, "e.off: no faces", [empty])
        self.assert_refused(run(self.path("none.off"), "-o", self.path("out.ma")), 3,
                            "none.off: cannot open for reading", [empty])
        nan = self.write("nan.off", TETRA.replace("0 1 0\n", "0 nan 0\n", 1))
        self.assert_refused(run(nan, "-o", self.path("out.ma")), 2, "nan.off:5: vertex 2 has a non-finite coordinate",
                            [empty, nan])

    def test_flat_mesh(self):
        mesh = self.write("flat.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n")
        self.assert_refused(run(mesh, "-o", self.path("out.ma")), 2, "flat.off: fewer than 4 non-coplanar samples",
                            [mesh])

    def test_bad_options(self):
        mesh = self.write("tet.off", TETRA)
        out = self.path("out.ma")
        self.assert_refused(run(mesh, "-o", out, "--samples", "lots"), 2,
                            "--samples: expected vertices, midpoints or a count, got 'lots'", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--samples", "-5"), 2, "--samples", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--merge-tol", "-1"), 2, "--merge-tol", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--drop-isolated", "2"), 2, "--drop-isolated", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--colour", "red"), 2, "--colour", [mesh])
        self.assert_refused(run(mesh), 2, "--output", [mesh])
        self.assert_refused(run(mesh, "-o", mesh), 2, "output would overwrite the input", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--stats", out), 2, "--stats names the output file", [mesh])
        self.assert_refused(run(mesh, "-o", os.path.join(self.dir, "no", "out.ma")), 2, "does not exist", [mesh])

    def test_simplify_writes_a_medial_mesh_and_its_stats(self):
        mesh = self.generate("torus.off", "torus")
        r = run(mesh, "-o", self.path("out.ma"), "--clamp-radius", "--simplify", "20",
                "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr, "")
        (v, e, f), lines = self.read_ma("out.ma")
        self.assertEqual(v, 20)
        edges = {tuple(sorted(int(x) for x in l[1:3])) for l in lines if l[0] == "e"}
        self.assertEqual(len(edges), e)
        for l in lines:
            if l[0] == "f":
                a, b, c = sorted(int(x) for x in l[1:4])
                self.assertTrue({(a, b), (a, c), (b, c)} <= edges, l)
            if l[0] == "v":
                self.assertGreater(float(l[4]), 0)
        s = self.stats("s.json")["simplify"]
        self.assertEqual(s["before"]["atoms"], 60)
        self.assertEqual(s["after"], {"atoms": 20, "edges": e, "faces": f, "cells": s["after"]["cells"]})
        self.assertTrue(s["target_reached"])
        self.assertEqual(s["collapses"], 40)
        self.assertEqual(s["complex"]["components_after"], 1)
        self.assertEqual(s["complex"]["euler_after"], 0)
        # Every sample of the torus lies within 1 % of the diagonal of the envelope.
        self.assertLess(s["samples_to_envelope"]["max_pct"], 1.0)
        for phase in ("setup", "prune", "quadrics", "collapse", "output"):
            self.assertGreaterEqual(s["seconds"][phase], 0)

    def test_simplify_percentage_and_unreachable_target(self):
        mesh = self.generate("torus.off", "torus")
        r = run(mesh, "-o", self.path("p.ma"), "--clamp-radius", "--simplify", "50%")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(self.read_ma("p.ma")[0][0], 30)
        # One atom cannot hold the torus's loop: the collapses stop above it, with a warning.
        r = run(mesh, "-o", self.path("one.ma"), "--clamp-radius", "--simplify", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("warning", r.stderr)
        self.assertIn("above the target of 1", r.stderr)
        self.assertGreaterEqual(self.read_ma("one.ma")[0][0], 3)

    def test_simplify_same_file_at_one_and_two_threads(self):
        mesh = self.generate("bumpy.off", "bumpy-torus", "--ring", "60", "--tube", "40")
        for threads in ("1", "2"):
            r = run(mesh, "-o", self.path("t%s.ma" % threads), "--simplify", "2%",
                    "--threads", threads)
            self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(self.load("t1.ma"), self.load("t2.ma"))

    def test_simplify_bad_targets(self):
        mesh = self.generate("torus.off", "torus")
        out = self.path("out.ma")
        self.assert_refused(run(mesh, "-o", out, "--simplify", "0"), 2,
                            "--simplify: must be >= 1 atom, not 0", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--simplify", "61"), 2,
                            "--simplify 61: more than the skeleton's 60 atoms (poles) of " + mesh,
                            [mesh])
        self.assert_refused(run(mesh, "-o", out, "--simplify", "many"), 2,
                            "--simplify: expected a count of atoms or a percentage, got 'many'", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--simplify", "0%"), 2,
                            "--simplify: a percentage must be in (0, 100], not 0%", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--simplify", "120%"), 2,
                            "a percentage must be in (0, 100]", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--max-excess", "0"), 2, "need --simplify", [mesh])
        self.assert_refused(run(mesh, "-o", out, "--slab-planes"), 2, "need --simplify", [mesh])

    def test_tetrahedron(self):
        # Its one circumcentre lies outside it; with the edge midpoints it has one pole.
        mesh = self.write("tet.off", TETRA)
        self.assert_refused(run(mesh, "-o", self.path("out.ma")), 2,
                            "tet.off: no Voronoi vertex of the samples lies inside the mesh", [mesh])
        r = run(mesh, "-o", self.path("out.ma"), "--samples", "midpoints")
        self.assertEqual(r.returncode, 0, r.stderr)
        header, lines = self.read_ma("out.ma")
        self.assertEqual(header, [1, 0, 0])
        self.assertEqual([float(x) for x in lines[0][1:4]], [0.25, 0.25, 0.25])

if __name__ == "__main__":
    unittest.main()
