# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Builds the compiled module mrepair._mrepair with CMake (target _mrepair of
python/CMakeLists.txt) for the interpreter that runs this script; the rest of
the metadata is in pyproject.toml. MREPAIR_BUILD_JOBS sets the parallel
compile jobs (default 2: each translation unit takes about 2 GB)."""

import os
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # the directory the module must land in, e.g. build/lib.../mrepair
        package_dir = Path(self.get_ext_fullpath(ext.name)).resolve().parent
        build_dir = Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DMREPAIR_BUILD_PYTHON=ON",
            "-DMREPAIR_BUILD_PYTHON_TESTS=OFF",
            "-DMREPAIR_BUILD_TESTS=OFF",
            "-DMREPAIR_BUILD_EXAMPLES=OFF",
            "-DMREPAIR_BUILD_TOOLS=OFF",
            "-DMREPAIR_BUILD_BENCHMARKS=OFF",
            "-DMREPAIR_BUILD_STUDIO=OFF",
            f"-DPython3_EXECUTABLE={sys.executable}",
            f"-DMREPAIR_PYTHON_OUTPUT_DIR={package_dir}",
        ]
        jobs = os.environ.get("MREPAIR_BUILD_JOBS", "2")
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "_mrepair", "-j", jobs],
                       check=True)


setup(
    packages=["mrepair", "mrepair.studio"],
    package_dir={"": "python"},
    package_data={"mrepair": ["__init__.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("mrepair._mrepair")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
