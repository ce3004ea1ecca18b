#!/usr/bin/python3
"""The render program end to end: real POV-Ray images of the requested size that show the
object where the camera puts it, reproducible bytes, shared views, and clean failures.

Usage: render_cli_test.py RENDER_BINARY MODELS_BINARY   (Debian's python3 with numpy, matplotlib)
"""
import json
import math
import os
import re
import shutil
import sys
import unittest

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "core", "tests", "support"))
import cli_test_util as U  # noqa: E402

RENDER, MODELS = U.programs_from_argv("render", "models")
W, H = 160, 120


def run(*args, env=None):
    return U.run(RENDER, *args, env=env)


def read_png(path):
    img = mpimg.imread(path)
    return np.asarray(img[:, :, :3], dtype=np.float64)


def object_mask(img):
    """Pixels that are not the white background."""
    return np.any(img < 0.97, axis=2)


def project(view, p):
    """Pixel position of model point p in the image of a view file (same maths as view.h)."""
    loc, at, sky = (np.array(view[k], dtype=float) for k in ("location", "look_at", "sky"))
    fwd = (at - loc) / np.linalg.norm(at - loc)
    right = np.cross(fwd, sky)
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    q = np.asarray(p, dtype=float) - loc
    depth = q @ fwd
    tan_h = math.tan(math.radians(view["angle"]) / 2)
    tan_v = tan_h * view["height"] / view["width"]
    x = (q @ right) / (depth * tan_h)
    y = (q @ up) / (depth * tan_v)
    return (x + 1) / 2 * view["width"], (1 - y) / 2 * view["height"]


def camera_block(scene_text):
    m = re.search(r"^camera \{\n.*?^\}\n", scene_text, re.S | re.M)
    return m.group(0) if m else None


