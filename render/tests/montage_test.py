#!/usr/bin/python3
"""montage.py: images land in their grid cells at their own size, labels are drawn in the
margins, bad usage fails cleanly without output.

Usage: montage_test.py MONTAGE_SCRIPT   (Debian's python3 with numpy, matplotlib)
"""
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

MONTAGE = os.path.abspath(sys.argv.pop(1)) if len(sys.argv) > 1 else "montage.py"
COLOURS = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0)]


def run(*args):
    return subprocess.run([sys.executable, MONTAGE, *args], capture_output=True, text=True)


class Montage(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.images = []
        for i, c in enumerate(COLOURS):  # 40 x 30 solid images, the last one smaller (20 x 10)
            h, w = (30, 40) if i < 3 else (10, 20)
            path = os.path.join(self.dir, "img%d.png" % i)
            mpimg.imsave(path, np.tile(np.array(c, dtype=float), (h, w, 1)))
            self.images.append(path)

    def tearDown(self):
        self.tmp.cleanup()

    def test_grid_with_labels(self):
        out = os.path.join(self.dir, "grid.png")
        r = run(*self.images, "-o", out, "--columns", "2", "--gap", "4", "--font-size", "10",
                "--column-label", "Original", "--column-label", "Union",
                "--row-label", "Hand", "--row-label", "Knot")
        self.assertEqual(r.returncode, 0, r.stderr)
        img = mpimg.imread(out)[:, :, :3]
        band = 20  # 2 x font size
        self.assertEqual(img.shape[:2], (band + 2 * 30 + 4, band + 2 * 40 + 4))
        for i, c in enumerate(COLOURS):
            row, col = divmod(i, 2)
            y = band + row * 34 + 15
            x = band + col * 44 + 20
            np.testing.assert_allclose(img[y, x], c, atol=1e-6, err_msg="cell %d" % i)
        # The small image is centred in its cell; around it, white.
        np.testing.assert_allclose(img[band + 34 + 2, band + 44 + 2], (1, 1, 1), atol=1e-6)
        # Labels put dark pixels in the top band and the left band, none in the corner.
        top = img[:band, band:]
        left = img[band:, :band]
        self.assertLess(top.min(), 0.5)
        self.assertLess(left.min(), 0.5)
        self.assertGreater(img[:band, :band].min(), 0.99)

    def test_empty_cell_and_no_labels(self):
        out = os.path.join(self.dir, "grid.png")
        r = run(self.images[0], "-", self.images[1], "-o", out, "--columns", "3", "--gap", "0")
        self.assertEqual(r.returncode, 0, r.stderr)
        img = mpimg.imread(out)[:, :, :3]
        self.assertEqual(img.shape[:2], (30, 120))
        np.testing.assert_allclose(img[15, 60], (1, 1, 1), atol=1e-6)
        np.testing.assert_allclose(img[15, 100], COLOURS[1], atol=1e-6)

    def assert_fails(self, r, code, message, out):
        self.assertEqual(r.returncode, code, r.stderr)
        self.assertIn(message, r.stderr)
        self.assertFalse(os.path.exists(out))
        self.assertEqual(sorted(os.listdir(self.dir)), sorted(os.path.basename(p) for p in self.images))

    def test_bad_usage(self):
        out = os.path.join(self.dir, "grid.png")
        self.assert_fails(run(*self.images, "-o", out, "--columns", "2", "--row-label", "A"), 2,
                          "1 row labels for 2 rows", out)
        self.assert_fails(run(*self.images, "-o", out, "--columns", "2", "--column-label", "A"), 2,
                          "1 column labels for 2 columns", out)
        self.assert_fails(run(*self.images, "-o", out, "--columns", "0"), 2, "--columns must be >= 1",
                          out)
        self.assert_fails(run(*self.images, "-o", out), 2, "--columns", out)
        self.assert_fails(run(*self.images, "-o", os.path.join(self.dir, "g.jpg"), "--columns", "2"),
                          2, "must be a .png", out)
        self.assert_fails(run(self.images[0], "-o", self.images[0], "--columns", "1"), 2,
                          "would overwrite the input", out)

    def test_missing_and_broken_images(self):
        out = os.path.join(self.dir, "grid.png")
        self.assert_fails(run(os.path.join(self.dir, "none.png"), "-o", out, "--columns", "1"), 3,
                          "none.png: cannot open for reading", out)
        broken = os.path.join(self.dir, "broken.png")
        with open(broken, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\nnot really")
        self.images.append(broken)
        self.assert_fails(run(broken, "-o", out, "--columns", "1"), 3, "broken.png: not a readable image",
                          out)


if __name__ == "__main__":
    unittest.main()
