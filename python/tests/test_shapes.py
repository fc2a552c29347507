# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""comap.Shape and comap.match_shapes: prepared once, the same maps as comap.match, and safe to
match from several Python threads at once (the C++ code runs without the GIL)."""

import threading

import numpy as np
import pytest

import comap
from test_match import pair, result  # noqa: F401 (fixtures)


@pytest.fixture(scope="module")
def shapes(pair):
    V1, F1, V2, F2 = pair
    return comap.Shape(V1, F1, name="mesh 1"), comap.Shape(V2, F2, name="mesh 2")


def test_prepared_shapes_give_the_maps_of_match(pair, result, shapes):
    s1, s2 = shapes
    assert s1.number_of_vertices == len(pair[0])
    assert set(s1.preparation_seconds) == {"mesh", "spectrum", "descriptors", "distances", "initialization", "total"}
    assert s1.preparation_seconds["total"] > 0
    assert "642 vertices" in repr(s1)
    m12, m21, info = comap.match_shapes(s1, s2)
    assert np.array_equal(m12, result[0]) and np.array_equal(m21, result[1])
    assert info["stage_seconds"]["preparation"] == 0
    # Given maps, on shapes and on arrays.
    init = (np.roll(result[0], 1), result[1])
    a = comap.match_shapes(s1, s2, init=init)
    b = comap.match(*pair, init=init)
    assert a[2]["initial_maps"] == "given"
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


def test_threads_share_prepared_shapes(result, shapes):
    s1, s2 = shapes
    out = [None, None]

    def run(k):
        out[k] = comap.match_shapes(s1, s2)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for m12, m21, _ in out:
        assert np.array_equal(m12, result[0]) and np.array_equal(m21, result[1])


def test_shape_errors(pair, shapes):
    V1, F1, V2, F2 = pair
    with pytest.raises(TypeError, match="shape_2 must be a comap.Shape"):
        comap.match_shapes(shapes[0], (V2, F2))
    bad = V1.copy()
    bad[3, 1] = np.inf
    with pytest.raises(ValueError, match="scan 7: vertex 3 has a non-finite coordinate"):
        comap.Shape(bad, F1, name="scan 7")
    with pytest.raises(ValueError, match="initial map 1->2 has 641 entries"):
        comap.match_shapes(*shapes, init=(np.arange(641), np.arange(642)))
    # The shape keeps its arrays, read-only.
    with pytest.raises(ValueError):
        shapes[0].V[0, 0] = 1
