"""volspline.batch on a LocalCluster of 2 workers (docs/python.md, "Batch runs (Dask)").

200 small models, broken ones among them (bad JSON, a missing file, folded volumes), and one
worker killed in the middle of the run: every model has exactly one row, the broken ones with
the CLI's error and exit code, the good ones with the figures the CLI gives run directly on the
same file; a rerun runs only what is not done.
"""
import concurrent.futures
import csv
import json
import logging
import os
from pathlib import Path
import signal
import subprocess
import sys

import pytest

dask = pytest.importorskip("dask", reason="volspline.batch needs Dask: apt-get install python3-dask")
distributed = pytest.importorskip("distributed", reason="volspline.batch needs Dask: apt-get install python3-distributed")
import distributed.diagnostics.plugin  # noqa: E402

from volspline import batch  # noqa: E402

GOOD_PER_KIND = 97  # boxes and tubes: 194 good models, 6 broken ones, 200 in all


@pytest.fixture(scope="module")
def cli_path():
    path = os.environ.get("VOLSPLINE_CLI")
    if not path:
        pytest.skip("VOLSPLINE_CLI is not set (run through ctest)")
    return path


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                       silence_logs=logging.CRITICAL)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def run_cli(cli_path, *args):
    r = subprocess.run([cli_path, *map(str, args)], capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def transformed(model, scale, shift):
    """The model under x -> scale x + shift (a point at infinity, weight 0, is a direction: scaled only)."""
    out = json.loads(json.dumps(model))
    for o in out["objects"]:
        weights = o.get("weights")
        o["control_points"] = [[scale * c + (0 if weights is not None and weights[i] == 0 else shift[k])
                                for k, c in enumerate(p)] for i, p in enumerate(o["control_points"])]
    return out


def folded_box():
    """A trilinear box whose corner (1, 1, 1) is pulled through to (-1, -1, -1): J = 1 at the
    corner (0, 0, 0) and J = -5 at (1, 1, 1), so the Jacobian changes sign."""
    points = [[float(i), float(j), float(k)] for k in (0, 1) for j in (0, 1) for i in (0, 1)]
    points[7] = [-1.0, -1.0, -1.0]
    return {"volspline": 1, "objects": [{"name": "folded", "type": "bspline_volume", "degree": [1, 1, 1],
                                         "knots": [[0, 0, 1, 1]] * 3, "control_points": points}]}


@pytest.fixture(scope="module")
def library(tmp_path_factory, cli_path):
    """200 model paths, and which are broken and how."""
    base = tmp_path_factory.mktemp("base")
    for kind, args in {"box": ["--size", "1,2,3"], "tube": ["--radius", "2", "--height", "1", "--inner", "1"]}.items():
        code, _, err = run_cli(cli_path, "make", "box" if kind == "box" else "cylinder", *args, "-o", base / f"{kind}.json")
        assert code == 0, err
    bases = {kind: json.loads((base / f"{kind}.json").read_text()) for kind in ("box", "tube")}
    folder = tmp_path_factory.mktemp("models")
    models, broken = [], {}
    for i in range(GOOD_PER_KIND):
        for kind, model in bases.items():
            path = folder / f"{kind}-{i:03}.json"
            path.write_text(json.dumps(transformed(model, 1 + 0.01 * i, [i, -0.5 * i, 0.25])))
            models.append(str(path))
    for i in range(2):
        bad = folder / f"bad-json-{i}.json"
        bad.write_text('{"volspline": 1, "objects": [ {"type": ')
        missing = folder / f"missing-{i}.json"
        folded = folder / f"folded-{i}.json"
        folded.write_text(json.dumps(transformed(folded_box(), 1 + i, [0, 0, 0])))
        broken.update({str(bad): "bad-json", str(missing): "missing", str(folded): "folded"})
        # spread among the good ones, so that some fail on each worker
        models[40 * i + 7:40 * i + 7] = [str(bad), str(missing), str(folded)]
    assert len(models) == 200 and len(set(models)) == 200
    return models, broken


def without_seconds(x):
    if isinstance(x, dict):
        return {k: without_seconds(v) for k, v in x.items() if "seconds" not in k}
    if isinstance(x, list):
        return [without_seconds(v) for v in x]
    return x


def direct_figures(cli_path, operation, path, extra=()):
    """The figures of the CLI run directly on one model, as the batch's command line runs it."""
    spec = batch.OPERATIONS[operation]
    code, out, err = run_cli(cli_path, *spec["command"], path, *spec["args"], *extra)
    return code, (json.loads(out)["objects"] if out.strip() else None), err


def check_rows_once(summary, models):
    assert [row["file"] for row in summary.rows] == models
    with open(summary.jsonl_path) as f:
        lines = [json.loads(line) for line in f]
    assert sorted(r["file"] for r in lines) == sorted(models)
    with open(summary.csv_path, newline="") as f:
        table = list(csv.DictReader(f))
    assert sorted(r["file"] for r in table) == sorted(models)
    return lines, table


def test_jacobian_of_200_models_with_a_worker_killed_midway(client, library, cli_path, tmp_path):
    models, broken = library
    killed = []

    def kill_one_worker(_row, done, _total):
        if done == 50 and not killed:
            pids = client.run(os.getpid)
            address, pid = sorted(pids.items())[0]
            os.kill(pid, signal.SIGKILL)
            killed.append(address)

    summary = batch.run_batch("jacobian", models, tmp_path / "out", client=client, cli=cli_path, progress=kill_one_worker)
    assert killed, "the run ended before a worker could be killed"
    assert summary.ran == 200 and summary.skipped == 0
    assert summary.cluster_failures == []
    lines, table = check_rows_once(summary, models)
    rows = {r["file"]: r for r in lines}
    assert summary.failed == len(broken)

    for path, how in broken.items():
        row = rows[path]
        assert row["status"] == "failed"
        if how == "folded":
            assert row["exit_code"] == 3 and row["verdict"] == "invalid"
            assert "invalid Jacobian" in row["error"]
            (figure,) = row["figures"]
            assert figure["lower"] < 0 < figure["upper"]
        else:
            assert row["exit_code"] == 2
            assert os.path.basename(path) in row["error"], row["error"]

    # the good ones: the CLI's own figures on the same file, run directly (2 at a time)
    good = [m for m in models if m not in broken]
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        direct = dict(zip(good, pool.map(lambda m: direct_figures(cli_path, "jacobian", m), good)))
    for path in good:
        row = rows[path]
        code, figures, err = direct[path]
        assert code == 0, err
        assert row["status"] == "ok" and row["exit_code"] == 0 and row["error"] == ""
        assert row["verdict"] == "valid" and row["objects"] == 1
        assert without_seconds(row["figures"]) == without_seconds(figures)
    csv_rows = {r["file"]: r for r in table}
    for path in good[:5]:
        assert float(csv_rows[path]["lower"]) == rows[path]["figures"][0]["lower"]

    # the cluster has its two workers back (the nanny restarted the killed one)
    client.wait_for_workers(2, timeout=30)

    # a rerun skips every model done, failures included
    again = batch.run_batch("jacobian", models, tmp_path / "out", client=client, cli=cli_path)
    assert again.ran == 0 and again.skipped == 200
    assert [without_seconds(r) for r in again.rows] == [without_seconds(r) for r in summary.rows]
    # ... runs just the models whose rows are gone
    for path in good[:5]:
        os.unlink(batch.result_path(str(tmp_path / "out"), batch.model_key(path)))
    again = batch.run_batch("jacobian", models, tmp_path / "out", client=client, cli=cli_path)
    assert again.ran == 5 and again.skipped == 195
    check_rows_once(again, models)
    # ... and the failed ones when asked
    again = batch.run_batch("jacobian", models, tmp_path / "out", client=client, cli=cli_path, redo_failed=True)
    assert again.ran == len(broken) and again.failed == len(broken)
    # other arguments are another request: nothing is skipped
    again = batch.run_batch("jacobian", models[:4], tmp_path / "out", client=client, cli=cli_path,
                            extra_args=["--bounds", "cone"])
    assert again.ran == 4


def test_mass_equals_the_cli_and_scales_with_the_cube_of_the_factor(client, library, cli_path, tmp_path):
    models, broken = library
    sample = [m for m in models if m not in broken][:20] + list(broken)[:2]
    summary = batch.run_batch("mass", sample, tmp_path / "out", client=client, cli=cli_path)
    lines, table = check_rows_once(summary, sample)
    rows = {r["file"]: r for r in lines}
    for path in sample[:20]:
        code, figures, err = direct_figures(cli_path, "mass", path)
        assert code == 0, err
        assert rows[path]["figures"] == figures
    # the boxes 1 x 2 x 3 scaled by 1 + 0.01 i
    for i in range(10):
        (box,) = rows[[m for m in sample if os.path.basename(m) == f"box-{i:03}.json"][0]]["figures"]
        assert box["volume"] == pytest.approx(6 * (1 + 0.01 * i) ** 3, rel=1e-13)
    assert {r["file"]: r["status"] for r in lines if r["status"] != "ok"} == {p: "failed" for p in sample[20:]}


@pytest.mark.parametrize("operation,extra,suffix", [
    ("boundary", ["--face-resolution", "4"], ".ply"),
    ("convert", [], ".json"),
    ("view", ["--size", "64,48", "--faces"], ".png"),
])
def test_operations_with_outputs(client, library, cli_path, tmp_path, operation, extra, suffix):
    models, broken = library
    sample = [m for m in models if m not in broken][:3] + [m for m, how in broken.items() if how == "bad-json"][:1]
    summary = batch.run_batch(operation, sample, tmp_path / "out", client=client, cli=cli_path, extra_args=extra)
    lines, _ = check_rows_once(summary, sample)
    for row in lines[:3]:
        assert row["status"] == "ok", row["error"]
        assert row["outputs"] and all(os.path.isfile(p) for p in row["outputs"])
        assert row["outputs"][0].endswith(suffix)
        assert os.path.dirname(row["outputs"][0]) == str(tmp_path / "out" / "outputs")
    bad = lines[3]
    assert bad["status"] == "failed" and bad["exit_code"] == 2 and bad["outputs"] == []
    if operation == "boundary":
        for row in lines[:3]:
            direct_stats = tmp_path / "direct.stats.json"
            code, _, err = run_cli(cli_path, "boundary", row["file"], "-o", tmp_path / "direct.ply", "--stats",
                                   direct_stats, *extra)
            assert code == 0, err
            assert without_seconds(row["figures"]) == without_seconds(json.loads(direct_stats.read_text()))
    if operation == "convert":
        for row in lines[:3]:
            code, figures, err = direct_figures(cli_path, "info", row["outputs"][0])
            _, original, _ = direct_figures(cli_path, "info", row["file"])
            assert code == 0, err
            assert row["objects"] == len(original) == len(figures)
    if operation == "view":
        assert all((row["figures"]["width"], row["figures"]["height"]) == (64, 48) for row in lines[:3])


def test_a_crashing_or_hanging_cli_costs_only_its_rows(client, tmp_path):
    fake = tmp_path / "fake-volspline"
    fake.write_text('#!/bin/sh\ncase "$(basename "$2")" in\n  *crash*) kill -SEGV $$ ;;\n  *hang*) exec sleep 60 ;;\nesac\n'
                    'echo \'{"objects": [{"type": "bspline_volume"}]}\'\n')
    fake.chmod(0o755)
    names = ["fine-0.json", "crash.json", "hang.json", "fine-1.json"]
    models = [str(tmp_path / n) for n in names]
    for m in models:
        Path(m).write_text("{}\n")  # the fake ignores the content; the batch checks that the file exists
    summary = batch.run_batch("info", models, tmp_path / "out", client=client, cli=str(fake), timeout=2)
    rows = {os.path.basename(r["file"]): r for r in summary.rows}
    assert rows["fine-0.json"]["status"] == rows["fine-1.json"]["status"] == "ok", rows
    assert rows["fine-0.json"]["objects"] == 1
    assert rows["crash.json"]["exit_code"] == -signal.SIGSEGV and "SIGSEGV" in rows["crash.json"]["error"]
    assert "timed out after 2 s" in rows["hang.json"]["error"]


def test_command_line(cli_path, library, tmp_path):
    models, broken = library
    good = [m for m in models if m not in broken][:2]
    missing = [m for m, how in broken.items() if how == "missing"][0]
    env = dict(os.environ, VOLSPLINE_CLI=cli_path)
    command = [sys.executable, "-m", "volspline.batch", "mass", *good, missing, "--out", str(tmp_path / "out"),
               "--workers", "1", "--csv", str(tmp_path / "table.csv")]
    r = subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 3, r.stderr  # one model failed
    assert "3 models: 2 ok, 1 failed" in r.stdout
    with open(tmp_path / "table.csv", newline="") as f:
        table = list(csv.DictReader(f))
    assert [row["file"] for row in table] == [*good, missing]
    assert float(table[0]["volume"]) == pytest.approx(6.0, rel=1e-13)
    assert table[2]["exit_code"] == "2" and os.path.basename(missing) in table[2]["error"]
    r = subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)
    assert "(0 run, 3 skipped as done)" in r.stdout
    r = subprocess.run([sys.executable, "-m", "volspline.batch", "nonsense", "--out", str(tmp_path)],
                       capture_output=True, text=True, env=env)
    assert r.returncode == 2 and "invalid choice" in r.stderr



