#!/usr/bin/python3
"""CTest regression (label `regression`): for every reference model of Table 1, the garbing of
its paper atoms (vertex poles) is a closed, oriented 2-manifold with the union of the atoms'
topology (M1's components and Euler characteristic too) and no intersecting or degenerate
triangles, and its Hausdorff and RMS distances to the original stay under the reviewed bounds of
regression_thresholds.json (proposed by experiments/propose_bounds.py from measure() below).
It also reports (NOTE lines, not failures) issue 7's accuracy targets: H(M2, G) within one leaf
side at depth d, and H(M2, O) <= H(G, O) + 0.25% of the diagonal.

Usage: experiments/regression.py BUILD MODEL
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402

BOUNDS = os.path.join(H.HERE, "regression_thresholds.json")
# The bounded distances of M2 to the original (% of its diagonal), with their names in messages.
METRICS = {"hausdorff_pct": "Hausdorff", "rms_pct": "RMS"}


def load_bounds(path=BOUNDS):
    """The bounds file: {"about": ..., "models": {model: {metric: bound in % of the diagonal, ...}}}."""
    with open(path) as f:
        return json.load(f)


def measure(build, name):
    """Skeletonizes reference model `name` (paper atoms), garbs the atoms and measures M2: the
    programs' reports `skeleton`, `garb`, `check` (M2's defects), `distance` (M2 against the
    original, 300,000 samples: the bounded metrics), `to_g` (M2 against G) and `g_o` (G against the
    original), and `leaf_pct`, one leaf side at depth d in % of the diagonal."""
    with tempfile.TemporaryDirectory() as work:
        R = H.Runner(build, work)
        original = R.model(name)
        atoms = R.path("atoms.ma")
        sk = R.run_stats("skeletonize", original, "-o", atoms, stats=R.path("sk.json"))
        m2 = R.path("m2.off")
        g = R.run_stats("garb", atoms, "-o", m2, stats=R.path("g.json"))
        check = R.run("evaluate", "check", m2, "--json")
        d = R.run("evaluate", "distance", m2, original, "--samples", 300000, "--json")
        samples = 2 * max(g["m2"]["vertices"], sk["samples"]) + 1000
        to_g = R.run("evaluate", "atoms", m2, atoms, "--diagonal", d["diagonal"], "--samples", samples, "--json")
        g_o = R.run("evaluate", "atoms", original, atoms, "--samples", samples, "--json")
    return {"skeleton": sk, "garb": g, "check": check, "distance": d, "to_g": to_g, "g_o": g_o,
            "leaf_pct": 100 * g["root_side"] / 2 ** g["min_depth"] / d["diagonal"]}


def main(build, name):
    bounds = load_bounds()["models"][name]
    m = measure(build, name)
    sk, g, check, d, to_g, g_o, leaf_pct = (m[k] for k in ("skeleton", "garb", "check", "distance", "to_g", "g_o",
                                                            "leaf_pct"))
    problems = []
    if not (check["closed"] and check["manifold"] and check["oriented"]):
        problems.append("M2 is not a closed oriented 2-manifold")
    union = sk["union"]
    m1 = g["m1"]
    if (m1["components"], m1["euler"]) != (union["components"], union["euler"]):
        problems.append("M1 has %d component(s), Euler characteristic %d; the union of the atoms %d, %d" % (
            m1["components"], m1["euler"], union["components"], union["euler"]))
    if (check["components"], check["euler"]) != (union["components"], union["euler"]):
        problems.append("M2 has %d component(s), Euler characteristic %d; the union of the atoms %d, %d" % (
            check["components"], check["euler"], union["components"], union["euler"]))
    if check["intersecting_pairs"] or check["degenerate_triangles"]:
        problems.append("%d intersecting pairs, %d degenerate triangles" % (
            check["intersecting_pairs"], check["degenerate_triangles"]))
    # Issue 7's accuracy targets, reported (not asserted): one leaf side is a heuristic bound
    # (a leaf active through a crease fill can lie about a leaf from G), and homer's
    # topology-preserving atoms exceed it slightly (results/atoms.md).
    notes = []
    if to_g["hausdorff_pct"] > leaf_pct:
        notes.append("H(M2, G) %.3f%% above one leaf side %.3f%%" % (to_g["hausdorff_pct"], leaf_pct))
    if d["hausdorff_pct"] > g_o["hausdorff_pct"] + 0.25:
        notes.append("H(M2, O) %.3f%% above H(G, O) %.3f%% + 0.25%%" % (d["hausdorff_pct"], g_o["hausdorff_pct"]))
    for metric, label in METRICS.items():
        if d[metric] > bounds[metric]:
            problems.append("%s %.3f%% above the bound %.3f%%" % (label, d[metric], bounds[metric]))
    print("%s: M2 V %d, genus %d, H %.3f%% (bound %.3f), RMS %.3f%% (bound %.3f), H(M2,G) %.3f%% (leaf %.3f%%), "
          "H(G,O) %.3f%%, garbing %.2f s" % (
              name, g["m2"]["vertices"], check["genus"], d["hausdorff_pct"], bounds["hausdorff_pct"], d["rms_pct"],
              bounds["rms_pct"], to_g["hausdorff_pct"], leaf_pct, g_o["hausdorff_pct"], g["seconds"]["garbing"]))
    for n in notes:
        print("NOTE %s: %s" % (name, n))
    for p in problems:
        print("FAIL %s: %s" % (name, p))
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
