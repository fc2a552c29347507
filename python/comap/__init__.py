# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Dense, accurate and cycle-consistent point-to-point maps between two triangle meshes.

The Python interface of Surface_mesh_correspondence (the C++ library behind the ``comap``
command line). Meshes are numpy arrays: ``V`` of shape (n, 3), the vertex positions, and ``F`` of
shape (m, 3), the triangles as 0-based vertex indices. Maps are numpy arrays of 0-based vertex
indices: ``map_12[i]`` is the vertex of mesh 2 matched to vertex i of mesh 1.

    >>> import comap
    >>> map_12, map_21, info = comap.match(V1, F1, V2, F2)
"""

import numpy as _np

from . import _comap

__all__ = ["match"]

#: Whether the library runs its parallel code paths (Intel TBB), on every core by default.
has_tbb = _comap.has_tbb


def _points(V, name):
    a = _np.asarray(V)
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{name} must be an (n, 3) array of vertex positions, got shape {a.shape}")
    if a.dtype.kind not in "fiu":
        raise ValueError(f"{name} must hold numbers, got dtype {a.dtype}")
    return _np.ascontiguousarray(a, dtype=_np.float64)


def _indices(A, name, ndim, columns=None, what="vertex indices"):
    a = _np.asarray(A)
    if a.ndim != ndim or (columns is not None and a.shape[1] != columns):
        shape = "(m, %d)" % columns if columns is not None else "(n,)"
        raise ValueError(f"{name} must be an {shape} array of {what}, got shape {a.shape}")
    if a.size > 0 and a.dtype.kind not in "iu":
        raise ValueError(f"{name} must hold integers ({what}), got dtype {a.dtype}")
    if a.dtype.kind == "u" and a.size > 0 and a.max() > _np.iinfo(_np.int64).max:
        raise ValueError(f"{name} holds an index too large for a mesh")
    return _np.ascontiguousarray(a, dtype=_np.int64)


def match(V1, F1, V2, F2, init=None, landmarks=None):
    """Computes dense point-to-point maps between two triangle meshes, in both directions.

    The whole pipeline of the library's ``match_shapes()``: automatic initial maps (functional
    maps and ZoomOut; guided by ``landmarks`` when given), or the maps of ``init`` (their tears
    repaired, and compared with the automatic maps), then the coupled refinement of Azencot,
    Dubrovina and Guibas (2019), kept where it makes the maps better. The maps are the same as
    those of ``comap match`` on the same meshes.

    Parameters
    ----------
    V1, V2 : array_like, shape (n, 3)
        Vertex positions of mesh 1 and mesh 2 (any real dtype; converted to float64).
    F1, F2 : array_like, shape (m, 3)
        Triangles as 0-based vertex indices (any integer dtype), consistently oriented. Each mesh
        must be one connected, manifold surface (with or without boundary).
    init : pair of array_like, optional
        Initial maps ``(map_12, map_21)``: ``map_12`` of shape (n1,) holds, for each vertex of
        mesh 1, a 0-based vertex of mesh 2, and ``map_21`` of shape (n2,) the other way round.
        Default: automatic initial maps.
    landmarks : array_like, shape (k, 2), optional
        Known correspondences (vertex of mesh 1, vertex of mesh 2), 0-based, that guide the
        automatic initial maps (not with ``init``).

    Returns
    -------
    map_12 : numpy.ndarray of int64, shape (n1,)
        ``map_12[i]`` is the 0-based vertex of mesh 2 matched to vertex i of mesh 1.
    map_21 : numpy.ndarray of int64, shape (n2,)
        The map from mesh 2 to mesh 1.
    info : dict
        What the run did, with the keys of ``comap match --stats``: ``decisions`` (one line per
        decision), ``stage_seconds``, ``inconsistent_vertices_before`` / ``_after``,
        ``cycle_error_before`` / ``_after``, ``distortion_before`` / ``_after``, ``selection``,
        ``refinement`` (its TRW-S solves), ``unrefined_map_12`` / ``_21`` (the maps that entered
        the refinement), ...

    Raises
    ------
    ValueError
        Arrays of the wrong shape or type; meshes that are empty, not made of triangles, not
        manifold, not connected, with a non-finite coordinate or a face index out of range;
        initial maps or landmarks that are not maps between the meshes. The message names the
        mesh and the vertex or face.
    RuntimeError
        A numerical failure (e.g. an eigensolver that does not converge).
    """
    V1 = _points(V1, "V1")
    V2 = _points(V2, "V2")
    F1 = _indices(F1, "F1", 2, 3)
    F2 = _indices(F2, "F2", 2, 3)
    maps = None
    if init is not None:
        if landmarks is not None:
            raise ValueError("landmarks guide the automatic initial maps: give init or landmarks, not both")
        if len(init) != 2:
            raise ValueError("init must be a pair (map_12, map_21)")
        maps = (_indices(init[0], "init[0] (the map 1 -> 2)", 1),
                _indices(init[1], "init[1] (the map 2 -> 1)", 1))
    if landmarks is not None:
        landmarks = _indices(landmarks, "landmarks", 2, 2, "vertex pairs")
    return _comap.match(V1, F1, V2, F2, maps, landmarks)
