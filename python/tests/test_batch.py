# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The batch runner on 6 generated pairs, one with a corrupt mesh: 5 ok rows with their maps and
figures, 1 failed row with the mesh's error, exit status 1; maps equal comap.match's, in this
process and on a dask LocalCluster of 2 workers; a worker killed mid-batch costs only a retry of
its pair; an interrupted batch, run again, does not redo finished pairs; bad pairs files and
settings stop before any pair."""

import csv
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import comap
import comap.batch
from test_match import bumpy, icosphere, write_off


def shape(k):
    """Shape k: the bumpy sphere bent by an angle of its own, with its vertices in an order of
    its own; returns V, F and `order` (vertex j of the shape is vertex order[j] of shape 0)."""
    V, F = icosphere(3)
    V = bumpy(V)
    a = 0.08 * k * V[:, 2]
    bent = np.column_stack((V[:, 0] * np.cos(a) + V[:, 2] * np.sin(a), V[:, 1], -V[:, 0] * np.sin(a) + V[:, 2] * np.cos(a)))
    order = np.random.default_rng(k).permutation(len(V)) if k else np.arange(len(V))
    position = np.argsort(order)
    return bent[order], position[F], order


@pytest.fixture(scope="module")
def collection(tmp_path_factory):
    """Shapes 0-4 as OFF files with ground truth (.vts: the template's vertices, here shape 0's,
    on each shape), one corrupt mesh, and a pairs file of 6 pairs (the fourth uses the corrupt
    mesh; the second starts from given maps)."""
    d = tmp_path_factory.mktemp("collection")
    os.mkdir(d / "meshes")
    orders = {}
    for k in range(5):
        V, F, order = shape(k)
        write_off(d / "meshes" / f"s{k}.off", V, F)
        orders[k] = order
        np.savetxt(d / "meshes" / f"s{k}.vts", np.argsort(order) + 1, fmt="%d")
    V, F, _ = shape(1)
    write_off(d / "meshes" / "corrupt.off", V, F)
    lines = (d / "meshes" / "corrupt.off").read_text().splitlines()
    lines[2 + 10] = "0.5 nan 0.25"
    (d / "meshes" / "corrupt.off").write_text("\n".join(lines) + "\n")
    # Given maps for the pair s0 -> s2: the truth, shifted by one vertex on 40 vertices.
    truth_02 = np.argsort(orders[2])
    init = truth_02.copy()
    init[:40] = truth_02[1:41]
    np.savetxt(d / "init_12.map", init + 1, fmt="%d")
    np.savetxt(d / "init_21.map", orders[2] + 1, fmt="%d")
    rows = [("s0", "s1", "", ""), ("s0", "s2", "init_12.map", "init_21.map"), ("s1", "s3", "", ""),
            ("s0", "corrupt", "", ""), ("s2", "s4", "", ""), ("s3", "s0", "", "")]
    with open(d / "pairs.csv", "w") as f:
        f.write("source,target,init_12,init_21,gt_source,gt_target\n")
        for a, b, i12, i21 in rows:
            gt = (f"meshes/{a}.vts", f"meshes/{b}.vts") if b != "corrupt" else ("", "")
            f.write(f"meshes/{a}.off,meshes/{b}.off,{i12},{i21},{gt[0]},{gt[1]}\n")
    return d


def run_batch(collection, out, *options, env=None):
    run = subprocess.run([sys.executable, "-m", "comap.batch", str(collection / "pairs.csv"), "--out", str(out),
                          *options], capture_output=True, text=True, timeout=900, env=env)
    with open(out / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return run, out, rows


@pytest.fixture(scope="module")
def batch(collection):
    """The batch in this process, one pair after the other (--workers 0)."""
    return run_batch(collection, collection / "out", "--workers", "0")


@pytest.fixture(scope="module")
def dask_batch(collection):
    """The batch on an embedded LocalCluster of 2 workers; the worker that gets the pair s1-s3 dies
    the first time (a test hook), so that the pair is retried on another worker."""
    env = dict(os.environ, COMAP_BATCH_TEST_DIE_ON=f"s1-s3:{collection / 'died'}")
    return run_batch(collection, collection / "out_dask", "--workers", "2", env=env)


def test_five_ok_rows_and_one_failed_row(batch):
    run, out, rows = batch
    assert run.returncode == 1, run.stderr
    assert "5 of 6 pairs ok" in run.stderr
    assert [r["status"] for r in rows] == ["ok", "ok", "ok", "failed", "ok", "ok"]
    failed = rows[3]
    assert failed["name"] == "s0-corrupt"
    assert "corrupt.off:13: vertex 10 has a non-finite coordinate" in failed["error"]
    assert failed["map_12"] == "" and not os.path.exists(out / "maps" / "s0-corrupt_12.map")
    assert "failed: s0-corrupt: " in run.stderr
    assert list(rows[0].keys()) == comap.batch.RESULT_COLUMNS
    for r in rows[:3] + rows[4:]:
        assert r["error"] == ""
        assert float(r["seconds"]) >= float(r["match_seconds"]) > 0
        assert int(r["vertices_source"]) == 642
        # Near-isometric pairs of a smooth shape: accurate, consistent maps.
        assert float(r["mean_error_12"]) < 0.02 and float(r["mean_error_21"]) < 0.02
        assert float(r["within_0.025_12"]) > 0.8
        assert int(r["inconsistent_vertices"]) < 0.2 * 2 * 642
        assert 0 <= float(r["cycle_error_1"]) < 0.02 and 0.8 < float(r["coverage_12"]) <= 1
    # Nothing but the outputs: no temporary file left.
    assert sorted(os.listdir(out)) == ["maps", "results.csv"]
    assert len(os.listdir(out / "maps")) == 10


def test_dask_workers_give_the_same_results(collection, batch, dask_batch):
    run, out, rows = dask_batch
    assert run.returncode == 1, run.stderr
    assert os.path.exists(collection / "died")  # a worker died during s1-s3 ...
    assert [r["status"] for r in rows] == ["ok", "ok", "ok", "failed", "ok", "ok"]  # ... and cost nothing
    assert rows[3]["error"] == batch[2][3]["error"]
    for r in rows:
        if r["status"] == "ok":
            for k in ("map_12", "map_21"):
                assert (out / r[k]).read_text() == (batch[1] / r[k]).read_text(), r["name"]


def test_interrupted_batch_is_resumed(collection, tmp_path):
    # Kill a batch once two pairs are done; run it again: the finished pairs are kept as they
    # were (same files, not rewritten), the others are done.
    out = tmp_path / "out"
    process = subprocess.Popen([sys.executable, "-m", "comap.batch", str(collection / "pairs.csv"), "--out", str(out),
                                "--workers", "0", "--quiet"])
    deadline = time.time() + 300
    done = []
    while time.time() < deadline and len(done) < 2 and process.poll() is None:
        time.sleep(0.02)
        if (out / "results.csv").exists():
            with open(out / "results.csv", newline="") as f:
                done = list(csv.DictReader(f))
    process.send_signal(signal.SIGKILL)
    process.wait()
    assert 2 <= len(done) < 6, "the batch ended before it could be interrupted"
    with open(out / "results.csv", newline="") as f:
        done = list(csv.DictReader(f))
    stamps = {r["name"]: (out / r["map_12"]).stat().st_mtime_ns for r in done if r["status"] == "ok"}
    run, _, rows = run_batch(collection, out, "--workers", "0")
    assert run.returncode == 1
    assert [r["status"] for r in rows] == ["ok", "ok", "ok", "failed", "ok", "ok"]
    for name, stamp in stamps.items():
        assert (out / "maps" / f"{name}_12.map").stat().st_mtime_ns == stamp, name
    # --redo matches them again.
    run, _, rows = run_batch(collection, out, "--workers", "0", "--redo")
    assert any((out / "maps" / f"{name}_12.map").stat().st_mtime_ns != stamp for name, stamp in stamps.items())


def test_maps_are_those_of_match(collection, batch):
    _, out, rows = batch
    for r in (rows[0], rows[1]):
        V1, F1 = comap.read_mesh(r["source"])
        V2, F2 = comap.read_mesh(r["target"])
        init = None
        if r["name"] == "s0-s2":
            init = (comap.read_map(collection / "init_12.map"), comap.read_map(collection / "init_21.map"))
        m12, m21, _ = comap.match(V1, F1, V2, F2, init=init)
        assert np.array_equal(comap.read_map(out / r["map_12"]), m12)
        assert np.array_equal(comap.read_map(out / r["map_21"]), m21)


def test_function_and_settings(collection, tmp_path):
    pairs = tmp_path / "two.csv"
    pairs.write_text(f"name,source,target\nfirst,{collection}/meshes/s0.off,{collection}/meshes/s1.off\n"
                     f"second,{collection}/meshes/s1.off,{collection}/meshes/s0.off\n")
    rows = comap.batch.run_batch(pairs, tmp_path / "out", settings={"use_refinement": False}, threads=1,
                                 progress=False, workers=0)
    assert [r["status"] for r in rows] == ["ok", "ok"]
    assert "mean_error_12" not in rows[0]  # no ground truth, no accuracy
    V1, F1 = comap.read_mesh(collection / "meshes" / "s0.off")
    V2, F2 = comap.read_mesh(collection / "meshes" / "s1.off")
    m12, _, _ = comap.match(V1, F1, V2, F2, settings={"use_refinement": False})
    assert np.array_equal(comap.read_map(tmp_path / "out" / "maps" / "first_12.map"), m12)


@pytest.mark.parametrize("text, words", [
    ("", "the file is empty"),
    ("source,target\n", "no pair"),
    ("source,destination\na.off,b.off\n", "unknown column 'destination'"),
    ("target\nb.off\n", "no 'source' column"),
    ("source,target,init_12\na.off,b.off,x.map\n", ":2: give both init_12 and init_21"),
    ("source,target\na.off,\n", ":2: no target"),
])
def test_bad_pairs_files(tmp_path, text, words):
    (tmp_path / "pairs.csv").write_text(text)
    run = subprocess.run([sys.executable, "-m", "comap.batch", str(tmp_path / "pairs.csv"), "--out",
                          str(tmp_path / "out")], capture_output=True, text=True, timeout=120)
    assert run.returncode == 2
    assert words in run.stderr, run.stderr
    assert not os.path.exists(tmp_path / "out")


def test_bad_settings_and_missing_pairs_file(collection, tmp_path):
    (tmp_path / "s.json").write_text('{\n  // a comment\n  "number_of_candidate": 5\n}\n')
    run = subprocess.run([sys.executable, "-m", "comap.batch", str(collection / "pairs.csv"), "--out",
                          str(tmp_path / "out"), "--settings", str(tmp_path / "s.json")],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and 'did you mean "number_of_candidates"' in run.stderr
    run = subprocess.run([sys.executable, "-m", "comap.batch", str(tmp_path / "missing.csv"), "--out",
                          str(tmp_path / "out")], capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and "missing.csv" in run.stderr
    run = subprocess.run([sys.executable, "-m", "comap.batch", str(collection / "pairs.csv")],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and "--out" in run.stderr


def test_results_file_has_the_permissions_of_a_new_file(tmp_path):
    """The results table is written through a temporary file (0600) but ends with the permissions
    open() would give it, or those of the file it replaces."""
    mask = os.umask(0o022)
    try:
        path = tmp_path / "results.csv"
        comap.batch.write_results(str(path), [{"name": "a-b", "status": "ok"}])
        assert os.stat(path).st_mode & 0o777 == 0o644
        os.chmod(path, 0o640)
        comap.batch.write_results(str(path), [])
        assert os.stat(path).st_mode & 0o777 == 0o640
        with open(path, newline="") as f:
            assert list(csv.DictReader(f)) == []
        assert sorted(os.listdir(tmp_path)) == ["results.csv"]
    finally:
        os.umask(mask)

