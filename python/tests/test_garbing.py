#!/usr/bin/python3
"""The Python module `garbing` (CTest python_module_test): the sphere gives the paper's row,
every function equals its program to the bit (garb, skeletonize with and without --simplify,
evaluate distance and check, the .ma reader and writer), and bad arrays raise ValueError with
the programs' one-line messages. PYTHONPATH holds the module; MG_BIN the programs.
"""
import json
import math
import os
import subprocess
import tempfile
import unittest

import numpy as np

import garbing

BIN = os.environ["MG_BIN"]


def run(program, *args):
    r = subprocess.run([os.path.join(BIN, program), *map(str, args)], capture_output=True,
                       text=True, stdin=subprocess.DEVNULL)
    if r.returncode != 0:
        raise AssertionError("%s failed: %s" % (program, r.stderr))
    return r.stdout


def read_off(path):
    """(V float64 (n, 3), F int (m, 3)) of a triangle OFF file as our writer writes it."""
    with open(path) as f:
        tokens = [line.split() for line in f if line.strip() and not line.startswith("#")]
    assert tokens[0] == ["OFF"], tokens[0]
    nv, nf = int(tokens[1][0]), int(tokens[1][1])
    v = np.array([[float(x) for x in row[:3]] for row in tokens[2:2 + nv]])
    f = np.array([[int(x) for x in row[1:4]] for row in tokens[2 + nv:2 + nv + nf]])
    return v, f


def ring(n=60, major=1.0, radius=0.3):
    t = 2 * math.pi * np.arange(n) / n
    return np.stack([major * np.cos(t), major * np.sin(t), np.zeros(n)], axis=1), np.full(n, radius)


