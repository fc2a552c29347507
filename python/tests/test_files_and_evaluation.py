# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""comap's files (meshes, maps) and evaluation functions, against what the test wrote and against
independent references: great-circle distances on a sphere, numpy brute force."""

import os

import numpy as np
import pytest

import comap
from test_match import icosphere, write_off


@pytest.fixture(scope="module")
def sphere():
    return icosphere(4)  # 2562 vertices on the unit sphere


def mesh_area(V, F):
    return 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1).sum()


# ---------------------------------------------------------------------------------------- meshes

def test_read_mesh_off_obj_ply(tmp_path):
    V, F = icosphere(1)
    write_off(tmp_path / "a.off", V, F)
    V2, F2 = comap.read_mesh(tmp_path / "a.off")
    assert V2.dtype == np.float64 and F2.dtype == np.int64
    assert np.array_equal(V2, V) and np.array_equal(F2, F)
    with open(tmp_path / "a.obj", "w") as f:
        f.write("# an OBJ file\nmtllib none.mtl\n")
        for p in V:
            f.write("v %r %r %r\n" % tuple(p))
        f.write("vn 0 0 1\n")
        for k, t in enumerate(F):
            # 1-based "i/t/n" entries, and negative (relative) indices on one face
            if k == 5:
                f.write("f %d %d %d\n" % tuple(int(i) - len(V) for i in t))
            else:
                f.write("f %d/1/1 %d//1 %d\n" % tuple(int(i) + 1 for i in t))
    V3, F3 = comap.read_mesh(str(tmp_path / "a.obj"))
    assert np.array_equal(V3, V) and np.array_equal(F3, F)
    with open(tmp_path / "a.ply", "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\nproperty double y\n"
                "property double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                % (len(V), len(F)))
        for p in V:
            f.write("%r %r %r\n" % tuple(p))
        for t in F:
            f.write("3 %d %d %d\n" % tuple(t))
    V4, F4 = comap.read_mesh(tmp_path / "a.ply")
    assert np.array_equal(V4, V) and np.array_equal(F4, F)


def test_read_mesh_errors_name_file_and_line(tmp_path):
    V, F = icosphere(1)
    write_off(tmp_path / "nan.off", V, F)
    lines = (tmp_path / "nan.off").read_text().splitlines()
    lines[2 + 7] = "0 nan 1"  # vertex 7 is on line 10
    (tmp_path / "nan.off").write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"nan.off:10: vertex 7 has a non-finite coordinate"):
        comap.read_mesh(tmp_path / "nan.off")
    lines = (tmp_path / "nan.off").read_text().splitlines()
    lines[2 + 7] = "0 0 1"
    lines[2 + len(V) + 3] = "3 0 1 %d" % len(V)  # face 3
    (tmp_path / "range.off").write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"range.off:%d: face 3 refers to vertex %d" % (2 + len(V) + 4, len(V))):
        comap.read_mesh(tmp_path / "range.off")
    (tmp_path / "short.off").write_text("\n".join(lines[:20]) + "\n")
    with pytest.raises(OSError, match="short.off: truncated"):
        comap.read_mesh(tmp_path / "short.off")
    with pytest.raises(OSError, match="cannot open .*missing.off"):
        comap.read_mesh(tmp_path / "missing.off")
    with pytest.raises(OSError, match="it is a directory"):
        os.mkdir(tmp_path / "dir.off")
        comap.read_mesh(tmp_path / "dir.off")
    (tmp_path / "points.xyz").write_text("0 0 0\n")
    with pytest.raises(OSError, match="unknown mesh format"):
        comap.read_mesh(tmp_path / "points.xyz")


# ------------------------------------------------------------------------------------------ maps

def test_map_files_round_trip(tmp_path):
    m = np.random.default_rng(3).integers(0, 1000, 500)
    comap.write_map(tmp_path / "m.map", m)
    text = (tmp_path / "m.map").read_text().split()
    assert [int(x) for x in text] == list(m + 1)  # 1-based by default, like comap
    assert np.array_equal(comap.read_map(tmp_path / "m.map"), m)
    comap.write_map(tmp_path / "m0.map", m.astype(np.int32), index_base=0)
    assert [int(x) for x in (tmp_path / "m0.map").read_text().split()] == list(m)
    assert np.array_equal(comap.read_map(tmp_path / "m0.map", index_base=0), m)
    # Replaced atomically: no temporary file is left beside the outputs.
    comap.write_map(tmp_path / "m.map", m[::-1])
    assert np.array_equal(comap.read_map(tmp_path / "m.map"), m[::-1])
    assert sorted(os.listdir(tmp_path)) == ["m.map", "m0.map"]


def test_map_file_errors(tmp_path):
    (tmp_path / "bad.map").write_text("1\n2\nseven\n")
    with pytest.raises(OSError, match="bad.map:3"):
        comap.read_map(tmp_path / "bad.map")
    (tmp_path / "zero.map").write_text("1\n0\n")
    with pytest.raises(OSError, match="zero.map:2"):
        comap.read_map(tmp_path / "zero.map")
    with pytest.raises(OSError):
        comap.read_map(tmp_path / "missing.map")
    with pytest.raises(OSError):
        comap.write_map(tmp_path / "no" / "such" / "folder.map", [1, 2])
    with pytest.raises(ValueError, match="entry 1 is -2"):
        comap.write_map(tmp_path / "neg.map", [1, -2])
    with pytest.raises(ValueError, match="index_base"):
        comap.read_map(tmp_path / "zero.map", index_base=2)


# ------------------------------------------------------------------------------------ evaluation

def great_circle(V, a, b):
    return np.arccos(np.clip((V[a] * V[b]).sum(axis=1), -1, 1))


def test_geodesic_errors_are_great_circle_distances(sphere):
    V, F = sphere
    rng = np.random.default_rng(5)
    map_ = rng.permutation(len(V))
    gt = rng.choice(len(V), 300, replace=False)
    errors = comap.geodesic_errors(V, F, map_, gt, gt)
    reference = great_circle(V, map_[gt], gt) / np.sqrt(mesh_area(V, F))
    assert errors.shape == (300,)
    far = reference > 0.1
    assert np.all(np.abs(errors[far] - reference[far]) < 0.03 * reference[far])
    assert np.all(np.abs(errors - reference) < 0.01)
    # A perfect map has no error.
    assert np.all(comap.geodesic_errors(V, F, np.arange(len(V)), gt, gt) == 0)
    # The symmetric ground truth: each sample's error is the smaller of the two.
    antipodes = np.array([np.argmax(-(V @ V[i])) for i in gt])
    sym = comap.geodesic_errors(V, F, map_, gt, gt, gt_target_symmetric=antipodes)
    other = comap.geodesic_errors(V, F, map_, gt, antipodes)
    assert np.allclose(sym, np.minimum(errors, other))


def test_cycle_errors_coverage_and_inconsistency(sphere):
    V, F = sphere
    n = len(V)
    rng = np.random.default_rng(9)
    perm = rng.permutation(n)
    inverse = np.argsort(perm)
    assert np.all(comap.cycle_errors(V, F, perm, inverse) == 0)
    # With the identity back, the cycle of x ends at perm[x].
    cycle = comap.cycle_errors(V, F, perm, np.arange(n))
    reference = great_circle(V, np.arange(n), perm) / np.sqrt(mesh_area(V, F))
    assert np.all(np.abs(cycle - reference) < 0.01)
    # Coverage and inconsistency against brute force.
    m12 = rng.integers(0, n, n)
    m21 = rng.integers(0, n, n)
    m21[m12[:1000]] = np.arange(1000)
    assert comap.coverage(m12, n) == pytest.approx(len(np.unique(m12)) / n)
    brute = np.sum(m21[m12] != np.arange(n)) + np.sum(m12[m21] != np.arange(n))
    assert comap.inconsistent_vertices(m12, m21) == brute
    assert comap.inconsistent_vertices(perm, inverse) == 0


def test_evaluation_errors(sphere):
    V, F = sphere
    n = len(V)
    with pytest.raises(ValueError, match="ground truth"):
        comap.geodesic_errors(V, F, np.arange(n), [0, 1, 2], [0, 1])
    with pytest.raises(ValueError, match="map"):
        comap.geodesic_errors(V, F, np.full(n, n), [0], [0])
    with pytest.raises(ValueError, match="map_12"):
        comap.inconsistent_vertices([0, 5], [0, 1])
    with pytest.raises(ValueError, match="map"):
        comap.coverage([0, 7], 5)
    with pytest.raises(ValueError, match="map 1->2 has 3 entries"):
        comap.cycle_errors(V, F, [0, 1, 2], np.arange(n))
