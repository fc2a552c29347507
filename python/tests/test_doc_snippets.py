# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every Python snippet of README.md and doc/python.md runs, in order, on a generated pair whose
arrays and files have the names the snippets use (V1, F1, V2, F2, V0, F0, scans; a.off, b.ply,
a_b.map, b_a.map, a.vts, b.vts)."""

import os
import pathlib
import re
import sys

import numpy as np
import pytest

import comap
from test_match import pair, write_off  # noqa: F401 (fixture)

ROOT = pathlib.Path(__file__).resolve().parents[2]


def snippets(document):
    return re.findall(r"```python\n(.*?)```", (ROOT / document).read_text(), re.S)


def write_ply(path, V, F):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\n"
                "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(V), len(F)))
        for p in V:
            f.write("%r %r %r\n" % tuple(float(c) for c in p))
        for t in F:
            f.write("3 %d %d %d\n" % tuple(t))


@pytest.mark.parametrize("document", ["README.md", "doc/python.md"])
def test_snippets_run(document, pair, tmp_path, monkeypatch, capsys):
    V1, F1, V2, F2 = pair
    write_off(tmp_path / "a.off", V1, F1)
    write_ply(tmp_path / "b.ply", V2, F2)
    order = np.random.default_rng(7).permutation(len(V1))  # the pair's construction (test_match)
    np.savetxt(tmp_path / "a_b.map", np.argsort(order) + 1, fmt="%d")
    np.savetxt(tmp_path / "b_a.map", order + 1, fmt="%d")
    np.savetxt(tmp_path / "a.vts", np.arange(len(V1)) + 1, fmt="%d")
    np.savetxt(tmp_path / "b.vts", np.argsort(order) + 1, fmt="%d")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "argv", ["match_files.py", "a.off", "b.ply", "12.map", "21.map"])
    namespace = {"V1": V1, "F1": F1, "V2": V2, "F2": F2, "V0": V1, "F0": F1, "scans": [(V2, F2)],
                 "__name__": "__snippet__"}
    blocks = snippets(document)
    assert blocks, f"{document} has no Python snippet"
    for k, code in enumerate(blocks):
        exec(compile(code, f"{document} snippet {k + 1}", "exec"), namespace)
    assert len(namespace["map_12"]) == len(V1)
    if document == "doc/python.md":
        # The files snippet started from the true maps, the evaluation snippet measured them.
        assert os.path.exists("out_12.map") and os.path.exists("12.map")
        assert namespace["errors"].mean() < 0.01
