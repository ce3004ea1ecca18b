"""The reproduction's pictures: the depth-sweep and accuracy-vs-size plots (matplotlib), and the
POV-Ray renders laid out by render/montage.py (Figures 11, 14 and 15)."""
import os
import subprocess

import harness as H
from jobs import render, render_job

FIGURE15 = ["hand", "knot", "eight", "anchor_dense", "homer", "bumpy_torus"]
CELL = (400, 300)  # pixels of one render


def save_figure(plt, fig, path):
    fig.tight_layout()
    fig.savefig(path + ".partial.png", dpi=110)
    os.replace(path + ".partial.png", path)
    plt.close(fig)


def plots(out, sweep_rows, paper):
    """depth_sweep.png (H, RMS and size against d, beside the paper's Monkey) and
    accuracy_vs_size.png (garbing, OpenVDB and union of balls by size), into the folder `out`."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    models = sorted({r["model"] for r in sweep_rows})
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    for m in models:
        g = [r for r in sweep_rows if r["model"] == m and r["method"] == "garbing"]
        d = [r["depth"] for r in g]
        axes[0].plot(d, [r["hausdorff_pct"] for r in g], "o-", label=m)
        axes[1].plot(d, [r["rms_pct"] for r in g], "o-", label=m)
        axes[2].semilogy(d, [r["vertices"] for r in g], "o-", label=m)
    p = paper["depth_sweep"]["Monkey"]
    axes[0].plot([x["d"] for x in p], [x["h"] for x in p], "k--", label="paper Monkey")
    axes[1].plot([x["d"] for x in p], [x["rms"] for x in p], "k--", label="paper Monkey")
    axes[2].semilogy([x["d"] for x in p], [x["m2_v"] for x in p], "k--", label="paper Monkey")
    for ax, t in zip(axes, ("Hausdorff (% diag)", "RMS (% diag)", "M2 vertices")):
        ax.set_xlabel("minimal depth d")
        ax.set_title(t)
        ax.grid(alpha=0.3)
    axes[0].legend()
    save_figure(plt, fig, os.path.join(out, "depth_sweep.png"))

    fig, axes = plt.subplots(1, len(models), figsize=(6 * len(models), 4.2))
    axes = axes if len(models) > 1 else [axes]
    for ax, m in zip(axes, models):
        for method, style in (("garbing", "o-"), ("openvdb", "s--"), ("union of balls", "^")):
            rs = sorted([r for r in sweep_rows if r["model"] == m and r["method"] == method], key=lambda r: r["vertices"])
            ax.loglog([r["vertices"] for r in rs], [r["hausdorff_pct"] for r in rs], style, label=method)
        ax.set_xlabel("vertices")
        ax.set_ylabel("Hausdorff to the original (% diag)")
        ax.set_title(m)
        ax.grid(alpha=0.3, which="both")
        ax.legend()
    save_figure(plt, fig, os.path.join(out, "accuracy_vs_size.png"))


def montage(images, out, columns, column_labels, row_labels):
    args = ["/usr/bin/python3", os.path.join(H.ROOT, "render", "montage.py"), *images, "-o", out,
            "--columns", str(columns)]
    for c in column_labels:
        args += ["--column-label", c]
    for r in row_labels:
        args += ["--row-label", r]
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        raise H.StepError("montage failed: " + r.stderr.strip())


def fresh_view(R, name):
    """A view file path for a new framing: renders through it share one camera."""
    view = R.path("figures", name)
    if os.path.exists(view):
        os.remove(view)
    return view


def figures(out, build, work, rows, fig11, fig14):
    """figure15.png (original, union of spheres, garbing mesh per model), figure14.png (the cube
    refined) and figure11.png (dual against no dual), into the folder `out`."""
    R = H.Runner(build, work)
    by_name = {r["name"]: r for r in rows}
    jobs, cells = [], []
    for n in FIGURE15:
        if n not in by_name:
            continue
        view = fresh_view(R, n + "_view.json")
        cells.append(render(R, [R.model(n)], R.path("figures", n + "_original.png"), view, CELL))
        for tag, inp in (("spheres", by_name[n]["atom_sets"]["paper"]["atoms"]),
                         ("garbing", by_name[n]["atom_sets"]["paper"]["m2"])):
            png = R.path("figures", "%s_%s.png" % (n, tag))
            jobs.append(("render %s %s" % (n, tag), render_job, (build, work, [inp], view, png, CELL)))
            cells.append(png)
    H.run_pool(jobs, os.cpu_count(), lambda m: None)
    montage(cells, os.path.join(out, "figure15.png"), 3,
            ["Original", "Union of spheres", "Garbing mesh"], [n for n in FIGURE15 if n in by_name])
    if fig14:
        view = fresh_view(R, "cube_view.json")
        imgs = [render(R, [r["mesh"]], R.path("figures", "cube_refine%d.png" % r["refine"]), view, CELL, flat=True)
                for r in fig14]
        montage(imgs, os.path.join(out, "figure14.png"), 3,
                ["--refine %d: H %s%%, RMS %s%%" % (r["refine"], H.fmt(r["hausdorff_pct"]), H.fmt(r["rms_pct"]))
                 for r in fig14], [])
    if fig11:
        n = fig11[0]["model"]
        view = fresh_view(R, n + "_fig11_view.json")
        imgs = [render(R, [R.path(n, "fig11_%s.off" % tag)], R.path("figures", "%s_fig11_%s.png" % (n, tag)), view,
                       CELL, flat=True) for tag in ("dual", "no_dual")]
        montage(imgs, os.path.join(out, "figure11.png"), 2,
                ["dual of M1 (after repair)", "M1 itself (--no-dual, after repair)"], [n])
