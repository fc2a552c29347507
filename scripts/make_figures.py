#!/usr/bin/python3
# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Makes the pictures of the README and the manual (doc/fig/) from the project's own outputs:

- demo_maps.png: the demo pair coloured by the map (`comap demo`'s coloured PLY files): the
  target coloured by position, the source coloured through the final map, and through the ground
  truth; software-rendered here (numpy z-buffer, Lambert shading), no viewer needed;
- cumulative_error.svg: the cumulative error curves of the current defaults, copied from the
  outputs of `comap bench` (FAUST_r and TOSCA_r subsets, benchmark/README.md);
- pipeline.svg: the stages of match_shapes().

    build/bin/comap demo --out out/demo
    scripts/make_figures.py --demo out/demo [--bench out/faust20 out/tosca19] [--out doc/fig]

Needs only python3 and python3-numpy.
"""

import argparse
import os
import shutil
import struct
import sys
import tempfile
import zlib

import numpy as np


def read_colored_ply(path):
    """Vertices (n, 3), colours (n, 3) in [0, 1] and triangles (m, 3) of an ASCII PLY as `comap`
    writes them (x y z red green blue per vertex, "3 i j k" per face)."""
    with open(path) as f:
        counts, properties = {}, []
        element = None
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "element":
                element = words[1]
                counts[element] = int(words[2])
            elif words[0] == "property" and element == "vertex":
                properties.append(words[-1])
            elif words[0] == "end_header":
                break
        if properties[:6] != ["x", "y", "z", "red", "green", "blue"]:
            raise ValueError(f"{path}: expected vertices with x y z red green blue, found {' '.join(properties)}")
        rows = [f.readline().split() for _ in range(counts["vertex"])]
        V = np.array([[float(w) for w in r[:3]] for r in rows])
        C = np.array([[int(w) for w in r[3:6]] for r in rows]) / 255.0
        faces = [f.readline().split() for _ in range(counts["face"])]
        F = np.array([[int(w) for w in r[1:4]] for r in faces if r and r[0] == "3"], dtype=np.int64)
    return V, C, F


def view_frame(V):
    """An orthographic view of a standing figure: the longest axis of the bounding box up, the
    shortest as the viewing direction."""
    extent = V.max(axis=0) - V.min(axis=0)
    order = np.argsort(extent)  # shortest, middle, longest
    return order[1], order[2], order[0]


def render(V, C, F, axes, size, light=(0.3, 0.5, 1.0)):
    """An RGB image (float in [0, 1], white background, `size` pixels tall and as wide as the
    mesh's outline needs) of the mesh seen along `axes` = (right, up, towards the viewer),
    Lambert-shaded per face, vertex colours interpolated."""
    right, up, depth = axes
    P = np.stack([V[:, right], V[:, up], V[:, depth]], axis=1)
    lo, hi = P[:, :2].min(axis=0), P[:, :2].max(axis=0)
    scale = 0.92 * size / (hi - lo).max()
    width = int(np.ceil((hi - lo)[0] * scale / 0.92)) + 2
    centre = (lo + hi) / 2
    X = (P[:, 0] - centre[0]) * scale + width / 2
    Y = size / 2 - (P[:, 1] - centre[1]) * scale
    Z = P[:, 2]
    image = np.ones((size, width, 3))
    zbuffer = np.full((size, width), -np.inf)
    light = np.asarray(light, dtype=float) / np.linalg.norm(light)
    normals = np.cross(P[F[:, 1]] - P[F[:, 0]], P[F[:, 2]] - P[F[:, 0]])
    lengths = np.linalg.norm(normals, axis=1)
    lengths[lengths == 0] = 1
    shade = 0.35 + 0.65 * np.abs(normals @ light) / lengths
    for t, (a, b, c) in enumerate(F):
        xs, ys = X[[a, b, c]], Y[[a, b, c]]
        x0, x1 = int(max(np.floor(xs.min()), 0)), int(min(np.ceil(xs.max()), width - 1))
        y0, y1 = int(max(np.floor(ys.min()), 0)), int(min(np.ceil(ys.max()), size - 1))
        if x0 > x1 or y0 > y1:
            continue
        det = (ys[1] - ys[2]) * (xs[0] - xs[2]) + (xs[2] - xs[1]) * (ys[0] - ys[2])
        if abs(det) < 1e-12:
            continue
        gx, gy = np.meshgrid(np.arange(x0, x1 + 1) + 0.5, np.arange(y0, y1 + 1) + 0.5)
        l0 = ((ys[1] - ys[2]) * (gx - xs[2]) + (xs[2] - xs[1]) * (gy - ys[2])) / det
        l1 = ((ys[2] - ys[0]) * (gx - xs[2]) + (xs[0] - xs[2]) * (gy - ys[2])) / det
        l2 = 1 - l0 - l1
        inside = (l0 >= -1e-9) & (l1 >= -1e-9) & (l2 >= -1e-9)
        if not inside.any():
            continue
        z = l0 * Z[a] + l1 * Z[b] + l2 * Z[c]
        window = zbuffer[y0:y1 + 1, x0:x1 + 1]
        front = inside & (z > window)
        if not front.any():
            continue
        window[front] = z[front]
        colour = (l0[..., None] * C[a] + l1[..., None] * C[b] + l2[..., None] * C[c]) * shade[t]
        image[y0:y1 + 1, x0:x1 + 1][front] = np.clip(colour[front], 0, 1)
    return image


def write_png(path, image):
    """An RGB PNG (8 bits per channel) from a float image in [0, 1], written atomically."""
    data = (np.clip(image, 0, 1) * 255 + 0.5).astype(np.uint8)
    height, width = data.shape[:2]
    raw = b"".join(b"\x00" + data[y].tobytes() for y in range(height))

    def chunk(kind, payload):
        return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload) & 0xFFFFFFFF)

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    write_atomically(path, png)


def write_atomically(path, data):
    folder = os.path.dirname(os.path.abspath(path))
    fd, temporary = tempfile.mkstemp(dir=folder, prefix=".fig-")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data if isinstance(data, bytes) else data.encode())
        os.chmod(temporary, 0o644)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise


def demo_figure(demo_dir, path, size=360):
    """The target coloured by position, the source through the final map and through the ground
    truth, side by side."""
    panels = []
    names = ["target_colors.ply", "source_final.ply", "source_ground_truth.ply"]
    meshes = [read_colored_ply(os.path.join(demo_dir, n)) for n in names]
    for V, C, F in meshes:
        panels.append(render(V, C, F, view_frame(V), size))
    gap = np.ones((size, size // 6, 3))
    write_png(path, np.concatenate([panels[0], gap, panels[1], gap, panels[2]], axis=1))


def pipeline_figure(path):
    """The stages of match_shapes() as boxes and arrows (SVG)."""
    stages = [("validation", "meshes and maps checked"),
              ("preparation", "spectra, HKS/WKS/SHOT, distance oracle"),
              ("initialization", "functional maps + coupled ZoomOut"),
              ("repair, comparison", "given maps only"),
              ("refinement", "coupled MRFs solved by TRW-S"),
              ("selection", "keep refined matches where better")]
    w, h, gap = 150, 58, 26
    width = len(stages) * w + (len(stages) - 1) * gap + 20
    out = [f'<?xml version="1.0" encoding="UTF-8"?>\n<svg xmlns="http://www.w3.org/2000/svg" width="{width}" '
           f'height="{h + 20}" font-family="sans-serif" font-size="11">',
           '<defs><marker id="a" markerWidth="8" markerHeight="8" refX="7" refY="4" orient="auto">'
           '<path d="M0,0 L8,4 L0,8 z" fill="#444"/></marker></defs>']
    for i, (name, what) in enumerate(stages):
        x = 10 + i * (w + gap)
        fill = "#f3f3f3" if name.startswith("repair") else "#dfe9f7"
        out.append(f'<rect x="{x}" y="10" width="{w}" height="{h}" rx="6" fill="{fill}" stroke="#456"/>')
        out.append(f'<text x="{x + w / 2}" y="33" text-anchor="middle" font-weight="bold">{name}</text>')
        out.append(f'<text x="{x + w / 2}" y="51" text-anchor="middle" font-size="9.5">{what}</text>')
        if i + 1 < len(stages):
            out.append(f'<line x1="{x + w}" y1="{10 + h / 2}" x2="{x + w + gap - 2}" y2="{10 + h / 2}" '
                       'stroke="#444" marker-end="url(#a)"/>')
    out.append("</svg>\n")
    write_atomically(path, "\n".join(out))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--demo", required=True, metavar="DIR", help="the folder of `comap demo --out DIR`")
    parser.add_argument("--bench", nargs="*", default=[], metavar="DIR",
                        help="folders of `comap bench --out DIR`: their cumulative_error.svg is copied")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "doc", "fig"),
                        metavar="DIR", help="where the figures go (default doc/fig)")
    args = parser.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    try:
        demo_figure(args.demo, os.path.join(args.out, "demo_maps.png"))
    except (OSError, ValueError, KeyError) as e:
        print(f"make_figures: {args.demo}: {e} (run build/bin/comap demo --out {args.demo} first)", file=sys.stderr)
        return 1
    pipeline_figure(os.path.join(args.out, "pipeline.svg"))
    for folder in args.bench:
        name = os.path.basename(os.path.normpath(folder))
        shutil.copyfile(os.path.join(folder, "cumulative_error.svg"), os.path.join(args.out, f"cumulative_error_{name}.svg"))
    print(f"figures written to {os.path.normpath(args.out)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
