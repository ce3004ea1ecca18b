#!/usr/bin/python3
"""Times POV-Ray renders of the issue's two performance cases (a report, not a test):
  - the bumpy torus reference model (31,752 faces), 800 x 600;
  - a union of 15,000 spheres: balls inside the bumpy torus, tangent to it at evenly spaced
    vertices (centre = vertex - rho n, radius rho = 0.6 x the local tube radius), 800 x 600.
Each case runs --repeat times with the render program's defaults; the table gives the scene
writing time (render --pov) and the whole render (scene + POV-Ray + PNG), min and median.

Usage: render/bench_render.py --build BUILD [--repeat 3] [--threads 0] [--keep DIR]
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def read_off(path):
    with open(path) as f:
        tokens = [t for line in f for t in line.split("#")[0].split()]
    assert tokens[0] == "OFF"
    nv, nf = int(tokens[1]), int(tokens[2])
    at = 4
    points = np.array(tokens[at:at + 3 * nv], dtype=float).reshape(nv, 3)
    at += 3 * nv
    faces = []
    for _ in range(nf):
        k = int(tokens[at])
        faces.append([int(t) for t in tokens[at + 1:at + 1 + k]])
        at += 1 + k
    return points, np.array(faces)


def inner_balls(off, count):
    """`count` balls inside a torus of major radius 1 about z, tangent at evenly spaced vertices."""
    points, faces = read_off(off)
    a, b, c = points[faces[:, 0]], points[faces[:, 1]], points[faces[:, 2]]
    fn = np.cross(b - a, c - a)
    normals = np.zeros_like(points)
    for k in range(3):
        np.add.at(normals, faces[:, k], fn)
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    chosen = np.unique(np.linspace(0, len(points) - 1, count).round().astype(int))
    p, n = points[chosen], normals[chosen]
    core = np.c_[p[:, :2] / np.linalg.norm(p[:, :2], axis=1)[:, None], np.zeros(len(p))]
    rho = 0.6 * np.linalg.norm(p - core, axis=1)
    return p - rho[:, None] * n, rho


def timed(cmd):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("bench_render: %s failed: %s" % (cmd[0], r.stderr.strip()))
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", required=True)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=0, help="POV-Ray threads (0 = every core)")
    ap.add_argument("--keep", help="keep the images and scenes in this folder")
    args = ap.parse_args()
    render = os.path.join(args.build, "bin", "render")
    torus = os.path.join(args.build, "models", "bumpy_torus.off")
    if not os.path.exists(torus):
        subprocess.run([sys.executable, os.path.join(ROOT, "experiments", "models.py"), "--build",
                        args.build, "--models", "bumpy_torus", "--quiet"], check=True)
    out = args.keep or tempfile.mkdtemp(prefix="bench_render_")
    os.makedirs(out, exist_ok=True)
    atoms = os.path.join(out, "bumpy_torus_balls.ma")
    centres, radii = inner_balls(torus, 15000)
    with open(atoms, "w") as f:
        f.write("%d 0 0\n" % len(radii))
        for c, r in zip(centres, radii):
            f.write("v %.17g %.17g %.17g %.17g\n" % (c[0], c[1], c[2], r))

    print("cores: %d, load average before: %.2f %.2f %.2f" % ((os.cpu_count(),) + os.getloadavg()))
    print("| case | input | scene (render --pov) | render 800x600, min | median |")
    print("|---|---|---|---|---|")
    for name, path, what in (("mesh", torus, "31,752 faces"), ("spheres", atoms, "%d atoms" % len(radii))):
        base = [render, path, "--width", "800", "--height", "600", "--threads", str(args.threads)]
        scene = min(timed(base + ["--pov", os.path.join(out, name + ".pov")]) for _ in range(args.repeat))
        runs = [timed(base + ["-o", os.path.join(out, name + ".png")]) for _ in range(args.repeat)]
        print("| %s | %s | %.2f s | %.2f s | %.2f s |" % (name, what, scene, min(runs),
                                                        statistics.median(runs)))
    print("load average after: %.2f %.2f %.2f" % os.getloadavg())
    if not args.keep:
        print("(images in %s)" % out)


if __name__ == "__main__":
    main()
