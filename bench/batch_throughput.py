#!/usr/bin/python3
"""Throughput of volspline.batch (models per second) with 1 and 2 workers on the same models,
in the same run, and their ratio.

    PYTHONPATH=build/python bench/batch_throughput.py --cli build/bin/volspline \
        [--models 100] [--operation jacobian] [--workers 1,2] [-- extra CLI arguments]

The models are copies of `volspline make` solids (boxes and hollow cylinders), scaled and moved.
Each worker count gets its own LocalCluster, started before the clock and warmed by one task, and
its own output folder, so nothing is skipped; the time is from the first task submitted to the
last row written, tables included. Google Benchmark does not fit a Python pipeline: a script.
"""
import argparse
import json
import logging
import os
import subprocess
import sys
import tempfile
import time


def make_models(cli, folder, count):
    bases = {}
    for kind, args in {"box": ["box", "--size", "1,2,3"],
                       "tube": ["cylinder", "--radius", "2", "--height", "1", "--inner", "1"]}.items():
        path = os.path.join(folder, f"base-{kind}.json")
        subprocess.run([cli, "make", *args, "-o", path], check=True, capture_output=True)
        with open(path) as f:
            bases[kind] = json.load(f)
    models = []
    for i in range(count):
        kind = "box" if i % 2 == 0 else "tube"
        model = json.loads(json.dumps(bases[kind]))
        for o in model["objects"]:
            w = o.get("weights")
            o["control_points"] = [[(1 + 0.01 * i) * c + (0 if w is not None and w[j] == 0 else 0.5 * i)
                                    for c in p] for j, p in enumerate(o["control_points"])]
        path = os.path.join(folder, f"{kind}-{i:04}.json")
        with open(path, "w") as f:
            json.dump(model, f)
        models.append(path)
    return models


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cli", default=os.environ.get("VOLSPLINE_CLI"), help="the volspline executable")
    p.add_argument("--models", type=int, default=100)
    p.add_argument("--operation", default="jacobian")
    p.add_argument("--workers", default="1,2", help="worker counts, comma separated (default 1,2)")
    args = p.parse_args(argv)
    from distributed import Client, LocalCluster

    from volspline import batch

    cli = batch.find_cli(args.cli)
    with tempfile.TemporaryDirectory(prefix="volspline-batch-bench-") as tmp:
        models = make_models(cli, tmp, args.models)
        rates = {}
        for n in [int(x) for x in args.workers.split(",")]:
            with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                              silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
                batch.run_batch(args.operation, models[:1], os.path.join(tmp, f"warm-{n}"), client=client, cli=cli,
                                extra_args=extra)
                start = time.perf_counter()
                summary = batch.run_batch(args.operation, models, os.path.join(tmp, f"out-{n}"), client=client,
                                          cli=cli, extra_args=extra)
                seconds = time.perf_counter() - start
            assert summary.ran == len(models) and summary.failed == 0, [r["error"] for r in summary.rows if r["error"]]
            cli_seconds = sum(r["seconds"] for r in summary.rows)
            rates[n] = len(models) / seconds
            print(f"{args.operation}, {len(models)} models, {n} worker(s): {seconds:.2f} s, {rates[n]:.1f} models/s "
                  f"(CLI time per model {1e3 * cli_seconds / len(models):.1f} ms)", flush=True)
        counts = sorted(rates)
        for n in counts[1:]:
            print(f"ratio {n} workers / {counts[0]}: {rates[n] / rates[counts[0]]:.2f} (CPUs: {os.cpu_count()})")


if __name__ == "__main__":
    main()
