#!/usr/bin/python3
"""Propose the CTest regression's bounds (experiments/regression_thresholds.json) for review.

Measures every Table 1 model (or those of --models) exactly as experiments/regression.py does
(the same function, regression.measure) and prints, for every model and metric, the current
bound, the measurement, the proposed bound and the difference (proposed - current). Only with
--write does it rewrite the file (the entries of the models not measured are kept); its diff is
then reviewed and committed like code. Nothing else writes the bounds.

Policy: proposed bound = measured x 1.05 + 0.02 (% of the original's bounding-box diagonal),
rounded up to 3 decimals. The outputs are deterministic (byte-identical at any thread count),
so the margin only admits small reviewed changes.

Usage: experiments/propose_bounds.py BUILD [--models a,b] [--write] [--bounds FILE]
Exit codes: 0 success, 1 a program failed, 2 bad usage.
"""
import argparse
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import regression    # noqa: E402
from jobs import TABLE1_MODELS  # noqa: E402

FACTOR = 1.05  # relative margin on the measurement
SLACK = 0.02   # absolute margin, % of the diagonal
ABOUT = ("Bounds of the CTest regression (experiments/regression.py BUILD MODEL) on M2's Hausdorff and RMS "
         "distances to the original (paper atoms), in % of the original's bounding-box diagonal. Reviewed "
         "numbers: experiments/propose_bounds.py BUILD measures what the regression measures and prints "
         "the proposal; only with --write does it rewrite this file, whose diff is then reviewed and "
         "committed. Policy: proposed bound = measured x 1.05 + 0.02, rounded up to 3 decimals. The outputs "
         "are deterministic (byte-identical at any thread count), so the margin only admits small reviewed "
         "changes. Nothing else writes this file.")


def proposed_bound(measured):
    """measured x 1.05 + 0.02, rounded up to 3 decimals (the rounding of x 1000 forgives float noise)."""
    return math.ceil(round((measured * FACTOR + SLACK) * 1000, 6)) / 1000


def short_commit():
    """The source tree's commit, as `git rev-parse --short HEAD` gives it."""
    r = subprocess.run(["git", "-C", H.ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    return r.stdout.strip() if r.returncode == 0 else "an unknown commit"


def entry(distance, commit):
    """A model's entry of the bounds file from its `evaluate distance` report."""
    out = {metric: proposed_bound(distance[metric]) for metric in regression.METRICS}
    out.update({"measured_" + metric: round(distance[metric], 4) for metric in regression.METRICS})
    out["why"] = "measured %.4f (H) and %.4f (RMS) by experiments/propose_bounds.py at %s + 5%% + 0.02" % (
        distance["hausdorff_pct"], distance["rms_pct"], commit)
    return out


def row(name, metric, current, measured, proposed):
    bound = "%.3f" % current if current is not None else "-"
    diff = "%+.3f" % (proposed - current) if current is not None else "new"
    return "%-13s %-14s %9s %9.4f %9.3f %10s" % (name, metric, bound, measured, proposed, diff)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("build", help="build folder (programs in bin/, reference models in models/)")
    ap.add_argument("--models", help="comma-separated subset of: " + ", ".join(TABLE1_MODELS))
    ap.add_argument("--write", action="store_true", help="rewrite the bounds file with the proposal")
    ap.add_argument("--bounds", default=regression.BOUNDS, help="the bounds file (default: %(default)s)")
    args = ap.parse_args(argv)
    names = args.models.split(",") if args.models else TABLE1_MODELS
    unknown = [n for n in names if n not in TABLE1_MODELS]
    if unknown:
        ap.error("unknown model(s): %s (known: %s)" % (", ".join(unknown), ", ".join(TABLE1_MODELS)))
    current = regression.load_bounds(args.bounds)["models"]
    commit = short_commit()
    print("%-13s %-14s %9s %9s %9s %10s" % ("model", "metric", "bound", "measured", "proposed", "difference"))
    proposal = {}
    for name in names:
        try:
            distance = regression.measure(os.path.abspath(args.build), name)["distance"]
        except H.StepError as e:
            H.die(str(e), "propose_bounds")
        proposal[name] = entry(distance, commit)
        for metric in regression.METRICS:
            print(row(name, metric, current.get(name, {}).get(metric), distance[metric], proposal[name][metric]),
                  flush=True)
    if not args.write:
        print("not written: pass --write to rewrite %s with the proposal" % args.bounds)
        return 0
    models = dict(current)
    models.update(proposal)
    H.write_atomically(os.path.abspath(args.bounds), json.dumps({"about": ABOUT, "models": models}, indent=2) + "\n")
    print("wrote %s: review its diff before committing it" % args.bounds)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
