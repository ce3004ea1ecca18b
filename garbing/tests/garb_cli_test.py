#!/usr/bin/python3
"""The garb program at its edges: output, stats, exit codes, one-line messages, no partial output."""
import json
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "core", "tests", "support"))
import cli_test_util as U  # noqa: E402

GARB, MODELS = U.programs_from_argv("garb", "models")


def run(*args):
    return U.run(GARB, *args)


class GarbCli(U.CliTestCase):
    def setUp(self):
        super().setUp()
        self.ma = self.write("one.ma", "1 0 0\nv 0 0 0 1\n")

    def test_one_sphere_gives_the_papers_face_count_and_stats(self):
        r = run(self.ma, "-o", self.path("m.off"), "--m1", self.path("m1.obj"),
                "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        stats = json.load(open(self.path("s.json")))
        self.assertEqual(stats["min_depth"], 4)
        self.assertEqual(stats["m1"]["faces"], 1344)
        self.assertEqual(stats["m1"]["genus"], 0)
        self.assertFalse(stats["hit_max_depth"])
        info = U.run(MODELS, "info", self.path("m1.obj"), "--json")
        self.assertEqual(json.loads(info.stdout)["faces"], 1344)

    def test_same_output_at_one_and_two_threads(self):
        ma = self.write("ring.ma", "".join("%r %r 0 0.3\n" % (
            math.cos(k * 0.10471975511965977), math.sin(k * 0.10471975511965977)) for k in range(60)))
        for t in ("1", "2"):
            r = run(ma, "-o", self.path("t%s.off" % t), "--threads", t)
            self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(open(self.path("t1.off"), "rb").read(), open(self.path("t2.off"), "rb").read())

    def test_full_lists_keep_every_ball_the_default_prunes_dense_ones(self):
        # A dense double row of overlapping balls: most cells meet many that others cover.
        ma = self.write("row.ma", "".join("%r %r 0 0.4\n" % (0.02 * k, 0.05 * (k % 2)) for k in range(120)))
        per = {}
        for name, extra in (("pruned", ()), ("full", ("--full-lists",)), ("pruned1", ("--threads", "1"))):
            r = run(ma, "-o", self.path(name + ".off"), "--stats", self.path(name + ".json"), *extra)
            self.assertEqual(r.returncode, 0, r.stderr)
            per[name] = json.load(open(self.path(name + ".json")))
            self.assertTrue(per[name]["m2"]["closed"])
            self.assertEqual(per[name]["m2"]["genus"], 0)
        # The pruning's scratch is per thread: the same mesh at one and two threads.
        self.assertEqual(open(self.path("pruned.off"), "rb").read(), open(self.path("pruned1.off"), "rb").read())
        self.assertTrue(per["pruned"]["pruned_lists"])
        self.assertFalse(per["full"]["pruned_lists"])
        self.assertLess(2 * per["pruned"]["listed_per_active_leaf"]["balls_mean"],
                        per["full"]["listed_per_active_leaf"]["balls_mean"])
        # An envelope's lists are never pruned.
        capsule = self.write("c.ma", "2 1 0\nv 0 0 0 1\nv 4 0 0 0.5\ne 0 1\n")
        r = run(capsule, "-o", self.path("c.off"), "--stats", self.path("c.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertFalse(json.load(open(self.path("c.json")))["pruned_lists"])

    def test_envelope_with_a_slab_and_no_cone(self):
        # Each ball holds the next: every edge is dropped (its hull is a ball), the face's slab
        # stays. G then has slabs and no cones, a case the octree's cone search must skip.
        ma = self.write("nested.ma", "3 0 1\nv 0 0 0 1\nv 0.1 0 0 2\nv 0 0.2 0 3\nf 0 1 2\n")
        r = run(ma, "-o", self.path("n.off"), "--stats", self.path("n.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        stats = json.load(open(self.path("n.json")))
        self.assertEqual((stats["m2"]["cones"], stats["m2"]["slabs"]), (0, 1))
        self.assertEqual((stats["m2"]["components"], stats["m2"]["genus"]), (1, 0))
        self.assertTrue(stats["m2"]["closed"])

    def test_medial_mesh_garbs_its_envelope(self):
        # Two disjoint balls joined by an edge: one capsule; their balls alone: two spheres.
        ma = self.write("capsule.ma", "2 1 0\nv 0 0 0 1\nv 4 0 0 0.5\ne 0 1\n")
        r = run(ma, "-o", self.path("m.off"), "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        stats = json.load(open(self.path("s.json")))
        self.assertEqual(stats["m2"]["primitives"], "ma")
        self.assertEqual(stats["m2"]["cones"], 1)
        self.assertEqual(stats["m2"]["envelope"]["edges"], 1)
        self.assertEqual((stats["m2"]["components"], stats["m2"]["genus"]), (1, 0))
        r = run(ma, "-o", self.path("b.off"), "--primitives", "rt", "--stats", self.path("b.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        stats = json.load(open(self.path("b.json")))
        self.assertEqual((stats["m2"]["primitives"], stats["m2"]["cones"]), ("rt", 0))
        self.assertEqual(stats["m2"]["components"], 2)

    def test_check_topology_matches_on_a_ring(self):
        ma = self.write("ring.ma", "".join("%r %r 0 0.3\n" % (
            math.cos(k * 0.10471975511965977), math.sin(k * 0.10471975511965977)) for k in range(60)))
        r = run(ma, "-o", self.path("m.off"), "--check-topology", "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr, "")
        check = json.load(open(self.path("s.json")))["topology_check"]
        self.assertEqual((check["union_components"], check["union_euler"]), (1, 0))
        self.assertEqual((check["m2_components"], check["m2_euler"]), (1, 0))
        self.assertTrue(check["matches"])

    def test_depth_stop_and_topology_mismatch_are_reported(self):
        # Two balls 1e-6 apart: the criteria keep splitting the gap until the depth stop, and
        # M2 glues the two spheres (the union has two components).
        ma = self.write("near.ma", "2 0 0\nv 0 0 0 1\nv 2.000001 0 0 1\n")
        r = run(ma, "-o", self.path("m.off"), "--max-depth", "9", "--check-topology",
                "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 2, r.stderr)
        self.assertIn("garb: warning: %s: the octree's depth stop (level 9) kept" % ma, lines[0])
        self.assertIn("near-tangent or nearly coincident balls", lines[0])
        self.assertIn("M2 has 1 component(s) and Euler characteristic 2, the union of the balls 2 "
                      "and 4", lines[1])
        stats = json.load(open(self.path("s.json")))
        self.assertTrue(stats["hit_max_depth"])
        self.assertGreater(stats["depth_stopped_cells"], 0)
        self.assertFalse(stats["topology_check"]["matches"])
        # Without --check-topology: the depth stop's line alone.
        r = run(ma, "-o", self.path("n.off"), "--max-depth", "9")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)

    def test_tolerance_thins_dense_atoms_at_the_same_depth(self):
        # Two interleaved rows of nearly equal balls: each ball of the second row lies in its
        # neighbour of the first up to a small slack.
        rows = "".join("%r 0 0 0.4\n%r 0.001 0 0.399\n" % (0.01 * k, 0.01 * k + 0.001) for k in range(100))
        ma = self.write("rows.ma", rows)
        for name, extra in (("exact", ()), ("thin", ("--tolerance", "0.25")),
                            ("thin1", ("--tolerance", "0.25", "--threads", "1")),
                            ("contain", ("--tolerance", "0.25", "--thinning", "contain"))):
            r = run(ma, "-o", self.path(name + ".off"), "--stats", self.path(name + ".json"), *extra)
            self.assertEqual(r.returncode, 0, r.stderr)
        exact, thin, contain = (json.load(open(self.path(n + ".json")))
                                for n in ("exact", "thin", "contain"))
        self.assertNotIn("thinning", exact)
        t, c = thin["thinning"], contain["thinning"]
        self.assertEqual(t["tolerance_leaf_sides"], 0.25)
        self.assertEqual((t["method"], c["method"]), ("cover", "contain"))
        self.assertEqual(t["atoms_kept"] + t["atoms_dropped"], 200)
        self.assertLessEqual(t["atoms_kept"], 100)
        # Along a row of nearly equal balls, neighbours cover a ball far beyond one container's
        # reach: the cover pass keeps a fraction of what containment keeps.
        self.assertGreater(t["atoms_covered"], 0)
        self.assertEqual(c["atoms_covered"], 0)
        self.assertLess(3 * t["atoms_kept"], c["atoms_kept"])
        self.assertTrue(contain["m2"]["closed"])
        self.assertEqual(thin["atoms"], 200)  # the input's count
        self.assertEqual(thin["min_depth"], exact["min_depth"])
        self.assertAlmostEqual(t["slack"], 0.25 * exact["root_side"] / 2 ** exact["min_depth"], places=12)
        self.assertTrue(thin["m2"]["closed"])
        self.assertEqual(thin["m2"]["genus"], 0)
        self.assertEqual(open(self.path("thin.off"), "rb").read(), open(self.path("thin1.off"), "rb").read())

    def test_tolerance_refuses_an_envelope_and_a_negative_value(self):
        ma = self.write("capsule.ma", "2 1 0\nv 0 0 0 1\nv 4 0 0 0.5\ne 0 1\n")
        r = run(ma, "-o", self.path("m.off"), "--tolerance", "0.1")
        self.assert_refused(r, 2, "capsule.ma: --tolerance thins the atoms' balls", [self.path("m.off")])
        r = run(ma, "-o", self.path("m.off"), "--tolerance", "0.1", "--primitives", "rt")
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run(ma, "-o", self.path("e.off"), "--tolerance", "0.1", "--cones", "edges")
        self.assert_refused(r, 2, "capsule.ma: --tolerance thins the atoms' balls: the cones of the "
                            "file's edges (--cones edges)", [self.path("e.off")])
        r = run(self.ma, "-o", self.path("n.off"), "--tolerance", "-1")
        self.assert_refused(r, 2, "--tolerance: must be >= 0, not -1", [self.path("n.off")])
        for extra in (("--thinning", "contain"), ("--tolerance", "0", "--thinning", "cover")):
            r = run(self.ma, "-o", self.path("n.off"), *extra)
            self.assert_refused(r, 2, "--thinning chooses how --tolerance thins: give --tolerance "
                                "F > 0", [self.path("n.off")])
        r = run(self.ma, "-o", self.path("n.off"), "--tolerance", "0.1", "--thinning", "union")
        self.assert_refused(r, 2, "--thinning: union not in {cover,contain}", [self.path("n.off")])

    def test_coordinates_too_large_for_a_cube(self):
        # The bounding cube's side overflows to infinity: refused, not an endless depth search.
        ma = self.write("huge.ma", "1e308 0 0 1\n-1e308 0 0 1\n")
        for extra in ((), ("--tolerance", "0.1")):
            r = run(ma, "-o", self.path("m.off"), *extra)
            self.assert_refused(r, 2, "bounding cube has an infinite side", [self.path("m.off")])

    def test_check_topology_refuses_an_envelope(self):
        ma = self.write("capsule.ma", "2 1 0\nv 0 0 0 1\nv 4 0 0 0.5\ne 0 1\n")
        self.assert_refused(run(ma, "-o", self.path("m.off"), "--check-topology"), 2,
                            "--check-topology compares with the union of the balls")

    def test_cone_options_choose_rt(self):
        ma = self.write("capsule.ma", "2 1 0\nv 0 0 0 1\nv 4 0 0 0.5\ne 0 1\n")
        r = run(ma, "-o", self.path("m.off"), "--primitives", "ma", "--cones", "edges")
        self.assert_refused(r, 2, "choose the cones of --primitives rt, not ma", [self.path("m.off")])
        r = run(ma, "-o", self.path("m.off"), "--spheres-only", "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(json.load(open(self.path("s.json")))["m2"]["primitives"], "rt")

    def test_bad_medial_mesh_lines_are_refused_by_file_and_line(self):
        atoms = "v 0 0 0 1\nv 2 0 0 1\nv 0 2 0 1\n"
        for name, text, message in [
                ("loop.ma", "3 1 0\n" + atoms + "e 2 2\n", "loop.ma:5: edge joins atom 2 to itself"),
                ("rep.ma", "3 0 1\n" + atoms + "f 0 1 0\n", "rep.ma:5: face repeats atom 0"),
                ("far.ma", "3 0 1\n" + atoms + "f 0 1 3\n", "far.ma:5: face index 3 out of range [0, 3)")]:
            r = run(self.write(name, text), "-o", self.path("m.off"), "--stats", self.path("s.json"))
            self.assert_refused(r, 2, message, [self.path("m.off"), self.path("s.json")])

    def test_collinear_face_is_reduced_and_counted(self):
        # Three balls on a line: the face's hull is its edge hulls' (no slab), one capsule.
        ma = self.write("line.ma", "3 0 1\nv 0 0 0 1\nv 2 0 0 0.8\nv 5 0 0 0.6\nf 0 1 2\n")
        r = run(ma, "-o", self.path("m.off"), "--stats", self.path("s.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        stats = json.load(open(self.path("s.json")))
        self.assertEqual(stats["m2"]["envelope"]["collinear_faces"], 1)
        self.assertEqual((stats["m2"]["slabs"], stats["m2"]["cones"]), (0, 3))
        self.assertEqual((stats["m2"]["components"], stats["m2"]["genus"]), (1, 0))

    def test_zero_radius_needs_a_medial_mesh(self):
        r = run(self.write("p.ma", "0 0 0 1\n3 0 0 0\n"), "-o", self.path("m.off"))
        self.assert_refused(r, 2, "atom 1 has radius 0", [self.path("m.off")])
        ma = self.write("cone.ma", "2 1 0\nv 0 0 0 1\nv 3 0 0 0\ne 0 1\n")
        r = run(ma, "-o", self.path("m.off"))
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_missing_input(self):
        r = run(self.path("none.ma"), "-o", self.path("m.off"))
        self.assert_refused(r, 3, "none.ma: cannot open for reading", [self.path("m.off")])

    def test_empty_input(self):
        r = run(self.write("e.ma", ""), "-o", self.path("m.off"))
        self.assert_refused(r, 2, "e.ma: empty file, no atoms", [self.path("m.off")])

    def test_nan_and_negative_radius(self):
        r = run(self.write("n.ma", "1 0 0\nv 0 0 0 nan\n"), "-o", self.path("m.off"))
        self.assert_refused(r, 2, "n.ma:2: radius must be finite, got nan", [self.path("m.off")])
        r = run(self.write("z.ma", "0 0 0 1\n0 0 1 -0.3\n"), "-o", self.path("m.off"))
        self.assert_refused(r, 2, "z.ma:2: radius must be >= 0, got -0.3", [self.path("m.off")])

    def test_min_depth_above_max_depth(self):
        r = run(self.ma, "-o", self.path("m.off"), "--min-depth", "9", "--max-depth", "8",
                "--stats", self.path("s.json"))
        self.assert_refused(r, 2, "min depth 9 must be in [0, max depth 8]",
                            [self.path("m.off"), self.path("s.json")])

    def test_unknown_option_and_bad_criterion(self):
        r = run(self.ma, "-o", self.path("m.off"), "--smooth")
        self.assert_refused(r, 2, "--smooth", [self.path("m.off")])
        r = run(self.ma, "-o", self.path("m.off"), "--no-criterion", "5")
        self.assert_refused(r, 2, "--no-criterion", [self.path("m.off")])

    def test_out_of_range_numbers(self):
        for option, value, message in (("--cone-collar", "-1", "--cone-collar: must be >= 0, not -1"),
                                       ("--repair-rounds", "-2", "--repair-rounds: must be >= 0, not -2"),
                                       ("--max-gap", "-0.5", "--max-gap: must be >= 0, not -0.5"),
                                       ("--max-travel", "0", "--max-travel: must be > 0, not 0"),
                                       ("--max-travel", "nan", "--max-travel: must be > 0, not nan"),
                                       ("--refine", "x", "--refine: 'x' is not a number")):
            r = run(self.ma, "-o", self.path("m.off"), option, value)
            self.assert_refused(r, 2, message, [self.path("m.off")])

    def test_output_never_overwrites_the_input(self):
        r = run(self.ma, "-o", self.ma)
        self.assertEqual(r.returncode, 2)
        self.assertEqual(open(self.ma).read(), "1 0 0\nv 0 0 0 1\n")

    def test_outputs_appear_together_or_not_at_all(self):
        # Issue 21: M1 was renamed into place before M2 and the statistics were written, and
        # stayed when they failed. /proc/self takes no new file, even from root.
        m1, m2 = self.path("m1.off"), self.path("m2.off")
        r = run(self.ma, "-o", m2, "--m1", m1, "--stats", "/proc/self/s.json")
        self.assert_refused(r, 3, "/proc/self/s.json: cannot open for writing", [m1, m2])
        r = run(self.ma, "-o", "/proc/self/m2.off", "--m1", m1, "--stats", self.path("s.json"))
        self.assert_refused(r, 3, "/proc/self/m2.off: cannot open for writing", [m1, self.path("s.json")])

    def test_output_naming_a_folder_or_another_output(self):
        os.mkdir(self.path("d.off"))
        r = run(self.ma, "-o", self.path("d.off"))
        self.assert_refused(r, 2, "d.off: output path is a folder")
        r = run(self.ma, "-o", self.path("m.off"), "--m1", self.path("m.off"))
        self.assert_refused(r, 2, "m.off: --m1 names the output file", [self.path("m.off")])
        r = run(self.ma, "-o", self.path("m.off"), "--stats", self.path("m.off"))
        self.assert_refused(r, 2, "--stats names the mesh file", [self.path("m.off")])

    def test_unknown_output_extension(self):
        r = run(self.ma, "-o", self.path("m.vtk"))
        self.assert_refused(r, 2, "unknown mesh extension", [self.path("m.vtk")])


if __name__ == "__main__":
    unittest.main()
