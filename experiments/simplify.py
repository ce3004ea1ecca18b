#!/usr/bin/python3
"""Simplified medial meshes: each reference model's poles collapsed to 1 %, 2 % and 5 % of their
count (at least 50 atoms) by `skeletonize --simplify`, measured as envelopes and garbed.

For each model (the sampling of experiments/models.json's "simplify" entry, else its skeleton's)
and each fraction: the simplified medial mesh's atoms, edges and faces, collapses and refusals,
seconds; H(G, O), two-sided, between its envelope G (balls, cones, slabs) and the original O
(`evaluate atoms --primitives ma`); M2 garbed from it (`garb`, the envelope), its components
and genus against the original's, H(M2, O). The unsimplified poles (their atoms garbed alone, as
Table 1) are the reference row. Writes results/simplify.{csv,md,png}.

Usage: experiments/simplify.py [--build build] [--models a,b] [--quick] [--jobs N] [--scheduler ADDRESS]
       [--results DIR]
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import jobs as J     # noqa: E402

MODELS = J.TABLE1_MODELS + ["cube"]
QUICK = J.QUICK_MODELS
FRACTIONS = [1, 2, 5]  # % of the pole count
MIN_ATOMS = 50

COLUMNS = ["model", "fraction", "poles", "target", "atoms", "edges", "faces", "target_reached",
           "collapses", "refused_topology", "refused_outside", "refused_excess",
           "refused_shortfall", "seconds",
           "h_g_o", "rms_g_o", "m2_v", "components", "genus", "expected_components",
           "expected_genus", "h_m2_o", "poles_h_g_o", "poles_h_m2_o"]
HEADERS = ["model", "% of poles", "poles", "target", "atoms", "edges", "faces", "reached",
           "collapses", "refused (topology)", "refused (outside)", "refused (excess)",
           "refused (shortfall)",
           "simplify s", "H(G, O) %", "RMS(G, O) %", "M2 V", "M2 components", "M2 genus",
           "O components", "O genus", "H(M2, O) %", "poles: H(G, O) %", "poles: H(M2, O) %"]


def target_atoms(poles, fraction):
    """The atom count for `fraction` % of `poles`: at least MIN_ATOMS, at most the poles."""
    return min(poles, max(MIN_ATOMS, round(poles * fraction / 100)))


def simplify_job(build, work, name, fractions=FRACTIONS, poles_row=True):
    """One model's rows, one per fraction: its simplified medial mesh measured and garbed, and
    (`poles_row`) the unsimplified poles garbed alone for reference."""
    R = H.Runner(build, work)
    model = H.models_by_name()[name]
    original = R.model(name)
    info = R.run("models", "info", original, "--json")
    sampling = J.skeleton_args(model, "simplify")
    # The poles alone, garbed as Table 1 garbs them: the reference.
    poles = R.path(name, "simplify_poles.ma")
    sk = R.run_stats("skeletonize", original, "-o", poles, *sampling,
                     stats=R.path(name, "simplify_poles.json"), label="%s skeletonize" % name)
    base = {"model": name, "poles": sk["atoms"], "expected_components": info["components"],
            "expected_genus": info["genus"]}
    if poles_row:
        g_o = R.run("evaluate", "atoms", original, poles, "--json", label="%s poles G to O" % name)
        m2 = R.path(name, "simplify_poles_m2.off")
        R.run("garb", poles, "-o", m2, label="%s garb poles" % name)
        d = R.run("evaluate", "distance", m2, original, "--json", label="%s poles M2 to O" % name)
        base.update({"poles_h_g_o": g_o["hausdorff_pct"], "poles_h_m2_o": d["hausdorff_pct"]})
    rows = []
    for fraction in fractions:
        target = target_atoms(sk["atoms"], fraction)
        tag = "simplify_%d" % fraction
        ma = R.path(name, tag + ".ma")
        s = R.run_stats("skeletonize", original, "-o", ma, *sampling, "--simplify", target,
                        stats=R.path(name, tag + ".json"),
                        label="%s skeletonize --simplify %d" % (name, target))["simplify"]
        go = R.run("evaluate", "atoms", original, ma, "--primitives", "ma", "--json",
                   label="%s simplified G to O" % name)
        m2 = R.path(name, tag + "_m2.off")
        gb = R.run_stats("garb", ma, "-o", m2, stats=R.path(name, tag + "_garb.json"),
                         label="%s garb simplified" % name)
        d = R.run("evaluate", "distance", m2, original, "--json", label="%s M2 to O" % name)
        row = dict(base)
        row.update({
            "fraction": fraction, "target": target, "atoms": s["after"]["atoms"],
            "edges": s["after"]["edges"], "faces": s["after"]["faces"],
            "target_reached": "yes" if s["target_reached"] else "no",
            "collapses": s["collapses"], "refused_topology": s["refusals"]["topology"],
            "refused_outside": s["refusals"]["outside"], "refused_excess": s["refusals"]["excess"],
            "refused_shortfall": s["refusals"]["shortfall"],
            "seconds": s["seconds"]["simplify"], "h_g_o": go["hausdorff_pct"],
            "rms_g_o": go["rms_pct"], "m2_v": gb["m2"]["vertices"],
            "components": gb["m2"]["components"], "genus": gb["m2"]["genus"],
            "h_m2_o": d["hausdorff_pct"],
            "closed_oriented": gb["m2"]["closed"] and gb["m2"]["oriented"],
            "folds": gb["m2"]["intersecting_pairs_after_repair"]})
        rows.append(row)
    return rows


def plot(out, rows):
    """simplify.png: H(G, O) and H(M2, O) against the atom count, per model; the poles' H(M2, O)
    as a marker at their count."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from figures import save_figure

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    models = []
    for r in rows:
        if r["model"] not in models:
            models.append(r["model"])
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, m in enumerate(models):
        mine = sorted((r for r in rows if r["model"] == m), key=lambda r: r["atoms"])
        c = colours[k % len(colours)]
        for ax, key, poles_key in ((axes[0], "h_g_o", "poles_h_g_o"),
                                   (axes[1], "h_m2_o", "poles_h_m2_o")):
            ax.plot([r["atoms"] for r in mine], [r[key] for r in mine], "o-", color=c, label=m)
            ax.plot([mine[0]["poles"]], [mine[0][poles_key]], "x", color=c, markersize=8)
    for ax, title in ((axes[0], "H(envelope G, O), % of the diagonal"),
                      (axes[1], "H(M2, O), % of the diagonal")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.axhline(2, color="grey", linestyle=":", linewidth=1)
        ax.set_xlabel("atoms (o: simplified at 1, 2, 5 % of the poles; x: the poles, atoms alone)")
        ax.set_title(title)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    save_figure(plt, fig, os.path.join(out, "simplify.png"))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(H.ROOT, "build"))
    ap.add_argument("--models", help="comma-separated subset of: " + ", ".join(MODELS))
    ap.add_argument("--quick", action="store_true", help="three small models")
    ap.add_argument("--jobs", type=int, default=os.cpu_count(), help="parallel jobs")
    ap.add_argument("--scheduler", help="run the jobs on the Dask cluster of this scheduler address "
                    "(host:port; default: a local process pool of --jobs)")
    ap.add_argument("--results", help="write the results here instead of results/")
    args = ap.parse_args(argv)
    args.build = os.path.abspath(args.build)  # the jobs may run elsewhere (--scheduler)
    names = args.models.split(",") if args.models else (QUICK if args.quick else MODELS)
    unknown = [n for n in names if n not in MODELS]
    if unknown:
        H.die("unknown model(s): %s" % ", ".join(unknown), "simplify")
    out = os.path.abspath(args.results) if args.results else H.RESULTS
    os.makedirs(out, exist_ok=True)
    work = os.path.join(os.path.abspath(args.build), "experiments-work")
    start = time.time()
    try:
        jobs = [("simplify " + n, simplify_job, (args.build, work, n)) for n in names]
        results = H.run_pool(jobs, args.jobs, H.log, args.scheduler)
    except H.StepError as e:
        H.die(str(e), "simplify")
    rows = [r for n in names for r in results["simplify " + n]]
    H.write_csv(os.path.join(out, "simplify.csv"), rows, COLUMNS)
    plot(out, rows)
    command = "experiments/simplify.py" + (" --models " + args.models if args.models else "") + (
        " --quick" if args.quick and not args.models else "")
    text = (
        "# Simplified medial meshes (`skeletonize --simplify`)\n\n"
        "Each model's poles (the sampling of experiments/models.json's \"simplify\" entry, else "
        "its skeleton's, with their "
        "regular-triangulation connectivity) collapsed to 1, 2 and 5 %% of their count, at least "
        "%d atoms, by spherical quadric error times the stability ratio "
        "(docs/algorithm.md \"Simplification\"). G: the simplified medial mesh's envelope (balls, "
        "a cone per edge, a slab per face); O: the original; M2: G garbed (`garb`, default "
        "options). Distances two-sided, in %% of O's bounding-box diagonal. Poles: the same "
        "atoms unsimplified, their union garbed alone (the paper's path, Table 1's atom "
        "sets).\n\n"
        "Command: `%s` (%.0f s, %d jobs on %d cores).\n\n%s\n\n"
        "![H against the atom count](simplify.png)\n" % (
            MIN_ATOMS, command, time.time() - start, args.jobs, os.cpu_count(),
            H.markdown_table(rows, COLUMNS, HEADERS)))
    H.write_atomically(os.path.join(out, "simplify.md"), text)
    H.log("wrote %s/simplify.{csv,md,png}" % out)


if __name__ == "__main__":
    main(sys.argv[1:])
