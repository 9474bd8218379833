# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""The studio's HTTP server and its JSON/binary API.

One Session per server: the input mesh ("before") and the latest result
("after": a repair or clean run, a remeshing, or the gap-closing sequence's
current mesh). Jobs are serialised by a lock; the server threads only to keep
serving assets while a job runs.

API (all under /api; errors are {"error": message} with status 400/404/500):
  GET  state                 title, sizes, inspect report of the input, face budget, settings
  GET  mesh/before|after     binary mesh: 4 uint32 (n vertices, m triangles, faces of the
                             full mesh, flags: 1 = decimated preview), 3n float32, 3m uint32
  GET  defects/before|after  the defect overlay (doc/studio.md), arrays as base64 float32
  POST run                   {mode: clean|repair, profile, skip: [step], params: {...}}
  POST remesh                {mode: uniform|adaptive, source: result|input, edge_length,
                              tolerance, feature_angle, iterations}
  POST gap/init              {tolerance, relative, lambda_, source: input|result}: a GapClosingSequence
  POST gap/move              {distance} | {forward: k} | {backward: k}
  GET  export/before|after?format=off|obj|ply|stl   the mesh file (mrepair.write)
  POST reset                 forgets the result
"""

import argparse
import json
import mimetypes
import os
import posixpath
import struct
import sys
import tempfile
import threading
import time
import urllib.parse
import webbrowser
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

import numpy as np

from .. import _mrepair
from .._studio_assets import DEFAULT_FACE_BUDGET, find_studio_assets, json_default, overlay_json, preview

CLEAN_STEPS = ("remove_degenerate_vertices", "relax_spikes", "remove_unrelaxable_spikes", "clean_boundaries",
               "remove_small_components", "fill_small_holes", "fix_near_degenerate_faces",
               "relax_spikes_again", "ensure_valid_mesh")
EXPORT_FORMATS = ("off", "obj", "ply", "stl")


class ApiError(Exception):
    def __init__(self, message, status=HTTPStatus.BAD_REQUEST):
        super().__init__(message)
        self.status = status


def _number(params, key, kind=float, minimum=None):
    """params[key] as kind, None when absent or null; ApiError when not a number."""
    v = params.get(key)
    if v is None or v == "":
        return None
    try:
        x = kind(v)
    except (TypeError, ValueError):
        raise ApiError("%s: not a number: %r" % (key, v))
    if kind is float and not np.isfinite(x):
        raise ApiError("%s: not finite" % key)
    if minimum is not None and x < minimum:
        raise ApiError("%s must be >= %s" % (key, minimum))
    return x


class _Side:
    """a mesh on one side of the view, with its previews and overlay computed on demand."""

    def __init__(self, V, F, report=None, label=""):
        self.V = np.asarray(V, dtype=np.float64)
        self.F = F
        self.report = report
        self.label = label
        self._binary = None
        self._overlay = None

    def binary(self, face_budget):
        if self._binary is None:
            P, I, faces, decimated = preview(self.V, self.F, face_budget)
            header = struct.pack("<4I", len(P), len(I), faces, 1 if decimated else 0)
            self._binary = header + P.astype("<f4").tobytes() + I.astype("<u4").tobytes()
        return self._binary

    def overlay(self, options):
        if self._overlay is None:
            o = _mrepair.defect_overlay(self.V, self.F, **options)
            self._overlay = json.dumps(overlay_json(o), default=json_default).encode()
        return self._overlay


class Session:
    """the state of one studio: the input, the latest result, the gap-closing sequence."""

    def __init__(self, path, face_budget=DEFAULT_FACE_BUDGET, settings=None, inspect_options=None):
        self.path = os.fspath(path)
        self.title = os.path.basename(self.path)
        V, F = _mrepair.read(self.path)
        self.face_budget = int(face_budget)
        self.settings = settings
        self.inspect_options = dict(inspect_options or {})
        self.lock = threading.Lock()
        report = _mrepair.inspect(V, F, **self.inspect_options)
        self.before = _Side(V, F, report, "input")
        self.after = None
        self.gap = None
        self.gap_source = None

    # ---- state ------------------------------------------------------------------------------
    def manifold(self):
        """True when the input is a manifold, consistently oriented mesh (what `clean` takes)."""
        d = self.before.report.get("defects", {})
        keys = ("non_manifold_edges", "non_manifold_vertices", "inconsistent_orientation_edges",
                "invalid_polygons", "repeated_index_faces", "duplicate_faces")
        return all(not d.get(k) for k in keys)

    def state(self):
        inp = self.before.report.get("input", {})
        return {"title": self.title, "path": self.path, "vertices": int(len(self.before.V)),
                "faces": int(inp.get("faces", len(self.before.F))), "manifold": self.manifold(),
                "report": self.before.report, "face_budget": self.face_budget, "settings": self.settings,
                "has_result": self.after is not None}

    def side(self, which):
        if which == "before":
            return self.before
        if which == "after":
            if self.after is None:
                raise ApiError("no result yet: run a job first", HTTPStatus.NOT_FOUND)
            return self.after
        raise ApiError("unknown mesh %r (before or after)" % which, HTTPStatus.NOT_FOUND)

    def _result(self, V, F, report, label, seconds):
        self.after = _Side(V, F, report, label)
        self.gap = None
        return {"label": label, "report": report, "seconds": seconds, "vertices": int(len(V)),
                "faces": int(len(F))}

    # ---- jobs ------------------------------------------------------------------------------
    def run(self, body):
        mode = body.get("mode", "clean")
        profile = body.get("profile", "auto")
        if profile not in ("auto", "scan", "cad"):
            raise ApiError("profile must be auto, scan or cad")
        p = body.get("params") or {}
        skip = list(body.get("skip") or [])
        unknown = [s for s in skip if s not in CLEAN_STEPS]
        if unknown:
            raise ApiError("unknown cleaning step(s): %s" % ", ".join(unknown))
        common = dict(spike_angle=_number(p, "spike_angle", float, 0), max_hole=_number(p, "max_hole", int, 0),
                      min_component=_number(p, "min_component", int, 0),
                      iterations=_number(p, "iterations", int, 0))
        V, F = self.before.V, self.before.F
        t0 = time.perf_counter()
        if mode == "clean":
            V2, F2, report = _mrepair.clean(
                V, F, profile=profile, skip=skip or None, boundary_angle=_number(p, "boundary_angle"),
                density=_number(p, "density", float, 0), fair=bool(p.get("fair", False)), **common)
        elif mode == "repair":
            if skip:
                raise ApiError("the cleaning steps are chosen one by one with the clean job only")
            V2, F2, report = _mrepair.repair(
                V, F, profile=profile, close_gaps=_number(p, "close_gaps", float, 0),
                merge_epsilon=_number(p, "merge_epsilon", float, 0),
                resolve_intersections=bool(p.get("self_intersections", True)), **common)
        else:
            raise ApiError("mode must be clean or repair")
        return self._result(V2, F2, report, mode, time.perf_counter() - t0)

    def remesh(self, body):
        src = self.after if body.get("source", "result") == "result" and self.after is not None else self.before
        mode = body.get("mode", "uniform")
        kw = dict(feature_angle=_number(body, "feature_angle", float, 0),
                  iterations=_number(body, "iterations", int, 1))
        V, F = src.V, src.F
        if mode == "uniform":
            e = _number(body, "edge_length", float, 0)
            kw["edge_length"] = e if e else _mean_edge_length(V, F)
        elif mode == "adaptive":
            t = _number(body, "tolerance", float, 0)
            kw["tolerance"] = t if t else 1e-3 * _diagonal(V)
        else:
            raise ApiError("mode must be uniform or adaptive")
        t0 = time.perf_counter()
        V2, F2, report = _mrepair.remesh(V, F, **kw)
        report = dict(report)
        report["studio"] = {"source": src.label, "mode": mode,
                            **{k: v for k, v in kw.items() if v is not None}}
        return self._result(V2, F2, report, "remesh", time.perf_counter() - t0)

    def gap_init(self, body):
        tol = _number(body, "tolerance", float, 0)
        if not tol:
            raise ApiError("give the gap-closing tolerance (> 0)")
        lam = _number(body, "lambda_", float, 0)
        # the input, or the result (e.g. a soup repaired with close_gaps=0: a mesh with its gaps)
        if body.get("source") == "result" and self.after is not None:
            src = self.gap_source if self.gap is not None else self.after
        else:
            src = self.before
        self.gap = None
        seq = _mrepair.GapClosingSequence(src.V, src.F, tol, relative=bool(body.get("relative")),
                                          lambda_=0.5 if lam is None else lam)
        self.gap, self.gap_source = seq, src
        return self._gap_state()

    def gap_move(self, body):
        if self.gap is None:
            raise ApiError("build the gap-closing sequence first")
        if "distance" in body:
            self.gap.to_distance(_number(body, "distance", float, 0) or 0.0)
        elif "forward" in body:
            self.gap.forward(_number(body, "forward", int, 0) or 0)
        elif "backward" in body:
            self.gap.backward(_number(body, "backward", int, 0) or 0)
        else:
            raise ApiError("give distance, forward or backward")
        return self._gap_state()

    def _gap_state(self):
        seq = self.gap
        report = seq.report()
        if seq.position == 0:
            # exactly the sequence's input: with its contractions undone the library's mesh is
            # the same surface, but some faces may come back re-created (another order or
            # first corner)
            V, F = self.gap_source.V, self.gap_source.F
        else:
            V, F = seq.mesh()
        self.after = _Side(V, F, report, "gap closing")
        return {"position": seq.position, "size": seq.size, "current_distance": seq.current_distance,
                "max_distance": seq.max_distance, "vertices": int(len(V)), "faces": int(len(F)),
                "report": report}

    def export(self, which, fmt):
        if fmt not in EXPORT_FORMATS:
            raise ApiError("format must be one of " + ", ".join(EXPORT_FORMATS))
        s = self.side(which)
        with tempfile.TemporaryDirectory(prefix="mrepair-studio-") as d:
            path = os.path.join(d, "%s.%s" % (which, fmt))
            _mrepair.write(path, s.V, s.F, binary=fmt in ("ply", "stl"))
            with open(path, "rb") as f:
                return f.read()


def _diagonal(V):
    V = np.asarray(V, dtype=np.float64)
    return float(np.linalg.norm(V.max(axis=0) - V.min(axis=0))) if len(V) else 1.0


def _mean_edge_length(V, F):
    from .._studio_assets import triangles
    T = triangles(F)
    V = np.asarray(V, dtype=np.float64)
    if not len(T):
        raise ApiError("the mesh has no face")
    e = np.concatenate([V[T[:, 1]] - V[T[:, 0]], V[T[:, 2]] - V[T[:, 1]], V[T[:, 0]] - V[T[:, 2]]])
    return float(np.linalg.norm(e, axis=1).mean())


class Handler(BaseHTTPRequestHandler):
    server_version = "mrepair-studio/1"
    session = None      # set by make_server
    assets = None
    quiet = False

    def log_message(self, fmt, *args):
        if not self.quiet:
            sys.stderr.write("studio: " + (fmt % args) + "\n")

    def _send(self, body, ctype, status=HTTPStatus.OK, headers=None):
        self.send_response(status)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        for k, v in (headers or {}).items():
            self.send_header(k, v)
        self.end_headers()
        self.wfile.write(body)

    def _json(self, obj, status=HTTPStatus.OK):
        self._send(json.dumps(obj, default=json_default).encode(), "application/json", status)

    def _body(self):
        n = int(self.headers.get("Content-Length") or 0)
        if not n:
            return {}
        try:
            body = json.loads(self.rfile.read(n))
        except ValueError as e:
            raise ApiError("the request is not JSON: %s" % e)
        if not isinstance(body, dict):
            raise ApiError("the request must be a JSON object")
        return body

    def _handle(self, method):
        url = urllib.parse.urlsplit(self.path)
        path = url.path
        try:
            if path.startswith("/api/"):
                return self._api(method, path[5:].strip("/").split("/"), urllib.parse.parse_qs(url.query))
            if method != "GET":
                raise ApiError("not found", HTTPStatus.NOT_FOUND)
            return self._asset(path)
        except ApiError as e:
            self._json({"error": str(e)}, e.status)
        except (ValueError, OSError, RuntimeError) as e:
            # the library's reasons (bad input, a failed job) are the user's to read
            self._json({"error": "%s: %s" % (type(e).__name__, e)}, HTTPStatus.BAD_REQUEST)
        except Exception as e:  # noqa: BLE001 - the server keeps serving
            self._json({"error": "internal error: %s: %s" % (type(e).__name__, e)},
                       HTTPStatus.INTERNAL_SERVER_ERROR)

    def do_GET(self):
        self._handle("GET")

    def do_POST(self):
        self._handle("POST")

    def _asset(self, path):
        rel = posixpath.normpath(urllib.parse.unquote(path)).lstrip("/")
        if rel in ("", "."):
            rel = "index.html"
        if rel.startswith("..") or "\\" in rel:
            raise ApiError("not found", HTTPStatus.NOT_FOUND)
        full = os.path.join(self.assets, *rel.split("/"))
        if not os.path.isfile(full):
            raise ApiError("not found: /" + rel, HTTPStatus.NOT_FOUND)
        with open(full, "rb") as f:
            body = f.read()
        ctype = mimetypes.guess_type(full)[0] or "application/octet-stream"
        if ctype.startswith("text/") or ctype.endswith("javascript"):
            ctype += "; charset=utf-8"
        self._send(body, ctype)

    def _api(self, method, parts, query):
        s = self.session
        route = (method, parts[0] if parts else "")
        arg = parts[1] if len(parts) > 1 else None
        if route == ("GET", "state"):
            with s.lock:
                return self._json(s.state())
        if route == ("GET", "mesh"):
            with s.lock:
                body = s.side(arg).binary(s.face_budget)
            return self._send(body, "application/octet-stream")
        if route == ("GET", "defects"):
            with s.lock:
                body = s.side(arg).overlay(s.inspect_options)
            return self._send(body, "application/json")
        if route == ("GET", "export"):
            fmt = (query.get("format") or ["off"])[0].lower()
            with s.lock:
                body = s.export(arg, fmt)
            name = "%s-%s.%s" % (os.path.splitext(s.title)[0], "result" if arg == "after" else "input", fmt)
            return self._send(body, "application/octet-stream",
                              headers={"Content-Disposition": 'attachment; filename="%s"' % name})
        if method == "POST":
            body = self._body()
            with s.lock:
                if route[1] == "run":
                    return self._json(s.run(body))
                if route[1] == "remesh":
                    return self._json(s.remesh(body))
                if route[1] == "gap" and arg == "init":
                    return self._json(s.gap_init(body))
                if route[1] == "gap" and arg == "move":
                    return self._json(s.gap_move(body))
                if route[1] == "reset":
                    s.after, s.gap = None, None
                    return self._json({"ok": True})
        raise ApiError("no such API call: %s /api/%s" % (method, "/".join(parts)), HTTPStatus.NOT_FOUND)


def make_server(session, port=0, assets=None, quiet=False):
    """a ThreadingHTTPServer on 127.0.0.1:port (0: a free port) serving `session`."""
    assets = assets or find_studio_assets("index.html")
    handler = type("StudioHandler", (Handler,), {"session": session, "assets": assets, "quiet": quiet})
    server = ThreadingHTTPServer(("127.0.0.1", port), handler)
    server.daemon_threads = True
    return server


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m mrepair.studio",
                                 description="the mrepair studio: see the defects, steer the repair, scrub the "
                                             "gap closing and remesh, in a browser (served on 127.0.0.1)")
    ap.add_argument("mesh", help="an OFF, OBJ, PLY or STL file")
    ap.add_argument("--port", type=int, default=0, help="the port (default: a free one)")
    ap.add_argument("--no-browser", action="store_true", help="do not open a browser; print the address")
    ap.add_argument("--face-budget", type=int, default=DEFAULT_FACE_BUDGET,
                    help="meshes with more faces are shown as a decimated preview (default %(default)s)")
    ap.add_argument("--settings", help="a settings JSON file saved by the studio, applied when the page opens")
    ap.add_argument("--quiet", action="store_true", help="do not log the requests")
    a = ap.parse_args(argv)
    try:
        settings = None
        if a.settings:
            with open(a.settings, encoding="utf-8") as f:
                settings = json.load(f)
        assets = find_studio_assets("index.html")
        session = Session(a.mesh, face_budget=a.face_budget, settings=settings)
        server = make_server(session, a.port, assets, quiet=a.quiet)
    except (OSError, ValueError) as e:
        print("mrepair studio: %s" % e, file=sys.stderr)
        return 2
    url = "http://127.0.0.1:%d/" % server.server_address[1]
    print("mrepair studio: %s on %s (Ctrl-C stops)" % (session.title, url), flush=True)
    if not a.no_browser:
        webbrowser.open(url)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
    return 0
