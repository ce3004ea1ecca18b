#!/usr/bin/python3
"""CTest regression (label `regression`): a reference model's poles (the documented sampling)
simplified to 2 % of their count, at least 50 atoms (`skeletonize --simplify`): the target is
reached, M2 garbed from the simplified medial mesh is closed, oriented and fold-free with the
original's components and genus, and H(G, O), two-sided, between the envelope and the original
is at most 2 % of the diagonal (issue 19's bound).

Usage: experiments/simplify_regression.py BUILD MODEL
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H   # noqa: E402
import simplify as S  # noqa: E402

BOUND_PCT = 2.0


def main(build, name):
    with tempfile.TemporaryDirectory() as work:
        row = S.simplify_job(build, work, name, fractions=(2,), poles_row=False)[0]
    problems = []
    if row["target_reached"] != "yes":
        problems.append("stopped at %d atoms, target %d" % (row["atoms"], row["target"]))
    if not row["closed_oriented"] or row["folds"]:
        problems.append("M2 not closed and oriented, or %d intersecting pairs" % row["folds"])
    if (row["components"], row["genus"]) != (row["expected_components"], row["expected_genus"]):
        problems.append("M2 has %d components of genus %d, the original %d of genus %d" % (
            row["components"], row["genus"], row["expected_components"], row["expected_genus"]))
    if not row["h_g_o"] <= BOUND_PCT:
        problems.append("H(G, O) %.4g%% exceeds %.4g%%" % (row["h_g_o"], BOUND_PCT))
    print("%s: %d poles -> %d atoms, %d edges, %d faces in %.2f s; H(G, O) %.4g%%, M2 %d "
          "components, genus %d, H(M2, O) %.4g%%" % (
              name, row["poles"], row["atoms"], row["edges"], row["faces"], row["seconds"],
              row["h_g_o"], row["components"], row["genus"], row["h_m2_o"]))
    if problems:
        H.die("; ".join(problems), "simplify_regression " + name)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        H.die("usage: simplify_regression.py BUILD MODEL", "simplify_regression")
    main(sys.argv[1], sys.argv[2])
