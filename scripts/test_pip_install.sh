#!/usr/bin/env bash
# Issue 51, as a new user does it: a fresh venv from Debian's python3, then
# `pip install --no-build-isolation .`, then the package's entry points from a
# folder outside the source tree, with no build folder on PATH or PYTHONPATH
# and no MREPAIR_* variable: `mrepair --help`, `mrepair repair` (with --html),
# `python3 -m mrepair.batch` over three meshes, `python3 -m mrepair.studio`
# read over HTTP; then `pip wheel`, the wheel into a second venv, the CLI
# check again. CTest runs it as the test pip_install (python/CMakeLists.txt).
#
#   scripts/test_pip_install.sh GENERATOR
#
# GENERATOR: the mrepair-generate program (test data only; not on PATH).
# MREPAIR_CMAKE_BUILD_DIR (optional): a configured build of this tree that
# setup.py builds its three targets in and packages instead of configuring
# one of its own (CTest passes its own build folder: seconds instead of a
# full compile). pip runs offline (PIP_NO_INDEX): NumPy, setuptools and wheel
# come from Debian through --system-site-packages.
set -euo pipefail
generate=$(realpath "$1")
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/mrepair-pip.XXXXXX")
studio_pid=
cleanup() {
  if [ -n "$studio_pid" ]; then kill "$studio_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "test_pip_install: FAILED: $*" >&2; exit 1; }
step() { echo "== $* ($(date +%s.%N | cut -c1-14))"; }

export PIP_NO_INDEX=1 PIP_DISABLE_PIP_VERSION_CHECK=1 PYTHONDONTWRITEBYTECODE=1
unset PYTHONPATH MREPAIR_CLI MREPAIR_STUDIO_ASSETS MREPAIR_GENERATE VIRTUAL_ENV
# PATH without any folder of the source or build tree
clean_path=$(printf '%s' "$PATH" | tr ':' '\n' | grep -v -e "^$src" -e '^$' | paste -sd: -)

step "venv 1 and pip install --no-build-isolation ."
/usr/bin/python3 -m venv --system-site-packages "$work/venv1"
(cd "$src" && PATH="$clean_path" "$work/venv1/bin/pip" install -q --no-build-isolation .)

outside="$work/outside"
mkdir -p "$outside/in/sub"
cd "$outside"
"$generate" scan --output "$outside/in/scan.off" --faces 3000 --seed 1 >/dev/null
"$generate" cad --output "$outside/in/cad.stl" --faces 2000 --seed 2 >/dev/null
"$generate" scan --output "$outside/in/sub/bumpy.ply" --faces 2000 --seed 3 --holes 2 >/dev/null

# the CLI of a venv: its bin/ first on PATH (what `activate` does)
cli_check() {
  local venv=$1
  local p="$venv/bin:$clean_path"
  [ "$(PATH="$p" command -v mrepair)" = "$venv/bin/mrepair" ] || fail "mrepair on PATH is not $venv/bin/mrepair"
  PATH="$p" mrepair --help | grep -q "repair" || fail "mrepair --help"
  rm -f out.off report.html
  PATH="$p" mrepair repair in/scan.off out.off --html report.html --quiet || fail "mrepair repair"
  [ -s out.off ] || fail "mrepair repair wrote no mesh"
  grep -q 'id="mrepair-payload"' report.html || fail "mrepair repair --html wrote no report"
  [ -f "$venv/share/mrepair/studio/report_template.html" ] || fail "no studio assets in $venv/share"
}

step "venv 1: mrepair --help, mrepair repair --html"
cli_check "$work/venv1"

step "venv 1: the program finds the assets beside itself, before any compiled-in folder"
mkdir -p "$work/moved/bin" "$work/moved/share/mrepair/studio"
cp "$work/venv1/bin/mrepair" "$work/moved/bin/"
sed 's|</head>|<meta name="mrepair-test" content="moved-prefix"></head>|' \
  "$work/venv1/share/mrepair/studio/report_template.html" > "$work/moved/share/mrepair/studio/report_template.html"
"$work/moved/bin/mrepair" repair in/scan.off out.off --html moved.html --quiet
grep -q 'content="moved-prefix"' moved.html || fail "the program used a template other than the one beside it"

# the venv's python without its bin/ on PATH (an inactive venv): the
# package finds its program and its assets on its own
py="$work/venv1/bin/python3"
step "venv 1: python3 -m mrepair.batch over 3 meshes"
PATH="$clean_path" "$py" -m mrepair.batch in out --workers 2 --quiet >batch.log 2>&1 || { cat batch.log; fail "mrepair.batch"; }
[ "$(wc -l < out/manifest.jsonl)" -eq 3 ] || fail "the manifest has $(wc -l < out/manifest.jsonl) lines, not 3"
PATH="$clean_path" "$py" - <<'EOF' || fail "mrepair.batch outputs"
import json, os
records = [json.loads(l) for l in open("out/manifest.jsonl")]
assert sorted(r["path"] for r in records) == ["cad.stl", "scan.off", "sub/bumpy.ply"], records
for r in records:
    assert r["status"] in ("ok", "partial"), r
    assert os.path.getsize(os.path.join("out", r["path"])) > 0, r
EOF

step "venv 1: python3 -m mrepair.studio, its page over HTTP"
port=$("$py" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
PATH="$clean_path" "$py" -m mrepair.studio in/scan.off --no-browser --port "$port" --quiet >studio.log 2>&1 &
studio_pid=$!
PATH="$clean_path" "$py" - "$port" <<'EOF' || { cat studio.log; fail "the studio's page"; }
import re, sys, time, urllib.request
base = "http://127.0.0.1:%s/" % sys.argv[1]
for _ in range(300):
    try:
        page = urllib.request.urlopen(base, timeout=5).read().decode()
        break
    except OSError:
        time.sleep(0.2)
else:
    sys.exit("the studio did not answer on " + base)
refs = re.findall(r'''(?:src|href)\s*=\s*["']([^"']+)["']''', page)
scripts = re.findall(r'''<script[^>]*\bsrc\s*=\s*["']([^"']+)["']''', page)
assert scripts, "the page loads no script"
# every address the page asks for is its own server's (relative) or inline
outside = [r for r in refs if re.match(r"^(?:[a-z][a-z0-9+.-]*:|//)", r, re.I) and not r.startswith("data:")]
assert not outside, "the page asks for outside addresses: %s" % outside
for ref in refs:
    if ref.startswith("data:"):
        continue
    body = urllib.request.urlopen(base + ref.lstrip("/"), timeout=10).read().decode()
    assert body, ref
    # no module import, stylesheet import or font from another host
    remote = re.findall(r'''(?:\bimport\s*\(?\s*["']|@import\s+(?:url\()?["']?|url\(\s*["']?)((?:https?:)?//[^"')\s]+)''', body)
    assert not remote, "%s asks for %s" % (ref, remote)
print("studio page: %d bytes, scripts %s, %d references, none outside" % (len(page), scripts, len(refs)))
EOF
kill "$studio_pid"
wait "$studio_pid" 2>/dev/null || true
studio_pid=

step "pip wheel --no-build-isolation --no-deps ."
(cd "$src" && PATH="$clean_path" "$work/venv1/bin/pip" wheel -q --no-build-isolation --no-deps -w "$work/wheels" .)
wheels=("$work"/wheels/*.whl)
[ ${#wheels[@]} -eq 1 ] || fail "pip wheel made ${#wheels[@]} wheels"
"$py" - "${wheels[0]}" <<'EOF' || fail "the wheel's contents"
import re, sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
need = [r"^mrepair/_mrepair\..*\.so$", r"^mrepair/batch\.py$", r"^mrepair/studio/server\.py$",
        r"^mrepair-[^/]+\.data/data/bin/mrepair$",
        r"^mrepair-[^/]+\.data/data/share/mrepair/studio/index\.html$",
        r"^mrepair-[^/]+\.data/data/share/mrepair/studio/report_template\.html$",
        r"^mrepair-[^/]+\.data/data/share/mrepair/studio/assets/studio\.js$"]
missing = [n for n in need if not any(re.match(n, x) for x in names)]
assert not missing, "missing from the wheel: %s" % missing
EOF

step "venv 2: pip install the wheel, the CLI check again"
/usr/bin/python3 -m venv --system-site-packages "$work/venv2"
PATH="$clean_path" "$work/venv2/bin/pip" install -q "${wheels[0]}"
cli_check "$work/venv2"
PATH="$clean_path" "$work/venv2/bin/python3" -c '
import sys, mrepair, mrepair.batch, mrepair._studio_assets as a
assert a.find_studio_assets("index.html") == sys.prefix + "/share/mrepair/studio", a.find_studio_assets("index.html")
assert mrepair.batch.find_cli() == sys.prefix + "/bin/mrepair", mrepair.batch.find_cli()
' || fail "venv 2: the package does not find its program and assets"
step "passed"
