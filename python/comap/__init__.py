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

import numbers as _numbers
import os as _os

import numpy as _np

from . import _comap

__all__ = ["match", "Shape", "match_shapes", "Stopped", "settings", "check_settings", "read_settings", "read_mesh", "read_map", "write_map", "geodesic_errors", "cycle_errors", "coverage",
           "inconsistent_vertices"]

#: Whether the library runs its parallel code paths (Intel TBB), on every core by default.
has_tbb = _comap.has_tbb

#: Raised when a ``progress`` callback returned False (a RuntimeError).
Stopped = _comap.Stopped
Stopped.__doc__ = """Raised by match and match_shapes when their progress callback returned False:
the run stopped at that event, and no maps were returned (a RuntimeError)."""

_REGISTRY = {s["name"]: s for s in _comap.settings_registry()}


def settings():
    """The settings registry: a dict from each setting's name to what the registry says of it
    (``type``, ``default``, ``default_for_given_maps``, ``range``, ``stage``, ``documentation``),
    in registry order. doc/settings.md explains them; ``comap settings`` prints them as a file."""
    return {name: {k: v for k, v in s.items() if k != "name"} for name, s in _REGISTRY.items()}


def check_settings(settings):
    """Checks a dict of settings by registry name without running anything: raises ValueError for
    an unknown name (naming the closest valid one), a value of the wrong type or out of its
    range."""
    _comap.check_settings(_settings(settings, allow_preparation=True))


def read_settings(file):
    """Reads a settings file, as ``comap match --settings`` does: one JSON object from registry
    names to values, with ``//`` comments; ``null`` keeps a setting's default (such entries are
    left out). ``comap settings`` prints every setting in this form. Returns a dict for the
    ``settings=`` of ``match``, ``Shape`` and ``match_shapes``. Raises ``OSError`` for a file that
    cannot be read or is malformed and ``ValueError`` for an unknown name (naming the closest
    valid one) or a bad value, both naming the file and the line."""
    return _comap.read_settings(_path(file))


def _setting_value(name, v):
    if isinstance(v, (bool, _np.bool_)):
        return bool(v)
    if isinstance(v, str):
        return v
    if isinstance(v, _numbers.Real):
        return float(v)
    if isinstance(v, (list, tuple, _np.ndarray)):
        items = list(v)
        if all(isinstance(x, _numbers.Real) and not isinstance(x, (bool, _np.bool_)) for x in items):
            return [float(x) for x in items]
        if all(isinstance(x, (list, tuple, _np.ndarray)) for x in items):
            return [[float(y) for y in x] for x in items]
    raise ValueError(f"setting {name}: {v!r} is not a number, a Boolean, a word or a list of numbers")


def _settings(given, allow_preparation=False):
    """The settings dict as the C++ half takes it; unknown names are refused by the library,
    naming the closest valid one."""
    if given is None:
        return {}
    if not isinstance(given, dict):
        raise ValueError(f"settings must be a dict from setting names to values, got {type(given).__name__}")
    out = {}
    for name, v in given.items():
        if not allow_preparation and name in _REGISTRY and _REGISTRY[name]["stage"] == "preparation":
            raise ValueError(f"{name} is a setting of the shapes' preparation: give it to comap.Shape(..., settings=)")
        out[str(name)] = _setting_value(name, v)
    return out


def _threads(threads):
    if threads is None:
        return 0
    if isinstance(threads, bool) or not isinstance(threads, _numbers.Integral) or threads < 1:
        raise ValueError(f"threads must be a positive integer or None (every core), got {threads!r}")
    return int(threads)


def _progress(progress):
    if progress is not None and not callable(progress):
        raise ValueError("progress must be a callable progress(stage, fraction) or None")
    return progress


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


