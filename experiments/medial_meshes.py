#!/usr/bin/python3
"""Medial meshes: garb each medial mesh as its envelope (balls, cones, slabs), against OpenVDB.

Two families of medial meshes:
- each reference model's `skeletonize --connectivity` medial mesh (the documented sampling: the
  regular-triangulation edges and triangles inside the object), dense: 60-10,000 atoms;
- analytic ones from `models generate medial-*`, sparse: 2-40 atoms, as Q-MAT writes them.

For each: garb (the envelope, `--primitives ma`) -> evaluate against its own envelope G and,
for reference models, the original; the OpenVDB baseline of the same envelope (its exact signed
distance sampled, `evaluate vdb`) at M2's vertex count, measured the same way, and the vertex
count OpenVDB needs to come as close to G as M2; the same atoms garbed alone (`--primitives rt`,
the paper's path) for comparison. Times and peak memory are taken afterwards, one program at a
time: medians of 3 runs. Writes results/medial_meshes.{csv,md,png} and
results/medial_meshes_renders.png.

Usage: experiments/medial_meshes.py [--build build] [--models a,b] [--quick] [--jobs N] [--scheduler ADDRESS]
       [--results DIR]
"""
import argparse
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import jobs as J     # noqa: E402

# Analytic medial meshes (`models generate SHAPE`) and their envelope's (components, genus).
ANALYTIC = {
    "medial-capsule": (1, 0),
    "medial-slab": (1, 0),
    "medial-ring": (1, 1),
    "medial-disc": (1, 0),
    "medial-sheets": (1, 0),
    "medial-hand": (1, 0),
}
ALL_SETS = J.TABLE1_MODELS + list(ANALYTIC)
QUICK_SETS = J.QUICK_MODELS + ["medial-ring", "medial-hand"]
TIMING_RUNS = 3

COLUMNS = ["set", "kind", "atoms", "edges", "faces", "slabs", "no_tangent", "d", "depth", "m2_v",
           "components", "genus", "expected_components", "expected_genus", "h_m2_g", "leaf",
           "h_m2_o", "h_g_o", "folds", "seconds", "peak_mb", "vdb_v", "vdb_components", "vdb_genus",
           "vdb_h_g", "vdb_h_o", "vdb_seconds", "vdb_peak_mb", "vdb_over_garbing_s",
           "vdb_over_garbing_mb", "vdb_same_h_v", "vdb_same_h_seconds", "rt_m2_v", "rt_components",
           "rt_genus", "rt_h_m2_g", "rt_h_m2_o", "rt_seconds"]
ENVELOPE = ["set", "atoms", "edges", "faces", "d", "depth", "m2_v", "components", "genus",
            "expected_components", "expected_genus", "h_m2_g", "leaf", "h_m2_o", "h_g_o", "folds"]
ENVELOPE_HEADERS = ["medial mesh", "atoms", "edges", "faces", "d", "depth", "M2 V", "components",
                    "genus", "expected components", "expected genus", "H(M2, G) %",
                    "leaf side %", "H(M2, O) %", "H(G, O) %", "folds"]
BASELINE = ["set", "m2_v", "seconds", "peak_mb", "vdb_v", "vdb_components", "vdb_genus",
            "h_m2_g", "vdb_h_g", "h_m2_o", "vdb_h_o", "vdb_seconds", "vdb_peak_mb",
            "vdb_over_garbing_s", "vdb_over_garbing_mb", "vdb_same_h_v", "vdb_same_h_seconds"]
BASELINE_HEADERS = ["medial mesh", "M2 V", "garbing s", "garbing MB", "OpenVDB V",
                    "OpenVDB components", "OpenVDB genus", "H(M2, G) %", "H(OpenVDB, G) %",
                    "H(M2, O) %", "H(OpenVDB, O) %", "OpenVDB s", "OpenVDB MB",
                    "OpenVDB s / garbing s", "OpenVDB MB / garbing MB",
                    "OpenVDB V at H(M2, G)", "its OpenVDB s"]
ATOMS_ALONE = ["set", "m2_v", "rt_m2_v", "components", "rt_components", "genus", "rt_genus",
               "h_m2_o", "rt_h_m2_o", "rt_h_m2_g", "rt_seconds"]
ATOMS_ALONE_HEADERS = ["medial mesh", "envelope M2 V", "atoms alone M2 V", "envelope components",
                       "atoms alone components", "envelope genus", "atoms alone genus",
                       "envelope H(M2, O) %", "atoms alone H(M2, O) %",
                       "atoms alone H(M2, its G) %", "atoms alone garbing s"]


