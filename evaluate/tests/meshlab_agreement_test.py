#!/usr/bin/python3
"""`evaluate distance` against MeshLab's "Hausdorff Distance" filter (meshlabserver, run under
xvfb-run): same sampling on both sides (faces only, area-uniform, the same count), MaxDist far
above the diagonal (MeshLab silently drops samples beyond it), both directions. Hausdorff and
RMS, one-sided and two-sided, must agree within 3% (relative).

Fails when meshlabserver or xvfb-run is missing: ./test.sh installs them.
usage: meshlab_agreement_test.py EVALUATE MODELS MODELS_DIR [-v]
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

EVALUATE = sys.argv.pop(1) if len(sys.argv) > 1 else "evaluate"
MODELS = sys.argv.pop(1) if len(sys.argv) > 1 else "models"
MODELS_DIR = sys.argv.pop(1) if len(sys.argv) > 1 else "build/models"

SAMPLES = 200000
TOLERANCE = 0.03

FILTER = """ <filter name="Hausdorff Distance">
  <Param type="RichMesh" value="{sampled}" name="SampledMesh"/>
  <Param type="RichMesh" value="{target}" name="TargetMesh"/>
  <Param type="RichBool" value="false" name="SaveSample"/>
  <Param type="RichBool" value="false" name="SampleVert"/>
  <Param type="RichBool" value="false" name="SampleEdge"/>
  <Param type="RichBool" value="false" name="SampleFauxEdge"/>
  <Param type="RichBool" value="true" name="SampleFace"/>
  <Param type="RichInt" value="{samples}" name="SampleNum"/>
  <Param type="RichAbsPerc" value="{max_dist}" min="0" max="{max_dist}" name="MaxDist"/>
 </filter>
