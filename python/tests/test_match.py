# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""comap.match on numpy arrays: the same maps as `comap match` on the same meshes, bit for bit;
array-likes of other types converted, not refused; bad input raises a ValueError naming it."""

import os
import subprocess

import numpy as np
import pytest

import comap


def icosphere(level):
    """A unit sphere from a subdivided icosahedron, faces oriented outwards."""
    t = (1 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    V = [np.array(v, float) / np.linalg.norm(v) for v in V]
    for _ in range(level):
        midpoint = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                m = V[a] + V[b]
                V.append(m / np.linalg.norm(m))
                midpoint[key] = len(V) - 1
            return midpoint[key]

        F = [f for a, b, c in F for f in ((a, middle(a, b), middle(c, a)), (b, middle(b, c), middle(a, b)),
                                          (c, middle(c, a), middle(b, c)), (middle(a, b), middle(b, c), middle(c, a)))]
    return np.array(V), np.array(F, dtype=np.int64)


def bumpy(V):
    """An elongated shape with bumps that break the sphere's symmetries."""
    x, y, z = V[:, 0], V[:, 1], V[:, 2]
    s = 1 + 0.15 * np.sin(3 * z + 0.5) * np.cos(2 * np.arctan2(y, x) + 0.3 * z) + 0.08 * np.cos(5 * x - 1.1 * z)
    return np.column_stack((s * x, s * y, 2 * s * z))


@pytest.fixture(scope="module")
def pair():
    """Mesh 1, and mesh 2: mesh 1 bent and with its vertices in another order. Coordinates are
    float32 values, so that float32 arrays hold the same meshes."""
    V, F = icosphere(3)
    V1 = bumpy(V).astype(np.float32).astype(np.float64)
    bent = V1.copy()
    angle = 0.25 * bent[:, 2]
    bent[:, 0], bent[:, 2] = (V1[:, 0] * np.cos(angle) + V1[:, 2] * np.sin(angle),
                              -V1[:, 0] * np.sin(angle) + V1[:, 2] * np.cos(angle))
    order = np.random.default_rng(7).permutation(len(V))  # vertex k of mesh 2 is vertex order[k] of mesh 1
    position = np.empty_like(order)
    position[order] = np.arange(len(order))
    V2 = bent[order].astype(np.float32).astype(np.float64)
    F2 = position[F]
    return V1, F, V2, F2


@pytest.fixture(scope="module")
def result(pair):
    return comap.match(*pair)


def write_off(path, V, F):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(V), len(F)))
        for p in V:
            f.write("%r %r %r\n" % tuple(float(c) for c in p))
        for t in F:
            f.write("3 %d %d %d\n" % tuple(t))


def test_maps_are_maps_between_the_meshes(pair, result):
    V1, F1, V2, F2 = pair
    map_12, map_21, info = result
    assert map_12.dtype == np.int64 and map_12.shape == (len(V1),)
    assert map_21.dtype == np.int64 and map_21.shape == (len(V2),)
    assert map_12.min() >= 0 and map_12.max() < len(V2)
    assert map_21.min() >= 0 and map_21.max() < len(V1)
    assert info["initial_maps"] == "automatic"
    assert info["decisions"] and all(isinstance(d, str) for d in info["decisions"])
    assert info["stage_seconds"]["total"] > 0
    assert info["unrefined_map_12"].shape == map_12.shape


