"""Shared plumbing of the experiment scripts: running the programs, the manifests, JSON, tables,
a job pool.

Every number the experiments write comes from a program's JSON output or from the paper's tables
in paper_tables.json; nothing is typed in.
"""
import concurrent.futures
import contextlib
import csv
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
RESULTS = os.path.join(ROOT, "results")


class StepError(RuntimeError):
    pass


class Runner:
    """Runs the project's programs from <build>/bin and keeps their JSON reports."""

    def __init__(self, build, work):
        self.build = os.path.abspath(build)
        self.work = os.path.abspath(work)
        os.makedirs(self.work, exist_ok=True)

    def bin(self, name):
        return os.path.join(self.build, "bin", name)

    def path(self, *parts):
        p = os.path.join(self.work, *parts)
        os.makedirs(os.path.dirname(p), exist_ok=True)
        return p

    def model(self, name):
        """The reference model `name` as experiments/models.py materialises it."""
        return os.path.join(self.build, "models", name + ".off")

    def run(self, program, *args, json_out=None, label=""):
        """Runs a program; returns its JSON report (from --stats FILE or stdout --json)."""
        cmd = [self.bin(program), *map(str, args)]
        t0 = time.time()
        r = subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL)
        if r.returncode != 0:
            raise StepError("%s failed (exit %d): %s\n  command: %s" % (
                label or program, r.returncode, r.stderr.strip().splitlines()[-1:] or "",
                " ".join(cmd)))
        if json_out:
            with open(json_out) as f:
                data = json.load(f)
        elif "--json" in args:
            data = json.loads(r.stdout)
        else:
            data = {}
        data.setdefault("_wall", time.time() - t0)
        return data

    def run_stats(self, program, *args, stats, label=""):
        """Runs a program with `--stats STATS` last; returns that report."""
        return self.run(program, *args, "--stats", stats, json_out=stats, label=label)


def load_json(name):
    with open(os.path.join(HERE, name)) as f:
        return json.load(f)


def load_manifest():
    """experiments/models.json: the reference models."""
    return load_json("models.json")


def models_by_name():
    """The manifest's models, {name: entry}."""
    return {m["name"]: m for m in load_manifest()["models"]}


def paper_tables():
    """experiments/paper_tables.json: the paper's Tables 1 and 2 and its depth sweep."""
    return load_json("paper_tables.json")


def write_atomically(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    tmp = path + ".partial"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def write_csv(path, rows, columns):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    tmp = path + ".partial"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow([r.get(c, "") for c in columns])
    os.replace(tmp, path)


def markdown_table(rows, columns, headers=None):
    headers = headers or columns
    out = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(columns)]
    for r in rows:
        out.append("| " + " | ".join(fmt(r.get(c, "")) for c in columns) + " |")
    return "\n".join(out)


def fmt(x):
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, float):
        if x == 0:
            return "0"
        if abs(x) >= 100:
            return "%.0f" % x
        if abs(x) >= 1:
            return "%.2f" % x
        return "%.3g" % x
    return str(x)


@contextlib.contextmanager
def executor(workers, scheduler=None):
    """The jobs' executor (a concurrent.futures.Executor): the local process pool with
    `workers` processes, or, given a Dask scheduler's address, that cluster's workers
    (Debian's python3-distributed). Dask workers must see the repository, the build and the
    work folders at the same paths (a shared file system); a worker plugin puts this folder on
    their module path: docs/experiments.md."""
    if not scheduler:
        with concurrent.futures.ProcessPoolExecutor(max_workers=workers) as pool:
            yield pool
        return
    try:
        import distributed
    except ImportError:
        raise StepError("--scheduler needs Dask's distributed (Debian: python3-distributed)")
    try:
        client = distributed.Client(scheduler, timeout=15)
    except (OSError, ValueError) as e:  # unreachable; a malformed address
        raise StepError("cannot reach the Dask scheduler at %s: %s" % (scheduler, e))

    class ExperimentsPath(distributed.WorkerPlugin):
        """Makes the experiment modules importable on every worker, present or joining later
        (the jobs are pickled by reference to them; this class, local, travels by value)."""

        def __init__(self, folder):
            self.folder = folder

        def setup(self, worker):
            if self.folder not in sys.path:
                sys.path.insert(0, self.folder)

    try:
        try:
            client.register_worker_plugin(ExperimentsPath(HERE), name="mg-experiments-path")
        except Exception as e:  # a worker that cannot take it: one line, not a traceback
            raise StepError("Dask scheduler at %s: cannot set up the workers: %s" % (scheduler, e))
        with client.get_executor(pure=False) as pool:
            yield pool
    finally:
        client.close()


def run_pool(jobs, workers, progress, scheduler=None):
    """Runs (name, function, args) jobs on the executor (the local process pool, or a Dask
    cluster given its scheduler's address); returns {name: result}. The first failure stops
    the run with its message. Results do not depend on where a job ran."""
    results = {}
    with executor(workers, scheduler) as pool:
        futures = {pool.submit(fn, *args): name for name, fn, args in jobs}
        for fut in concurrent.futures.as_completed(futures):
            name = futures[fut]
            try:
                results[name] = fut.result()
            except Exception as e:  # the first failure ends the run, with its message
                for f in futures:
                    f.cancel()
                raise StepError("%s: %s" % (name, e))
            progress("done  %s" % name)
    return results


def log(message):
    print("[%s] %s" % (time.strftime("%H:%M:%S"), message), flush=True)


def die(message, program="reproduce"):
    print("%s: %s" % (program, message), file=sys.stderr, flush=True)
    sys.exit(1)
