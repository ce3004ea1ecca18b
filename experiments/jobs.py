"""The reproduction's jobs: one function per job (model x parameters), run on a local process
pool by reproduce.py, each returning the programs' reports as plain data; and the timings of
Table 2, taken afterwards one program at a time.

A job gets the build folder and a work folder, never a Runner, so that it pickles.
"""
import statistics

import harness as H

TABLE1_MODELS = ["sphere", "torus", "knot", "eight", "hand", "homer", "anchor_dense", "bumpy_torus"]
QUICK_MODELS = ["sphere", "torus", "eight"]
FIGURE11 = ["hand", "homer", "anchor_dense"]
SWEEP = ["homer", "torus"]
ATOM_SAMPLES = 50000   # evaluate atoms, per side
MATCH_SAMPLES = 200000  # distance samples inside the OpenVDB Hausdorff search

CONE_FILTERS = [0.0, 0.5, 0.8, 0.9, 0.95]
# (circle-ratio filter, collar limit in rc / 8; 0 = none): every filter without a collar limit,
# then collar limits around the default (0.9, 1).
CONE_SETTINGS = [(f, 0) for f in CONE_FILTERS] + [(0.9, 0.5), (0.9, 1), (0.9, 2), (0.0, 1)]

# POV-Ray 3.7 at more than one thread now and then shades a few pixels differently from run to
# run (measured: the cube's --refine 2 figure, 3 renders in 14 at 2 threads, 3 pixels off by
# 1/255; none in 20 at one thread). The renders run as parallel jobs anyway.
RENDER_THREADS = ("--threads", 1)


def skeleton_args(model, kind):
    """skeletonize options for an atom set: 'paper' (vertex poles as they come), 'topology' (the
    documented sampling, clamped when that keeps the topology), 'simplify' (the sampling
    `skeletonize --simplify` starts from: the model's "simplify" entry, else 'topology'),
    'dense' (clamped + 20k)."""
    if kind == "paper":
        return []
    s = model["skeleton"]
    if kind == "simplify":
        s = model.get("simplify", s)
        kind = "topology"
    if kind == "topology":
        return ["--samples", str(s["samples"])] + (["--clamp-radius"] if s["clamp"] else [])
    return ["--samples", "20000", "--clamp-radius"]


def atoms_of(R, name, file_name, kind="paper"):
    """Skeletonizes reference model `name` into R.path(name, file_name) (atom set `kind`, see
    skeleton_args); returns the original's path and the atoms'."""
    original = R.model(name)
    atoms = R.path(name, file_name)
    R.run("skeletonize", original, "-o", atoms, *skeleton_args(H.models_by_name()[name], kind))
    return original, atoms


def atom_samples(vertices):
    """`evaluate atoms` samples per side for a mesh of `vertices` vertices."""
    return max(ATOM_SAMPLES, 2 * vertices + 1000)


def garb_and_measure(R, name, original, atoms, tag):
    """garb (with --check-topology: M2 against the union of the balls, in its stats) + distances
    to the original and to G; returns a row of numbers."""
    m2 = R.path(name, tag + "_m2.off")
    g = R.run_stats("garb", atoms, "-o", m2, "--m1", R.path(name, tag + "_m1.off"),
                    "--check-topology", stats=R.path(name, tag + "_garb.json"),
                    label="%s garb %s" % (name, tag))
    d = R.run("evaluate", "distance", m2, original, "--json", label="%s distance %s" % (name, tag))
    dg = R.run("evaluate", "atoms", m2, atoms, "--diagonal", d["diagonal"], "--samples",
               atom_samples(g["m2"]["vertices"]), "--json", label="%s atoms %s" % (name, tag))
    return {"m2": m2, "garb": g, "dist": d, "to_g": dg}


