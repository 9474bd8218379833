#!/usr/bin/env bash
# Fetches a CGAL release from the Debian archive into a folder, without
# installing anything: `apt-get download` with a sources list, package lists
# and cache of its own (the machine's apt configuration and installed packages
# stay as they are), then `dpkg-deb -x`. CGAL is header-only, so the unpacked
# package is a complete CGAL to build against.
#
#   bash scripts/fetch_cgal.sh [DIR] [SUITE]
#
# DIR defaults to build/cgal-trixie, SUITE to trixie (Debian 13: CGAL 6.0.1).
# Prints the folder to give CMake as CGAL_DIR on its last line; a second call
# with the package already unpacked prints it without downloading.
set -euo pipefail
cd "$(dirname "$0")/.."
suite="${2:-trixie}"
dir="$(realpath -m "${1:-build/cgal-$suite}")"
find_config() { find "$dir/root" -name CGALConfig.cmake -printf '%h\n' 2>/dev/null | head -n 1 || true; }

config="$(find_config)"
if [ -z "$config" ]; then
  command -v apt-get >/dev/null || { echo "fetch_cgal.sh: needs apt-get (Debian or Ubuntu)" >&2; exit 1; }
  keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  [ -r "$keyring" ] || { echo "fetch_cgal.sh: $keyring missing (package debian-archive-keyring)" >&2; exit 1; }
  rm -rf "$dir"
  mkdir -p "$dir/apt/lists/partial" "$dir/apt/cache/archives/partial" "$dir/pkg" "$dir/root"
  echo "deb [signed-by=$keyring] http://deb.debian.org/debian $suite main" > "$dir/apt/sources.list"
  apt_private=(-o "Dir::Etc::SourceList=$dir/apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
               -o "Dir::State::Lists=$dir/apt/lists" -o "Dir::Cache=$dir/apt/cache"
               -o Dir::State::status=/dev/null -o Debug::NoLocking=1
               -o APT::Sandbox::User="$(id -un)")
  apt-get "${apt_private[@]}" -qq update
  (cd "$dir/pkg" && apt-get "${apt_private[@]}" -qq download libcgal-dev)
  dpkg-deb -x "$dir"/pkg/libcgal-dev_*.deb "$dir/root"
  rm -rf "$dir/apt"  # the lists are tens of MB; only the package is kept
  config="$(find_config)"
  [ -n "$config" ] || { echo "fetch_cgal.sh: no CGALConfig.cmake in the package" >&2; exit 1; }
fi
version="$(sed -n 's/^#define CGAL_VERSION \(.*\)$/\1/p' "$dir/root/usr/include/CGAL/version.h")"
echo "CGAL $version from Debian $suite in $dir/root" >&2
echo "$config"
