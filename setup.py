# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Builds the whole tool for pip from one CMake build of the same headers:
the compiled module mrepair._mrepair (target _mrepair), the `mrepair` program
(target mrepair-cli), installed into the environment's bin/, and the studio's
web assets (target mrepair-studio-assets, an npm build), installed into
<prefix>/share/mrepair/studio, where the program and the package look for
them. The rest of the metadata is in pyproject.toml.

Environment:
  MREPAIR_BUILD_JOBS      parallel compile jobs (default 2: each translation unit takes about 2 GB)
  MREPAIR_BUILD_STUDIO    OFF installs no studio (no Node.js needed; `mrepair.studio` and
                          `--html` then say the assets are missing); default: required
  MREPAIR_CMAKE_BUILD_DIR an existing configured CMake build folder of this source tree (with
                          MREPAIR_BUILD_PYTHON=ON and the tools) to build the three targets in and
                          package, instead of configuring one in setuptools' temporary folder
                          (the CI test reuses the build of the test pass this way)
"""

import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
TARGETS = ["_mrepair", "mrepair-cli"]
STUDIO_TARGET = "mrepair-studio-assets"
# the files of the studio's build folder the program and the package read
STUDIO_PATTERNS = ("*.html", "*.js", "*.css")
NODE_HELP = ("install Node.js >= 18 and npm (Debian: apt-get install nodejs npm; the build runs `npm ci`, "
             "which needs the npm registry), or set MREPAIR_BUILD_STUDIO=OFF to install mrepair "
             "without its studio")


class BuildError(Exception):
    pass


def _studio_wanted():
    value = os.environ.get("MREPAIR_BUILD_STUDIO", "ON").strip().upper()
    return value not in ("OFF", "0", "NO", "FALSE")


def _check_node():
    """stops before the long C++ build when the studio cannot be built."""
    node = shutil.which("node") or shutil.which("nodejs")
    npm = shutil.which("npm")
    if not node or not npm:
        missing = " and ".join(n for n, p in (("node", node), ("npm", npm)) if not p)
        raise BuildError(f"mrepair: the studio's web assets need {missing}, not found on PATH: {NODE_HELP}")
    version = subprocess.run([node, "--version"], stdout=subprocess.PIPE, text=True).stdout.strip()
    m = re.match(r"v?(\d+)", version)
    if not m or int(m.group(1)) < 18:
        raise BuildError(f"mrepair: the studio's web assets need Node.js >= 18, found {version or '?'}: {NODE_HELP}")


def _cache_value(build_dir, name):
    """a variable of build_dir/CMakeCache.txt, or None."""
    try:
        text = (build_dir / "CMakeCache.txt").read_text(encoding="utf-8", errors="replace")
    except OSError:
        return None
    m = re.search(r"^%s:[A-Z]+=(.*)$" % re.escape(name), text, re.M)
    return m.group(1) if m else None


def _copy_tree(src, dst, patterns):
    for pattern in patterns:
        for f in sorted(src.rglob(pattern)):
            target = dst / f.relative_to(src)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(f, target)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # the directory the module must land in, e.g. build/lib.../mrepair
        package_dir = Path(self.get_ext_fullpath(ext.name)).resolve().parent
        studio = _studio_wanted()
        try:
            if studio:
                _check_node()
            reuse = os.environ.get("MREPAIR_CMAKE_BUILD_DIR")
            if reuse:
                build_dir, module_dir = self._reuse_build(Path(reuse).resolve(), studio)
            else:
                build_dir = Path(self.build_temp).resolve() / "cmake"
                module_dir = package_dir
                self._configure(build_dir, package_dir, studio)
            targets = TARGETS + ([STUDIO_TARGET] if studio else [])
            jobs = os.environ.get("MREPAIR_BUILD_JOBS", "2")
            subprocess.run(["cmake", "--build", str(build_dir), "--target", *targets, "-j", jobs], check=True)
        except BuildError as e:
            sys.exit(f"error: {e}")
        self._stage(build_dir, module_dir, package_dir, studio)

    def _configure(self, build_dir, package_dir, studio):
        subprocess.run([
            "cmake", "-S", str(ROOT), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DMREPAIR_BUILD_PYTHON=ON",
            "-DMREPAIR_BUILD_PYTHON_TESTS=OFF",
            "-DMREPAIR_BUILD_TESTS=OFF",
            "-DMREPAIR_BUILD_EXAMPLES=OFF",
            "-DMREPAIR_BUILD_TOOLS=ON",
            "-DMREPAIR_BUILD_BENCHMARKS=OFF",
            "-DMREPAIR_BUILD_STUDIO=" + ("ON" if studio else "OFF"),
            # the wheel is installed anywhere: no build or install folder compiled in
            "-DMREPAIR_RELOCATABLE=ON",
            f"-DPython3_EXECUTABLE={sys.executable}",
            f"-DMREPAIR_PYTHON_OUTPUT_DIR={package_dir}",
        ], check=True)

    def _reuse_build(self, build_dir, studio):
        """(build folder, the folder its module is built into) after checking that it is a
        build of this source tree, with the Python module for this interpreter."""
        home = _cache_value(build_dir, "CMAKE_HOME_DIRECTORY")
        if home is None:
            raise BuildError(f"MREPAIR_CMAKE_BUILD_DIR={build_dir} is not a configured CMake build folder")
        if Path(home).resolve() != ROOT:
            raise BuildError(f"MREPAIR_CMAKE_BUILD_DIR={build_dir} builds {home}, not {ROOT}")
        if _cache_value(build_dir, "MREPAIR_BUILD_PYTHON") != "ON" or \
                _cache_value(build_dir, "MREPAIR_BUILD_TOOLS") != "ON":
            raise BuildError(f"MREPAIR_CMAKE_BUILD_DIR={build_dir} needs MREPAIR_BUILD_PYTHON=ON and MREPAIR_BUILD_TOOLS=ON")
        python = _cache_value(build_dir, "Python3_EXECUTABLE")
        suffix = subprocess.run([python, "-c", "import sysconfig; print(sysconfig.get_config_var('EXT_SUFFIX'))"],
                                stdout=subprocess.PIPE, text=True).stdout.strip() if python else ""
        if suffix != sysconfig.get_config_var("EXT_SUFFIX"):
            raise BuildError(f"MREPAIR_CMAKE_BUILD_DIR={build_dir} builds the module for {python}, "
                             f"not for {sys.executable}")
        if studio and _cache_value(build_dir, "MREPAIR_BUILD_STUDIO") == "OFF":
            raise BuildError(f"MREPAIR_CMAKE_BUILD_DIR={build_dir} has MREPAIR_BUILD_STUDIO=OFF")
        module_dir = _cache_value(build_dir, "MREPAIR_PYTHON_OUTPUT_DIR")
        return build_dir, Path(module_dir) if module_dir else build_dir / "python" / "mrepair"

    def _stage(self, build_dir, module_dir, package_dir, studio):
        """the module into the package; the program and the assets into the data files
        (bin/ and share/mrepair/studio/ under the environment's prefix)."""
        module = "_mrepair" + sysconfig.get_config_var("EXT_SUFFIX")
        if module_dir != package_dir:
            package_dir.mkdir(parents=True, exist_ok=True)
            shutil.copy2(module_dir / module, package_dir / module)
        # no build folder named in the package, whichever build made it (the
        # studio's assets are looked for under sys.prefix)
        (package_dir / "_paths.py").write_text(
            "# Written by setup.py: the pip package names no build or install folder.\n"
            'STUDIO_BUILD_DIR = ""\nSTUDIO_INSTALL_DIR = ""\n', encoding="utf-8")
        data = Path(self.build_temp).resolve() / "data"
        shutil.rmtree(data, ignore_errors=True)
        (data / "bin").mkdir(parents=True)
        shutil.copy2(build_dir / "tools" / "mrepair", data / "bin" / "mrepair")
        data_files = [("bin", [str(data / "bin" / "mrepair")])]
        if studio:
            assets = build_dir / "studio"
            if not (assets / "index.html").is_file():
                sys.exit(f"error: mrepair: the studio's web assets were not built into {assets}")
            _copy_tree(assets, data / "studio", STUDIO_PATTERNS)
            by_dir = {}
            for f in sorted((data / "studio").rglob("*")):
                if f.is_file():
                    rel = f.parent.relative_to(data / "studio").as_posix()
                    dest = "share/mrepair/studio" + ("" if rel == "." else "/" + rel)
                    by_dir.setdefault(dest, []).append(str(f))
            data_files += sorted(by_dir.items())
        # install_data (run after the build) installs them; pip puts a wheel's
        # data files under the environment's prefix
        self.distribution.data_files = data_files


setup(
    packages=["mrepair", "mrepair.studio"],
    package_dir={"": "python"},
    package_data={"mrepair": ["__init__.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("mrepair._mrepair")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
