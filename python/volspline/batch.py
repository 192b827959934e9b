"""volspline.batch: one volspline operation over many model files, on a Dask cluster.

    python3 -m volspline.batch OPERATION MODELS... --out DIR [--workers N] [--scheduler ADDR]
                               [--csv F] [--jsonl F] [-- extra CLI arguments]

OPERATION is ``jacobian``, ``boundary``, ``convert``, ``view``, ``info`` or ``mass`` (``info
--mass``). Every model is one Dask task that runs the ``volspline`` command line on it in a
subprocess, with a timeout: a model that crashes or hangs the CLI costs its own row, never a
worker, and the figures are the CLI's own (its ``--json`` or ``--stats`` output). Each model's
row is written atomically to ``DIR/results/KEY.json`` as soon as it is known; a rerun with the
same operation and arguments skips the models that have one, and ``DIR/results.csv`` and
``DIR/results.jsonl`` are assembled from these files at the end. Outputs (meshes, models,
pictures) go to ``DIR/outputs/``. See docs/python.md, "Batch runs (Dask)".

    >>> from volspline.batch import run_batch
    >>> summary = run_batch("jacobian", ["a.json", "b.json"], "out", workers=2)
    >>> [row["verdict"] for row in summary.rows]
"""
from __future__ import annotations

import argparse
import csv
import hashlib
import io
import json
import logging
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import uuid
from dataclasses import dataclass, field
from typing import Callable, Iterable, Optional, Sequence

MODEL_EXTENSIONS = (".json", ".xml", ".itd", ".vtu")

# What each operation runs: the CLI subcommand and its fixed arguments (the model comes first,
# then these, then the user's extra arguments), the output extension by default (None: no
# output file), and which output extensions are accepted.
OPERATIONS = {
    "jacobian": {"command": ["jacobian"], "args": ["--json", "--fail-invalid"], "output": None},
    "boundary": {"command": ["boundary"], "args": [], "output": "ply", "formats": ("ply", "obj", "stl")},
    "convert": {"command": ["convert"], "args": [], "output": "json", "formats": ("json", "xml", "itd", "vtu")},
    "view": {"command": ["view"], "args": [], "output": "png", "formats": ("png",)},
    "info": {"command": ["info"], "args": ["--json"], "output": None},
    "mass": {"command": ["info"], "args": ["--mass", "--json"], "output": None},
}

# The columns of the CSV file, in order: the common ones, then per operation a few figures
# summed or bounded over the model's objects (all figures are in the JSON lines file).
CSV_COLUMNS = ["file", "operation", "status", "exit_code", "seconds", "objects", "verdict"]
CSV_SUMMARY = {
    "jacobian": ["lower", "upper", "cells"],
    "boundary": ["triangles", "cells_examined"],
    "convert": ["bytes"],
    "view": ["triangles", "width", "height", "bytes"],
    "info": ["types"],
    "mass": ["volume"],
}
CSV_TAIL = ["outputs", "error", "figures"]

DEFAULT_TIMEOUT = 600.0


class BatchError(Exception):
    """A batch that cannot start: unknown operation, no CLI, no Dask (the CLI exits 2)."""


@dataclass
class BatchSummary:
    """What run_batch did: one row per model, in the order the models were given."""

    rows: list
    ran: int = 0
    skipped: int = 0
    failed: int = 0
    csv_path: str = ""
    jsonl_path: str = ""
    seconds: float = 0.0
    cluster_failures: list = field(default_factory=list)


# --------------------------------------------------------------------------------------------
# Finding things


def find_cli(explicit: Optional[str] = None) -> str:
    """The volspline executable: `explicit`, else $VOLSPLINE_CLI, else the one beside this
    package (the build tree's bin/, or PREFIX/bin for an installed package), else PATH."""
    if explicit:
        if not (os.path.isfile(explicit) and os.access(explicit, os.X_OK)):
            raise BatchError(f"--cli {explicit}: not an executable file")
        return os.path.abspath(explicit)
    env = os.environ.get("VOLSPLINE_CLI")
    if env:
        if not (os.path.isfile(env) and os.access(env, os.X_OK)):
            raise BatchError(f"VOLSPLINE_CLI={env}: not an executable file")
        return os.path.abspath(env)
    package = os.path.dirname(os.path.abspath(__file__))
    # build/python/volspline -> build/bin; PREFIX/lib/python3.X/dist-packages/volspline -> PREFIX/bin
    for up in (2, 4):
        candidate = os.path.join(package, *[".."] * up, "bin", "volspline")
        if os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return os.path.realpath(candidate)
    found = shutil.which("volspline")
    if found:
        return os.path.abspath(found)
    raise BatchError("cannot find the volspline command line: give --cli PATH or set VOLSPLINE_CLI")


