# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""mrepair.locate_defects, defect_overlay and preview_mesh (doc/studio.md):
the located defects are as many as mrepair.inspect counts, and are where
the definitions say; the overlay draws them; the preview keeps the budget."""

import base64
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import mrepair
from meshes import grid, sphere, two_sheets

GENERATE = os.environ.get("MREPAIR_GENERATE")
needs_generate = pytest.mark.skipif(not GENERATE or not Path(GENERATE).exists(),
                                    reason="MREPAIR_GENERATE not set")

# kind of locate_defects -> key of the report's "defects" section
REPORT_KEY = mrepair.DEFECT_REPORT_KEYS
KINDS = list(REPORT_KEY)


def instances(kind, entry):
    """the number of listed instances of one kind"""
    if kind in ("boundary_loops",):
        return len(entry["loops"])
    if kind == "small_holes":
        assert len(entry["loops"]) == len(entry["indices"])
        return len(entry["indices"])
    if kind == "non_manifold_edges":
        return len(entry["edges"])
    if kind in ("non_manifold_vertices", "spikes"):
        return len(entry["vertices"])
    if kind == "near_degenerate_faces":
        return len(entry["faces"])
    if kind == "small_components":
        assert sum(len(c) for c in entry["components"]) == len(entry["faces"])
        return len(entry["components"])
    if kind == "crossing_pairs":
        assert len(entry["touching"]) == len(entry["pairs"])
        return len(entry["pairs"])
    if kind == "t_junctions":
        assert len(entry["edges"]) == len(entry["vertices"])
        return len(entry["vertices"])
    raise AssertionError(kind)


def edge_faces(F):
    """undirected edge -> number of faces"""
    count = {}
    for f in F:
        f = list(f)
        for i in range(len(f)):
            e = tuple(sorted((int(f[i]), int(f[(i + 1) % len(f)]))))
            count[e] = count.get(e, 0) + 1
    return count


def check(V, F, **options):
    """locate_defects agrees with inspect and with the definitions; returns the locations"""
    report = mrepair.inspect(V, F, **options)
    d = report["defects"]
    loc = mrepair.locate_defects(V, F, **options)
    assert list(loc) == KINDS
    for kind, key in REPORT_KEY.items():
        expected = d[key] if isinstance(d[key], int) else 0  # "not computed"
        assert loc[kind]["count"] == expected, kind
        assert instances(kind, loc[kind]) == expected, kind
    ef = edge_faces(F)
    for a, b in loc["non_manifold_edges"]["edges"]:
        assert ef[tuple(sorted((int(a), int(b))))] > 2
    for loop in loc["boundary_loops"]["loops"]:
        walks = [loop] if -1 not in loop else np.split(loop, np.where(loop == -1)[0] + 1)
        for w in walks:
            w = [int(x) for x in w if x != -1]
            pairs = zip(w, w[1:] + w[:1]) if -1 not in loop else zip(w, w[1:])
            for a, b in pairs:
                assert ef[tuple(sorted((a, b)))] == 1, "loop edge is not a boundary edge"
    loops = loc["boundary_loops"]["loops"]
    for i, holes in zip(loc["small_holes"]["indices"], loc["small_holes"]["loops"]):
        assert np.array_equal(loops[i], holes)
    tol = report["thresholds"]["t_junction_tolerance"]
    Va = np.asarray(V, dtype=float)
    for v, (a, b) in zip(loc["t_junctions"]["vertices"], loc["t_junctions"]["edges"]):
        assert ef[tuple(sorted((int(a), int(b))))] == 1
        p, x, y = Va[v], Va[a], Va[b]
        t = np.dot(p - x, y - x) / np.dot(y - x, y - x)
        assert 0 < t < 1 and np.linalg.norm(x + t * (y - x) - p) <= tol
    nf = len(F)
    for f, g in loc["crossing_pairs"]["pairs"]:
        assert 0 <= f < g < nf
    for f in loc["near_degenerate_faces"]["faces"]:
        assert 0 <= f < nf
    return loc


def test_clean_sphere_has_no_defects():
    V, F = sphere()
    loc = check(V, F)
    for kind in KINDS:
        assert loc[kind]["count"] == 0


def test_open_grid_has_one_loop():
    V, F = grid(6, 4)
    loc = check(V, F)
    assert loc["boundary_loops"]["count"] == 1
    assert len(loc["boundary_loops"]["loops"][0]) == 20  # 2 x (6 + 4) boundary edges
    assert loc["small_holes"]["count"] == 1


def test_non_manifold_edge():
    V = np.array([(0, 0, 0), (1, 0, 0), (0.5, 1, 0), (0.5, -1, 0), (0.5, 0, 1)], dtype=float)
    F = np.array([(0, 1, 2), (1, 0, 3), (0, 1, 4)])
    loc = check(V, F)
    assert loc["non_manifold_edges"]["count"] == 1
    assert sorted(loc["non_manifold_edges"]["edges"][0].tolist()) == [0, 1]


def test_t_junctions():
    V, F = two_sheets(0.0, ny_left=8, ny_right=4)
    loc = check(V, F)
    # the left sheet's seam vertices between the right sheet's ones
    assert loc["t_junctions"]["count"] == 4


def test_crossing_pair():
    V = np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0.2, 0.2, -1), (0.3, 0.2, 1), (0.2, 0.3, 1)], dtype=float)
    F = np.array([(0, 1, 2), (3, 4, 5)])
    loc = check(V, F)
    assert loc["crossing_pairs"]["pairs"].tolist() == [[0, 1]]
    assert not loc["crossing_pairs"]["touching"][0]
    off = mrepair.locate_defects(V, F, self_intersections=False)
    assert off["crossing_pairs"]["count"] == 0 and not off["crossing_pairs"]["computed"]


def test_spike_and_non_manifold_vertex():
    V, F = grid(4, 4)
    V[12, 2] = 5.0  # the centre vertex, far up
    # a second sheet touching the first at one corner vertex only
    V2, F2 = grid(2, 2, x0=1.0)
    V2[:, 1] += 1.0
    loc = check(np.vstack([V, V2]), np.vstack([F, F2 + len(V)]))
    assert 12 in loc["spikes"]["vertices"].tolist()
    loc = check(np.vstack([V, V2[1:]]), np.vstack([F, np.where(F2 == 0, 24, F2 - 1 + len(V))]))
    assert loc["non_manifold_vertices"]["vertices"].tolist() == [24]


def test_small_components_and_thresholds():
    V1, F1 = sphere()
    V2, F2 = sphere(rings=4, sectors=6, radius=0.1)
    V2[:, 0] += 3
    V, F = np.vstack([V1, V2]), np.vstack([F1, F2 + len(V1)])
    loc = check(V, F, small_component=100)
    assert loc["small_components"]["count"] == 1
    assert sorted(loc["small_components"]["faces"].tolist()) == list(range(len(F1), len(F)))
    assert check(V, F, small_component=1)["small_components"]["count"] == 0


def test_mesh_view():
    V, F = grid(6, 6)
    F = np.delete(F, [14, 15, 40], axis=0)  # two holes
    V[24, 2] = 3.0  # and a spike
    report = mrepair.inspect(V, F)
    loc = mrepair.locate_defects(V, F, mesh=True)
    assert loc["boundary_loops"]["count"] == report["mesh"]["boundary_loops"] == 3
    assert loc["small_holes"]["count"] == report["mesh"]["small_holes"]
    for kind in ("spikes", "near_degenerate_faces", "non_manifold_vertices", "crossing_pairs"):
        assert loc[kind]["count"] == report["defects"][REPORT_KEY[kind]]
    ef = edge_faces(F)
    for loop in loc["boundary_loops"]["loops"]:
        w = loop.tolist()
        assert all(ef[tuple(sorted(e))] == 1 for e in zip(w, w[1:] + w[:1]))
    o = mrepair.defect_overlay(V, F, mesh=True)
    assert len(o["kinds"]["boundary_loops"]["segments"]) == report["defects"]["boundary_edges"]
    assert np.allclose(o["kinds"]["spikes"]["points"], V[loc["spikes"]["vertices"]])
    # a bowtie is no polygon mesh
    bow = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (-1, 0, 0), (-1, -1, 0)], dtype=float)
    with pytest.raises(ValueError):
        mrepair.locate_defects(bow, [(0, 1, 2), (0, 3, 4)], mesh=True)
    assert mrepair.locate_defects(bow, [(0, 1, 2), (0, 3, 4)])["non_manifold_vertices"]["count"] == 1


@needs_generate
@pytest.mark.parametrize("args", [
    ["scan", "--faces", "20000", "--seed", "3", "--spikes", "6", "--holes", "3", "--jagged-holes", "2",
     "--islands", "3", "--slivers", "20", "--pinned-danglers", "2", "--foldovers", "2", "--tunnels", "1"],
    ["cad", "--faces", "8000", "--seed", "5", "--fins", "2", "--pinched", "2", "--duplicates", "3",
     "--degenerate", "3", "--flipped", "2"],
])
def test_generated_meshes(tmp_path, args):
    out = tmp_path / "mesh.ply"
    subprocess.run([GENERATE] + args + ["--output", str(out)], check=True, capture_output=True)
    V, F = mrepair.read(out)
    loc = check(V, F)
    assert sum(loc[k]["count"] for k in KINDS) > 0
    o = mrepair.defect_overlay(V, F)
    for kind in KINDS:
        assert o["kinds"][kind]["count"] == loc[kind]["count"]


def test_overlay_arrays():
    V, F = two_sheets(0.0, ny_left=8, ny_right=4)
    loc = mrepair.locate_defects(V, F)
    o = mrepair.defect_overlay(V, F)
    assert list(o["kinds"]) == KINDS
    colors = {"boundary_loops": "#1f77b4", "crossing_pairs": "#ff0000", "t_junctions": "#2ca02c"}
    for kind, k in o["kinds"].items():
        assert k["count"] == loc[kind]["count"]
        assert k["points"].dtype == np.float32 and k["points"].shape[1] == 3
        assert k["segments"].shape[1] == 6 and k["triangles"].shape[1] == 9
        assert k["drawn"] == k["count"] and not k["truncated"]
        assert (k["first"] is None) == (k["count"] == 0)
        if kind in colors:
            assert k["color"] == colors[kind]
    tj = o["kinds"]["t_junctions"]
    assert tj["points"].shape == (4, 3) and tj["segments"].shape == (4, 6)
    assert np.allclose(tj["points"], np.asarray(V)[loc["t_junctions"]["vertices"]])
    loops = o["kinds"]["boundary_loops"]
    assert len(loops["segments"]) == sum(len(l) for l in loc["boundary_loops"]["loops"])
    # the first loop's centre lies within its radius of each of its points
    c, r = np.array(loops["first"]), loops["first_radius"]
    first = np.asarray(V)[loc["boundary_loops"]["loops"][0]]
    assert np.all(np.linalg.norm(first - c, axis=1) <= r * (1 + 1e-6))
    # capped
    capped = mrepair.defect_overlay(V, F, max_elements=3)["kinds"]["t_junctions"]
    assert capped["count"] == 4 and capped["drawn"] == 1 and capped["truncated"]
    assert capped["points"].shape == (1, 3) and capped["segments"].shape == (1, 6)


def test_overlay_faces():
    V1, F1 = sphere()
    V2, F2 = sphere(rings=4, sectors=6, radius=0.1)
    V2[:, 0] += 3
    V, F = np.vstack([V1, V2]), np.vstack([F1, F2 + len(V1)])
    comp = mrepair.defect_overlay(V, F, small_component=100)["kinds"]["small_components"]
    assert comp["triangles"].shape == (len(F2), 9)
    assert np.allclose(np.sort(comp["triangles"].reshape(-1, 3), axis=0),
                       np.sort(V2[F2].reshape(-1, 3).astype(np.float32), axis=0))


def test_preview():
    V, F = sphere(rings=40, sectors=80)
    n = len(F)
    V2, F2, decimated = mrepair.preview_mesh(V, F, n)
    assert not decimated and V2.dtype == np.float32 and F2.dtype == np.uint32
    assert np.array_equal(F2, F) and np.allclose(V2, V)
    for budget in (n // 2, 1000, 100):
        V2, F2, decimated = mrepair.preview_mesh(V, F, budget)
        assert decimated and 0 < len(F2) <= budget
        assert F2.max() < len(V2)
        assert np.all((F2[:, 0] != F2[:, 1]) & (F2[:, 1] != F2[:, 2]) & (F2[:, 0] != F2[:, 2]))
        assert len({tuple(sorted(f)) for f in F2.tolist()}) == len(F2)
        assert len(F2) > budget / 10  # not needlessly coarse
        assert np.all(np.abs(np.linalg.norm(V2, axis=1) - 1) < 0.5)  # near the sphere
    V2, F2, decimated = mrepair.preview_mesh(V, F, 0)
    assert decimated and len(F2) == 0
    # polygons become triangles
    quads = [[0, 1, 2, 3]]
    V2, F2, decimated = mrepair.preview_mesh(np.eye(4, 3), quads, 10)
    assert F2.tolist() == [[0, 1, 2], [0, 2, 3]] and not decimated


# ---- mrepair repair --html (the CLI writes the same overlay into the HTML report) ----

CLI = os.environ.get("MREPAIR_CLI")
needs_cli = pytest.mark.skipif(not CLI or not Path(CLI).exists(), reason="MREPAIR_CLI not set")

# a stand-in for the viewer's template: the placeholder line inside the payload element
STAND_IN = """<!doctype html>
<html><head><title>stand-in</title></head><body>
<script type="application/json" id="mrepair-payload">
/*MREPAIR_PAYLOAD*/
</script>
</body></html>
"""


def payload_of(html):
    """the JSON of the payload element of a written report"""
    start = html.index('id="mrepair-payload">') + len('id="mrepair-payload">')
    return json.loads(html[start:html.index("</script>", start)])


def decode(b64, dtype, width):
    return np.frombuffer(base64.b64decode(b64), dtype=np.dtype(dtype).newbyteorder("<")).reshape(-1, width)


@needs_cli
def test_cli_html_report(tmp_path):
    assets = tmp_path / "assets"
    assets.mkdir()
    (assets / "report_template.html").write_text(STAND_IN)
    V, F = two_sheets(0.0, ny_left=8, ny_right=4)
    V = np.vstack([V, [(5, 5, 5), (6, 5, 5), (5, 6, 5)]])  # a small component
    F = np.vstack([F, [(len(V) - 3, len(V) - 2, len(V) - 1)]])
    src = tmp_path / "in.off"
    mrepair.write(src, V, F)
    out, html, rep = tmp_path / "out.off", tmp_path / "report.html", tmp_path / "report.json"
    env = dict(os.environ, MREPAIR_STUDIO_ASSETS=str(assets))
    run = subprocess.run([CLI, "repair", str(src), str(out), "--html", str(html), "--report", str(rep),
                          "--input-self-intersections", "--html-faces", "100"],
                         capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    assert "warning" not in run.stderr
    text = html.read_text()
    assert "/*MREPAIR_PAYLOAD*/" not in text and text.startswith("<!doctype html>")
    p = payload_of(text)
    report = json.loads(rep.read_text())
    assert p["version"] == 1 and p["title"] == "in.off"
    for section in ("before", "after"):
        assert list(p["defects"][section]["kinds"]) == KINDS
        for kind, key in REPORT_KEY.items():
            k = p["defects"][section]["kinds"][kind]
            expected = report[section]["defects"][key]
            assert k["count"] == (expected if isinstance(expected, int) else 0), (section, kind)
            for name, size in (("points", 12), ("segments", 24), ("triangles", 36)):
                assert len(base64.b64decode(k[name])) % size == 0, (section, kind, name)
            assert k["drawn"] == k["count"] and not k["truncated"]
        # the report embedded is the one --report writes (timings aside)
        assert p["report"][section]["defects"] == report[section]["defects"]
    before = p["defects"]["before"]["kinds"]
    assert before["t_junctions"]["count"] == 4
    assert np.allclose(decode(before["t_junctions"]["points"], np.float32, 3),
                       V[mrepair.locate_defects(V, F)["t_junctions"]["vertices"]])
    assert before["small_components"]["count"] >= 1
    # meshes: the input has 2 x 64 + 2 x 32 + 1 triangles, above the budget of 100
    m = p["meshes"]["before"]
    assert m["faces"] == len(F) and m["decimated"]
    idx = decode(m["indices"], np.uint32, 3)
    assert 0 < len(idx) <= 100 and idx.max() < len(decode(m["positions"], np.float32, 3))
    assert p["settings"]["preview_face_budget"] == 100
    # the same overlay as the Python call, on the same soup and thresholds
    o = mrepair.defect_overlay(V, F, small_hole=report["before"]["thresholds"]["max_hole_vertices"])
    assert np.allclose(decode(before["boundary_loops"]["segments"], np.float32, 6),
                       o["kinds"]["boundary_loops"]["segments"])


@needs_cli
def test_cli_inspect_html(tmp_path):
    assets = tmp_path / "assets"
    assets.mkdir()
    (assets / "report_template.html").write_text(STAND_IN)
    V, F = two_sheets(0.0, ny_left=8, ny_right=4)
    src, html = tmp_path / "in.ply", tmp_path / "inspect.html"
    mrepair.write(src, V, F)
    run = subprocess.run([CLI, "inspect", str(src), "--json", "--html", str(html)], capture_output=True,
                         text=True, env=dict(os.environ, MREPAIR_STUDIO_ASSETS=str(assets)))
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout)
    p = payload_of(html.read_text())
    assert p["meshes"]["after"] is None and p["defects"]["after"] is None
    assert p["report"]["defects"] == report["defects"]
    loc = mrepair.locate_defects(V, F)
    for kind, key in REPORT_KEY.items():
        assert p["defects"]["before"]["kinds"][kind]["count"] == report["defects"][key] == loc[kind]["count"]
    m = p["meshes"]["before"]
    assert not m["decimated"] and m["faces"] == len(F)
    assert np.array_equal(decode(m["indices"], np.uint32, 3), F)
    assert np.allclose(decode(m["positions"], np.float32, 3), V)


@needs_cli
def test_cli_finds_the_template_beside_itself(tmp_path):
    """a program at PREFIX/bin/mrepair reads PREFIX/share/mrepair/studio before any folder
    compiled into it (a pip or moved install), and MREPAIR_STUDIO_ASSETS before that."""
    prefix = tmp_path / "prefix"
    (prefix / "bin").mkdir(parents=True)
    assets = prefix / "share" / "mrepair" / "studio"
    assets.mkdir(parents=True)
    (assets / "report_template.html").write_text(STAND_IN.replace("stand-in", "beside the program"))
    cli = prefix / "bin" / "mrepair"
    cli.write_bytes(Path(CLI).read_bytes())
    cli.chmod(0o755)
    V, F = grid(2, 2)
    src = tmp_path / "in.off"
    mrepair.write(src, V, F)
    env = {k: v for k, v in os.environ.items() if k != "MREPAIR_STUDIO_ASSETS"}
    html = tmp_path / "report.html"
    run = subprocess.run([str(cli), "inspect", str(src), "--html", str(html)], capture_output=True, text=True,
                         env=env)
    assert run.returncode == 0, run.stderr
    assert "<title>beside the program</title>" in html.read_text()
    named = tmp_path / "named"
    named.mkdir()
    (named / "report_template.html").write_text(STAND_IN.replace("stand-in", "named"))
    run = subprocess.run([str(cli), "inspect", str(src), "--html", str(html)], capture_output=True, text=True,
                         env=dict(env, MREPAIR_STUDIO_ASSETS=str(named)))
    assert run.returncode == 0, run.stderr
    assert "<title>named</title>" in html.read_text()


@needs_cli
def test_cli_html_without_template_fails_before_work(tmp_path):
    V, F = grid(2, 2)
    src = tmp_path / "in.off"
    mrepair.write(src, V, F)
    out, html = tmp_path / "out.off", tmp_path / "report.html"
    env = dict(os.environ, MREPAIR_STUDIO_ASSETS=str(tmp_path / "nothing-here"))
    run = subprocess.run([CLI, "repair", str(src), str(out), "--html", str(html)],
                         capture_output=True, text=True, env=env)
    assert run.returncode == 2
    assert "report_template.html" in run.stderr and "mrepair-studio-assets" in run.stderr
    assert not out.exists() and not html.exists()
    run = subprocess.run([CLI, "inspect", str(src), "--html", str(html)], capture_output=True, text=True, env=env)
    assert run.returncode == 2 and "report_template.html" in run.stderr and not html.exists()