def test_diagnostics_are_those_of_the_returned_maps(pair, result):
    # The diagnostics' consistency figures, recounted with numpy from the maps returned (after)
    # and from the maps that entered the refinement (before); the regions cover every vertex.
    V1, F1, V2, F2 = pair
    map_12, map_21, info = result
    g = info["diagnostics"]
    for maps, phase in (((map_12, map_21), "after"),
                        ((info["unrefined_map_12"], info["unrefined_map_21"]), "before")):
        x12, x21 = maps
        for (x, y, key) in ((x12, x21, "map_12"), (x21, x12, "map_21")):
            d = g[key][phase]
            assert d["vertices"] == len(x)
            assert d["inconsistent_fraction"] == pytest.approx(np.mean(y[x] != np.arange(len(x))))
            assert 0 <= d["orientation_reversal"] < 0.05  # accurate maps keep the orientation
            assert len(d["regions"]) == 16
            assert sum(r["vertices"] for r in d["regions"]) == len(x)
            assert d["energy"] == pytest.approx(
                sum(r["energy"] * r["vertices"] for r in d["regions"]) / len(x))
    for labels, n, key in ((g["regions_1"], len(V1), "map_12"), (g["regions_2"], len(V2), "map_21")):
        assert labels.shape == (n,) and labels.min() == 0 and labels.max() == 15
        counts = [r["vertices"] for r in g[key]["after"]["regions"]]
        assert counts == list(np.bincount(labels, minlength=16))


def test_maps_are_accurate(pair, result):
    # Mesh 2 is mesh 1 bent, with its vertices reordered: the true match of vertex i of mesh 1 is
    # vertex position[i] of mesh 2. On this smooth, asymmetric pair nearly all matches are exact.
    V1, F1, V2, F2 = pair
    map_12, map_21, _ = result
    order = np.random.default_rng(7).permutation(len(V1))
    assert np.mean(order[map_12] == np.arange(len(V1))) > 0.9
    assert np.mean(map_21 == order) > 0.9
    error = np.linalg.norm(V1[order[map_12]] - V1, axis=1)
    assert np.median(error) < 0.05


def test_same_maps_as_the_command_line(tmp_path, pair, result):
    V1, F1, V2, F2 = pair
    write_off(tmp_path / "a.off", V1, F1)
    write_off(tmp_path / "b.off", V2, F2)
    subprocess.run([os.environ.get("COMAP", "comap"), "match", str(tmp_path / "a.off"), str(tmp_path / "b.off"),
                    "--out-12", str(tmp_path / "12.txt"), "--out-21", str(tmp_path / "21.txt"),
                    "--index-base", "0", "--quiet"], check=True, timeout=600)
    assert np.array_equal(np.loadtxt(tmp_path / "12.txt", dtype=np.int64), result[0])
    assert np.array_equal(np.loadtxt(tmp_path / "21.txt", dtype=np.int64), result[1])


def test_other_types_and_layouts_are_converted(pair, result):
    V1, F1, V2, F2 = pair
    V1_fortran = np.asfortranarray(V1.astype(np.float32))
    wide = np.zeros((len(F2), 6), dtype=np.int32)
    wide[:, ::2] = F2  # a non-contiguous view
    m12, m21, _ = comap.match(V1_fortran, F1.astype(np.uint32), V2.tolist(), wide[:, ::2])
    assert np.array_equal(m12, result[0]) and np.array_equal(m21, result[1])


def test_given_maps(pair, result):
    V1, F1, V2, F2 = pair
    m12, m21, info = comap.match(V1, F1, V2, F2, init=(result[0].astype(np.int32), list(result[1])))
    assert info["initial_maps"] == "given"
    assert m12.shape == result[0].shape and m21.shape == result[1].shape


def message(error):
    return str(error.value)


