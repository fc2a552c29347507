#!/usr/bin/env python3
# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Is the ground truth more isometric than our map?

For every map of a `comap bench` run whose mean error exceeds --min-error, compares the geodesic
distortion of the map with that of the ground-truth correspondence on the same samples: 100
farthest-point samples among the source's ground-truth vertices (NAME.vts), distortion = mean over
sample pairs of |d_S(s_i, s_j) / sqrt(A_S) - d_T(T(s_i), T(s_j)) / sqrt(A_T)|, with graph (edge
path) geodesics. Where the ground truth distorts more than the map, an isometry-based objective
(the distortion score of the automatic maps, the pairwise term of the refinement) prefers the
wrong map: no search can fix such a map without another prior.

    python3 benchmark/ground_truth_distortion.py --data DIR --run OUT [--min-error 0.05]

DIR is the dataset (off/, corres/), OUT a `comap bench` output directory (pairs.csv, maps/).
Needs numpy and scipy (Debian: python3-scipy).
"""
import argparse
import csv

import numpy as np
import scipy.sparse as sp
import scipy.sparse.csgraph as cg


def load_off(path):
    with open(path) as f:
        t = f.read().split()
    if t[0] != 'OFF':
        raise SystemExit(f'{path}: not an OFF file')
    nv, nf = int(t[1]), int(t[2])
    i = 4
    V = np.array(t[i:i + 3 * nv], float).reshape(nv, 3)
    i += 3 * nv
    F = np.array(t[i:i + 4 * nf], int).reshape(nf, 4)[:, 1:]
    return V, F


def load_indices(path):
    return np.loadtxt(path, dtype=int) - 1  # 1-based files


class Shape:
    def __init__(self, data, name):
        V, F = load_off(f'{data}/off/{name}.off')
        E = np.vstack([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
        w = np.linalg.norm(V[E[:, 0]] - V[E[:, 1]], axis=1)
        G = sp.coo_matrix((w, (E[:, 0], E[:, 1])), shape=(len(V), len(V))).tocsr()
        self.graph = G.maximum(G.T)
        n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
        self.scale = np.sqrt(0.5 * np.linalg.norm(n, axis=1).sum())
        self.gt = load_indices(f'{data}/corres/{name}.vts')

    def distances(self, sources, targets):
        return cg.dijkstra(self.graph, indices=sources)[:, targets] / self.scale

    def samples(self, count):
        """Farthest-point samples among the ground-truth vertices (positions in self.gt)."""
        chosen = [0]
        d = self.distances([self.gt[0]], self.gt)[0]
        for _ in range(count - 1):
            j = int(np.argmax(d))
            chosen.append(j)
            d = np.minimum(d, self.distances([self.gt[j]], self.gt)[0])
        return np.array(chosen)


def distortion(source, target, source_vertices, images):
    ds = source.distances(source_vertices, source_vertices)
    dt = target.distances(images, images)
    return np.abs(ds - dt).mean()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--data', required=True)
    ap.add_argument('--run', required=True)
    ap.add_argument('--min-error', type=float, default=0.05)
    ap.add_argument('--samples', type=int, default=100)
    args = ap.parse_args()
    shapes = {}

    def shape(name):
        if name not in shapes:
            shapes[name] = Shape(args.data, name)
        return shapes[name]

    rows = [r for r in csv.DictReader(open(f'{args.run}/pairs.csv'))
            if float(r['refined_error']) > args.min_error]
    worse = 0
    for r in rows:
        a, b = r['source'], r['target']
        S, T = shape(a), shape(b)
        m = load_indices(f'{args.run}/maps/{a}_{b}.map')
        k = S.samples(args.samples)
        src = S.gt[k]
        ours = distortion(S, T, src, m[src])
        truth = distortion(S, T, src, T.gt[k])
        worse += truth >= ours
        print(f'{a} -> {b}: error {float(r["refined_error"]):.3f}, distortion of the map {ours:.4f}, '
              f'of the ground truth {truth:.4f}{"  (ground truth distorts more)" if truth >= ours else ""}',
              flush=True)
    print(f'{len(rows)} maps with error > {args.min_error}; on {worse} the ground truth distorts '
          f'geodesics at least as much as the map')


if __name__ == '__main__':
    main()