class Garbing(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def torus(self):
        off = self.path("torus.off")
        run("models", "generate", "torus", "-o", off)
        return off, read_off(off)

    def test_one_ball_gives_the_papers_sphere_row(self):
        v, f, stats = garbing.garb(np.array([[0.5, -1.0, 2.0]]), np.array([1.5]))
        self.assertEqual(v.shape, (1344, 3))
        self.assertEqual(f.shape, (2684, 3))
        self.assertEqual(v.dtype, np.float64)
        self.assertEqual(f.dtype, np.int32)
        self.assertEqual(stats["min_depth"], 4)
        self.assertFalse(stats["hit_max_depth"])
        np.testing.assert_allclose(np.linalg.norm(v - [0.5, -1.0, 2.0], axis=1), 1.5, rtol=1e-9)
        c = garbing.check(v, f)
        self.assertTrue(c["closed"] and c["manifold"] and c["oriented"])
        self.assertEqual((c["components"], c["genus"], c["intersecting_pairs"]), (1, 0, 0))

    def test_garb_equals_the_program(self):
        centres, radii = ring()
        ma = self.path("ring.ma")
        garbing.write_ma(ma, centres, radii)
        run("garb", ma, "-o", self.path("ring.off"), "--threads", 1)
        v_cli, f_cli = read_off(self.path("ring.off"))
        for threads in (1, 2):
            v, f, _ = garbing.garb(centres, radii, threads=threads)
            np.testing.assert_array_equal(v, v_cli)
            np.testing.assert_array_equal(f, f_cli)
        # An option passes through as the program's does.
        run("garb", ma, "-o", self.path("ring4.off"), "--min-depth", 4)
        v4, f4, s4 = garbing.garb(centres, radii, min_depth=4)
        np.testing.assert_array_equal(v4, read_off(self.path("ring4.off"))[0])
        self.assertEqual(s4["min_depth"], 4)
        # --tolerance: the same thinned mesh, with its count of kept atoms.
        run("garb", ma, "-o", self.path("ringt.off"), "--tolerance", 1, "--min-depth", 4)
        vt, ft, st = garbing.garb(centres, radii, min_depth=4, tolerance=1.0)
        np.testing.assert_array_equal(vt, read_off(self.path("ringt.off"))[0])
        np.testing.assert_array_equal(ft, read_off(self.path("ringt.off"))[1])
        self.assertEqual(st["thinning"]["atoms_kept"] + st["thinning"]["atoms_dropped"], len(radii))
        self.assertGreater(st["thinning"]["atoms_dropped"], 0)
        self.assertNotIn("thinning", s4)
        self.assertEqual(st["thinning"]["method"], "cover")
        run("garb", ma, "-o", self.path("ringc.off"), "--tolerance", 1, "--min-depth", 4,
            "--thinning", "contain")
        vc, fc, sc = garbing.garb(centres, radii, min_depth=4, tolerance=1.0, thinning="contain")
        np.testing.assert_array_equal(vc, read_off(self.path("ringc.off"))[0])
        self.assertEqual(sc["thinning"]["method"], "contain")
        self.assertEqual(sc["thinning"]["atoms_covered"], 0)
        with self.assertRaisesRegex(ValueError, "tolerance must be finite and >= 0"):
            garbing.garb(centres, radii, tolerance=-1)
        with self.assertRaisesRegex(ValueError, "thinning must be 'cover' or 'contain'"):
            garbing.garb(centres, radii, tolerance=1.0, thinning="union")
        with self.assertRaisesRegex(ValueError, "thinning chooses how tolerance thins"):
            garbing.garb(centres, radii, thinning="cover")

    def write_slab(self):
        ma = self.path("slab.ma")
        run("models", "generate", "medial-slab", "-o", ma)
        return ma

    def test_medial_mesh_envelope_equals_the_program(self):
        ma = self.write_slab()
        centres, radii, edges, faces = garbing.read_ma(ma)
        self.assertEqual(faces.shape[1], 3)
        run("garb", ma, "-o", self.path("slab.off"))
        v, f, stats = garbing.garb(centres, radii, edges, faces)
        self.assertEqual(stats["primitives"], "ma")
        v_cli, f_cli = read_off(self.path("slab.off"))
        np.testing.assert_array_equal(v, v_cli)
        np.testing.assert_array_equal(f, f_cli)

    def test_skeletonize_equals_the_program(self):
        off, (v, f) = self.torus()
        run("skeletonize", off, "-o", self.path("t.ma"), "--clamp-radius")
        c_cli, r_cli, _, _ = garbing.read_ma(self.path("t.ma"))
        centres, radii = garbing.skeletonize(v, f, clamp_radius=True)
        np.testing.assert_array_equal(centres, c_cli)
        np.testing.assert_array_equal(radii, r_cli)
        # Random samples: a count as an int or as the program's digits.
        run("skeletonize", off, "-o", self.path("r.ma"), "--samples", 2000)
        c_cli = garbing.read_ma(self.path("r.ma"))[0]
        for samples in (2000, "2000"):
            np.testing.assert_array_equal(garbing.skeletonize(v, f, samples=samples)[0], c_cli)
        # Simplified, with connectivity: four arrays, as `skeletonize --simplify 20`.
        run("skeletonize", off, "-o", self.path("s.ma"), "--clamp-radius", "--simplify", 20)
        expected = garbing.read_ma(self.path("s.ma"))
        got = garbing.skeletonize(v, f, clamp_radius=True, simplify=20)
        self.assertEqual(len(got), 4)
        self.assertEqual(got[0].shape, (20, 3))
        for a, b in zip(got, expected):
            np.testing.assert_array_equal(a, b)

    def test_distance_and_check_equal_the_program(self):
        off, (v, f) = self.torus()
        sphere = self.path("sphere.off")
        run("models", "generate", "sphere", "-o", sphere, "--frequency", 6)
        vs, fs = read_off(sphere)
        cli = json.loads(run("evaluate", "distance", off, sphere, "--json", "--samples", 20000))
        d = garbing.distance(v, f, vs, fs, samples=20000)
        for key in ("hausdorff", "rms", "mean", "diagonal", "hausdorff_pct"):
            self.assertEqual(d[key], cli[key], key)
        check = json.loads(run("evaluate", "check", off, "--json"))
        c = garbing.check(v, f)
        self.assertEqual(c["genus"], 1)
        self.assertEqual(c["intersecting_pairs"], check["intersecting_pairs"])
        self.assertEqual(c["min_angle_deg"], check["min_angle_deg"])

    def test_ma_round_trip(self):
        centres, radii = ring(5)
        edges = np.array([[0, 1], [1, 2]])
        garbing.write_ma(self.path("r.ma"), centres, radii, edges)
        c, r, e, f = garbing.read_ma(self.path("r.ma"))
        np.testing.assert_array_equal(c, centres)
        np.testing.assert_array_equal(r, radii)
        np.testing.assert_array_equal(e, edges)
        self.assertEqual(f.shape, (0, 3))

    def test_bad_arrays_raise_with_one_line(self):
        centres, radii = ring(4)
        cases = [
            ((centres[:, :2], radii), "centres: expected an array of shape (n, 3)"),
            ((centres, radii[:3]), "radii: expected an array of shape (4,)"),
            ((np.array([[math.nan, 0, 0]]), [1.0]), "centres: row 0 is not finite"),
            ((centres, [1.0, -1.0, 1.0, 1.0]), "atom 1"),
            ((centres, radii, np.array([[0, 7]])), "edges: row 0 has index 7, out of range (4)"),
        ]
        for args, message in cases:
            with self.assertRaises(ValueError) as e:
                garbing.garb(*args)
            self.assertIn(message, str(e.exception))
            self.assertNotIn("\n", str(e.exception))
        with self.assertRaises(ValueError) as e:
            garbing.garb(centres, radii, max_depth=30)
        self.assertIn("max_depth must be in [1, 20]", str(e.exception))
        with self.assertRaises(ValueError) as e:
            garbing.check(np.zeros((3, 3)), np.array([[0, 1, 5]]))
        self.assertIn("mesh faces: row 0 has index 5, out of range (3)", str(e.exception))
        off, (v, f) = self.torus()
        with self.assertRaises(ValueError) as e:
            garbing.skeletonize(v, f[:-1])  # a hole: not closed
        self.assertIn("mesh", str(e.exception))
        with self.assertRaises(ValueError) as e:
            garbing.skeletonize(v, f, samples="many")
        self.assertIn("samples: expected vertices, midpoints or a count", str(e.exception))
        with self.assertRaises(ValueError) as e:  # indices must be integers, not truncated
            garbing.check(np.zeros((3, 3)), np.array([[0.0, 1.9, 2.2]]))
        self.assertIn("mesh faces: expected an integer array, got dtype float64", str(e.exception))
        for no_faces in (np.array([], dtype=int), np.zeros((0, 3), dtype=int)):
            with self.assertRaises(ValueError) as e:
                garbing.check(np.zeros((3, 3)), no_faces)
            self.assertIn("mesh: no faces", str(e.exception))
        with self.assertRaises(ValueError) as e:
            garbing.skeletonize(v, f, samples=2.5)
        self.assertIn("samples: expected vertices, midpoints or a count, got 2.5", str(e.exception))
        c, r, e_, f_ = garbing.read_ma(self.write_slab())
        with self.assertRaises(ValueError) as e:  # a cone option on an envelope, as garb says
            garbing.garb(c, r, e_, f_, primitives="ma", cone_filter=0.5)
        self.assertIn("choose the cones of primitives='rt', not 'ma'", str(e.exception))
        with self.assertRaises(OSError) as e:
            garbing.read_ma(self.path("missing.ma"))
        self.assertIn("missing.ma", str(e.exception))
        # Nothing written by a failing write.
        with self.assertRaises(ValueError):
            garbing.write_ma(self.path("bad.ma"), centres, [1.0, math.nan, 1.0, 1.0])
        self.assertFalse(os.path.exists(self.path("bad.ma")))


if __name__ == "__main__":
    unittest.main()
