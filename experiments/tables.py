"""The reproduction's tables: rows built from the jobs' reports (jobs.py), and their CSV and
Markdown files in the results folder.

Distances are in % of the original's bounding-box diagonal, rounded to 3 decimals.
"""
import os

import harness as H
from jobs import CONE_SETTINGS

TABLE1_COLUMNS = ["model", "source", "orig_v", "orig_f", "atoms", "m2_v", "m2_f", "h", "rms", "skin_v", "skin_f",
                  "skin_h", "skin_rms", "d", "rc", "cones", "fallbacks", "folds_repaired", "peak_mb", "h_m2_g",
                  "h_g_o"]
BASELINE_COLUMNS = ["model", "method", "v", "f", "h", "rms", "components", "genus", "intersecting_pairs",
                    "degenerate"]
SMOOTHNESS_COLUMNS = ["model", "method", "mean_deg", "p95_deg"]
ATOMS_COLUMNS = ["model", "atoms_set", "atoms", "union_topology_ok", "h_g_o", "rms_g_o", "h_m2_g", "rms_m2_g",
                 "h_m2_o", "rms_m2_o", "m2_v", "m2_genus", "m2_components"]
SWEEP_COLUMNS = ["model", "method", "depth", "auto", "vertices", "hausdorff_pct", "rms_pct", "seconds"]
FIGURE14_COLUMNS = ["refine", "vertices", "faces", "hausdorff_pct", "rms_pct"]
CONE_COLUMNS = ["model", "cone_filter", "cone_collar", "cones", "h_g_o", "rms_g_o"]
CONE_SUMMARY_COLUMNS = ["cone_filter", "cone_collar", "mean_h_g_o", "mean_rms_g_o", "worst_h_g_o"]
BASELINES = (("garbing", "garbing"), ("skin", "CGAL skin"), ("union", "CGAL union of balls"),
             ("vdb_vertices", "OpenVDB, same V"), ("vdb_hausdorff", "OpenVDB, same H"))


def pct(x):
    return round(x, 3)


def table1(rows, paper):
    out = []
    for r in rows:
        p = paper["table1"].get(r["paper_row"], {})
        a = r["atom_sets"]["paper"]
        g, d, skin = a["garb"], a["dist"], r["baselines"]["skin"]
        label = r["paper_row"] + (" (stand-in: %s)" % r["name"] if r["stand_in"] else "")
        out.append({
            "model": label, "source": "ours",
            "orig_v": r["original"]["vertices"], "orig_f": r["original"]["faces"],
            "atoms": g["atoms"], "m2_v": g["m2"]["vertices"], "m2_f": g["m2"]["faces"],
            "h": pct(d["hausdorff_pct"]), "rms": pct(d["rms_pct"]),
            "skin_v": skin["run"]["vertices"], "skin_f": skin["run"]["faces"],
            "skin_h": pct(skin["dist"]["hausdorff_pct"]), "skin_rms": pct(skin["dist"]["rms_pct"]),
            "d": g["min_depth"], "rc": round(g["rc"], 5), "cones": g["m2"]["cones"],
            "fallbacks": g["m2"]["fallback_zero_direction"] + g["m2"]["fallback_missed"] + g["m2"]["fallback_too_far"],
            "folds_repaired": "%d->%d" % (g["m2"]["intersecting_pairs_before_repair"], g["m2"]["intersecting_pairs_after_repair"]),
            "peak_mb": round(g["peak_memory_mb"], 1),
            "h_m2_g": pct(a["to_g"]["hausdorff_pct"]), "h_g_o": pct(a["g_vs_original"]["hausdorff_pct"] * 1.0),
        })
        if p:
            out.append({"model": r["paper_row"], "source": "paper", **p})
    return out


def baselines_table(rows):
    out = []
    for r in rows:
        for key, label in BASELINES:
            c = r["check"][key]
            if key == "garbing":
                dist = r["atom_sets"]["paper"]["dist"]
                size = r["atom_sets"]["paper"]["garb"]["m2"]
            else:
                dist = r["baselines"][key]["dist"]
                size = r["baselines"][key]["run"]
            out.append({"model": r["name"], "method": label, "v": size["vertices"], "f": size["faces"],
                        "h": pct(dist["hausdorff_pct"]), "rms": pct(dist["rms_pct"]),
                        "components": c.get("components"), "genus": c.get("genus"),
                        "intersecting_pairs": c["intersecting_pairs"],
                        "degenerate": c["degenerate_triangles"]})
    return out