def collect_models(paths: Iterable[str], files_from: Optional[str] = None) -> list:
    """Absolute model paths, each once, in the order given: a folder stands for the model files
    under it (by extension, sorted); anything else is taken as a model file, so that a missing
    one gets its row with the CLI's error."""
    listed = list(paths)
    if files_from:
        with open(files_from, encoding="utf-8") if files_from != "-" else sys.stdin as f:
            listed += [line.strip() for line in f if line.strip() and not line.startswith("#")]
    models, seen = [], set()
    for p in listed:
        if os.path.isdir(p):
            found = []
            for root, _dirs, files in os.walk(p):
                found += [os.path.join(root, n) for n in files if n.lower().endswith(MODEL_EXTENSIONS)]
            expanded = sorted(found)
        else:
            expanded = [p]
        for m in expanded:
            a = os.path.abspath(m)
            if a not in seen:
                seen.add(a)
                models.append(a)
    return models


def model_key(path: str) -> str:
    """A file name for a model's result: its readable stem and a hash of its absolute path, so
    models of the same name in different folders do not collide."""
    stem = re.sub(r"[^A-Za-z0-9._-]", "_", os.path.splitext(os.path.basename(path))[0])[:60] or "model"
    return f"{stem}-{hashlib.sha1(path.encode('utf-8', 'surrogateescape')).hexdigest()[:12]}"


def signature(operation: str, extra_args: Sequence[str], output_format: Optional[str]) -> str:
    """Identifies what a result answers: a rerun skips a model only for the same request."""
    text = json.dumps([operation, list(extra_args), output_format])
    return hashlib.sha1(text.encode()).hexdigest()[:16]


# --------------------------------------------------------------------------------------------
# Writing and reading results