def match(V1, F1, V2, F2, init=None, landmarks=None, settings=None, threads=None, progress=None):
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
        must be one connected surface (with or without boundary); non-manifold edges and
        vertices and faces of zero area are handled (``info["irregularities_1"]``).
    init : pair of array_like, optional
        Initial maps ``(map_12, map_21)``: ``map_12`` of shape (n1,) holds, for each vertex of
        mesh 1, a 0-based vertex of mesh 2, and ``map_21`` of shape (n2,) the other way round.
        Default: automatic initial maps.
    landmarks : array_like, shape (k, 2), optional
        Known correspondences (vertex of mesh 1, vertex of mesh 2), 0-based, that guide the
        automatic initial maps (not with ``init``).
    settings : dict, optional
        Expert settings by registry name (``comap.settings()``, doc/settings.md), e.g.
        ``{"number_of_candidates": 60, "ring_schedule": [3, 2, 1]}``. An unknown name raises a
        ValueError naming the closest valid one; a value out of its range names the range.
    threads : int, optional
        The number of threads of this run (default: every core).
    progress : callable, optional
        ``progress(stage, fraction)``, called as each stage ("preparation", "initialization",
        "refinement", ...) begins (0), progresses and ends (1), from the run's threads, one call
        at a time. Returning False stops the run (``comap.Stopped``); an exception it raises stops
        the run and is re-raised. Ctrl-C stops the run too (KeyboardInterrupt), at its next event.

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
        ``diagnostics`` (the ground-truth-free diagnostics of each direction before and after
        the refinement, over each mesh and per region, with ``regions_1`` / ``_2``: the region
        of every vertex), ``confidence`` (``score`` in [0, 1], ``low``: the maps are probably
        wrong as a whole, ``reason``), ``refinement`` (its TRW-S solves), ``unrefined_map_12`` / ``_21`` (the
        maps that entered the refinement), ``irregularities_1`` / ``_2`` (what the input check
        found in each mesh and the matching handled, 0-based: ``non_manifold_edges`` (k, 2),
        ``non_manifold_vertices``, ``degenerate_faces``), ...

    Raises
    ------
    ValueError
        Arrays of the wrong shape or type; meshes that are empty, not made of triangles, not
        connected, inconsistently oriented, with a non-finite coordinate, a face index out of
        range or a face repeating a vertex (non-manifold edges and vertices and faces of zero
        area are matched);
        initial maps or landmarks that are not maps between the meshes. The message names the
        mesh and the vertex or face.
    RuntimeError
        A numerical failure (e.g. an eigensolver that does not converge).
    comap.Stopped
        The ``progress`` callback returned False.
    """
    V1 = _points(V1, "V1")
    V2 = _points(V2, "V2")
    F1 = _indices(F1, "F1", 2, 3)
    F2 = _indices(F2, "F2", 2, 3)
    maps, landmarks = _inputs(init, landmarks)
    return _comap.match(V1, F1, V2, F2, maps, landmarks, _settings(settings, allow_preparation=True), _threads(threads),
                        _progress(progress))


class Shape:
    """A mesh prepared once for matching against many: its Laplace-Beltrami spectrum, its
    descriptors, its geodesic distance oracle and the automatic initialisation's data, computed
    when the Shape is made (most of the time of a ``match``).

        >>> template = comap.Shape(V0, F0, name="template")
        >>> for V, F in scans:
        ...     map_12, map_21, info = comap.match_shapes(template, comap.Shape(V, F))

    ``V``, ``F``: as for ``match``. ``name`` names the mesh in error messages. ``settings``: the
    settings of the preparation (and those of the initialisation its data depend on), by registry
    name as for ``match``; the settings of stage "preparation" can only be given here.
    ``threads``: as for ``match``. Raises ``ValueError`` as ``match`` does for a mesh it refuses.
    """

    def __init__(self, V, F, name="mesh", settings=None, threads=None):
        self.V = _points(V, "V")
        self.F = _indices(F, "F", 2, 3)
        self.V.flags.writeable = False
        self.F.flags.writeable = False
        self.name = str(name)
        self._shape = _comap.Shape(self.V, self.F, self.name, _settings(settings, allow_preparation=True), _threads(threads))

    @property
    def number_of_vertices(self):
        """The number of vertices."""
        return self._shape.number_of_vertices

    @property
    def preparation_seconds(self):
        """Seconds spent preparing the shape, per part (mesh, spectrum, descriptors, distances,
        initialization) and in total."""
        return self._shape.preparation_seconds

    def __repr__(self):
        return f"comap.Shape({self.name!r}, {self.number_of_vertices} vertices, {len(self.F)} triangles)"


def match_shapes(shape_1, shape_2, init=None, landmarks=None, settings=None, threads=None, progress=None):
    """``match`` on two prepared shapes (``Shape``): the same maps as ``match`` on their arrays
    with the same settings, without preparing the shapes again. ``init``, ``landmarks``,
    ``settings`` (except those of stage "preparation", given to ``Shape``), ``threads``,
    ``progress`` and the returned ``(map_12, map_21, info)`` are as for ``match``;
    ``info["stage_seconds"]["preparation"]`` is 0. A shape can be matched by several threads at
    once (the C++ code runs without the GIL)."""
    for k, s in (("shape_1", shape_1), ("shape_2", shape_2)):
        if not isinstance(s, Shape):
            raise TypeError(f"{k} must be a comap.Shape, got {type(s).__name__}")
    maps, landmarks = _inputs(init, landmarks)
    return _comap.match_shapes(shape_1._shape, shape_2._shape, maps, landmarks, _settings(settings),
                               _threads(threads), _progress(progress))


def _inputs(init, landmarks):
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
    return maps, landmarks


def _map(A, name):
    return _indices(A, name, 1, what="vertex indices")


def _path(file):
    return _os.fspath(file)


def read_mesh(file):
    """Reads a triangle mesh from an OFF, OBJ, PLY or STL file.

    Returns ``(V, F)``: ``V`` the (n, 3) float64 vertex positions in the order of the file (vertex
    i of the maps is the i-th point of the file), ``F`` the (m, 3) int64 triangles, 0-based.

    The mesh gets the checks of ``match``. Raises ``OSError`` for a file that cannot be read
    (missing, a directory, an unknown format, truncated or malformed) and ``ValueError`` for a
    mesh ``match`` refuses (a non-finite coordinate, a face index out of range, a non-triangle,
    several components, ...); for OFF and OBJ files the message names the line
    ("a.off:12: vertex 9 has a non-finite coordinate").
    """
    return _comap.read_mesh(_path(file))


def read_map(file, index_base=1):
    """Reads a vertex map or a ground-truth correspondence list: one vertex index per line
    (lines starting with '#' and empty lines are skipped), ``index_base``-based in the file
    (1, the default, as in the FAUST_r and TOSCA_r .map and .vts files and ``comap``'s default;
    or 0). Returns a 0-based int64 numpy array. Raises ``OSError`` for a missing file or a line that is
    not an index >= index_base, naming the file and the line."""
    if index_base not in (0, 1):
        raise ValueError(f"index_base must be 0 or 1, got {index_base!r}")
    return _comap.read_map(_path(file), index_base)


def write_map(file, map, index_base=1):
    """Writes a 0-based vertex map, one index per line, ``index_base``-based in the file (1 by
    default, as ``comap`` writes them). The file is replaced atomically: a temporary file in the
    same folder renamed into place, so a killed run never leaves a truncated map."""
    if index_base not in (0, 1):
        raise ValueError(f"index_base must be 0 or 1, got {index_base!r}")
    _comap.write_map(_path(file), _map(map, "map"), index_base)


def geodesic_errors(V, F, map, gt_source, gt_target, gt_target_symmetric=None):
    """Geodesic errors of a map from a source mesh to the target mesh ``(V, F)`` against ground
    truth: sample k says that source vertex ``gt_source[k]`` corresponds to target vertex
    ``gt_target[k]``, and its error is the geodesic distance on the target between
    ``map[gt_source[k]]`` and ``gt_target[k]``, divided by the square root of the target's area
    (the benchmarks' normalisation). With ``gt_target_symmetric`` (the ground truth composed with
    the target's intrinsic symmetry), each error is the smaller of the two.

    For two shapes with .vts files (a shared template's vertices on each shape): ``gt_source`` is
    the source's list, ``gt_target`` the target's. Returns one float64 error per sample; e.g.
    ``errors.mean()`` and ``(errors <= 0.025).mean()``. Raises ``ValueError`` for lists of
    different lengths or an index out of range.
    """
    sym = None if gt_target_symmetric is None else _map(gt_target_symmetric, "gt_target_symmetric")
    return _comap.geodesic_errors(_points(V, "V"), _indices(F, "F", 2, 3), _map(map, "map"),
                                  _map(gt_source, "gt_source"), _map(gt_target, "gt_target"), sym)


def cycle_errors(V1, F1, map_12, map_21):
    """Cycle consistency of ``map_12`` (mesh 1 -> mesh 2) and ``map_21`` (back): for every vertex
    x of mesh 1 ``(V1, F1)``, the geodesic distance on mesh 1 between x and
    ``map_21[map_12[x]]``, divided by the square root of mesh 1's area. Returns one float64
    value per vertex of mesh 1 (0 where the cycle returns to x)."""
    return _comap.cycle_errors(_points(V1, "V1"), _indices(F1, "F1", 2, 3), _map(map_12, "map_12"),
                               _map(map_21, "map_21"))


def coverage(map, target_vertices):
    """The fraction of the ``target_vertices`` vertices of the target that ``map`` reaches."""
    return _comap.coverage(_map(map, "map"), int(target_vertices))


def inconsistent_vertices(map_12, map_21):
    """The number of vertices x with ``map_21[map_12[x]] != x`` plus the number of vertices y
    with ``map_12[map_21[y]] != y``: up to a factor 2, the cycle-consistency measure of Eq. (4) of
    Azencot, Dubrovina and Guibas (2019)."""
    return _comap.inconsistent_vertices(_map(map_12, "map_12"), _map(map_21, "map_21"))