@pytest.mark.parametrize("bad, words", [
    (lambda V, F: (V[:, :2], F), ["V1", "(n, 3)", "(642, 2)"]),
    (lambda V, F: (V, F[:, :2]), ["F1", "(m, 3)"]),
    (lambda V, F: (V, F.astype(float)), ["F1", "integers"]),
    (lambda V, F: (np.where(np.arange(len(V))[:, None] == 5, np.nan, V), F), ["mesh 1", "vertex 5", "non-finite"]),
    (lambda V, F: (V, np.where(np.arange(len(F))[:, None] == 3, len(V), F)), ["mesh 1", "face 3", "refers to vertex 642"]),
    (lambda V, F: (V, np.where(np.arange(len(F))[:, None] == 3, -1, F)), ["mesh 1", "face 3", "refers to vertex -1"]),
    (lambda V, F: (V, np.where((np.arange(len(F))[:, None] == 3) & (np.arange(3) == 1), F[:, :1], F)),
     ["mesh 1", "face 3", "repeats vertex"]),
    (lambda V, F: (V, np.vstack([F[:, ::-1][:1], F[1:]])), ["mesh 1", "inconsistently oriented"]),
    (lambda V, F: (np.vstack([V, V + 5]), np.vstack([F, F + len(V)])), ["mesh 1", "2 connected components"]),
])
def test_bad_meshes_raise_value_errors(pair, bad, words):
    V1, F1, V2, F2 = pair
    V, F = bad(V1, F1)
    with pytest.raises(ValueError) as e:
        comap.match(V, F, V2, F2)
    for w in words:
        assert w in message(e), message(e)


def test_non_manifold_and_degenerate_meshes_are_matched(pair, tmp_path):
    """A fin on an edge of mesh 2 and a face of zero area: matched, and reported in info."""
    V1, F1, V2, F2 = pair
    i, j, k = F2[0]
    normal = np.cross(V2[j] - V2[i], V2[k] - V2[i])
    tip = 0.5 * (V2[i] + V2[j]) + np.linalg.norm(V2[j] - V2[i]) * normal / np.linalg.norm(normal)
    V = np.vstack([V2, tip])
    F = np.vstack([F2, [[i, j, len(V2)]]])
    a, b, c = F[100]
    V[c] = V[a] + 0.5 * (V[b] - V[a])  # face 100 flattened: its vertex c at the middle of (a, b)
    m12, m21, info = comap.match(V1, F1, V, F)
    assert m12.shape == (len(V1),) and m21.shape == (len(V),)
    assert info["irregularities_2"]["non_manifold_edges"].tolist() == [sorted([int(i), int(j)])]
    assert list(info["irregularities_2"]["degenerate_faces"]) == [100]
    assert len(info["irregularities_1"]["non_manifold_edges"]) == 0
    assert any("input: mesh 2 has 1 non-manifold edge, 1 degenerate face" in d for d in info["decisions"])
    # read_mesh gives such a file the checks of match, which it passes.
    write_off(tmp_path / "fin.off", V, F)
    V_read, F_read = comap.read_mesh(str(tmp_path / "fin.off"))
    assert np.array_equal(F_read, F)


def test_too_small_meshes_raise_value_errors(pair):
    V1, F1, V2, F2 = pair
    V, F = icosphere(2)
    with pytest.raises(ValueError, match="mesh 2 has 162 vertices, too few"):
        comap.match(V1, F1, bumpy(V), F)


def test_bad_maps_and_landmarks_raise_value_errors(pair, result):
    V1, F1, V2, F2 = pair
    with pytest.raises(ValueError, match="init must be a pair"):
        comap.match(V1, F1, V2, F2, init=(result[0],))
    with pytest.raises(ValueError, match=r"init\[0\].*641 entries.*642 vertices"):
        comap.match(V1, F1, V2, F2, init=(result[0][1:], result[1]))
    bad = result[1].copy()
    bad[17] = len(V1)
    with pytest.raises(ValueError, match=r"init\[1\].*entry 17 is 642"):
        comap.match(V1, F1, V2, F2, init=(result[0], bad))
    with pytest.raises(ValueError, match="landmarks.*vertex pairs"):
        comap.match(V1, F1, V2, F2, landmarks=[1, 2, 3])
    with pytest.raises(ValueError, match=r"landmark \(3, 642\)"):
        comap.match(V1, F1, V2, F2, landmarks=[(0, 0), (3, 642)])
    with pytest.raises(ValueError, match="not both"):
        comap.match(V1, F1, V2, F2, init=result[:2], landmarks=[(0, 0)])
