#!/usr/bin/python3
"""The evaluate program at its edges: reports, determinism, exit codes, one-line messages,
no partial output."""
import json
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "core", "tests", "support"))
import cli_test_util as U  # noqa: E402

EVALUATE, MODELS = U.programs_from_argv("evaluate", "models")


def run(*args):
    return U.run(EVALUATE, *args)


def run_json(*args):
    r = run(*args, "--json")
    if r.returncode != 0:
        raise AssertionError("evaluate %s failed: %s" % (" ".join(args), r.stderr))
    return json.loads(r.stdout)


class EvaluateCli(U.CliTestCase):
    shared_folder = True
    message_prefix = "evaluate: "

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        for name, args in [("s1.off", ["sphere", "--frequency", "16", "--radius", "1"]),
                           ("s11.off", ["sphere", "--frequency", "16", "--radius", "1.1"]),
                           ("torus.off", ["torus", "--ring", "60", "--tube", "20"])]:
            U.generate(MODELS, os.path.join(cls.dir, name), *args)
        with open(os.path.join(cls.dir, "one.ma"), "w") as f:
            f.write("1 0 0\nv 0.5 -0.25 0.125 0.7\n")

    def is_leftover(self, name):
        return "partial" in name or ".tmp" in name

    # --- distance -------------------------------------------------------------------------
    def test_distance_reports_the_issue_keys(self):
        j = run_json("distance", self.path("s1.off"), self.path("s11.off"), "--samples", "100000")
        for key in ("hausdorff", "rms", "hausdorff_pct", "rms_pct", "mean", "mean_pct",
                    "samples", "diagonal", "mesh_to_reference", "reference_to_mesh"):
            self.assertIn(key, j)
        for side in ("mesh_to_reference", "reference_to_mesh"):
            for key in ("max", "max_pct", "mean", "rms", "rms_pct", "samples"):
                self.assertIn(key, j[side])
        self.assertAlmostEqual(j["hausdorff"], 0.1, delta=0.001)
        self.assertAlmostEqual(j["diagonal"], 2.2 * math.sqrt(3), delta=1e-9)
        self.assertAlmostEqual(j["hausdorff_pct"], 100 * j["hausdorff"] / j["diagonal"], places=12)
        self.assertEqual(j["hausdorff"], max(j["mesh_to_reference"]["max"],
                                             j["reference_to_mesh"]["max"]))
        self.assertEqual(j["rms"], max(j["mesh_to_reference"]["rms"],
                                       j["reference_to_mesh"]["rms"]))
        self.assertEqual(j["samples"], 100000)
        self.assertEqual(j["sampling"], "metro")

    def test_distance_default_sample_count(self):
        j = run_json("distance", self.path("s1.off"), self.path("s1.off"))
        self.assertEqual(j["samples"], 1000000)
        self.assertLess(j["hausdorff"], 1e-12)

    def test_distance_is_the_same_at_one_and_two_threads(self):
        args = ["distance", self.path("torus.off"), self.path("s1.off"), "--samples", "50000"]
        one = run_json("--threads", "1", *args)
        two = run_json(*args, "--threads", "2")
        del one["seconds"], two["seconds"]
        self.assertEqual(one, two)

    def test_distance_faces_only_and_stats_file(self):
        stats = self.path("d.json")
        r = run("distance", self.path("s1.off"), self.path("s11.off"), "--samples", "20000",
                "--faces-only", "--json", "--stats", stats)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(stats) as f:
            printed, written = json.loads(r.stdout), json.load(f)
        self.assertEqual(printed, written)
        self.assertEqual(written["sampling"], "faces")
        self.assertEqual(written["mesh_to_reference"]["weighted_samples"], 20000)

    def test_distance_text_report(self):
        r = run("distance", self.path("s1.off"), self.path("s11.off"), "--samples", "20000")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("Hausdorff 0.1", r.stdout)

    # --- normals and check ----------------------------------------------------------------
    def test_normals(self):
        j = run_json("normals", self.path("s1.off"), self.path("s1.off"), "--samples", "20000")
        self.assertLess(j["mean_deg"], 5.0)
        self.assertLessEqual(j["mean_deg"], j["p95_deg"])
        flat = run_json("normals", self.path("s1.off"), self.path("s1.off"), "--samples",
                        "20000", "--flat-reference")
        self.assertLess(flat["max_deg"], 1e-6)
        self.assertEqual(flat["reference_normals"], "flat")

    def test_check(self):
        j = run_json("check", self.path("torus.off"))
        self.assertEqual(j["genus"], 1)
        self.assertTrue(j["closed"] and j["manifold"] and j["oriented"])
        self.assertEqual(j["intersecting_pairs"], 0)
        self.assertEqual(j["degenerate_triangles"], 0)
        self.assertEqual(j["valence_histogram"], {"6": 1200})
        open_box = self.write("open.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                          "3 0 1 2\n3 0 2 3\n")
        j = run_json("check", open_box)
        self.assertFalse(j["closed"])
        self.assertEqual(j["boundary_edges"], 4)
        self.assertEqual(j["genus"], -1)

    def test_check_reads_a_non_manifold_file_without_dropping_faces(self):
        # Three triangles on one edge: a half-edge reader would drop one.
        fan = self.write("fan.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n"
                                    "3 0 1 2\n3 1 0 3\n3 0 1 4\n")
        j = run_json("check", fan)
        self.assertEqual(j["faces"], 3)
        self.assertEqual(j["nonmanifold_edges"], 1)
        self.assertFalse(j["manifold"])

    # --- baselines ------------------------------------------------------------------------
    def baseline(self, method, *extra):
        out = self.path(method + ".off")
        j = run_json(method, self.path("one.ma"), "-o", out, *extra)
        info = json.loads(U.run(MODELS, "info", out, "--json").stdout)
        self.assertEqual(info["vertices"], j["vertices"])
        self.assertEqual(info["faces"], j["faces"])
        self.assertTrue(info["closed"] and info["manifold"] and info["oriented"])
        self.assertEqual(info["genus"], 0)
        return j

    def test_skin_union_vdb_report_size_and_time(self):
        for method in ("skin", "union", "vdb"):
            j = self.baseline(method, "--repeat", "3")
            self.assertEqual(len(j["seconds"]["runs"]), 3)
            self.assertLessEqual(j["seconds"]["min"], j["seconds"]["median"])
            self.assertLessEqual(j["seconds"]["median"], j["seconds"]["max"])
            self.assertEqual(j["atoms"], 1)
        j = self.baseline("skin", "--shrink", "0.3", "--subdivisions", "1")
        self.assertEqual(j["shrink"], 0.3)
        self.assertEqual(j["subdivisions"], 1)

    def test_vdb_match_vertices(self):
        j = self.baseline("vdb", "--match-vertices", "5000")
        self.assertLessEqual(len(j["probes"]), 5)
        self.assertLess(abs(j["vertices"] / 5000 - 1), 0.05)
        self.assertEqual(j["matched"], j["vertices"])
        self.assertEqual(j["dropped_spheres"], 0)

    def test_vdb_match_hausdorff(self):
        sphere = self.path("atom_sphere.off")
        U.generate(MODELS, sphere, "sphere", "--frequency", "30", "--radius", "0.7")
        # The atom is off the origin: its own sphere mesh is the reference after a shift.
        shifted = self.path("atom_sphere_shifted.off")
        with open(sphere) as f, open(shifted, "w") as g:
            lines = f.read().splitlines()
            nv = int(lines[1].split()[0])
            g.write("\n".join(lines[:2]) + "\n")
            for line in lines[2:2 + nv]:
                x, y, z = map(float, line.split())
                g.write("%r %r %r\n" % (x + 0.5, y - 0.25, z + 0.125))
            g.write("\n".join(lines[2 + nv:]) + "\n")
        j = self.baseline("vdb", "--match-hausdorff", "0.5", shifted, "--samples", "100000")
        self.assertLessEqual(len(j["probes"]), 5)
        self.assertAlmostEqual(j["matched"], 0.5, delta=0.05)
        self.assertEqual(j["match"], "hausdorff_pct")

    def test_vdb_match_envelope(self):
        capsule = self.write("capsule_env.ma", "2 1 0\nv 0 0 0 0.5\nv 2 0.1 -0.05 0.35\ne 0 1\n")
        out = self.path("capsule_env.off")
        # --samples 1: twice the vertices of each probe (raised), every vertex sampled.
        j = run_json("vdb", capsule, "-o", out, "--match-envelope", "0.2", "--samples", "1")
        for key in ("match", "target", "matched", "diagonal", "probes", "clamped",
                    "out_of_reach", "voxel", "vertices"):
            self.assertIn(key, j)
        self.assertEqual(j["match"], "envelope_hausdorff_pct")
        self.assertEqual(j["target"], 0.2)
        self.assertEqual(j["primitives"], "ma")
        self.assertLessEqual(len(j["probes"]), 5)
        for p in j["probes"]:
            self.assertEqual(set(p), {"voxel", "value", "vertices"})
        if not j["clamped"]:
            self.assertAlmostEqual(j["matched"], 0.2, delta=0.03)
        best = [p for p in j["probes"] if p["value"] == j["matched"]]
        self.assertEqual(len(best), 1)
        self.assertEqual((j["voxel"], j["vertices"]), (best[0]["voxel"], best[0]["vertices"]))
        # `evaluate atoms` on the mesh written measures the same distance.
        a = run_json("atoms", out, capsule, "--diagonal", repr(j["diagonal"]), "--samples",
                     str(2 * j["vertices"]))
        self.assertAlmostEqual(a["hausdorff_pct"], j["matched"], delta=1e-6 * j["matched"])
        # A diagonal twice as long: the same distance in model units is half the percentage.
        j2 = run_json("vdb", capsule, "-o", out, "--match-envelope", "0.1", "--samples", "1",
                      "--diagonal", repr(2 * j["diagonal"]))
        self.assertEqual(j2["diagonal"], 2 * j["diagonal"])
        self.assertAlmostEqual(j2["voxel"], j["voxel"], delta=1e-9 * j["voxel"])
        self.assertAlmostEqual(j2["matched"], j["matched"] / 2, delta=1e-9 * j["matched"])
        # The text report says what was matched.
        r = run("vdb", capsule, "-o", out, "--match-envelope", "0.2", "--samples", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("% Hausdorff to G (of the diagonal", r.stdout)

    def test_vdb_same_file_at_one_and_two_threads(self):
        ring = self.write("ring.ma", "".join(
            "%r %r 0 0.3\n" % (math.cos(k * math.pi / 6), math.sin(k * math.pi / 6))
            for k in range(12)))
        outs = []
        for t in ("1", "2"):
            out = self.path("ring%s.off" % t)
            r = run("--threads", t, "vdb", ring, "-o", out, "--voxel", "0.02")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out, "rb") as f:
                outs.append(f.read())
        self.assertEqual(outs[0], outs[1])

    def test_vdb_envelope_of_a_medial_mesh(self):
        # Two disjoint balls and their edge: the envelope is one capsule, the balls two spheres.
        capsule = self.write("capsule.ma", "2 1 0\nv 0 0 0 0.5\nv 2 0.1 -0.05 0.35\ne 0 1\n")
        outs = {}
        for name, threads, extra in [("ma1", "1", []), ("ma2", "2", []),
                                     ("rt", "2", ["--primitives", "rt"])]:
            out = self.path("capsule_%s.off" % name)
            j = run_json("--threads", threads, "vdb", capsule, "-o", out, "--voxel", "0.03",
                         *extra)
            info = json.loads(U.run(MODELS, "info", out, "--json").stdout)
            self.assertEqual(info["vertices"], j["vertices"])
            self.assertTrue(info["closed"] and info["manifold"] and info["oriented"])
            with open(out, "rb") as f:
                outs[name] = (j, info, f.read())
        j, info, _ = outs["ma1"]
        self.assertEqual((j["primitives"], j["cones"], j["slabs"]), ("ma", 1, 0))
        self.assertEqual((info["components"], info["genus"]), (1, 0))
        self.assertEqual(outs["ma1"][2], outs["ma2"][2])
        j, info, _ = outs["rt"]
        self.assertEqual((j["primitives"], j["cones"], j["slabs"]), ("rt", 0, 0))
        self.assertEqual(info["components"], 2)
        # One face, its voxel searched.
        face = self.write("face.ma", "3 0 1\nv 0 0 0 0.3\nv 2 0 0.1 0.2\nv 0.8 1.6 0 0.25\n"
                                     "f 0 1 2\n")
        out = self.path("face.off")
        j = run_json("vdb", face, "-o", out, "--match-vertices", "5000")
        self.assertEqual((j["primitives"], j["cones"], j["slabs"]), ("ma", 3, 1))
        self.assertLess(abs(j["vertices"] / 5000 - 1), 0.05)
        info = json.loads(U.run(MODELS, "info", out, "--json").stdout)
        self.assertEqual((info["components"], info["genus"], info["closed"]), (1, 0, True))

    # --- bad input ------------------------------------------------------------------------
    def test_missing_file(self):
        r = run("distance", self.path("none.off"), self.path("s1.off"))
        self.assert_refused(r, 3, "none.off: cannot open for reading")
        out = self.path("m.off")
        r = run("skin", self.path("none.ma"), "-o", out)
        self.assert_refused(r, 3, "none.ma: cannot open for reading", [out])

    def test_unreadable_mesh(self):
        bad = self.write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n")
        r = run("check", bad)
        self.assert_refused(r, 2, "bad.off")
        junk = self.write("junk.obj", "this is not a mesh\n")
        r = run("normals", junk, self.path("s1.off"))
        self.assert_refused(r, 2, "junk.obj")

    def test_empty_mesh(self):
        empty = self.write("empty.off", "OFF\n0 0 0\n")
        r = run("distance", self.path("s1.off"), empty)
        self.assert_refused(r, 2, "empty.off: no faces")
        flat = self.write("flat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n")
        r = run("distance", flat, self.path("s1.off"))
        self.assert_refused(r, 2, "flat.off: the surface has zero area")

    def test_empty_atoms(self):
        out = self.path("e.off")
        r = run("union", self.write("e.ma", ""), "-o", out)
        self.assert_refused(r, 2, "e.ma: empty file, no atoms", [out])

    def test_shrink_one_or_more_points_to_union(self):
        out = self.path("skin1.off")
        for shrink in ("1", "1.5"):
            r = run("skin", self.path("one.ma"), "-o", out, "--shrink", shrink)
            self.assert_refused(r, 2, "use `evaluate union`", [out])
        r = run("skin", self.path("one.ma"), "-o", out, "--shrink", "0")
        self.assert_refused(r, 2, "--shrink must be in (0, 1)", [out])

    def test_bad_options(self):
        out = self.path("v.off")
        r = run("vdb", self.path("one.ma"), "-o", out, "--voxel", "0.1", "--match-vertices", "10")
        self.assert_refused(r, 2, "excludes", [out])
        r = run("vdb", self.path("one.ma"), "-o", out, "--match-hausdorff", "x",
                self.path("s1.off"))
        self.assert_refused(r, 2, "'x' is not a percentage", [out])
        for bad, message in [("0", "--match-envelope: must be > 0, not 0"),
                             ("-1", "--match-envelope: must be > 0, not -1"),
                             ("nan", "--match-envelope: must be > 0, not nan"),
                             ("x", "--match-envelope: 'x' is not a number")]:
            r = run("vdb", self.path("one.ma"), "-o", out, "--match-envelope", bad)
            self.assert_refused(r, 2, message, [out])
        r = run("vdb", self.path("one.ma"), "-o", out, "--match-envelope", "0.5", "--voxel",
                "0.1")
        self.assert_refused(r, 2, "--voxel excludes --match-envelope", [out])
        r = run("vdb", self.path("one.ma"), "-o", out, "--match-envelope", "0.5",
                "--match-hausdorff", "0.5", self.path("s1.off"))
        self.assert_refused(r, 2, "excludes --match-envelope", [out])
        r = run("vdb", self.path("one.ma"), "-o", out, "--diagonal", "3")
        self.assert_refused(r, 2, "--diagonal requires --match-envelope", [out])
        r = run("vdb", self.path("one.ma"), "-o", out, "--match-envelope", "0.5", "--diagonal",
                "-1")
        self.assert_refused(r, 2, "--diagonal: must be >= 0", [out])
        r = run("vdb", self.path("one.ma"), "-o", out, "--voxel", "5")
        self.assert_refused(r, 2, "every sphere is under 1.5 voxels", [out])
        r = run("vdb", self.path("one.ma"), "-o", out, "--primitives", "cones")
        self.assert_refused(r, 2, "unknown primitive set 'cones'", [out])
        r = run("skin", self.path("one.ma"), "-o", self.path("x.xyz"))
        self.assert_refused(r, 2, "unknown mesh extension", [self.path("x.xyz")])
        r = run("distance", self.path("s1.off"))
        self.assert_refused(r, 2, "reference")
        r = run("check", self.path("s1.off"), "--bogus")
        self.assert_refused(r, 2, "--bogus")

    def test_output_never_overwrites_an_input(self):
        ma = self.path("one.ma")
        with open(ma) as f:
            before = f.read()
        r = run("union", ma, "-o", ma)
        self.assertEqual(r.returncode, 2, r.stderr)
        with open(ma) as f:
            self.assertEqual(f.read(), before)
        r = run("distance", self.path("s1.off"), self.path("s11.off"), "--stats",
                self.path("s1.off"))
        self.assert_refused(r, 2, "would overwrite the input")
        out = self.path("same.off")
        r = run("skin", ma, "-o", out, "--stats", out)
        self.assert_refused(r, 2, "--stats and --output name the same file", [out])


if __name__ == "__main__":
    unittest.main(verbosity=2)