def write_atomic(path: str, text: str) -> None:
    """Writes `text` to `path` through a temporary file in the same folder and os.replace, so a
    reader (or a rerun after a crash) sees the whole old file or the whole new one."""
    folder = os.path.dirname(path) or "."
    tmp = os.path.join(folder, f".{os.path.basename(path)}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    try:
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def result_path(out: str, key: str) -> str:
    return os.path.join(out, "results", key + ".json")


def read_result(path: str, sig: str) -> Optional[dict]:
    """The stored row, if it exists, is whole and answers the same request with its outputs
    still present; otherwise None (the model is run again)."""
    try:
        with open(path, encoding="utf-8") as f:
            row = json.load(f)
    except (OSError, ValueError):
        return None
    if not isinstance(row, dict) or row.get("signature") != sig:
        return None
    if row.get("status") == "ok" and not all(os.path.exists(p) for p in row.get("outputs", [])):
        return None
    return row


# --------------------------------------------------------------------------------------------
# One model (runs on a worker)


def _png_size(path: str):
    with open(path, "rb") as f:
        header = f.read(24)
    if len(header) == 24 and header[:8] == b"\x89PNG\r\n\x1a\n":
        return int.from_bytes(header[16:20], "big"), int.from_bytes(header[20:24], "big")
    return None, None


def _error_text(stderr: str) -> str:
    lines = [line for line in stderr.strip().splitlines() if line.strip()]
    errors = [line for line in lines if "error" in line]
    return "\n".join(errors or lines[-5:])


def _jacobian_failure(objects: list) -> str:
    parts = []
    for o in objects:
        if o.get("verdict") == "invalid":
            where = o.get("witness")
            value = o.get("witness_value")
            sign = "J = 0" if value == 0 else ("J < 0" if (value or 0) < 0 else "J > 0")
            at = f" at (u, v, w) = ({', '.join(repr(x) for x in where)})" if where else ""
            name = f" ({o['name']})" if o.get("name") else ""
            parts.append(f"object {o.get('object')}{name}: invalid Jacobian, {sign}{at}")
    return "; ".join(parts)


def _figures(operation: str, stdout: str, outputs: list, stats_path: Optional[str]):
    """The CLI's figures for the row: (objects, verdict, figures)."""
    if operation in ("jacobian", "info", "mass"):
        objects = json.loads(stdout)["objects"]
        verdict = None
        if operation == "jacobian":
            verdicts = [o.get("verdict") for o in objects]
            verdict = "invalid" if "invalid" in verdicts else "undecided" if "undecided" in verdicts else "valid"
        return len(objects), verdict, objects
    if operation == "boundary":
        with open(stats_path, encoding="utf-8") as f:
            stats = json.load(f)
        return len(stats.get("objects", [])) + len(stats.get("simplex_objects", [])), None, stats
    if operation == "convert":
        m = re.search(r"\((\d+) object\(s\)\)", stdout)
        return (int(m.group(1)) if m else None), None, {"bytes": os.path.getsize(outputs[0])}
    if operation == "view":
        m = re.search(r": (\d+) triangles(?: from (\d+) volume)?", stdout)
        width, height = _png_size(outputs[0])
        figures = {"triangles": int(m.group(1)) if m else None, "width": width, "height": height,
                   "bytes": os.path.getsize(outputs[0])}
        return (int(m.group(2)) if m and m.group(2) else None), None, figures
    raise BatchError(f"unknown operation '{operation}'")


def run_model(task: dict) -> dict:
    """Runs one model's task and writes its row to DIR/results/KEY.json (atomically). A model
    whose row is already there for the same request (a task retried after its worker died
    once the row was written) is not run again. Failures of the model are the row's; only a
    failure to write the row raises (and Dask retries the task)."""
    path = result_path(task["out"], task["key"])
    done = read_result(path, task["signature"])
    if done is not None:
        return done
    row = execute(task)
    write_atomic(path, json.dumps(row, sort_keys=True) + "\n")
    return row


def execute(task: dict) -> dict:
    """Runs the CLI on one model and makes its row (nothing written but the CLI's outputs)."""
    operation, key = task["operation"], task["key"]
    spec = OPERATIONS[operation]
    command = [task["cli"], *spec["command"], task["file"], *spec["args"]]
    outputs, stats_path = [], None
    if spec["output"]:
        out_file = os.path.join(task["out"], "outputs", f"{key}.{task['output_format'] or spec['output']}")
        command += ["-o", out_file]
        outputs.append(out_file)
    if operation == "boundary":
        stats_path = os.path.join(task["out"], "outputs", f"{key}.stats.json")
        command += ["--stats", stats_path]
        outputs.append(stats_path)
    command += list(task["extra_args"])
    row = {"file": task["file"], "operation": operation, "signature": task["signature"], "command": command,
           "status": "failed", "exit_code": None, "seconds": None, "objects": None, "verdict": None,
           "figures": None, "outputs": [], "error": "", "warnings": ""}
    timeout = task["timeout"]
    start = time.perf_counter()
    timed_out = False
    try:
        with subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              encoding="utf-8", errors="replace") as p:
            try:
                stdout, stderr = p.communicate(timeout=timeout)
            except subprocess.TimeoutExpired:
                p.kill()
                stdout, stderr = p.communicate()
                timed_out = True
    except OSError as e:
        row["seconds"] = time.perf_counter() - start
        row["error"] = f"cannot run {task['cli']}: {e}"
        return row
    row["seconds"] = time.perf_counter() - start
    row["exit_code"] = p.returncode
    if timed_out:
        row["error"] = f"timed out after {timeout:g} s (killed)"
        return row
    if p.returncode < 0:
        try:
            name = signal.Signals(-p.returncode).name
        except ValueError:
            name = f"signal {-p.returncode}"
        row["error"] = f"the CLI was killed by {name}" + (f": {_error_text(stderr)}" if stderr.strip() else "")
        return row
    # jacobian --fail-invalid ends with 3 after printing its figures: a verdict, not a crash.
    if p.returncode == 0 or (operation == "jacobian" and p.returncode == 3):
        try:
            row["objects"], row["verdict"], row["figures"] = _figures(operation, stdout, outputs, stats_path)
        except (ValueError, KeyError, OSError, TypeError) as e:
            row["error"] = f"cannot read the CLI's figures: {e}"
            return row
        if p.returncode == 0:
            row["status"] = "ok"
            row["outputs"] = outputs
            row["warnings"] = stderr.strip()
        else:
            row["error"] = _jacobian_failure(row["figures"]) or "invalid Jacobian"
        return row
    row["error"] = _error_text(stderr) or f"exit code {p.returncode}"
    return row


