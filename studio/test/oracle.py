# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""The library's side of the studio's browser test (studio.test.mjs): what the
page must show, computed here from the Python package, printed as JSON.

  oracle.py counts MESH                      defect counts of mrepair.inspect, by overlay kind
  oracle.py clean MESH [SKIP,..]             counts of the clean result (mrepair.clean, skip)
  oracle.py gap MESH TOL RELATIVE D1 D2 ..   moves a GapClosingSequence to D1, D2, ..: the sha256 of
                                             its mesh at each, as the page holds it (float32 positions,
                                             uint32 indices), and of its triangles as a set
  oracle.py input-hash MESH                  the same hash of the input mesh
  oracle.py faces FILE                       faces of a mesh file
  oracle.py remesh MESH EDGE                 sizes of mrepair.remesh(edge_length=EDGE)
  oracle.py html OUT MESH                    mrepair.html_report of mrepair.repair(MESH)
"""

import hashlib
import json
import sys

import numpy as np

import mrepair

# the overlay kinds and the inspect report's keys they count (doc/studio.md)
REPORT_KEYS = mrepair.DEFECT_REPORT_KEYS


def counts(V, F):
    d = mrepair.inspect(V, F)["defects"]
    return {k: d[r] for k, r in REPORT_KEYS.items()}


def mesh_hash(V, F):
    P = np.ascontiguousarray(np.asarray(V, dtype=np.float64).astype("<f4"))
    I = np.ascontiguousarray(np.asarray(F, dtype=np.int64).astype("<u4"))
    return hashlib.sha256(P.tobytes() + I.tobytes()).hexdigest()


def triangle_set(V, F):
    """the sha256 of a mesh's triangles as a set of corner-point triples (any face order, any first corner)"""
    T = np.ascontiguousarray(np.asarray(V, dtype=np.float64)[np.asarray(F, dtype=np.int64)])  # (m, 3, 3)
    T = np.sort(T.view([("x", "f8"), ("y", "f8"), ("z", "f8")]).reshape(len(T), 3), axis=1)
    T = np.sort(np.ascontiguousarray(T).view("V72").ravel())
    return hashlib.sha256(T.tobytes()).hexdigest()


def main(argv):
    cmd, path = argv[0], argv[1]
    if cmd == "html":
        V, F = mrepair.read(argv[2])
        V2, F2, report = mrepair.repair(V, F)
        mrepair.html_report(path, V, F, V2, F2, report, {"job": "repair", "profile": "auto"})
        return {"before": counts(V, F), "after": counts(V2, F2)}
    V, F = mrepair.read(path)
    if cmd == "faces":
        return {"vertices": len(V), "faces": len(F)}
    if cmd == "counts":
        return counts(V, F)
    if cmd == "input-hash":
        return mesh_hash(V, F)
    if cmd == "remesh":
        V2, F2, _ = mrepair.remesh(V, F, edge_length=float(argv[2]))
        return {"vertices": len(V2), "faces": len(F2)}
    if cmd == "clean":
        skip = [s for s in (argv[2] if len(argv) > 2 else "").split(",") if s]
        V2, F2, _ = mrepair.clean(V, F, profile="auto", skip=skip or None)
        return counts(V2, F2)
    if cmd == "gap":
        tol, relative = float(argv[2]), argv[3] == "1"
        seq = mrepair.GapClosingSequence(V, F, tol, relative=relative)
        out = {"size": seq.size, "max_distance": seq.max_distance, "hashes": []}
        for d in argv[4:]:
            seq.to_distance(float(d))
            W, G = seq.mesh()
            out["hashes"].append({"distance": float(d), "position": seq.position, "hash": mesh_hash(W, G),
                                  "triangles": triangle_set(W, G), "input_triangles": triangle_set(V, F)})
        return out
    raise SystemExit("unknown command " + cmd)


if __name__ == "__main__":
    print(json.dumps(main(sys.argv[1:])))
