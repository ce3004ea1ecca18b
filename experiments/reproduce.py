#!/usr/bin/python3
"""Reproduce the paper's tables and figures on the reference models (the main job of ./run.sh).

For every model: skeletonize -> garb -> evaluate against the original and against G -> CGAL skin
surface, union of balls and OpenVDB of the same atoms -> evaluate them -> timings -> renders.
Jobs (model x parameters, jobs.py) run on a local process pool; the timings of Table 2 are taken
afterwards, one program at a time, medians of 3. Writes results/ (tables.py, figures.py,
report.py): table1, table2, smoothness, atoms (skeleton vs mesher error), cone_filter,
depth_sweep, accuracy_vs_size, figure11, figure14, figure15, REPORT.md. It never writes the
regression bounds: experiments/propose_bounds.py proposes them for review.

Usage: experiments/reproduce.py [--build build] [--models a,b] [--quick] [--jobs N] [--scheduler ADDRESS] [--results DIR]
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures as F  # noqa: E402
import harness as H  # noqa: E402
import jobs as J     # noqa: E402
import models as M   # noqa: E402
import report as P   # noqa: E402
import tables as T   # noqa: E402


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(H.ROOT, "build"))
    ap.add_argument("--models", help="comma-separated subset of: " + ", ".join(J.TABLE1_MODELS))
    ap.add_argument("--quick", action="store_true", help="three small models, no sweeps or figures")
    ap.add_argument("--jobs", type=int, default=os.cpu_count(), help="parallel jobs")
    ap.add_argument("--scheduler", help="run the jobs on the Dask cluster of this scheduler address "
                    "(host:port; default: a local process pool of --jobs)")
    ap.add_argument("--results", help="write the results here instead of results/")
    args = ap.parse_args(argv)
    names = J.QUICK_MODELS if args.quick else J.TABLE1_MODELS
    if args.models:
        names = args.models.split(",")
        unknown = [n for n in names if n not in J.TABLE1_MODELS]
        if unknown:
            H.die("unknown model(s): %s (known: %s)" % (", ".join(unknown), ", ".join(J.TABLE1_MODELS)))
    return args, names


def job_list(build, work, names, quick, full):
    """(name, function, arguments) of every job: a model job per model and, in a full run, the
    sweeps, Figures 11 and 14 and the cone study."""
    jobs = [("model " + n, J.model_job, (build, work, n, quick)) for n in names]
    if full:
        jobs += [("sweep " + n, J.sweep_job, (build, work, n)) for n in J.SWEEP]
        jobs += [("figure11 " + n, J.figure11_job, (build, work, n)) for n in J.FIGURE11]
        jobs += [("figure14", J.figure14_job, (build, work))]
        jobs += [("cones " + n, J.cone_filter_job, (build, work, n)) for n in names]
    return jobs


def main(argv):
    args, names = parse_args(argv)
    out = os.path.abspath(args.results) if args.results else H.RESULTS
    command = "experiments/reproduce.py" + (" --quick" if args.quick else "") + (
        " --models " + args.models if args.models else "")
    t0 = time.time()
    build = os.path.abspath(args.build)
    work = os.path.join(build, "experiments-work" if not args.results else "experiments-test")
    full = not args.quick and not args.models
    os.makedirs(out, exist_ok=True)  # the renders are written before any table
    try:
        H.log("reference models")
        M.materialise(build, None, quiet=True)
        paper = H.paper_tables()
        jobs = job_list(build, work, names, args.quick, full)
        H.log("%d jobs on %d workers" % (len(jobs), args.jobs))
        done = H.run_pool(jobs, args.jobs, H.log, args.scheduler)
        rows = [done["model " + n] for n in names]
        sweep_rows = [r for n in (J.SWEEP if full else []) for r in done["sweep " + n]]
        fig11 = [done["figure11 " + n] for n in (J.FIGURE11 if full else [])]
        fig14 = done.get("figure14", [])
        cone_rows = [r for n in (names if full else []) for r in done["cones " + n]]
        times = J.timings(H.Runner(build, work), rows, H.log)
        if full:
            H.log("renders")
            F.figures(out, build, work, rows, fig11, fig14)
        t1, t2 = T.write_tables(out, rows, times, sweep_rows, fig11, fig14, paper, command)
        if sweep_rows:
            F.plots(out, sweep_rows, paper)
        P.report(out, t1, t2, sweep_rows, fig11, fig14, paper, command, time.time() - t0, args.quick)
        if cone_rows:
            T.write_cone_table(out, cone_rows, command)
    except (H.StepError, M.ModelError) as e:
        H.die(str(e))
    H.log("done in %.0f s; results in %s" % (time.time() - t0, out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