class RenderCli(U.CliTestCase):
    """The inputs are made once per class; every test writes into a folder of its own."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        inputs = U.temporary_folder(cls.addClassCleanup)
        cls.sphere = U.generate(MODELS, os.path.join(inputs, "sphere.off"), "sphere", "--frequency", "6")
        cls.atoms = os.path.join(inputs, "two.ma")  # two disjoint balls and an edge: a capsule
        with open(cls.atoms, "w") as f:
            f.write("2 1 0\nv -1 0 0 0.3\nv 1 0 0 0.6\ne 0 1\n")
        cls.atoms_alone = os.path.join(inputs, "two_alone.ma")
        with open(cls.atoms_alone, "w") as f:
            f.write("2 0 0\nv -1 0 0 0.3\nv 1 0 0 0.6\n")
        # One face whose centroid (0, 0.5, 0) lies outside its three balls, inside its slab.
        cls.face = os.path.join(inputs, "face.ma")
        with open(cls.face, "w") as f:
            f.write("3 0 1\nv -1 0 0 0.3\nv 1 0 0 0.4\nv 0 1.5 0 0.2\nf 0 1 2\n")

    def render_ok(self, *args):
        r = run(*args)
        self.assertEqual(r.returncode, 0, r.stderr)
        return r

    def assert_visible_and_centred(self, png):
        img = read_png(png)
        self.assertEqual(img.shape, (H, W, 3))
        self.assertGreater(img.var(), 0.01)  # not blank
        mask = object_mask(img)
        self.assertGreater(mask.mean(), 0.10)  # the object covers a real part of the frame
        ys, xs = np.nonzero(mask)
        # The object's extent is centred in the image (it is framed on its bounding box).
        self.assertLess(abs((xs.min() + xs.max() + 1) / 2 - W / 2), 0.1 * W)
        self.assertLess(abs((ys.min() + ys.max() + 1) / 2 - H / 2), 0.1 * H)
        # The framing keeps a white border: the object touches no image edge.
        self.assertFalse(mask[0, :].any() or mask[-1, :].any() or mask[:, 0].any() or mask[:, -1].any())
        return img, mask

    def test_sphere_mesh(self):
        png = self.path("sphere.png")
        self.render_ok(self.sphere, "-o", png, "--width", str(W), "--height", str(H))
        img, mask = self.assert_visible_and_centred(png)
        self.assertTrue(mask[H // 2, W // 2])
        # Smooth shading: the sphere shows a range of grey levels, lit from the upper left.
        lum = img.mean(axis=2)
        self.assertGreater(lum[mask].max() - lum[mask].min(), 0.3)
        ys, xs = np.nonzero(mask)
        upper_left = lum[mask & (np.arange(H)[:, None] < ys.mean()) & (np.arange(W)[None, :] < xs.mean())]
        lower_right = lum[mask & (np.arange(H)[:, None] > ys.mean()) & (np.arange(W)[None, :] > xs.mean())]
        self.assertGreater(upper_left.mean(), lower_right.mean())

    def test_two_atoms_coloured_by_radius_where_the_camera_puts_them(self):
        png, view = self.path("atoms.png"), self.path("view.json")
        self.render_ok(self.atoms, "-o", png, "--width", str(W), "--height", str(H), "--view", view,
                       "--primitives", "rt")  # the balls alone, the edge ignored
        img, mask = self.assert_visible_and_centred(png)
        with open(view) as f:
            v = json.load(f)
        red = mask & (img[:, :, 0] > 0.5) & (img[:, :, 2] < 0.3)
        blue = mask & (img[:, :, 2] > 0.5) & (img[:, :, 0] < 0.3)
        self.assertGreater(red.sum(), 50)
        self.assertGreater(blue.sum(), 4 * red.sum() * 0.5)  # radius 0.6 vs 0.3: ~4x the area
        for colour, centre in ((red, (-1, 0, 0)), (blue, (1, 0, 0))):
            ys, xs = np.nonzero(colour)
            px, py = project(v, centre)
            # The blob of each ball lies around its projected centre (shading shifts it a bit).
            self.assertLess(abs(xs.mean() - px), 0.06 * W, (xs.mean(), px))
            self.assertLess(abs(ys.mean() - py), 0.06 * H, (ys.mean(), py))
        self.assertLess(np.nonzero(red)[1].mean(), np.nonzero(blue)[1].mean())  # +x to the right

    def test_medial_mesh_is_drawn_as_its_envelope(self):
        # The capsule's cone fills the gap between its balls; the face's slab covers its
        # centroid, which no ball holds. --primitives rt draws the balls alone, as for a file
        # without the edge.
        for ma, gap in ((self.atoms, (-0.15, 0, 0)), (self.face, (0, 0.5, 0))):
            view = self.path(os.path.basename(ma) + ".json")
            envelope, balls = self.path("envelope.png"), self.path("balls.png")
            pov_envelope, pov_balls = self.path("envelope.pov"), self.path("balls.pov")
            self.render_ok(ma, "-o", envelope, "--pov", pov_envelope, "--width", str(W),
                           "--height", str(H), "--view", view)
            self.render_ok(ma, "-o", balls, "--pov", pov_balls, "--view", view, "--primitives", "rt")
            with open(view) as f:
                px, py = (int(c) for c in project(json.load(f), gap))
            self.assertTrue(object_mask(read_png(envelope))[py, px], ma)
            self.assertFalse(object_mask(read_png(balls))[py, px], ma)
            with open(pov_envelope) as f:
                text = f.read()
            self.assertEqual(len(re.findall(r"^cone \{", text, re.M)), 1 if ma == self.atoms else 3)
            self.assertEqual(text.count("mesh2 {"), 0 if ma == self.atoms else 1)
            with open(pov_balls) as f:
                text = f.read()
            self.assertNotIn("cone {", text)
            self.assertNotIn("mesh2", text)
        # The balls alone are the scene of the same atoms without edges and faces (after the
        # first line, which names the scene file).
        pov_alone = self.path("alone.pov")
        self.render_ok(self.atoms_alone, "--pov", pov_alone, "--view", self.path("two.ma.json"))
        self.render_ok(self.atoms, "--pov", pov_balls, "--view", self.path("two.ma.json"),
                       "--primitives", "rt")
        with open(pov_alone) as fa, open(pov_balls) as fb:
            alone, balls_text = fa.read(), fb.read()
        self.assertEqual(alone.split("\n", 1)[1].replace("two_alone.ma", "two.ma"),
                         balls_text.split("\n", 1)[1])

    def test_same_input_and_view_give_identical_bytes(self):
        # At one thread: POV-Ray 3.7 at more threads now and then shades a few pixels
        # differently from run to run (docs/reference.md, render).
        a, b, view = self.path("a.png"), self.path("b.png"), self.path("v.json")
        self.render_ok(self.sphere, self.atoms, "-o", a, "--width", str(W), "--height", str(H),
                       "--view", view, "--threads", "1")
        self.render_ok(self.sphere, self.atoms, "-o", b, "--view", view, "--threads", "1")
        with open(a, "rb") as fa, open(b, "rb") as fb:
            self.assertEqual(fa.read(), fb.read())

    def test_same_view_same_camera(self):
        view = self.path("v.json")
        pov_a, pov_b, pov_c = self.path("a.pov"), self.path("b.pov"), self.path("c.pov")
        self.render_ok(self.sphere, "--pov", pov_a, "--view", view, "--width", str(W),
                       "--height", str(H))
        with open(view) as f:
            written = f.read()
        self.render_ok(self.atoms, "--pov", pov_b, "--view", view)
        self.render_ok(self.atoms, "--pov", pov_c, "--width", str(W), "--height", str(H))
        with open(view) as f:
            self.assertEqual(f.read(), written)  # read, not rewritten
        cams = []
        for p in (pov_a, pov_b, pov_c):
            with open(p) as f:
                cams.append(camera_block(f.read()))
        self.assertIsNotNone(cams[0])
        self.assertEqual(cams[0], cams[1])
        self.assertNotEqual(cams[0], cams[2])  # framed on the atoms alone: another camera
        self.assertFalse(any(n.endswith(".png") for n in os.listdir(self.dir)))

    def test_view_with_another_aspect_is_refused(self):
        view = self.path("v.json")
        self.render_ok(self.sphere, "--pov", self.path("a.pov"), "--view", view, "--width", "160",
                       "--height", "120")
        r = run(self.sphere, "--pov", self.path("b.pov"), "--view", view, "--width", "100",
                "--height", "100")
        self.assertEqual(r.returncode, 2)
        self.assertIn("v.json: framed for 160x120", r.stderr)
        self.render_ok(self.sphere, "--pov", self.path("c.pov"), "--view", view, "--width", "320")

    def is_leftover(self, name):
        return name.endswith(".png")  # a refused run writes no image, not even a partial one

    def test_unknown_extension(self):
        bad = self.path("atoms.txt")
        shutil.copy(self.atoms, bad)
        png = self.path("x.png")
        self.assert_refused(run(bad, "-o", png), 2, "atoms.txt: unknown extension", [png])

    def test_missing_file(self):
        png = self.path("x.png")
        self.assert_refused(run(self.path("none.off"), "-o", png), 3,
                            "none.off: cannot open for reading", [png])

    def test_malformed_atoms(self):
        bad = self.path("bad.ma")
        with open(bad, "w") as f:
            f.write("1 0 0\nv 0 0 0 -1\n")
        png = self.path("x.png")
        self.assert_refused(run(bad, "-o", png), 2, "bad.ma:2: radius must be >= 0", [png])

    def test_no_povray_on_path(self):
        png = self.path("x.png")
        env = dict(os.environ, PATH=self.dir)
        self.assert_refused(run(self.sphere, "-o", png, "--width", "16", "--height", "12", env=env),
                            3, "'povray' not found on PATH", [png])

    def fake_povray(self, body):
        exe = self.path("fake-povray")
        with open(exe, "w") as f:
            f.write("#!/bin/sh\n" + body)
        os.chmod(exe, 0o755)
        return exe

    def test_failing_povray_leaves_no_partial_png(self):
        # Writes half an image to its +O file, reports an error and fails.
        exe = self.fake_povray(
            'for a in "$@"; do case "$a" in +O*) printf "\\211PNG\\r\\n" > "${a#+O}";; esac; done\n'
            'echo "File \'scene.pov\' line 3: Parse Error: Expected something, boom" >&2\n'
            'exit 1\n')
        png = self.path("x.png")
        self.assert_refused(run(self.sphere, "-o", png, "--povray", exe), 3,
                            "failed (exit status 1): File 'scene.pov' line 3: Parse Error: "
                            "Expected something, boom", [png])

    def test_povray_writing_no_image_is_an_error(self):
        exe = self.fake_povray("exit 0\n")
        png = self.path("x.png")
        self.assert_refused(run(self.sphere, "-o", png, "--povray", exe), 3,
                            "wrote no valid image", [png])

    def test_invalid_options(self):
        png = self.path("x.png")
        for args, message in (
                (["--width", "0"], "--width"),
                (["--transmit", "1.5"], "--transmit"),
                (["--normals", "cotan"], "--normals"),
                (["--colour", "red"], "--colour"),
                (["--primitives", "all"],
                 "--primitives: unknown primitive set 'all' (expected auto, ma or rt)"),
        ):
            self.assert_refused(run(self.sphere, "-o", png, *args), 2, message, [png])
        self.assert_refused(run(self.sphere, "-o", self.path("x.jpg")), 2, "must be a .png", [png])
        self.assert_refused(run(self.sphere), 2, "nothing to write", [png])
        self.assert_refused(run(self.sphere, "--pov", self.sphere), 2,
                            "would overwrite the input", [png])


if __name__ == "__main__":
    unittest.main()
