#!/usr/bin/env bash
# Installs what mrepair needs on Debian 12 (skips apt entirely when all is there).
set -euo pipefail
packages=(cmake g++ make debian-archive-keyring libcgal-dev libeigen3-dev libtbb-dev libboost-dev
          libgtest-dev libgmock-dev libbenchmark-dev libcgal-demo
          # the Python package (pybind11) and its tests; venv, setuptools and
          # wheel for `pip install --no-build-isolation .`
          pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest
          python3-venv python3-setuptools python3-wheel
          # `mrepair.batch` on a Dask cluster (python3-dask comes with it) and its test
          python3-distributed python3-dask
          # the studio's browser test (CTest studio_browser): headless chromium
          chromium)
# the studio's web assets are built with Node.js >= 18 and npm (CI has Node 20;
# Debian 12's nodejs is 18, which builds them too)
command -v node >/dev/null || packages+=(nodejs)
command -v npm >/dev/null || packages+=(npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
