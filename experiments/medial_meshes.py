#!/usr/bin/python3
"""Medial meshes: garb each reference model's medial mesh as its envelope (balls, cones, slabs).

For every model: skeletonize with the documented sampling and --connectivity (the regular-
triangulation edges and triangles inside the object) -> garb (the envelope, `--primitives ma`)
and, for comparison, garb of the same atoms alone (`--primitives rt`, the paper's path) ->
evaluate each against the original and against its own G. Writes results/medial_meshes.csv and
results/medial_meshes.md.

Usage: experiments/medial_meshes.py [--build build] [--models a,b] [--quick] [--jobs N]
       [--results DIR]
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import jobs as J     # noqa: E402

COLUMNS = ["model", "primitives", "atoms", "edges", "faces", "slabs", "no_tangent", "d", "depth",
           "m2_v", "components", "genus", "orig_components", "orig_genus", "h_m2_g", "leaf",
           "h_m2_o", "rms_m2_o", "folds", "seconds", "peak_mb"]
HEADERS = ["model", "G", "atoms", "edges", "faces", "slabs", "slabs w/o tangent triangles", "d",
           "depth", "M2 V", "components", "genus", "original's components", "original's genus",
           "H(M2, G) %", "leaf side %", "H(M2, O) %", "RMS(M2, O) %", "folds after repair",
           "garbing s", "peak MB"]


def medial_mesh_job(build, work, name, primitive_sets=("ma", "rt")):
    """The rows of one model: its medial mesh garbed as the envelope (ma), and its atoms alone
    (rt)."""
    model = H.models_by_name()[name]
    R = H.Runner(build, work)
    original = R.model(name)
    info = R.run("models", "info", original, "--json")
    mm = R.path(name, "medial_mesh.ma")
    sk = R.run_stats("skeletonize", original, "-o", mm, *J.skeleton_args(model, "topology"),
                     "--connectivity", stats=R.path(name, "medial_mesh_skel.json"),
                     label="%s skeletonize --connectivity" % name)
    rows = []
    for primitives in primitive_sets:
        m2 = R.path(name, "medial_mesh_%s.off" % primitives)
        g = R.run_stats("garb", mm, "-o", m2, "--primitives", primitives,
                        stats=R.path(name, "medial_mesh_%s_garb.json" % primitives),
                        label="%s garb %s" % (name, primitives))
        d = R.run("evaluate", "distance", m2, original, "--json", label="%s distance" % name)
        dg = R.run("evaluate", "atoms", m2, mm, "--primitives", primitives, "--diagonal",
                   d["diagonal"], "--samples", J.atom_samples(g["m2"]["vertices"]), "--json",
                   label="%s to G" % name)
        envelope = g["m2"].get("envelope", {})
        leaf = g["root_side"] / 2 ** g["min_depth"]
        rows.append({
            "model": name, "primitives": primitives, "atoms": g["atoms"],
            "edges": sk.get("edges", 0), "faces": sk.get("triangles", 0),
            "slabs": g["m2"]["slabs"],
            "no_tangent": envelope.get("slabs_without_tangent_triangles", 0),
            "d": g["min_depth"], "depth": g["depth"], "m2_v": g["m2"]["vertices"],
            "components": g["m2"]["components"], "genus": g["m2"]["genus"],
            "orig_components": info["components"], "orig_genus": info["genus"],
            "h_m2_g": dg["hausdorff_pct"], "leaf": 100 * leaf / d["diagonal"],
            "h_m2_o": d["hausdorff_pct"], "rms_m2_o": d["rms_pct"],
            "folds": g["m2"]["intersecting_pairs_after_repair"],
            "degenerate": g["m2"]["degenerate_after_repair"],
            "closed_oriented": g["m2"]["closed"] and g["m2"]["oriented"],
            "hit_max_depth": g["hit_max_depth"],
            "seconds": g["seconds"]["garbing"], "peak_mb": g["peak_memory_mb"]})
    return rows


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(H.ROOT, "build"))
    ap.add_argument("--models", help="comma-separated subset of: " + ", ".join(J.TABLE1_MODELS))
    ap.add_argument("--quick", action="store_true", help="the three small models")
    ap.add_argument("--jobs", type=int, default=os.cpu_count(), help="parallel jobs")
    ap.add_argument("--results", help="write the results here instead of results/")
    args = ap.parse_args(argv)
    names = args.models.split(",") if args.models else (
        J.QUICK_MODELS if args.quick else J.TABLE1_MODELS)
    unknown = [n for n in names if n not in J.TABLE1_MODELS]
    if unknown:
        H.die("unknown model(s): %s" % ", ".join(unknown), "medial_meshes")
    out = os.path.abspath(args.results) if args.results else H.RESULTS
    os.makedirs(out, exist_ok=True)
    work = os.path.join(os.path.abspath(args.build), "experiments-work")
    start = time.time()
    jobs = [("medial mesh " + n, medial_mesh_job, (args.build, work, n)) for n in names]
    results = H.run_pool(jobs, args.jobs, H.log)
    rows = [r for n in names for r in results["medial mesh " + n]]
    H.write_csv(os.path.join(out, "medial_meshes.csv"), rows, COLUMNS)
    command = "experiments/medial_meshes.py" + (" --models " + args.models if args.models else "") + (
        " --quick" if args.quick and not args.models else "")
    prose = (
        "Each reference model's medial mesh (`skeletonize --connectivity` with the documented "
        "sampling: the regular-triangulation edges and triangles inside the object) garbed as "
        "its envelope (G = balls, a cone per edge, a slab per face; `garb --primitives ma`, "
        "the default for such files), and the same atoms garbed alone (`--primitives rt`, the "
        "paper's path). H(M2, G) is two-sided, against each row's own G (`evaluate atoms`); the "
        "leaf side is the octree's at depth d. Distances in %% of the original's bounding-box "
        "diagonal; seconds of the garbing alone (no file I/O), 2 jobs at a time on 2 cores.\n\n"
        "Command: `%s` (%.0f s)." % (command, time.time() - start))
    text = "# Medial meshes: the envelope of balls, cones and slabs\n\n" + prose + "\n\n" + \
        H.markdown_table(rows, COLUMNS, HEADERS) + "\n"
    H.write_atomically(os.path.join(out, "medial_meshes.md"), text)
    H.log("wrote %s/medial_meshes.{csv,md}" % out)


if __name__ == "__main__":
    main(sys.argv[1:])