# --------------------------------------------------------------------------------------------
# The batch (runs on the client)


def _summary_figures(operation: str, row: dict) -> dict:
    figures = row.get("figures")
    if figures is None:
        return {}
    if operation == "jacobian":
        lows = [o["lower"] for o in figures if o.get("lower") is not None]
        highs = [o["upper"] for o in figures if o.get("upper") is not None]
        return {"lower": min(lows) if lows else None, "upper": max(highs) if highs else None,
                "cells": sum(o.get("cells", 0) for o in figures)}
    if operation == "mass":
        volumes = [o["volume"] for o in figures if "volume" in o]
        return {"volume": sum(volumes) if volumes else None}
    if operation == "info":
        return {"types": ";".join(o.get("type", "") for o in figures)}
    if operation == "boundary":
        return {"triangles": sum(figures.get("triangles", {}).values()) if isinstance(figures.get("triangles"), dict) else None,
                "cells_examined": figures.get("cells_examined")}
    return {k: figures.get(k) for k in CSV_SUMMARY[operation]}


def csv_text(operation: str, rows: Sequence[dict]) -> str:
    columns = CSV_COLUMNS + CSV_SUMMARY[operation] + CSV_TAIL
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=columns, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    for row in rows:
        line = {c: row.get(c) for c in CSV_COLUMNS}
        line.update(_summary_figures(operation, row))
        line["outputs"] = ";".join(row.get("outputs") or [])
        line["error"] = row.get("error", "")
        line["figures"] = json.dumps(row.get("figures"), separators=(",", ":"), sort_keys=True)
        writer.writerow({k: ("" if v is None else repr(v) if isinstance(v, float) else v) for k, v in line.items()})
    return buffer.getvalue()


def jsonl_text(rows: Sequence[dict]) -> str:
    return "".join(json.dumps(row, sort_keys=True) + "\n" for row in rows)


def _cluster_failure_row(task: dict, error: BaseException) -> dict:
    return {"file": task["file"], "operation": task["operation"], "signature": task["signature"], "command": [],
            "status": "failed", "exit_code": None, "seconds": None, "objects": None, "verdict": None, "figures": None,
            "outputs": [], "error": f"the task failed on the cluster ({type(error).__name__}: {error})", "warnings": ""}


def _start_cluster(workers: Optional[int], scheduler: Optional[str]):
    try:
        from distributed import Client, LocalCluster
    except ImportError as e:
        raise BatchError(f"volspline batch needs Dask ({e}); on Debian: apt-get install python3-dask python3-distributed")
    if scheduler:
        return Client(scheduler), None
    n = workers or len(os.sched_getaffinity(0))
    # Processes, one thread each: a task is a CLI subprocess, and a worker lost (killed, out of
    # memory) is restarted by its nanny while its tasks go to the others.
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                           silence_logs=logging.ERROR)
    return Client(cluster), cluster


