# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The type stub says what the package is (same functions, parameters and defaults); every public
name is documented; the example of doc/python.md is the file python/examples/match_files.py, and
it runs."""

import ast
import inspect
import os
import pathlib
import subprocess
import sys

import comap
from test_match import pair, write_off  # noqa: F401 (fixture)

ROOT = pathlib.Path(__file__).resolve().parents[2]


def stub_functions():
    tree = ast.parse((ROOT / "python" / "comap" / "__init__.pyi").read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = node
        elif isinstance(node, ast.ClassDef):
            out[node.name] = node
            for f in node.body:
                if isinstance(f, ast.FunctionDef):
                    out[node.name + "." + f.name] = f
    return out


def parameters(stub):
    a = stub.args
    names = [x.arg for x in a.args if x.arg != "self"]
    defaults = [ast.literal_eval(d) for d in a.defaults]
    return names, defaults


def real_parameters(f):
    ps = [p for p in inspect.signature(f).parameters.values() if p.name != "self"]
    return [p.name for p in ps], [p.default for p in ps if p.default is not inspect.Parameter.empty]


def test_stub_matches_the_package():
    stubs = stub_functions()
    for name in comap.__all__:
        obj = getattr(comap, name)
        assert name in stubs, f"{name} has no stub"
        assert obj.__doc__ and obj.__doc__.strip(), f"{name} has no docstring"
        if inspect.isfunction(obj):
            assert parameters(stubs[name]) == real_parameters(obj), name
    assert parameters(stubs["Shape.__init__"]) == real_parameters(comap.Shape.__init__)
    for prop in ("number_of_vertices", "preparation_seconds"):
        assert "Shape." + prop in stubs and getattr(comap.Shape, prop).__doc__


def test_documented_example_runs(tmp_path, pair):
    example = (ROOT / "python" / "examples" / "match_files.py").read_text()
    doc = (ROOT / "doc" / "python.md").read_text()
    assert "```python\n" + example + "```" in doc, "doc/python.md must show python/examples/match_files.py verbatim"
    V1, F1, V2, F2 = pair
    write_off(tmp_path / "a.off", V1, F1)
    write_off(tmp_path / "b.off", V2, F2)
    run = subprocess.run([sys.executable, str(ROOT / "python" / "examples" / "match_files.py"), "a.off", "b.off",
                          "12.map", "21.map"], cwd=tmp_path, capture_output=True, text=True, timeout=600,
                         env=dict(os.environ))
    assert run.returncode == 0, run.stderr
    assert "inconsistent vertices:" in run.stdout and "refinement done" in run.stderr
    m12 = comap.read_map(tmp_path / "12.map")
    m21 = comap.match(*pair)[1]
    assert len(m12) == len(V1) and len(comap.read_map(tmp_path / "21.map")) == len(V2)
    assert (comap.read_map(tmp_path / "21.map") == m21).all()
