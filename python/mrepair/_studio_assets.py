# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Where the studio's built web assets (index.html, report_template.html,
assets/) are, and the helpers that turn meshes and defect overlays into what
the page reads (the payload contract of doc/studio.md)."""

import base64
import os
import site
import sys
import sysconfig

import numpy as np

from . import _mrepair

TEMPLATE = "report_template.html"
PLACEHOLDER = "/*MREPAIR_PAYLOAD*/"
DEFAULT_FACE_BUDGET = 500_000  # the CLI's --html-faces default too


def _configured_dirs():
    """the build and install folders CMake wrote into _paths.py (absent in a source checkout)."""
    try:
        from . import _paths  # type: ignore[attr-defined]
    except ImportError:
        return []
    return [d for d in (getattr(_paths, "STUDIO_BUILD_DIR", ""), getattr(_paths, "STUDIO_INSTALL_DIR", "")) if d]


def installed_prefixes():
    """the prefixes pip installs this package's data files under: the environment's
    (a venv, or Debian's /usr/local), sys.prefix, and the user's (``pip install --user``)."""
    prefixes = [sysconfig.get_path("data"), sys.prefix, site.getuserbase()]
    return [p for i, p in enumerate(prefixes) if p and p not in prefixes[:i]]


def studio_asset_dirs():
    """the candidate folders, in the order they are tried: env MREPAIR_STUDIO_ASSETS alone when
    it is set (as the CLI: a folder named on purpose is never silently replaced), else the
    build folder, the install folder, <prefix>/share/mrepair/studio for each installed_prefixes()
    (where `pip install` puts them)."""
    env = os.environ.get("MREPAIR_STUDIO_ASSETS")
    if env:
        return [env]
    dirs = _configured_dirs()
    dirs += [os.path.join(p, "share", "mrepair", "studio") for p in installed_prefixes()]
    return dirs


def find_studio_assets(required=TEMPLATE):
    """the first folder of studio_asset_dirs() that holds `required`; raises FileNotFoundError
    saying how to build the assets when none does."""
    dirs = studio_asset_dirs()
    for d in dirs:
        if os.path.isfile(os.path.join(d, required)):
            return d
    raise FileNotFoundError(
        "the mrepair studio's web assets (%s) were not found in %s; `pip install .` installs them "
        "(with Node.js and npm), `cmake --build BUILD --target mrepair-studio-assets` builds them, "
        "or set MREPAIR_STUDIO_ASSETS to the folder that holds them" % (required, ", ".join(dirs)))


def b64(array, dtype):
    """base64 of the little-endian bytes of an array (converted to dtype)."""
    a = np.ascontiguousarray(np.asarray(array), dtype=np.dtype(dtype).newbyteorder("<"))
    return base64.b64encode(a.tobytes()).decode("ascii")


def triangles(F):
    """an integer (m, 3) array of triangles: polygons (a list of index lists) fanned, for display."""
    if isinstance(F, np.ndarray) and F.ndim == 2 and F.shape[1] == 3:
        return F
    tris = [(f[0], f[i], f[i + 1]) for f in F for i in range(1, len(f) - 1)]
    return np.asarray(tris, dtype=np.int64).reshape(-1, 3)


def preview(V, F, face_budget):
    """(positions float32 (n,3), indices uint32 (m,3), faces of the full mesh, decimated)."""
    T = triangles(F)
    P, I, decimated = _mrepair.preview_mesh(np.asarray(V, dtype=np.float64), T, int(face_budget))
    return np.asarray(P, dtype=np.float32), np.asarray(I, dtype=np.uint32), len(T), bool(decimated)


def payload_mesh(V, F, face_budget):
    P, I, faces, decimated = preview(V, F, face_budget)
    return {"positions": b64(P, np.float32), "indices": b64(I, np.uint32), "faces": int(faces),
            "decimated": decimated}


def overlay_json(overlay):
    """the overlay of defect_overlay() with its arrays as base64 float32 (the JSON form)."""
    def conv(x):
        if isinstance(x, dict):
            return {k: conv(v) for k, v in x.items()}
        if isinstance(x, np.ndarray):
            return b64(x, np.float32)
        if isinstance(x, (list, tuple)):
            return [conv(v) for v in x]
        if isinstance(x, np.generic):
            return x.item()
        return x
    return conv(overlay)


def json_default(x):
    """json.dumps default= for numpy scalars and arrays in reports."""
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError("not JSON serializable: %r" % type(x))