def run_batch(operation: str, models: Iterable[str], out: str, *, workers: Optional[int] = None,
              scheduler: Optional[str] = None, client=None, cli: Optional[str] = None,
              extra_args: Sequence[str] = (), output_format: Optional[str] = None,
              timeout: float = DEFAULT_TIMEOUT, retries: int = 2, redo_failed: bool = False,
              csv_path: Optional[str] = None, jsonl_path: Optional[str] = None,
              progress: Optional[Callable[[dict, int, int], None]] = None) -> BatchSummary:
    """Runs `operation` on every model in `models` on a Dask cluster and returns one row per
    model, in order (also written to `csv_path` and `jsonl_path`, by default DIR/results.csv
    and DIR/results.jsonl).

    The cluster is `client` if given, else the scheduler at `scheduler`, else a LocalCluster of
    `workers` worker processes (default: one per CPU), closed at the end. `extra_args` are
    appended to every CLI command; `output_format` is the extension of the outputs of
    boundary, convert and view. Each task runs the CLI with `timeout` seconds; a task whose
    worker dies is rerun by Dask (and `retries` more times if writing its row fails). Models
    whose row exists for the same request are skipped (failed ones too, unless `redo_failed`).
    `progress(row, done, total)` is called on the client as each model's row arrives.
    """
    if operation not in OPERATIONS:
        raise BatchError(f"unknown operation '{operation}': expected one of {', '.join(OPERATIONS)}")
    spec = OPERATIONS[operation]
    if output_format is not None:
        output_format = output_format.lstrip(".").lower()
        if not spec["output"]:
            raise BatchError(f"{operation} writes no output file: --format does not apply")
        if output_format not in spec["formats"]:
            raise BatchError(f"{operation}: expected --format {' or '.join(spec['formats'])}, got '{output_format}'")
    cli = find_cli(cli)
    models = collect_models(models)
    out = os.path.abspath(out)
    os.makedirs(os.path.join(out, "results"), exist_ok=True)
    if spec["output"]:
        os.makedirs(os.path.join(out, "outputs"), exist_ok=True)
    sig = signature(operation, extra_args, output_format)
    started = time.perf_counter()

    tasks, results = [], {}
    for path in models:
        key = model_key(path)
        row = read_result(result_path(out, key), sig)
        if row is not None and redo_failed and row.get("status") != "ok":
            # Removed, or the task would find it and return it as done.
            os.unlink(result_path(out, key))
        elif row is not None:
            results[key] = row
            continue
        tasks.append({"file": path, "key": key, "operation": operation, "cli": cli, "extra_args": list(extra_args),
                      "output_format": output_format, "out": out, "timeout": timeout, "signature": sig})
    summary = BatchSummary(rows=[], skipped=len(results), ran=len(tasks))
    done, total = 0, len(tasks)

    if tasks:
        own_client = client is None
        cluster = None
        if own_client:
            client, cluster = _start_cluster(workers, scheduler)
        try:
            from distributed import as_completed

            token = uuid.uuid4().hex[:8]
            futures = client.map(run_model, tasks, key=[f"volspline-{operation}-{t['key']}-{token}" for t in tasks],
                                 retries=retries, pure=False)
            by_key = {f.key: t for f, t in zip(futures, tasks)}
            for future in as_completed(futures):
                task = by_key[future.key]
                try:
                    row = future.result()
                except Exception as e:  # noqa: BLE001 - KilledWorker after too many deaths, or the row not written
                    row = _cluster_failure_row(task, e)
                    summary.cluster_failures.append(task["file"])
                    try:
                        write_atomic(result_path(out, task["key"]), json.dumps(row, sort_keys=True) + "\n")
                    except OSError:
                        pass
                results[task["key"]] = row
                done += 1
                if progress is not None:
                    progress(row, done, total)
                future.release()
        finally:
            if own_client:
                client.close()
                if cluster is not None:
                    cluster.close()

    # The tables come from the result files, each model once, in the order given.
    rows = []
    for path in models:
        key = model_key(path)
        row = read_result(result_path(out, key), sig) or results.get(key)
        if row is None:  # its row file vanished during the run
            row = _cluster_failure_row({"file": path, "operation": operation, "signature": sig},
                                       OSError(f"the row {result_path(out, key)} disappeared"))
        rows.append(row)
    summary.rows = rows
    summary.failed = sum(1 for r in rows if r.get("status") != "ok")
    summary.csv_path = os.path.abspath(csv_path) if csv_path else os.path.join(out, "results.csv")
    summary.jsonl_path = os.path.abspath(jsonl_path) if jsonl_path else os.path.join(out, "results.jsonl")
    write_atomic(summary.csv_path, csv_text(operation, rows))
    write_atomic(summary.jsonl_path, jsonl_text(rows))
    summary.seconds = time.perf_counter() - started
    return summary