def make_medial_mesh(R, name):
    """The medial mesh of set `name` (a reference model's --connectivity, or an analytic shape):
    (path, original mesh or None, expected (components, genus), skeletonize report or {})."""
    mm = R.path(name, "medial_mesh.ma")
    if name in ANALYTIC:
        R.run("models", "generate", name, "-o", mm, label="models generate " + name)
        return mm, None, ANALYTIC[name], {}
    model = H.models_by_name()[name]
    original = R.model(name)
    info = R.run("models", "info", original, "--json")
    sk = R.run_stats("skeletonize", original, "-o", mm, *J.skeleton_args(model, "topology"),
                     "--connectivity", stats=R.path(name, "medial_mesh_skel.json"),
                     label="%s skeletonize --connectivity" % name)
    return mm, original, (info["components"], info["genus"]), sk


def measure(R, name, mesh, mm, original, primitives, diagonal, label):
    """H(mesh, G) (and the diagonal it is a percentage of), H(mesh, O) when there is an original,
    and the mesh's topology."""
    info = R.run("models", "info", mesh, "--json")
    out = {"components": info["components"], "genus": info["genus"], "vertices": info["vertices"]}
    if original:
        d = R.run("evaluate", "distance", mesh, original, "--json", label="%s distance" % label)
        out["h_o"] = d["hausdorff_pct"]
        diagonal = diagonal or d["diagonal"]
    args = ["--diagonal", diagonal] if diagonal else []
    dg = R.run("evaluate", "atoms", mesh, mm, "--primitives", primitives, *args, "--samples",
               J.atom_samples(info["vertices"]), "--json", label="%s to G" % label)
    out["h_g"] = dg["hausdorff_pct"]
    out["diagonal"] = dg["diagonal"]
    return out


def medial_mesh_job(build, work, name, primitive_sets=("ma", "rt"), baseline=True):
    """One medial mesh's row: garbed as its envelope (ma); OpenVDB of the envelope at M2's
    vertex count and at M2's distance to G (`baseline`); its atoms garbed alone (rt)."""
    R = H.Runner(build, work)
    mm, original, expected, sk = make_medial_mesh(R, name)
    row = {"set": name, "kind": "analytic" if name in ANALYTIC else "reference",
           "expected_components": expected[0], "expected_genus": expected[1]}
    for primitives in primitive_sets:
        m2 = R.path(name, "medial_mesh_%s.off" % primitives)
        g = R.run_stats("garb", mm, "-o", m2, "--primitives", primitives,
                        stats=R.path(name, "medial_mesh_%s_garb.json" % primitives),
                        label="%s garb %s" % (name, primitives))
        m = measure(R, name, m2, mm, original, primitives, None, "%s M2 %s" % (name, primitives))
        if primitives == "rt":
            row.update({"rt_m2_v": g["m2"]["vertices"], "rt_components": g["m2"]["components"],
                        "rt_genus": g["m2"]["genus"], "rt_h_m2_g": m["h_g"],
                        "rt_h_m2_o": m.get("h_o", ""), "rt_seconds": g["seconds"]["garbing"]})
            continue
        envelope = g["m2"].get("envelope", {})
        row.update({
            "atoms": g["atoms"], "edges": envelope.get("edges", sk.get("edges", 0)),
            "faces": envelope.get("faces", sk.get("triangles", 0)), "slabs": g["m2"]["slabs"],
            "no_tangent": envelope.get("slabs_without_tangent_triangles", 0),
            "d": g["min_depth"], "depth": g["depth"], "m2_v": g["m2"]["vertices"],
            "components": g["m2"]["components"], "genus": g["m2"]["genus"],
            "h_m2_g": m["h_g"], "diagonal": m["diagonal"],
            "leaf": 100 * g["root_side"] / 2 ** g["min_depth"] / m["diagonal"],
            "h_m2_o": m.get("h_o", ""),
            "folds": g["m2"]["intersecting_pairs_after_repair"],
            "degenerate": g["m2"]["degenerate_after_repair"],
            "closed_oriented": g["m2"]["closed"] and g["m2"]["oriented"],
            "hit_max_depth": g["hit_max_depth"],
            "seconds": g["seconds"]["garbing"], "peak_mb": g["peak_memory_mb"]})
    if baseline and "ma" in primitive_sets and original:
        # The envelope's own distance to the original (the medial mesh's error, apart from M2's).
        go = R.run("evaluate", "atoms", original, mm, "--primitives", "ma", "--diagonal",
                   row["diagonal"], "--json", label="%s G to O" % name)
        row["h_g_o"] = go["hausdorff_pct"]
    if baseline and "ma" in primitive_sets:
        vdb = R.path(name, "vdb_same_v.off")
        v = R.run("evaluate", "vdb", mm, "-o", vdb, "--primitives", "ma", "--match-vertices",
                  row["m2_v"], "--json", label="%s vdb --match-vertices" % name)
        m = measure(R, name, vdb, mm, original, "ma", row["diagonal"], "%s vdb" % name)
        row.update({"vdb_voxel": v["voxel"], "vdb_v": v["vertices"],
                    "vdb_components": m["components"], "vdb_genus": m["genus"],
                    "vdb_h_g": m["h_g"], "vdb_h_o": m.get("h_o", "")})
        # The voxel at which OpenVDB comes as close to G as M2 (its H in model units).
        same = R.run("evaluate", "vdb", mm, "-o", R.path(name, "vdb_same_h.off"), "--primitives",
                     "ma", "--match-envelope", row["h_m2_g"], "--diagonal", row["diagonal"],
                     "--json", label="%s vdb --match-envelope" % name)
        row.update({"vdb_same_h_voxel": same["voxel"], "vdb_same_h_v": same["vertices"]})
    return [row]


