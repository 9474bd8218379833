#!/usr/bin/env bash
# CTest entry of issue 15: runs ../shared/real-meshes/check.sh (real defective
# meshes from other projects' test suites, kept outside the project) with the
# built mrepair and fails on any destroyed model, hang or crash, or invalid
# output, except for files whose whole input is degenerate (nothing valid can
# come out of those). Exits 77 (CTest: skipped) when the folder is absent.
#   usage: scripts/check_real_meshes.sh PATH/TO/mrepair [REAL_MESHES_DIR]
set -u
cli=${1:?usage: check_real_meshes.sh PATH/TO/mrepair [DIR]}
dir=${2:-$(cd "$(dirname "$0")/.." && pwd)/../shared/real-meshes}
[ -x "$dir/check.sh" ] || { echo "no $dir/check.sh: skipped"; exit 77; }
out=$(bash "$dir/check.sh" "$cli") || true
echo "$out"
python3 - "$cli" "$dir" <<PY
import json, subprocess, sys
cli, d = sys.argv[1], sys.argv[2]
rows = [l.split() for l in """$out""".splitlines()]
rows = [r for r in rows if len(r) >= 7 and r[1].lstrip('-').isdigit()]
bad = []
for r in rows:
    name, rc, valid = r[0], int(r[1]), r[5] == "1"
    if r[-1] == "DESTROYED": bad.append(name + ": destroyed"); continue
    if rc >= 124 or rc < 0: bad.append(name + ": hung or crashed (exit %d)" % rc); continue
    if not valid:
        i = json.loads(subprocess.run([cli, "inspect", d + "/" + name, "--json", "--no-self-intersections"],
                                      capture_output=True, text=True).stdout or "{}")
        de = i.get("defects", {}); n = i.get("input", {}).get("faces", 0)
        if n and de.get("degenerate_faces", 0) + de.get("duplicate_faces", 0) >= n: continue
        bad.append(name + ": invalid output")
print("%d files checked; %d failures" % (len(rows), len(bad)))
for b in bad: print("  " + b)
sys.exit(1 if bad or not rows else 0)
PY
