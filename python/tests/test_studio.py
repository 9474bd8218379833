# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""The studio's HTTP API (python/mrepair/studio/server.py) without a browser: a
server on a free port over a small mesh, asked the way the page asks. The page
itself is tested in a real browser by studio/test/studio.test.mjs (CTest
studio_browser)."""

import json
import os
import struct
import sys
import sysconfig
import threading
import urllib.error
import urllib.request

import numpy as np
import pytest

import mrepair
from mrepair.studio import Session, make_server
from meshes import grid, sphere


@pytest.fixture
def studio(tmp_path):
    # a sphere with a spike and a hole: defects to see, a hole to fill
    V, F = sphere(16, 32)
    V = V.copy()
    V[100] *= 1.8
    F = np.delete(F, [200, 201, 232, 233], axis=0)
    path = tmp_path / "sphere.off"
    mrepair.write(str(path), V, F)
    assets = tmp_path / "assets"
    assets.mkdir()
    (assets / "index.html").write_text("<!doctype html><title>studio</title>")
    session = Session(path, face_budget=100000)
    server = make_server(session, 0, str(assets), quiet=True)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    base = "http://127.0.0.1:%d" % server.server_address[1]

    def call(path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(base + path, data=data, headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=60) as r:
                return r.status, r.headers.get("Content-Type"), r.read()
        except urllib.error.HTTPError as e:
            return e.code, e.headers.get("Content-Type"), e.read()

    yield call, V, F
    server.shutdown()
    server.server_close()


def binary_mesh(body):
    n, m, faces, flags = struct.unpack_from("<4I", body)
    P = np.frombuffer(body, "<f4", 3 * n, 16).reshape(n, 3)
    I = np.frombuffer(body, "<u4", 3 * m, 16 + 12 * n).reshape(m, 3)
    return P, I, faces, flags


def test_state_and_input_mesh(studio):
    call, V, F = studio
    status, ctype, body = call("/")
    assert status == 200 and ctype.startswith("text/html")
    state = json.loads(call("/api/state")[2])
    assert state["faces"] == len(F) and state["manifold"]
    assert state["report"]["defects"] == mrepair.inspect(V, F)["defects"]
    status, ctype, body = call("/api/mesh/before")
    assert ctype == "application/octet-stream"
    P, I, faces, flags = binary_mesh(body)
    assert faces == len(F) and flags == 0
    np.testing.assert_array_equal(P, V.astype(np.float32))
    np.testing.assert_array_equal(I, F.astype(np.uint32))


def test_defect_counts_are_the_reports(studio):
    call, V, F = studio
    overlay = json.loads(call("/api/defects/before")[2])
    d = mrepair.inspect(V, F)["defects"]
    assert overlay["kinds"]["boundary_loops"]["count"] == d["boundary_loops"] > 0
    assert overlay["kinds"]["spikes"]["count"] == d["spiked_vertices"] > 0


def test_run_with_a_step_off(studio):
    call, V, F = studio
    assert call("/api/mesh/after")[0] == 404  # nothing run yet
    res = json.loads(call("/api/run", {"mode": "clean", "profile": "scan", "skip": [], "params": {}})[2])
    _, F_all, report = mrepair.clean(V, F, profile="scan")
    enabled = lambda r: {k: v["enabled"] for k, v in r["clean"]["steps"].items()}  # noqa: E731
    assert res["faces"] == len(F_all) and enabled(res["report"]) == enabled(report)
    assert binary_mesh(call("/api/mesh/after")[2])[2] == len(F_all)
    res = json.loads(call("/api/run", {"mode": "clean", "profile": "scan", "skip": ["fill_small_holes"],
                                       "params": {"spike_angle": 100}})[2])
    V2, F2, _ = mrepair.clean(V, F, profile="scan", skip="fill_small_holes", spike_angle=100)
    assert res["faces"] == len(F2) < len(F_all)
    assert enabled(res["report"])["fill_small_holes"] is False
    status, _, body = call("/api/run", {"mode": "clean", "skip": ["no_such_step"]})
    assert status == 400 and "no_such_step" in json.loads(body)["error"]
    status, _, body = call("/api/run", {"mode": "clean", "params": {"max_hole": "many"}})
    assert status == 400 and "max_hole" in json.loads(body)["error"]


def test_gap_scrubber_at_zero_is_the_input(tmp_path):
    # two sheets 0.01 apart: a crack the sequence closes
    V1, F1 = grid(8, 8)
    V2, F2 = grid(8, 8, x0=1.01)
    V = np.vstack([V1, V2])
    F = np.vstack([F1, F2 + len(V1)])
    path = tmp_path / "crack.off"
    mrepair.write(str(path), V, F)
    session = Session(path)
    g = session.gap_init({"tolerance": 0.05, "relative": False})
    assert g["position"] == 0 and g["max_distance"] == pytest.approx(0.05)
    g = session.gap_move({"distance": 0.05})
    assert g["position"] > 0
    seq = mrepair.GapClosingSequence(V, F, 0.05)
    seq.to_distance(0.05)
    W, G = seq.mesh()
    np.testing.assert_array_equal(session.after.V, W)
    g = session.gap_move({"distance": 0})
    assert g["position"] == 0
    np.testing.assert_array_equal(session.after.V, session.before.V)
    np.testing.assert_array_equal(session.after.F, session.before.F)
    with pytest.raises(Exception):
        session.gap_move({})


def test_export_and_remesh(studio, tmp_path):
    call, V, F = studio
    for fmt in ("off", "obj", "ply", "stl"):
        status, _, body = call("/api/export/before?format=" + fmt)
        assert status == 200
        p = tmp_path / ("x." + fmt)
        p.write_bytes(body)
        assert len(mrepair.read(str(p))[1]) == len(F)
    assert call("/api/export/before?format=dxf")[0] == 400
    res = json.loads(call("/api/remesh", {"mode": "uniform", "source": "input", "edge_length": 0.3})[2])
    _, F2, _ = mrepair.remesh(V, F, edge_length=0.3)
    assert res["faces"] == len(F2)


def test_assets_found_under_the_install_prefixes(tmp_path, monkeypatch):
    """a pip install puts the assets in <prefix>/share/mrepair/studio, prefix the
    environment's or the user's (--user): found with no variable and no build folder."""
    import site
    from mrepair import _studio_assets

    monkeypatch.delenv("MREPAIR_STUDIO_ASSETS", raising=False)
    monkeypatch.setattr(_studio_assets, "_configured_dirs", lambda: [])
    monkeypatch.setattr(site, "getuserbase", lambda: str(tmp_path))
    dirs = _studio_assets.studio_asset_dirs()
    assert dirs[0] == os.path.join(sysconfig.get_path("data"), "share", "mrepair", "studio")
    assert os.path.join(sys.prefix, "share", "mrepair", "studio") in dirs
    assets = tmp_path / "share" / "mrepair" / "studio"
    assert dirs[-1] == str(assets)
    with pytest.raises(FileNotFoundError, match="pip install"):
        _studio_assets.find_studio_assets("no-such-file.html")
    assets.mkdir(parents=True)
    (assets / "index.html").write_text("<!doctype html>")
    if not any(os.path.isfile(os.path.join(d, "index.html")) for d in dirs[:-1]):
        assert _studio_assets.find_studio_assets("index.html") == str(assets)


def test_html_report(tmp_path, monkeypatch):
    template = tmp_path / "report_template.html"
    template.write_text('<script type="application/json" id="mrepair-payload">\n/*MREPAIR_PAYLOAD*/\n</script>')
    monkeypatch.setenv("MREPAIR_STUDIO_ASSETS", str(tmp_path))
    V, F = sphere()
    out = tmp_path / "r.html"
    mrepair.html_report(str(out), V, F, V, F, {"note": "</script>"}, {"profile": "auto"})
    text = out.read_text()
    payload = json.loads(text.split('id="mrepair-payload">', 1)[1].rsplit("</script>", 1)[0])
    assert payload["version"] == 1 and payload["title"] == "r.html"
    assert payload["report"]["note"] == "</script>"   # escaped in the file, the same string read back
    assert payload["meshes"]["before"]["faces"] == len(F)
    assert set(payload["defects"]["after"]["kinds"]) >= {"boundary_loops", "spikes", "crossing_pairs"}
    # a folder named in MREPAIR_STUDIO_ASSETS is the only one looked in
    monkeypatch.setenv("MREPAIR_STUDIO_ASSETS", str(tmp_path / "nowhere"))
    with pytest.raises(FileNotFoundError, match="mrepair-studio-assets"):
        mrepair.html_report(str(out), V, F, V, F, {})


def test_preview_above_the_face_budget(tmp_path):
    V, F = sphere(30, 60)
    path = tmp_path / "big.off"
    mrepair.write(str(path), V, F)
    session = Session(path, face_budget=500)
    P, I, faces, flags = binary_mesh(session.before.binary(session.face_budget))
    assert flags == 1 and faces == len(F) and 0 < len(I) <= 500
    assert session.state()["face_budget"] == 500