def timings(R, rows, progress):
    """Garbing and OpenVDB seconds (medians of TIMING_RUNS) and peak memory, one program at a
    time, into the rows."""
    for row in rows:
        name = row["set"]
        progress("timing %s" % name)
        mm = R.path(name, "medial_mesh.ma")
        runs = [R.run_stats("garb", mm, "-o", R.path(name, "time_m2.off"), "--primitives", "ma",
                            stats=R.path(name, "time_garb_%d.json" % k)) for k in range(TIMING_RUNS)]
        row["seconds"] = statistics.median(g["seconds"]["garbing"] for g in runs)
        row["peak_mb"] = max(g["peak_memory_mb"] for g in runs)
        for prefix, voxel in (("vdb", row["vdb_voxel"]), ("vdb_same_h", row["vdb_same_h_voxel"])):
            v = R.run("evaluate", "vdb", mm, "-o", R.path(name, "time_vdb.off"), "--primitives",
                      "ma", "--voxel", voxel, "--repeat", TIMING_RUNS, "--json")
            row[prefix + "_seconds"] = v["seconds"]["median"]
            if prefix == "vdb":
                row["vdb_peak_mb"] = v["peak_memory_mb"]
        row["vdb_over_garbing_s"] = row["vdb_seconds"] / row["seconds"]
        row["vdb_over_garbing_mb"] = row["vdb_peak_mb"] / row["peak_mb"]


