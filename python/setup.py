# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Builds the extension module comap._comap with the project's CMake (the target _comap of the
whole project, whose root is the parent folder), for the interpreter that runs the build:

    python3 -m venv --system-site-packages ~/venvs/comap
    ~/venvs/comap/bin/pip install --no-build-isolation ./python

Environment: COMAP_CMAKE_ARGS adds arguments to the CMake configuration (e.g.
"-DSMC_NATIVE=OFF" for a module that runs on other CPUs than the build machine's),
COMAP_BUILD_JOBS sets the number of parallel compile jobs (default: the number of cores).
"""

import os
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        if not os.path.exists(os.path.join(ROOT, "include", "CGAL", "Surface_mesh_correspondence.h")):
            raise RuntimeError(f"comap is built from a clone of the whole project: {ROOT} is not its root")
        build = os.path.abspath(os.path.join(self.build_temp, "cmake"))
        os.makedirs(build, exist_ok=True)
        configure = ["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                     "-DBUILD_TESTING=OFF", "-DSMC_BUILD_EXAMPLES=OFF", "-DSMC_BUILD_BENCHMARKS=OFF",
                     "-DSMC_BUILD_TOOLS=OFF", "-DSMC_BUILD_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}"]
        configure += shlex.split(os.environ.get("COMAP_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        jobs = os.environ.get("COMAP_BUILD_JOBS", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", build, "--target", "_comap", "-j", jobs], check=True)
        built = os.path.join(build, "python", "comap", os.path.basename(self.get_ext_filename(ext.name)))
        if not os.path.exists(built):
            raise RuntimeError(f"the CMake build did not produce {built} (are pybind11-dev and python3-dev installed?)")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)


setup(ext_modules=[CMakeExtension("comap._comap")], cmdclass={"build_ext": CMakeBuild})