def table2(rows, times, paper):
    out = []
    for t in times:
        r = next(x for x in rows if x["name"] == t["name"])
        p = paper["table2"].get(r["paper_row"], {})
        out.append({"model": r["paper_row"], "garbing_s": round(t["garb"], 3), "skin_s": round(t["skin"], 3),
                    "union_s": round(t["union"], 3), "openvdb_s": round(t["vdb"], 3),
                    "skin_over_garbing": round(t["skin"] / t["garb"], 2) if t["garb"] > 0 else "",
                    "openvdb_over_garbing": round(t["vdb"] / t["garb"], 2) if t["garb"] > 0 else "",
                    "paper_skin_over_garbing": round(p["skin_s"] / p["garb_s"], 2) if p else "",
                    "garbing_peak_mb": t["peak_mb"]})
    return out


def atoms_table(rows):
    out = []
    for r in rows:
        for kind, a in r["atom_sets"].items():
            out.append({"model": r["name"], "atoms_set": kind, "atoms": a["garb"]["atoms"],
                        "union_topology_ok": a["skeleton"].get("union_matches_mesh"),
                        "h_g_o": pct(a["g_vs_original"]["hausdorff_pct"]), "rms_g_o": pct(a["g_vs_original"]["rms_pct"]),
                        "h_m2_g": pct(a["to_g"]["hausdorff_pct"]), "rms_m2_g": pct(a["to_g"]["rms_pct"]),
                        "h_m2_o": pct(a["dist"]["hausdorff_pct"]), "rms_m2_o": pct(a["dist"]["rms_pct"]),
                        "m2_v": a["garb"]["m2"]["vertices"], "m2_genus": a["garb"]["m2"]["genus"],
                        "m2_components": a["garb"]["m2"]["components"]})
    return out


def smoothness_table(rows):
    out = []
    for r in rows:
        for key, n in r["normals"].items():
            out.append({"model": r["name"], "method": key, "mean_deg": round(n["mean_deg"], 2),
                        "p95_deg": round(n["p95_deg"], 2)})
    return out


def cone_summary(rows):
    """Mean over models of H(G, O) and RMS per cone setting: the default is chosen on these."""
    out = []
    for f, c in CONE_SETTINGS + [("spheres only", "")]:
        sel = [r for r in rows if r["cone_filter"] == f and r["cone_collar"] == c]
        out.append({"cone_filter": f, "cone_collar": c,
                    "mean_h_g_o": round(sum(r["h_g_o"] for r in sel) / len(sel), 3),
                    "mean_rms_g_o": round(sum(r["rms_g_o"] for r in sel) / len(sel), 3),
                    "worst_h_g_o": max(r["h_g_o"] for r in sel)})
    return out


def write_markdown(path, heading, prose, *parts):
    """A Markdown file: the heading (a line, or a tuple of lines), the prose lines, then every part
    (a table or a line), each block after a blank line."""
    lines = list(heading if isinstance(heading, tuple) else [heading]) + [""] + list(prose)
    for part in parts:
        lines += ["", part]
    H.write_atomically(path, "\n".join(lines + [""]))


def write_table(out, name, rows, columns, heading, prose, *more):
    """<name>.csv: the rows; <name>.md: the heading, the prose, the rows' table and then `more`."""
    H.write_csv(os.path.join(out, name + ".csv"), rows, columns)
    write_markdown(os.path.join(out, name + ".md"), heading, prose, H.markdown_table(rows, columns), *more)


