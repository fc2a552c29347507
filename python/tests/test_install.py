# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The documented install (doc/python.md): a virtual environment that sees Debian's packages, and
pip building ./python with the project's CMake, with no package index. The installed module
imports from anywhere, shows its API and matches."""

import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]

CHECK = """
import sys
sys.path.insert(0, {tests!r})
import comap, test_match
print(comap.__file__)
help(comap.match)
V, F = test_match.icosphere(3)
V = test_match.bumpy(V)
m12, m21, info = comap.match(V, F, V, F)
print("identity", (m12 == range(len(V))).mean())
"""


def test_documented_install(tmp_path):
    venv = tmp_path / "venv"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PIP_INDEX_URL", "PIP_EXTRA_INDEX_URL")}
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True, timeout=120)
    subprocess.run([str(venv / "bin" / "pip"), "install", "--quiet", "--no-build-isolation", "--no-index",
                    str(ROOT / "python")], check=True, timeout=1200, env=env, cwd=ROOT)
    out = subprocess.run([str(venv / "bin" / "python"), "-c", CHECK.format(tests=str(ROOT / "python" / "tests"))],
                         check=True, timeout=300, env=env, cwd=tmp_path, capture_output=True, text=True).stdout
    installed = out.splitlines()[0]
    assert installed.startswith(str(venv))  # the installed module, not the build folder's
    package = pathlib.Path(installed).parent
    assert (package / "__init__.pyi").exists() and (package / "py.typed").exists()
    assert "match(V1, F1, V2, F2, init=None, landmarks=None, settings=None, threads=None, progress=None)" in out
    assert "Computes dense point-to-point maps" in out
    identity = float(out.split("identity")[1])
    assert identity > 0.9  # a shape matched with itself: the identity, nearly everywhere