def model_job(build, work, name, quick):
    """Table 1 row and its baselines for one model (paper atoms), plus the skeleton study."""
    model = H.models_by_name()[name]
    R = H.Runner(build, work)
    original = R.model(name)
    out = {"name": name, "paper_row": model["paper_row"], "stand_in": model.get("stand_in", False)}
    out["original"] = R.run("models", "info", original, "--json")
    diag = out["original"]["bbox_diagonal"]

    # Atom sets and the skeleton's own error H(G, O).
    out["atom_sets"] = {}
    for kind in (["paper"] if quick else ["paper", "topology"] + (["dense"] if name == "hand" else [])):
        atoms = R.path(name, kind + ".ma")
        sk = R.run_stats("skeletonize", original, "-o", atoms, *skeleton_args(model, kind),
                         stats=R.path(name, kind + "_skel.json"), label="%s skeletonize %s" % (name, kind))
        go = R.run("evaluate", "atoms", original, atoms, "--samples", atom_samples(out["original"]["vertices"]),
                   "--json", label="%s G vs original %s" % (name, kind))
        res = garb_and_measure(R, name, original, atoms, kind)
        out["atom_sets"][kind] = {"atoms": atoms, "skeleton": sk, "g_vs_original": go, **res}
    paper = out["atom_sets"]["paper"]
    atoms = paper["atoms"]
    m2_vertices = paper["garb"]["m2"]["vertices"]

    # Baselines on the paper atoms.
    base = {}
    skin = R.path(name, "skin.off")
    base["skin"] = {"run": R.run("evaluate", "skin", atoms, "-o", skin, "--json"), "mesh": skin}
    union = R.path(name, "union.off")
    base["union"] = {"run": R.run("evaluate", "union", atoms, "-o", union, "--json"), "mesh": union}
    vdbv = R.path(name, "vdb_vertices.off")
    base["vdb_vertices"] = {"run": R.run("evaluate", "vdb", atoms, "-o", vdbv, "--match-vertices",
                                         m2_vertices, "--json"), "mesh": vdbv}
    vdbh = R.path(name, "vdb_hausdorff.off")
    base["vdb_hausdorff"] = {"run": R.run("evaluate", "vdb", atoms, "-o", vdbh, "--match-hausdorff",
                                          "%.6g" % paper["dist"]["hausdorff_pct"], original,
                                          "--samples", MATCH_SAMPLES, "--json"), "mesh": vdbh}
    for key, b in base.items():
        b["dist"] = R.run("evaluate", "distance", b["mesh"], original, "--json", label="%s distance %s" % (name, key))
    out["baselines"] = base

    # Defects and smoothness of every output.
    meshes = {"garbing": paper["m2"], **{k: b["mesh"] for k, b in base.items()}}
    out["check"] = {k: R.run("evaluate", "check", m, "--json") for k, m in meshes.items()}
    out["normals"] = {k: R.run("evaluate", "normals", m, original, "--samples", 200000, "--json")
                      for k, m in meshes.items() if k != "vdb_hausdorff"}
    out["diagonal"] = diag
    return out


def distance_row(R, mesh, original, /, **row):
    """`row` (which may have a `mesh` of its own) with the Hausdorff and RMS distances (% of the
    diagonal) of `mesh` to `original`; returns it and the distance report."""
    dist = R.run("evaluate", "distance", mesh, original, "--json")
    return dict(row, hausdorff_pct=dist["hausdorff_pct"], rms_pct=dist["rms_pct"]), dist


def sweep_job(build, work, name):
    """Depth sweep and accuracy vs size for one model (paper atoms)."""
    R = H.Runner(build, work)
    original, atoms = atoms_of(R, name, "sweep.ma")
    base = R.run_stats("garb", atoms, "-o", R.path(name, "sweep_auto.off"), stats=R.path(name, "sweep_auto.json"))
    d_auto = base["min_depth"]
    depths = sorted(set(range(4, 9)) | {d for d in range(d_auto - 2, d_auto + 3) if 3 <= d <= 8})
    rows = []
    for d in depths:
        m2 = R.path(name, "sweep_d%d.off" % d)
        g = R.run_stats("garb", atoms, "-o", m2, "--min-depth", d, stats=R.path(name, "sweep_d%d.json" % d))
        row, dist = distance_row(R, m2, original, model=name, method="garbing", depth=d, auto=d == d_auto,
                                 vertices=g["m2"]["vertices"])
        rows.append(dict(row, seconds=g["seconds"]["garbing"]))
    diag = dist["diagonal"]
    for k in (100, 200, 400, 800):
        m = R.path(name, "vdb_%d.off" % k)
        v = R.run("evaluate", "vdb", atoms, "-o", m, "--voxel", diag / k, "--json")
        rows.append(distance_row(R, m, original, model=name, method="openvdb", depth="diag/%d" % k,
                                 vertices=v["vertices"])[0])
    u = R.run("evaluate", "union", atoms, "-o", R.path(name, "union_sweep.off"), "--json")
    rows.append(distance_row(R, R.path(name, "union_sweep.off"), original, model=name, method="union of balls",
                             depth="", vertices=u["vertices"])[0])
    return rows