def write_tables(out, rows, times, sweep_rows, fig11, fig14, paper, command):
    """Writes table1, table1_baselines, table2, smoothness, atoms and, when they ran, the depth
    sweep, figure11.md and figure14.csv into the folder `out`; returns Table 1's and Table 2's rows."""
    t1 = table1(rows, paper)
    extra = baselines_table(rows)
    H.write_csv(os.path.join(out, "table1_baselines.csv"), extra, BASELINE_COLUMNS)
    write_table(out, "table1", t1, TABLE1_COLUMNS,
                "# Table 1: garbing against CGAL's skin surface (paper atoms: poles of the vertices)", [
                    "Written by `%s`. Distances in %% of the original's bounding-box diagonal (`evaluate distance`," % command,
                    "Metro sampling, max(1e6, 10 (V_A + V_B)) samples per side). `ours` rows beside the paper's; stand-ins",
                    "are marked. d: minimal depth; rc: characteristic radius; fallbacks: closest-point fallbacks of the",
                    "migration; folds: intersecting triangle pairs before -> after repair; h_m2_g: Hausdorff from M2 to G",
                    "(the mesher's own error); h_g_o: from G to the original (the atoms' own error)."],
                "## Extra baselines, with `evaluate check` defects",
                "OpenVDB at the voxel giving M2's vertex count (same V) and at the voxel giving M2's Hausdorff (same H).",
                H.markdown_table(extra, BASELINE_COLUMNS))
    t2 = table2(rows, times, paper)
    write_table(out, "table2", t2, list(t2[0].keys()) if t2 else [],
                "# Table 2: times (seconds, medians of 3, one program at a time, 2 cores)", [
                    "Written by `%s`. Garbing: G + octree + M1 + M2 (`garb` stats, no file I/O); skin: CGAL" % command,
                    "`make_skin_surface_mesh_3` (shrink 0.5); union: CGAL union of balls; OpenVDB at the voxel matching",
                    "M2's Hausdorff. Ratios > 1: garbing is faster. The paper's ratio is from its own 2012 run."])
    write_table(out, "smoothness", smoothness_table(rows), SMOOTHNESS_COLUMNS,
                ("# Smoothness: angle between each output's facet normals and the original's normal at the",
                 "closest point (`evaluate normals`, degrees)"),
                ["Written by `%s`." % command])
    write_table(out, "atoms", atoms_table(rows), ATOMS_COLUMNS,
                "# How much error is the skeleton's and how much the mesher's", [
                    "Written by `%s`. Atom sets: `paper` = poles of the vertices as they come; `topology` = the" % command,
                    "documented sampling of experiments/models.json (clamped where that keeps the topology); `dense` =",
                    "clamped poles with 20,000 extra samples. h_g_o: G against the original (`evaluate atoms`, the",
                    "atoms' own error); h_m2_g: M2 against G (the mesher's); h_m2_o: M2 against the original."])
    if sweep_rows:
        H.write_csv(os.path.join(out, "depth_sweep.csv"), [r for r in sweep_rows if r["method"] == "garbing"],
                    SWEEP_COLUMNS)
        H.write_csv(os.path.join(out, "accuracy_vs_size.csv"), sweep_rows, SWEEP_COLUMNS)
    if fig11:
        write_markdown(os.path.join(out, "figure11.md"),
                       "# Figure 11: migrating the dual of M1 against migrating M1 itself (`garb --no-dual`)", [
                           "Written by `%s`. Intersecting triangle pairs right after migration (before repair) and" % command,
                           "after repair; paper atoms."],
                       H.markdown_table(fig11, list(fig11[0].keys())), "![dual vs no dual](figure11.png)")
    if fig14:
        H.write_csv(os.path.join(out, "figure14.csv"), fig14, FIGURE14_COLUMNS)
    return t1, t2


def write_cone_table(out, rows, command):
    """cone_filter.csv and cone_filter.md: H(G, O) per model and cone setting, after the means."""
    H.write_csv(os.path.join(out, "cone_filter.csv"), rows, CONE_COLUMNS)
    write_markdown(os.path.join(out, "cone_filter.md"), "# Which cones: H(G, O) against the cone filter", [
        "Written by `%s`. G = the union of the atoms' spheres and the cones of pairs adjacent in the" % command,
        "regular triangulation whose intersection circle has a radius of at least F times the smaller",
        "radius (`garb --cone-filter F`) and whose lateral surface stands off the crease of its two",
        "spheres by at most C rc / 8 (`--cone-collar C`, 0: no limit); atoms: the documented sampling",
        "of each model. `evaluate atoms` against the original, in % of its diagonal."],
        H.markdown_table(cone_summary(rows), CONE_SUMMARY_COLUMNS), H.markdown_table(rows, CONE_COLUMNS))
