#!/usr/bin/python3
"""The models program at its edges: exit codes, one-line messages, no partial output."""
import json
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "core", "tests", "support"))
import cli_test_util as U  # noqa: E402

MODELS, = U.programs_from_argv("models")


def run(*args):
    return U.run(MODELS, *args)


class ModelsCli(U.CliTestCase):
    def test_generate_then_info(self):
        out = os.path.join(self.dir, "t.off")
        r = run("generate", "torus", "--ring", "12", "--tube", "8", "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run("info", out, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        info = json.loads(r.stdout)
        self.assertEqual((info["vertices"], info["faces"], info["genus"]), (96, 192, 1))
        self.assertTrue(info["closed"])

    def test_generate_medial_mesh(self):
        out = os.path.join(self.dir, "ring.ma")
        r = run("generate", "medial-ring", "--atoms", "12", "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(os.listdir(self.dir), ["ring.ma"])
        with open(out) as f:
            lines = [line.split() for line in f if line.strip() and not line.startswith("#")]
        self.assertEqual(lines[0], ["12", "12", "0"])
        atoms = [l for l in lines[1:] if l[0] == "v"]
        edges = [l for l in lines[1:] if l[0] == "e"]
        self.assertEqual((len(atoms), len(edges)), (12, 12))
        self.assertFalse([l for l in lines[1:] if l[0] not in ("v", "e")])
        self.assertTrue(all(float(a[4]) > 0 for a in atoms))
        # The same file twice: nothing random.
        again = os.path.join(self.dir, "again.ma")
        self.assertEqual(run("generate", "medial-ring", "--atoms", "12", "-o", again).returncode, 0)
        with open(out) as a, open(again) as b:
            self.assertEqual(a.read(), b.read())

    def test_medial_shape_needs_a_ma_output(self):
        out = os.path.join(self.dir, "hand.off")
        r = run("generate", "medial-hand", "-o", out)
        self.assert_refused(r, 2, "medial-hand is a medial mesh: the output must be a .ma file",
                            [out])
        self.assertEqual(os.listdir(self.dir), [])

    def test_mesh_shape_refuses_a_ma_output(self):
        out = os.path.join(self.dir, "sphere.ma")
        r = run("generate", "sphere", "--frequency", "2", "-o", out)
        self.assert_refused(r, 2, "sphere is a triangle mesh: the output must be .off, .obj, "
                            ".ply or .stl", [out])
        self.assertEqual(os.listdir(self.dir), [])

    def test_bad_medial_parameters_leave_no_file(self):
        out = os.path.join(self.dir, "disc.ma")
        r = run("generate", "medial-disc", "--hex-rings", "0", "-o", out)
        self.assert_refused(r, 2, "rings must be in [1, 100]", [out])
        self.assertEqual(os.listdir(self.dir), [])

    def test_missing_input_is_an_io_error(self):
        r = run("info", os.path.join(self.dir, "none.off"))
        self.assertEqual(r.returncode, 3)
        self.assertIn("none.off: cannot open for reading", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1)

    def test_malformed_input_is_invalid(self):
        bad = os.path.join(self.dir, "bad.off")
        with open(bad, "w") as f:
            f.write("OFF\n3 1 0\n0 0 0\n1 0 0\n")
        r = run("info", bad)
        self.assertEqual(r.returncode, 2)
        self.assertIn("bad.off: file ends early", r.stderr)

    def test_bad_parameters_leave_no_file(self):
        out = os.path.join(self.dir, "s.off")
        r = run("generate", "sphere", "--frequency", "0", "-o", out)
        self.assertEqual(r.returncode, 2)
        self.assertIn("frequency must be >= 1", r.stderr)
        self.assertEqual(os.listdir(self.dir), [])

    def test_unknown_option_is_bad_usage(self):
        r = run("generate", "sphere", "--colour", "red", "-o", os.path.join(self.dir, "s.off"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("--colour", r.stderr)

    def test_missing_output_folder(self):
        r = run("generate", "sphere", "-o", os.path.join(self.dir, "no", "s.off"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("does not exist", r.stderr)


if __name__ == "__main__":
    unittest.main()
