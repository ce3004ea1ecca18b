#!/usr/bin/python3
"""CTest regression (label `regression`): a reference model's medial mesh (`skeletonize
--connectivity` with the documented sampling) garbed as its envelope (balls, cones, slabs):
M2 is closed and oriented, has no intersecting or degenerate triangle, has the original's
components and genus, the octree's depth stop did not fire, and H(M2, G), two-sided, is within
one leaf side at depth d.

Usage: experiments/medial_mesh_regression.py BUILD MODEL
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H          # noqa: E402
import medial_meshes as MM   # noqa: E402


def main(build, name):
    with tempfile.TemporaryDirectory() as work:
        row = MM.medial_mesh_job(build, work, name, ("ma",))[0]
    problems = []
    if not row["closed_oriented"]:
        problems.append("M2 is not closed and oriented")
    if row["folds"] or row["degenerate"]:
        problems.append("%d intersecting pairs, %d degenerate triangles" % (row["folds"], row["degenerate"]))
    if (row["components"], row["genus"]) != (row["orig_components"], row["orig_genus"]):
        problems.append("M2 has %d components of genus %d, the original %d of genus %d" % (
            row["components"], row["genus"], row["orig_components"], row["orig_genus"]))
    if row["hit_max_depth"]:
        problems.append("the octree's depth stop fired")
    if not row["h_m2_g"] <= row["leaf"]:
        problems.append("H(M2, G) %.4g%% exceeds one leaf side %.4g%%" % (row["h_m2_g"], row["leaf"]))
    print("%s: %d atoms, %d faces, M2 %d vertices, %d components, genus %d, H(M2, G) %.4g%% "
          "(leaf %.4g%%), H(M2, O) %.4g%%, %.2f s" % (
              name, row["atoms"], row["faces"], row["m2_v"], row["components"], row["genus"],
              row["h_m2_g"], row["leaf"], row["h_m2_o"], row["seconds"]))
    if problems:
        H.die("; ".join(problems), "medial_mesh_regression " + name)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        H.die("usage: medial_mesh_regression.py BUILD MODEL", "medial_mesh_regression")
    main(sys.argv[1], sys.argv[2])