# --------------------------------------------------------------------------------------------
# Command line


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="volspline batch",
        description="Run one volspline operation on many model files with Dask: one row per model "
        "(DIR/results.csv, DIR/results.jsonl), outputs in DIR/outputs; a rerun skips the models done.",
        epilog="Arguments after -- go to every CLI command (e.g. -- --tol 1e-6). Exit codes: 0 every model "
        "succeeded, 3 some failed (see their rows), 2 bad usage or no Dask.")
    p.add_argument("operation", choices=list(OPERATIONS), help="jacobian, boundary, convert, view, info, or mass (info --mass)")
    p.add_argument("models", nargs="*", help="model files, or folders of them (.json, .xml, .itd, .vtu)")
    p.add_argument("--out", required=True, metavar="DIR", help="folder of the results and outputs")
    p.add_argument("--files-from", metavar="LIST", help="also the model files listed in LIST, one a line ('-': stdin)")
    p.add_argument("--workers", type=int, metavar="N", help="worker processes of the local cluster (default: one per CPU)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="use the Dask cluster at ADDRESS (tcp://host:8786) instead")
    p.add_argument("--csv", metavar="F", help="the CSV table (default DIR/results.csv)")
    p.add_argument("--jsonl", metavar="F", help="the JSON lines table (default DIR/results.jsonl)")
    p.add_argument("--format", dest="output_format", metavar="EXT",
                   help="outputs' extension: boundary ply|obj|stl (ply), convert json|xml|itd|vtu (json), view png")
    p.add_argument("--cli", metavar="PATH", help="the volspline executable (default $VOLSPLINE_CLI, beside the package, PATH)")
    p.add_argument("--timeout", type=float, default=DEFAULT_TIMEOUT, metavar="S", help="seconds per model (default 600)")
    p.add_argument("--retries", type=int, default=2, metavar="N", help="reruns of a task that raised (default 2)")
    p.add_argument("--redo-failed", action="store_true", help="rerun the models whose stored row failed")
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors and the summary")
    p.add_argument("-v", "--verbose", action="store_true", help="print each failed model's error as its row arrives")
    return p


def main(argv: Optional[Sequence[str]] = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    extra = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1:]
    parser = _parser()
    args = parser.parse_args(argv)
    if args.workers is not None and args.workers < 1:
        parser.error("--workers: expected at least 1")
    if args.workers is not None and args.scheduler:
        parser.error("--workers and --scheduler exclude each other")
    if args.timeout <= 0:
        parser.error("--timeout: expected a number > 0")
    try:
        import dask  # noqa: F401
        import distributed  # noqa: F401
    except ImportError as e:
        print(f"volspline batch: error: needs Dask ({e}); on Debian: apt-get install python3-dask python3-distributed",
              file=sys.stderr)
        return 2
    models = collect_models(args.models, args.files_from)
    if not models:
        parser.error("no model files given")
    last = [0.0]

    def report(row, done, total):
        if args.verbose and row.get("status") != "ok":
            print(f"{'' if not sys.stderr.isatty() else chr(13)}volspline batch: {row['file']}: {row.get('error')}",
                  file=sys.stderr, flush=True)
        if args.quiet:
            return
        if sys.stderr.isatty():
            now = time.monotonic()
            if done != total and now - last[0] < 0.2:
                return
            last[0] = now
            print(f"\rvolspline batch: {done}/{total} models", end="\n" if done == total else "", file=sys.stderr, flush=True)
        elif done == total or done % max(1, total // 10) == 0:
            print(f"volspline batch: {done}/{total} models", file=sys.stderr, flush=True)

    try:
        summary = run_batch(args.operation, models, args.out, workers=args.workers, scheduler=args.scheduler,
                            cli=args.cli, extra_args=extra, output_format=args.output_format, timeout=args.timeout,
                            retries=args.retries, redo_failed=args.redo_failed, csv_path=args.csv,
                            jsonl_path=args.jsonl, progress=report)
    except BatchError as e:
        print(f"volspline batch: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"volspline batch: error: {e}", file=sys.stderr)
        return 2
    print(f"{len(summary.rows)} models: {len(summary.rows) - summary.failed} ok, {summary.failed} failed "
          f"({summary.ran} run, {summary.skipped} skipped as done), {summary.seconds:.1f} s; "
          f"{summary.csv_path}, {summary.jsonl_path}")
    return 3 if summary.failed else 0


if __name__ == "__main__":
    # Run through the package's module, not this copy as __main__, so that the tasks Dask ships
    # to workers refer to volspline.batch (importable there) rather than to __main__.
    from volspline.batch import main as _main

    sys.exit(_main())