def plot(out, rows):
    """medial_meshes.png: garbing against OpenVDB at the same vertex count, per medial mesh:
    seconds, peak memory, and the distance to the envelope."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from figures import save_figure

    names = [r["set"] for r in rows]
    x = range(len(rows))
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for ax, (key, vkey, title) in zip(axes, (
            ("seconds", "vdb_seconds", "seconds (median of %d)" % TIMING_RUNS),
            ("peak_mb", "vdb_peak_mb", "peak memory (MB)"),
            ("h_m2_g", "vdb_h_g", "H(mesh, envelope) (% diag)"))):
        ax.bar([i - 0.2 for i in x], [r[key] for r in rows], 0.4, label="garbing M2")
        ax.bar([i + 0.2 for i in x], [r[vkey] for r in rows], 0.4, label="OpenVDB, same V")
        ax.set_yscale("log")
        ax.set_xticks(list(x))
        ax.set_xticklabels(names, rotation=60, ha="right", fontsize=8)
        ax.set_title(title)
        ax.grid(alpha=0.3, axis="y", which="both")
    axes[0].legend()
    save_figure(plt, fig, os.path.join(out, "medial_meshes.png"))


RENDERS = ["medial-hand", "medial-disc", "medial-sheets", "medial-ring", "torus"]


def renders(out, build, work, names):
    """medial_meshes_renders.png: per medial mesh, its envelope as `render` draws it (balls,
    cones, slab triangles), M2, and OpenVDB's mesh at M2's vertex count, one camera per row."""
    from figures import CELL, fresh_view, montage
    R = H.Runner(build, work)
    rows = [n for n in RENDERS if n in names]
    if not rows:
        return
    jobs, cells = [], []
    for n in rows:
        view = fresh_view(R, n + "_medial_view.json")
        cells.append(J.render(R, [R.path(n, "medial_mesh.ma")],
                              R.path("figures", n + "_envelope.png"), view, CELL))
        for tag, mesh in (("garbing", "medial_mesh_ma.off"), ("openvdb", "vdb_same_v.off")):
            png = R.path("figures", "%s_medial_%s.png" % (n, tag))
            jobs.append(("render %s %s" % (n, tag), J.render_job,
                         (build, work, [R.path(n, mesh)], view, png, CELL)))
            cells.append(png)
    H.run_pool(jobs, os.cpu_count(), lambda m: None)
    montage(cells, os.path.join(out, "medial_meshes_renders.png"), 3,
            ["Envelope (render of the .ma)", "Garbing M2", "OpenVDB, M2's vertex count"], rows)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(H.ROOT, "build"))
    ap.add_argument("--models", help="comma-separated subset of: " + ", ".join(ALL_SETS))
    ap.add_argument("--quick", action="store_true", help="three small models, two analytic sets")
    ap.add_argument("--jobs", type=int, default=os.cpu_count(), help="parallel jobs")
    ap.add_argument("--scheduler", help="run the jobs on the Dask cluster of this scheduler address "
                    "(host:port; default: a local process pool of --jobs)")
    ap.add_argument("--results", help="write the results here instead of results/")
    args = ap.parse_args(argv)
    args.build = os.path.abspath(args.build)  # the jobs may run elsewhere (--scheduler)
    names = args.models.split(",") if args.models else (QUICK_SETS if args.quick else ALL_SETS)
    unknown = [n for n in names if n not in ALL_SETS]
    if unknown:
        H.die("unknown medial mesh(es): %s" % ", ".join(unknown), "medial_meshes")
    out = os.path.abspath(args.results) if args.results else H.RESULTS
    os.makedirs(out, exist_ok=True)
    work = os.path.join(os.path.abspath(args.build), "experiments-work")
    start = time.time()
    try:
        jobs = [("medial mesh " + n, medial_mesh_job, (args.build, work, n)) for n in names]
        results = H.run_pool(jobs, args.jobs, H.log, args.scheduler)
        rows = [r for n in names for r in results["medial mesh " + n]]
        timings(H.Runner(args.build, work), rows, H.log)
    except H.StepError as e:
        H.die(str(e), "medial_meshes")
    H.write_csv(os.path.join(out, "medial_meshes.csv"), rows, COLUMNS)
    plot(out, rows)
    try:
        renders(out, args.build, work, names)
    except H.StepError as e:
        H.die(str(e), "medial_meshes")
    command = "experiments/medial_meshes.py" + (" --models " + args.models if args.models else "") + (
        " --quick" if args.quick and not args.models else "")
    text = (
        "# Medial meshes: the envelope of balls, cones and slabs\n\n"
        "Each medial mesh is garbed as its envelope G (`garb --primitives ma`, the default for "
        "files with edges or faces: every ball, a cone per edge, a slab per face). Reference "
        "sets: each reference model's `skeletonize --connectivity` medial mesh (the documented "
        "sampling); analytic sets: `models generate medial-*`, whose envelope's topology is known. "
        "Distances in %% of the original's bounding-box diagonal (analytic sets: M2's); H two-sided "
        "(`evaluate atoms` against G, `evaluate distance` against the original O); the leaf side "
        "is the octree's at depth d. Expected topology: the original's, or the analytic "
        "envelope's.\n\n"
        "Command: `%s` (%.0f s, %d jobs on %d cores; times one program at a time, medians of %d "
        "runs, 2 threads).\n\n## The envelope garbed\n\n%s\n\n"
        "## Against OpenVDB\n\n"
        "OpenVDB: the envelope's exact signed distance sampled in a narrow band of its sparse "
        "grid and meshed by `volumeToMesh` (`evaluate vdb --primitives ma`), at the voxel whose "
        "mesh has M2's vertex count (`--match-vertices`), and at the voxel whose mesh is as close "
        "to G as M2 (`--match-envelope`). Seconds: the garbing without file I/O (`garb --stats`), "
        "OpenVDB's sampling and meshing (`--repeat %d`); peak memory: each program's peak "
        "resident size. Ratios above 1: the garbing is faster or smaller.\n\n%s\n\n"
        "![garbing against OpenVDB](medial_meshes.png)\n\n"
        "![envelope, garbing and OpenVDB](medial_meshes_renders.png)\n\n"
        "## The atoms alone\n\n"
        "The same atoms garbed without their edges and faces (`--primitives rt`: balls and "
        "regular-triangulation cones, the paper's path).\n\n%s\n" % (
            command, time.time() - start, args.jobs, os.cpu_count(), TIMING_RUNS,
            H.markdown_table(rows, ENVELOPE, ENVELOPE_HEADERS), TIMING_RUNS,
            H.markdown_table(rows, BASELINE, BASELINE_HEADERS),
            H.markdown_table(rows, ATOMS_ALONE, ATOMS_ALONE_HEADERS)))
    H.write_atomically(os.path.join(out, "medial_meshes.md"), text)
    H.log("wrote %s/medial_meshes.{csv,md,png}" % out)


if __name__ == "__main__":
    main(sys.argv[1:])