"""

RESULT = re.compile(r"Sampled (\d+) pts \(rng: \d+\) on (\S+) searched closest on (\S+)\s+"
                    r"min : (\S+)\s+max (\S+)\s+mean : (\S+)\s+RMS : (\S+)")


def read_off(path):
    with open(path) as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    assert words[0].endswith("OFF"), path
    nv, nf = int(words[1]), int(words[2])
    points = [tuple(map(float, words[4 + 3 * i:7 + 3 * i])) for i in range(nv)]
    rest, faces = words[4 + 3 * nv:], []
    for _ in range(nf):
        k = int(rest[0])
        faces.append(rest[1:1 + k])
        rest = rest[1 + k:]
    return points, faces


def write_off(path, points, faces):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(points), len(faces)))
        for p in points:
            f.write("%r %r %r\n" % p)
        for face in faces:
            f.write("%d %s\n" % (len(face), " ".join(face)))


def diagonal(points):
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    return math.dist(lo, hi)


def meshlab(a, b, max_dist, workdir):
    """Both one-sided results of MeshLab's filter: {(sampled, target): (max, mean, rms)}."""
    script = os.path.join(workdir, "hausdorff.mlx")
    with open(script, "w") as f:
        f.write("<!DOCTYPE FilterScript>\n<FilterScript>\n")
        for sampled, target in ((0, 1), (1, 0)):
            f.write(FILTER.format(sampled=sampled, target=target, samples=SAMPLES,
                                  max_dist=max_dist))
        f.write("</FilterScript>\n")
    log = os.path.join(workdir, "meshlab.log")
    if os.path.exists(log):
        os.remove(log)
    r = subprocess.run(["xvfb-run", "-a", "meshlabserver", "-i", a, "-i", b, "-s", script,
                        "-l", log], capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        raise AssertionError("meshlabserver failed (%d): %s" % (r.returncode, r.stderr[-2000:]))
    with open(log) as f:
        text = f.read()
    results = {}
    for m in RESULT.finditer(text):
        count, sampled, target = int(m.group(1)), m.group(2), m.group(3)
        if count != SAMPLES:
            raise AssertionError("MeshLab took %d samples, not %d" % (count, SAMPLES))
        results[(sampled, target)] = tuple(float(m.group(k)) for k in (5, 6, 7))
    names = (os.path.basename(a), os.path.basename(b))
    for key in (names, names[::-1]):
        if key not in results:
            raise AssertionError("no MeshLab result for %s -> %s in:\n%s" % (key + (text,)))
    return results[names], results[names[::-1]]


def ours(a, b):
    r = subprocess.run([EVALUATE, "distance", a, b, "--faces-only", "--samples", str(SAMPLES),
                        "--json"], capture_output=True, text=True)
    if r.returncode != 0:
        raise AssertionError("evaluate distance failed: " + r.stderr)
    j = json.loads(r.stdout)
    one = lambda s: (j[s]["max"], j[s]["mean"], j[s]["rms"])
    return one("mesh_to_reference"), one("reference_to_mesh")


class MeshLabAgreement(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        for tool in ("meshlabserver", "xvfb-run"):
            if shutil.which(tool) is None:
                raise AssertionError(tool + " not found: install Debian's meshlab and xvfb "
                                     "(./test.sh does), this test does not skip")
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = cls.tmp.name
        cls.rows = []

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()
        print("\n%-34s %-9s %12s %12s %8s" % ("pair", "value", "evaluate", "MeshLab", "rel"))
        for row in cls.rows:
            print("%-34s %-9s %12.6g %12.6g %7.2f%%" % row)

    def generate(self, name, *args):
        path = os.path.join(self.dir, name)
        subprocess.run([MODELS, "generate", *args, "-o", path], check=True)
        return path

    def compare(self, label, a, b):
        points = read_off(a)[0] + read_off(b)[0]
        max_dist = 100 * diagonal(points)  # far above: MeshLab drops samples beyond it
        ml_ab, ml_ba = meshlab(a, b, max_dist, self.dir)
        ev_ab, ev_ba = ours(a, b)
        values = {
            "H A->B": (ev_ab[0], ml_ab[0]), "H B->A": (ev_ba[0], ml_ba[0]),
            "RMS A->B": (ev_ab[2], ml_ab[2]), "RMS B->A": (ev_ba[2], ml_ba[2]),
            "Hausdorff": (max(ev_ab[0], ev_ba[0]), max(ml_ab[0], ml_ba[0])),
            "RMS": (max(ev_ab[2], ev_ba[2]), max(ml_ab[2], ml_ba[2])),
        }
        for what, (e, m) in values.items():
            rel = abs(e / m - 1)
            self.rows.append((label, what, e, m, 100 * rel))
            self.assertLess(rel, TOLERANCE, "%s %s: evaluate %g, MeshLab %g" % (label, what, e, m))

    def test_coarse_and_fine_torus(self):
        coarse = self.generate("torus_coarse.off", "torus", "--ring", "24", "--tube", "8")
        fine = self.generate("torus_fine.off", "torus", "--ring", "120", "--tube", "40")
        self.compare("torus 24x8 vs 120x40", coarse, fine)

    def test_two_spheres(self):
        a = self.generate("sphere_a.off", "sphere", "--frequency", "6", "--radius", "1")
        b = self.generate("sphere_b.off", "sphere", "--frequency", "20", "--radius", "1.05")
        self.compare("sphere f6 r1 vs f20 r1.05", a, b)

    def test_reference_model_and_a_perturbed_copy(self):
        hand = os.path.join(MODELS_DIR, "hand.off")
        if not os.path.exists(hand):
            raise AssertionError(hand + " missing: the reference_models fixture makes it")
        points, faces = read_off(hand)
        d = diagonal(points)
        # A smooth displacement of up to 1% of the diagonal along each axis.
        w = 2 * math.pi * 3 / d
        moved = [(x + 0.01 * d * math.sin(w * y), y + 0.01 * d * math.sin(w * z),
                  z + 0.01 * d * math.sin(w * x)) for x, y, z in points]
        a = os.path.join(self.dir, "hand.off")
        b = os.path.join(self.dir, "hand_perturbed.off")
        write_off(a, points, faces)
        write_off(b, moved, faces)
        self.compare("hand vs perturbed hand", a, b)


if __name__ == "__main__":
    unittest.main(verbosity=2)
