#!/usr/bin/python3
"""CTest regression (label `regression`): the pruned cell lists (garb's default on atoms) against
the paper's full lists (`--full-lists`) on a reference model's paper atoms (vertex poles). Both
meshes are closed, oriented and fold-free with the same components and Euler characteristic; the
pruned lists hold fewer balls per active leaf; and where the meshes differ the pruned one is no
farther from the object (H(M2, O) at most 1 % + 0.005 % of the diagonal above the full lists')
nor from G (H(M2, G) at most a tenth of a leaf side at depth d above). docs/algorithm.md,
"Pruned lists", has the measured table.

Usage: experiments/pruned_lists_regression.py BUILD MODEL
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402

MODES = {"pruned": (), "full": ("--full-lists",)}


def measure(build, name):
    """Per mode: garb's stats, evaluate check, distance to the original and to G (% diagonal)."""
    out = {}
    with tempfile.TemporaryDirectory() as work:
        R = H.Runner(build, work)
        original = R.model(name)
        atoms = R.path("atoms.ma")
        sk = R.run_stats("skeletonize", original, "-o", atoms, stats=R.path("sk.json"))
        for mode, extra in MODES.items():
            m2 = R.path(mode + ".off")
            g = R.run_stats("garb", atoms, "-o", m2, *extra, stats=R.path(mode + ".json"))
            check = R.run("evaluate", "check", m2, "--json")
            d = R.run("evaluate", "distance", m2, original, "--samples", 200000, "--json")
            samples = 2 * max(g["m2"]["vertices"], sk["samples"]) + 1000
            to_g = R.run("evaluate", "atoms", m2, atoms, "--diagonal", d["diagonal"], "--samples", samples,
                         "--json")
            out[mode] = {"garb": g, "check": check, "distance": d, "to_g": to_g,
                         "leaf_pct": 100 * g["root_side"] / 2 ** g["min_depth"] / d["diagonal"]}
    return out


def main(build, name):
    m = measure(build, name)
    p, f = m["pruned"], m["full"]
    problems = []
    for mode, r in m.items():
        c = r["check"]
        if not (c["closed"] and c["manifold"] and c["oriented"]):
            problems.append("%s: M2 is not a closed oriented 2-manifold" % mode)
        if c["intersecting_pairs"] or c["degenerate_triangles"]:
            problems.append("%s: %d intersecting pairs, %d degenerate triangles" % (
                mode, c["intersecting_pairs"], c["degenerate_triangles"]))
    if not p["garb"]["pruned_lists"] or f["garb"]["pruned_lists"]:
        problems.append("garb's pruned_lists: %s by default, %s with --full-lists" % (
            p["garb"]["pruned_lists"], f["garb"]["pruned_lists"]))
    topo = [(r["check"]["components"], r["check"]["euler"]) for r in (p, f)]
    if topo[0] != topo[1]:
        problems.append("components and Euler characteristic %s pruned, %s full" % topo)
    balls = [r["garb"]["listed_per_active_leaf"]["balls_mean"] for r in (p, f)]
    if balls[0] > balls[1]:
        problems.append("%.1f balls per active leaf pruned, %.1f full" % tuple(balls))
    h_o = [r["distance"]["hausdorff_pct"] for r in (p, f)]
    if h_o[0] > 1.01 * h_o[1] + 0.005:
        problems.append("H(M2, O) %.4f%% pruned, %.4f%% full" % tuple(h_o))
    h_g = [r["to_g"]["hausdorff_pct"] for r in (p, f)]
    if h_g[0] > h_g[1] + 0.1 * f["leaf_pct"]:
        problems.append("H(M2, G) %.4f%% pruned, %.4f%% full (leaf side %.3f%%)" % (h_g[0], h_g[1], f["leaf_pct"]))
    print("%s: balls per active leaf %.1f / %.1f, leaves %d / %d, H(M2, O) %.4f / %.4f %%, "
          "H(M2, G) %.4f / %.4f %% (pruned / full)" % (
              name, balls[0], balls[1], p["garb"]["leaves"], f["garb"]["leaves"], h_o[0], h_o[1], h_g[0], h_g[1]))
    for problem in problems:
        print("FAIL %s: %s" % (name, problem))
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
