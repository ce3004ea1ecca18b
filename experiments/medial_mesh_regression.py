#!/usr/bin/python3
"""CTest regression (label `regression`): a medial mesh garbed as its envelope (balls, cones,
slabs), either a reference model's (`skeletonize --connectivity` with the documented sampling)
or an analytic one (`models generate medial-*`): M2 is closed and oriented, has no intersecting
or degenerate triangle, has the expected components and genus (the original's, or the analytic
envelope's), the octree's depth stop did not fire, its depth is at most d + 2, and H(M2, G),
two-sided, is within one leaf side at depth d.

Usage: experiments/medial_mesh_regression.py BUILD SET
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H          # noqa: E402
import medial_meshes as MM   # noqa: E402


def main(build, name):
    with tempfile.TemporaryDirectory() as work:
        row = MM.medial_mesh_job(build, work, name, ("ma",), baseline=False)[0]
    problems = []
    if not row["closed_oriented"]:
        problems.append("M2 is not closed and oriented")
    if row["folds"] or row["degenerate"]:
        problems.append("%d intersecting pairs, %d degenerate triangles" % (row["folds"], row["degenerate"]))
    if (row["components"], row["genus"]) != (row["expected_components"], row["expected_genus"]):
        problems.append("M2 has %d components of genus %d, expected %d of genus %d" % (
            row["components"], row["genus"], row["expected_components"], row["expected_genus"]))
    if row["hit_max_depth"]:
        problems.append("the octree's depth stop fired")
    if row["depth"] > row["d"] + 2:
        problems.append("depth %d exceeds d + 2 = %d" % (row["depth"], row["d"] + 2))
    if not row["h_m2_g"] <= row["leaf"]:
        problems.append("H(M2, G) %.4g%% exceeds one leaf side %.4g%%" % (row["h_m2_g"], row["leaf"]))
    print("%s: %d atoms, %d faces, M2 %d vertices, %d components, genus %d, H(M2, G) %.4g%% "
          "(leaf %.4g%%), H(M2, O) %s, %.2f s" % (
              name, row["atoms"], row["faces"], row["m2_v"], row["components"], row["genus"],
              row["h_m2_g"], row["leaf"],
              "%.4g%%" % row["h_m2_o"] if row["h_m2_o"] != "" else "(no original)",
              row["seconds"]))
    if problems:
        H.die("; ".join(problems), "medial_mesh_regression " + name)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        H.die("usage: medial_mesh_regression.py BUILD SET", "medial_mesh_regression")
    main(sys.argv[1], sys.argv[2])