class FinishedVolsplineTasks(distributed.diagnostics.plugin.SchedulerPlugin):
    """Counts on the scheduler the batch tasks that finished there (keys `volspline-OPERATION-...`)."""
    name = "finished-volspline-tasks"

    def __init__(self):
        self.keys = set()

    def transition(self, key, start, finish, *args, **kwargs):
        if finish == "memory" and str(key).startswith("volspline-"):
            self.keys.add(str(key))


def test_scheduler_address_runs_on_that_cluster_and_leaves_it_running(client, library, cli_path, tmp_path):
    """`--scheduler ADDRESS` (a running cluster: the LocalCluster of this module, reached by its
    address only, from another process): the rows are the CLI's, every task finished on that
    scheduler, and the batch leaves the cluster and its workers running."""
    models, broken = library
    good = [m for m in models if m not in broken][:4]
    folded = [m for m, how in broken.items() if how == "folded"][0]
    address = client.scheduler.address
    assert address.startswith("tcp://")
    client.register_scheduler_plugin(FinishedVolsplineTasks())

    def finished_keys(dask_scheduler):
        return sorted(dask_scheduler.plugins[FinishedVolsplineTasks.name].keys)

    workers = set(client.scheduler_info()["workers"])
    env = dict(os.environ, VOLSPLINE_CLI=cli_path)
    out = tmp_path / "out"
    try:
        r = subprocess.run([sys.executable, "-m", "volspline.batch", "jacobian", *good, folded, "--out", str(out),
                            "--scheduler", address], capture_output=True, text=True, env=env, timeout=300)
        keys = client.run_on_scheduler(finished_keys)
    finally:
        client.run_on_scheduler(lambda dask_scheduler: dask_scheduler.remove_plugin(name=FinishedVolsplineTasks.name))
    assert r.returncode == 3, r.stderr  # the folded model
    assert "5 models: 4 ok, 1 failed" in r.stdout
    assert len(keys) == 5 and all(k.startswith("volspline-jacobian-") for k in keys)
    assert set(client.scheduler_info()["workers"]) == workers
    rows = {row["file"]: row for row in map(json.loads, (out / "results.jsonl").read_text().splitlines())}
    assert sorted(rows) == sorted([*good, folded])
    for path in good:
        code, figures, _ = direct_figures(cli_path, "jacobian", path)
        assert code == 0 and rows[path]["verdict"] == "valid"
        assert without_seconds(rows[path]["figures"]) == without_seconds(figures)
    assert rows[folded]["verdict"] == "invalid" and rows[folded]["exit_code"] == 3
    r = subprocess.run([sys.executable, "-m", "volspline.batch", "jacobian", *good, "--out", str(out),
                        "--scheduler", address, "--workers", "2"], capture_output=True, text=True, env=env)
    assert r.returncode == 2 and "exclude each other" in r.stderr