def figure11_job(build, work, name):
    """Dual vs no-dual migration: intersecting triangle pairs before repair."""
    R = H.Runner(build, work)
    atoms = atoms_of(R, name, "fig11.ma")[1]
    row = {"model": name}
    for tag, args in (("dual", []), ("no_dual", ["--no-dual"])):
        g = R.run_stats("garb", atoms, "-o", R.path(name, "fig11_%s.off" % tag), *args,
                        stats=R.path(name, "fig11_%s.json" % tag))
        row[tag + "_vertices"] = g["m2"]["vertices"]
        row[tag + "_folds_before"] = g["m2"]["intersecting_pairs_before_repair"]
        row[tag + "_folds_after"] = g["m2"]["intersecting_pairs_after_repair"]
    return row


def figure14_job(build, work):
    """The cube: M2 with --refine 0, 1, 2."""
    R = H.Runner(build, work)
    original, atoms = atoms_of(R, "cube", "fig14.ma", "topology")
    rows = []
    for k in (0, 1, 2):
        m = R.path("cube", "fig14_refine%d.off" % k)
        g = R.run_stats("garb", atoms, "-o", m, "--refine", k, stats=R.path("cube", "fig14_%d.json" % k))
        rows.append(distance_row(R, m, original, refine=k, vertices=g["m2"]["vertices"], faces=g["m2"]["faces"],
                                 mesh=m)[0])
    return rows


def cone_filter_job(build, work, name):
    """H(G, O) of one model's atoms (documented sampling) for several cone filters and none."""
    R = H.Runner(build, work)
    original, atoms = atoms_of(R, name, "cones.ma", "topology")
    info = R.run("models", "info", original, "--json")
    rows = []
    for setting in CONE_SETTINGS + [None]:
        args = ["--cones", "none"] if setting is None else ["--cone-filter", setting[0], "--cone-collar", setting[1]]
        a = R.run("evaluate", "atoms", original, atoms, *args, "--samples", atom_samples(info["vertices"]), "--json")
        rows.append({"model": name, "cone_filter": "spheres only" if setting is None else setting[0],
                     "cone_collar": "" if setting is None else setting[1], "cones": a["cones"],
                     "h_g_o": round(a["hausdorff_pct"], 3), "rms_g_o": round(a["rms_pct"], 3)})
    return rows


def render(R, inputs, png, view, size, flat=False):
    """One POV-Ray image of `inputs` through the view file `view` (written if missing)."""
    R.run("render", *inputs, "-o", png, "--view", view, *(["--flat"] if flat else []),
          "--width", size[0], "--height", size[1], *RENDER_THREADS)
    return png


def render_job(build, work, inputs, view, png, size):
    return render(H.Runner(build, work), inputs, png, view, size)


# --- timings (Table 2): one program at a time, medians of 3 -------------------------------------

def timings(R, rows, progress):
    out = []
    for row in rows:
        name = row["name"]
        atoms = row["atom_sets"]["paper"]["atoms"]
        progress("timing %s" % name)
        garb = []
        for k in range(3):
            g = R.run_stats("garb", atoms, "-o", R.path(name, "time_m2.off"), stats=R.path(name, "time_garb_%d.json" % k))
            garb.append(g["seconds"]["garbing"])
        skin = R.run("evaluate", "skin", atoms, "-o", R.path(name, "time_skin.off"), "--repeat", 3, "--json")
        union = R.run("evaluate", "union", atoms, "-o", R.path(name, "time_union.off"), "--repeat", 3, "--json")
        voxel = row["baselines"]["vdb_hausdorff"]["run"]["voxel"]
        vdb = R.run("evaluate", "vdb", atoms, "-o", R.path(name, "time_vdb.off"), "--voxel", voxel,
                    "--repeat", 3, "--json")
        out.append({"name": name, "garb": statistics.median(garb), "skin": skin["seconds"]["median"],
                    "union": union["seconds"]["median"], "vdb": vdb["seconds"]["median"], "voxel": voxel,
                    "peak_mb": row["atom_sets"]["paper"]["garb"]["peak_memory_mb"]})
    return out
