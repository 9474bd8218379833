# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""The Python package: every call on small meshes made here, bad input,
array ownership, the gap-closing sequence back to the exact input, progress
and cancellation."""

import _thread
import os
import signal
import threading
import time
import warnings

import numpy as np
import pytest

import mrepair
from meshes import canonical_faces, cube_quads, grid, sphere, two_sheets


def spiked_sphere():
    V, F = sphere(16, 32)
    V = V.copy()
    V[100] *= 1.6  # one vertex pulled far out: a spike
    return V, F


def defective_soup():
    """a sphere as a soup with defects: a duplicated face, a flipped face, a
    NaN vertex with its own face, a degenerate face."""
    V, F = sphere()
    F = F.copy()
    F[5] = F[5][::-1]
    V = np.vstack([V, [[np.nan, 0.0, 0.0]]])
    nan = len(V) - 1
    F = np.vstack([F, F[:1], [[0, 1, nan]], [[2, 2, 3]]])
    return V, F


# ---- every call ------------------------------------------------------------------------


@pytest.mark.parametrize("ext", ["off", "obj", "ply", "stl"])
def test_read_write_round_trip(tmp_path, ext):
    V, F = sphere()
    path = tmp_path / f"sphere.{ext}"
    mrepair.write(str(path), V, F)
    V2, F2 = mrepair.read(str(path))
    assert V2.dtype == np.float64 and V2.shape == V.shape
    assert F2.dtype == np.int64 and F2.shape == F.shape
    if ext == "stl":  # float32 on disk, corners merged in order of use
        np.testing.assert_allclose(V2[F2], V[F], atol=1e-6)
    else:
        assert np.array_equal(V2, V)
        assert np.array_equal(F2, F)


def test_read_write_polygons(tmp_path):
    V, F = cube_quads()
    path = tmp_path / "cube.off"
    mrepair.write(path, V, F)  # os.PathLike works too
    V2, F2 = mrepair.read(path)
    assert isinstance(F2, list) and F2 == F
    assert np.array_equal(V2, V)
    mrepair.write(tmp_path / "cube.ply", V, F, binary=True)
    assert mrepair.read(tmp_path / "cube.ply")[1] == F


def test_read_errors(tmp_path):
    with pytest.raises(OSError):
        mrepair.read(tmp_path / "missing.off")
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    with pytest.raises(ValueError):
        mrepair.read(bad)
    unknown = tmp_path / "mesh.xyz"
    unknown.write_text("0 0 0\n")
    with pytest.raises(ValueError):
        mrepair.read(unknown)


def test_inspect_closed_and_open():
    V, F = sphere()
    r = mrepair.inspect(V, F)
    assert r["status"] == "ok" and r["kind"] == "soup"
    assert r["input"]["faces"] == len(F)
    assert r["defects"]["closed"] is True
    assert r["defects"]["self_intersecting_pairs"] == 0
    assert r["mesh"]["built"] is True and r["mesh"]["boundary_loops"] == 0
    assert r["thresholds"]["spike_angle"] == 100
    V, F = grid(4, 4)
    r = mrepair.inspect(V, F, small_hole=5, self_intersections=False)
    assert r["defects"]["boundary_loops"] == 1 and r["defects"]["small_holes"] == 0
    assert r["defects"]["self_intersecting_pairs"] == "not computed"
    assert r["thresholds"]["max_hole_vertices"] == 5


def test_inspect_counts_defects_of_a_soup():
    V, F = defective_soup()
    r = mrepair.inspect(V, F)
    assert r["status"] == "non_finite_input"
    d = r["defects"]
    assert d["non_finite_vertices"] == 1
    assert d["duplicate_faces"] >= 1 and d["degenerate_faces"] >= 1
    assert d["inconsistent_orientation_edges"] > 0
    assert r["mesh"]["built"] is False


def test_compare_to_reference():
    V, F = sphere()
    inner = sphere(radius=0.3)[0]  # inside the sphere: kept
    beside = sphere(radius=0.3)[0] + [5.0, 0.0, 0.0]  # deleted: lost
    reference = np.vstack([V, inner, beside])
    r = mrepair.compare_to_reference(V, F, reference)
    assert r["status"] == "ok" and r["inside_tested"] is True
    assert r["vertices"] == len(reference)
    assert r["vertices_inside"] == len(inner)
    assert r["vertices_lost"] == len(beside)
    assert r["lost"].dtype == np.int64
    assert list(r["lost"]) == list(range(len(V) + len(inner), len(reference)))
    assert r["max_distance"] == pytest.approx(4.3)
    assert r["max_distance_relative"] == pytest.approx(4.3 / r["diagonal"])
    # an open grid encloses nothing; the tolerance decides
    V, F = grid(4, 4)
    lifted = np.array(V, dtype=float)
    lifted[3, 2] += 0.01
    assert mrepair.compare_to_reference(V, F, lifted)["vertices_lost"] == 1
    r = mrepair.compare_to_reference(V, F, lifted, tolerance=0.02)
    assert r["vertices_lost"] == 0 and r["inside_tested"] is False and r["tolerance"] == 0.02
    with pytest.raises(ValueError):
        mrepair.compare_to_reference(V, F, lifted, tolerance=-1.0)


def test_soup_to_manifold():
    V, F = defective_soup()
    V2, F2, report = mrepair.soup_to_manifold(V, F)
    assert set(report) == {"before", "soup", "after"}
    assert report["soup"]["status"] == "partial"  # the NaN face was dropped
    assert report["soup"]["faces_removed"]["non_finite"] == 1
    after = mrepair.inspect(V2, F2)
    assert after["defects"]["inconsistent_orientation_edges"] == 0
    assert after["defects"]["duplicate_faces"] == 0 and after["defects"]["closed"] is True
    assert np.isfinite(V2).all()
    assert len(F2) == len(sphere()[1])


def test_soup_to_manifold_stitches_within_epsilon():
    V, F = two_sheets(1e-4)
    _, _, loose = mrepair.soup_to_manifold(V, F)
    _, _, stitched = mrepair.soup_to_manifold(V, F, epsilon=1e-3)
    assert loose["soup"]["topology"]["edges_stitched"] == 0
    assert stitched["soup"]["topology"]["edges_stitched"] == 8


def test_close_gaps():
    V, F = two_sheets(1e-3)
    V2, F2, report = mrepair.close_gaps(V, F, 1e-2)
    g = report["close_gaps"]
    assert g["status"] == "ok" and g["boundary_loops_before"] == 2 and g["boundary_loops_after"] == 1
    assert g["max_displacement"] <= 1e-2 and "seconds" in g
    assert mrepair.inspect(V2, F2)["defects"]["boundary_loops"] == 1
    _, _, relative = mrepair.close_gaps(V, F, 0.01, relative=True)
    assert relative["close_gaps"]["tolerance"] == pytest.approx(0.01 * np.linalg.norm(V.max(0) - V.min(0)))
    _, _, one = mrepair.close_gaps(V, F, 1e-2, steps=1)
    assert one["close_gaps"]["operations"] == 1


def test_close_gaps_estimates_the_tolerance():
    V, F = two_sheets(1e-3)
    V2, F2, report = mrepair.close_gaps(V, F)
    g = report["close_gaps"]
    assert g["status"] == "ok" and g["tolerance_chosen_by"] == "auto"
    assert "tolerance_estimate" in g
    assert g["boundary_loops_after"] <= g["boundary_loops_before"]
    with pytest.raises(ValueError, match="tolerance"):
        mrepair.close_gaps(V, F, -1.0)


def test_close_gaps_repairs_a_soup_first():
    V, F = two_sheets(1e-3)
    F = np.vstack([F, F[:1]])  # a duplicate face: not a mesh
    with pytest.warns(UserWarning, match="soup"):
        _, _, report = mrepair.close_gaps(V, F, 1e-2)
    assert report["soup"]["faces_removed"]["duplicate"] == 1
    assert report["close_gaps"]["boundary_loops_after"] == 1


def test_gap_closing_sequence_steps_back_to_the_exact_input():
    V, F = two_sheets(2e-3, ny_left=8, ny_right=11)
    seq = mrepair.GapClosingSequence(V, F, 1e-2)
    assert seq.position == 0 and seq.current_distance == 0 and seq.max_distance == 1e-2
    n = seq.forward(1_000_000)
    assert n > 0 and seq.position == n == seq.size
    report = seq.report()
    assert report["vertex_edge"] > 0 and report["boundary_loops_after"] == 1
    closed_V, closed_F = seq.mesh()
    assert len(closed_V) < len(V)
    assert seq.backward(3) == 3 and seq.position == n - 3
    assert seq.forward(3) == 3
    V3, F3 = seq.mesh()
    assert np.array_equal(V3, closed_V) and canonical_faces(F3) == canonical_faces(closed_F)
    assert seq.backward(n) == n and seq.position == 0
    V0, F0 = seq.mesh()
    assert np.array_equal(V0, V)  # bit for bit
    assert canonical_faces(F0) == canonical_faces(F)


def test_gap_closing_sequence_to_distance():
    V, F = two_sheets(2e-3, ny_left=8, ny_right=11)
    seq = mrepair.GapClosingSequence(V, F, 1e-2)
    total = seq.forward(1_000_000)
    assert seq.to_distance(0.0) == -total
    forward = seq.to_distance(seq.max_distance)
    assert forward == total
    assert seq.to_distance(1e-9) < 0 and seq.current_distance <= 1e-9


def test_gap_closing_sequence_refuses_bad_input():
    V, F = two_sheets(2e-3)
    V = V.copy()
    V[3, 1] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        mrepair.GapClosingSequence(V, F, 1e-2)
    V, F = two_sheets(2e-3)
    with pytest.raises(ValueError, match="manifold"):
        mrepair.GapClosingSequence(V, np.vstack([F, F[:1]]), 1e-2)


def test_clean_relaxes_a_spike():
    V, F = spiked_sphere()
    before = mrepair.inspect(V, F)["defects"]["spiked_vertices"]
    V2, F2, report = mrepair.clean(V, F)
    assert before > 0
    assert report["clean"]["status"] in ("ok", "partial")
    assert report["clean"]["steps"]["relax_spikes"]["enabled"] is True
    assert mrepair.inspect(V2, F2)["defects"]["spiked_vertices"] < before


def test_clean_step_lists():
    V, F = spiked_sphere()
    _, _, only = mrepair.clean(V, F, only=["relax_spikes", "ensure_valid_mesh"])
    steps = only["clean"]["steps"]
    assert steps["relax_spikes"]["enabled"] and steps["ensure_valid_mesh"]["enabled"]
    assert not steps["fill_small_holes"]["enabled"]
    _, _, skip = mrepair.clean(V, F, skip="relax_spikes,clean_boundaries")
    assert not skip["clean"]["steps"]["relax_spikes"]["enabled"]
    assert skip["clean"]["steps"]["fill_small_holes"]["enabled"]
    _, _, auto = mrepair.clean(V, F, profile="auto")
    assert auto["clean"]["profile"]["chosen_by"] == "auto"
    with pytest.raises(ValueError, match="unknown step"):
        mrepair.clean(V, F, only="frobnicate")
    with pytest.raises(ValueError, match="profile"):
        mrepair.clean(V, F, profile="lidar")


def test_clean_triangulates_polygons_and_refuses_soups():
    V, F = cube_quads()
    V2, F2, report = mrepair.clean(V, F, profile="cad")
    assert report["triangulation"]["polygons"] == 6 and F2.shape == (12, 3)
    V, F = defective_soup()
    with pytest.raises(ValueError, match="repair"):
        mrepair.clean(V, F)


def test_repair_a_defective_soup():
    V, F = defective_soup()
    V2, F2, report = mrepair.repair(V, F)
    # a small soup is classified as a CAD/print model: its gaps are closed
    # with the automatic tolerance, unless close_gaps=0 turns that off
    stages = ["before", "soup_to_manifold", "clean", "resolve_intersections", "face_accounting", "after"]
    assert list(report) in (stages, stages[:2] + ["close_gaps"] + stages[2:])
    if "close_gaps" in report:
        assert report["close_gaps"]["tolerance_chosen_by"] == "auto"
    assert list(mrepair.repair(V, F, close_gaps=0)[2]) == stages
    assert report["soup_to_manifold"]["needed"] is True
    accounting = report["face_accounting"]
    assert accounting["reconciles"] is True and accounting["faces_out"] == len(F2)
    assert report["after"]["defects"]["closed"] is True
    assert report["after"]["defects"]["non_finite_vertices"] == 0
    assert F2.dtype == np.int64 and V2.dtype == np.float64 and np.isfinite(V2).all()


def test_repair_options():
    V, F = two_sheets(1e-3)
    _, _, report = mrepair.repair(V, F, profile="cad", close_gaps=1e-2, max_hole=20,
                                  self_intersections=False, resolve_intersections=False)
    assert "close_gaps" in report and report["close_gaps"]["boundary_loops_after"] == 1
    assert report["clean"]["profile"]["profile"] == "cad"
    assert report["after"]["defects"]["self_intersecting_pairs"] == "not computed"
    assert report["after"]["defects"]["intersection_free"] == "not computed"
    # the solid repair counts the pairs anyway: the output's count is known
    _, _, report = mrepair.repair(V, F, profile="cad", close_gaps=1e-2, max_hole=20,
                                  self_intersections=False)
    assert report["after"]["defects"]["intersection_free"] in ("yes", "no")
    V, F = cube_quads()
    _, F2, report = mrepair.repair(V, F)
    assert report["triangulation"]["polygons"] == 6 and F2.shape[1] == 3
    with pytest.raises(ValueError, match="profile"):
        mrepair.repair(V, F, profile="lidar")
    with pytest.raises(ValueError):
        mrepair.repair(V, F, close_gaps=-1.0)
    with pytest.raises(ValueError):
        mrepair.repair(V, F, max_hole=0)


def test_repair_merges_overlapping_shells():
    """two cubes passing through each other: one solid by default (the winding-number
    solidification; the union of the corefinement when it refuses), both kept (and
    their crossings reported) with merge_overlapping_shells=False."""
    V, F = cube_quads()
    V2 = np.vstack([V, V + 0.5])
    F2 = [list(f) for f in F] + [[i + 8 for i in f] for f in F]
    _, F3, report = mrepair.repair(V2, F2)
    section = report["resolve_intersections"]
    assert section["shells_solidified"] == 2 or (
        section["shells_merged"] == 2 and section["solids_from_unions"] == 1)
    assert report["after"]["defects"]["connected_components"] == 1
    assert report["after"]["defects"]["closed"] is True
    assert report["after"]["defects"]["intersection_free"] == "yes"
    assert report["face_accounting"]["reconciles"] is True and report["face_accounting"]["faces_out"] == len(F3)
    _, F4, kept = mrepair.repair(V2, F2, merge_overlapping_shells=False)
    assert len(F4) == 24 and kept["after"]["defects"]["connected_components"] == 2
    assert kept["after"]["defects"]["intersection_free"] == "no"
    assert "shells_kept_separate" in kept["resolve_intersections"]["crossing_left_by_reason"]
    _, _, off = mrepair.repair(V2, F2, resolve_intersections=False)
    assert "resolve_intersections" not in off


def test_remesh_modes():
    V, F = sphere(16, 32)
    V2, F2, report = mrepair.remesh(V, F, edge_length=0.2)
    assert report["remesh"]["mode"] == "uniform" and report["remesh"]["status"] == "ok"
    assert mrepair.inspect(V2, F2)["defects"]["closed"] is True
    _, F3, report = mrepair.remesh(V, F, faces=600)
    assert report["remesh"]["mode"] == "face_count" and 400 < len(F3) < 800
    _, _, report = mrepair.remesh(V, F, tolerance=0.01, iterations=3)
    assert report["remesh"]["mode"] == "adaptive"
    _, _, report = mrepair.remesh(V, F, tolerance=0.01, max_edge_length=0.3, iterations=2)
    assert report["remesh"]["status"] == "ok"
    with pytest.raises(ValueError, match="exactly one"):
        mrepair.remesh(V, F)
    with pytest.raises(ValueError, match="exactly one"):
        mrepair.remesh(V, F, edge_length=0.1, faces=100)


# ---- bad input ----------------------------------------------------------------------------------


def test_bad_shapes_and_dtypes():
    V, F = sphere()
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        mrepair.inspect(V[:, :2], F)
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        mrepair.repair(V.ravel(), F)
    with pytest.raises(ValueError, match="dtype"):
        mrepair.repair(V.astype(complex), F)
    with pytest.raises(ValueError, match="dtype"):
        mrepair.repair(np.array([["a", "b", "c"]]), F)
    with pytest.raises(ValueError, match="integer"):
        mrepair.repair(V, F.astype(np.float64))
    with pytest.raises(ValueError, match="shape"):
        mrepair.repair(V, F[:, :2])
    with pytest.raises(ValueError, match="at least 3"):
        mrepair.soup_to_manifold(V, [[0, 1, 2], [0, 1]])
    with pytest.raises(TypeError):
        mrepair.repair(V, F, progress=42)


@pytest.mark.parametrize("call", ["inspect", "soup_to_manifold", "repair", "clean", "remesh",
                                  "close_gaps", "write"])
def test_out_of_range_indices(call, tmp_path):
    V, F = sphere()
    for bad in (len(V), -1):
        F2 = F.copy()
        F2[7, 1] = bad
        with pytest.raises(ValueError, match=r"faces\[7\] refers to vertex"):
            if call == "write":
                mrepair.write(tmp_path / "x.off", V, F2)
            elif call == "remesh":
                mrepair.remesh(V, F2, edge_length=0.1)
            elif call == "close_gaps":
                mrepair.close_gaps(V, F2, 0.1)
            else:
                getattr(mrepair, call)(V, F2)


def test_nan_is_refused_where_the_library_refuses_it():
    V, F = sphere()
    V = V.copy()
    V[4, 2] = np.nan
    with pytest.raises(ValueError, match="non_finite_input"):
        mrepair.remesh(V, F, edge_length=0.1)
    # the repairing calls remove it, as the commands do
    V2, _, report = mrepair.repair(V, F)
    assert np.isfinite(V2).all() and report["soup_to_manifold"]["needed"] is True
    V3, _, _ = mrepair.clean(V, F)
    assert np.isfinite(V3).all()


def test_empty_input():
    with pytest.raises(ValueError, match="empty_input"):
        mrepair.repair(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64))
    r = mrepair.inspect([], [])
    assert r["status"] == "empty_input"


# ---- arrays in and out ------------------------------------------------------------------------------


def every_call(V, F):
    mrepair.inspect(V, F)
    mrepair.soup_to_manifold(V, F)
    mrepair.repair(V, F)
    mrepair.clean(V, F)
    mrepair.remesh(V, F, edge_length=0.3, iterations=2)
    mrepair.close_gaps(V, F, 0.01)
    seq = mrepair.GapClosingSequence(V, F, 0.01)
    seq.forward(10)


def test_inputs_are_never_changed():
    V, F = spiked_sphere()
    V0, F0 = V.copy(), F.copy()
    every_call(V, F)
    assert np.array_equal(V, V0) and np.array_equal(F, F0)
    V2, F2, _ = mrepair.repair(V, F)
    assert not np.shares_memory(V2, V) and not np.shares_memory(F2, F)
    V2[:] = 0  # outputs belong to the caller
    assert np.array_equal(V, V0)


class Tracked(np.ndarray):
    """an ndarray subclass, as trimesh's TrackedArray"""


def test_trimesh_style_arrays():
    V, F = spiked_sphere()
    expected = mrepair.repair(V, F)[2]["face_accounting"]
    wide = np.hstack([V, V])  # non-contiguous views
    variants = [
        (V.view(Tracked), F.view(Tracked)),
        (wide[:, :3], F),
        (np.asfortranarray(V), np.asfortranarray(F)),
        (V, F.astype(np.int32)),
        (V, F.astype(np.uint32)),
        (V.tolist(), F.tolist()),
    ]
    for Vi, Fi in variants:
        assert mrepair.repair(Vi, Fi)[2]["face_accounting"] == expected
    V32, _, _ = mrepair.repair(V.astype(np.float32), F)  # other real dtypes are converted
    assert V32.dtype == np.float64


# ---- progress, cancellation, GIL -------------------------------------------------------------------


def test_progress_reports_phases():
    V, F = spiked_sphere()
    seen = []
    mrepair.repair(V, F, profile="scan",
                   progress=lambda phase, fraction: seen.append((phase, fraction)))
    phases = {p for p, _ in seen}
    assert "relax_spikes" in phases
    assert all(0.0 <= f <= 1.0 for _, f in seen)


def test_progress_bar_helper():
    class Bar:
        total, n, description, refreshed = 100, 0, "", 0

        def set_description(self, d, refresh=True):
            self.description = d

        def refresh(self):
            self.refreshed += 1

    bar = Bar()
    V, F = spiked_sphere()
    mrepair.clean(V, F, progress=mrepair.progress_bar(bar))
    assert bar.refreshed > 0 and 0 <= bar.n <= 100 and bar.description


@pytest.mark.parametrize("call", ["repair", "clean", "soup_to_manifold", "remesh", "close_gaps",
                                  "inspect"])
def test_progress_returning_false_cancels(call):
    V, F = spiked_sphere()
    if call == "close_gaps":
        V, F = two_sheets(1e-3)
    kwargs = {"remesh": {"edge_length": 0.1}, "close_gaps": {"tolerance": 0.01}}.get(call, {})
    V0 = V.copy()
    with pytest.raises(mrepair.Cancelled) as info:
        getattr(mrepair, call)(V, F, progress=lambda phase, fraction: False, **kwargs)
    assert isinstance(info.value, KeyboardInterrupt)
    assert np.array_equal(V, V0)


def test_progress_exception_is_raised_again():
    V, F = spiked_sphere()

    def boom(phase, fraction):
        raise RuntimeError("boom in " + phase)

    with pytest.raises(RuntimeError, match="boom in"):
        mrepair.repair(V, F, progress=boom)


def test_ctrl_c_cancels():
    V, F = spiked_sphere()
    calls = []

    def press_ctrl_c(phase, fraction):
        if not calls:
            _thread.interrupt_main()  # what Ctrl-C does: a pending SIGINT
        calls.append(phase)

    with pytest.raises(KeyboardInterrupt):
        mrepair.repair(V, F, progress=press_ctrl_c)
    assert len(calls) < 10  # stopped at once, not at the end


def test_sigint_without_progress_callable():
    V, F = sphere(400, 800)  # about 640k faces: long enough to be interrupted, also when a
    # loaded machine delays the signal (160k faces: a 0.45 s job, once not stopped in CI)
    start = time.perf_counter()
    mrepair.repair(V, F)
    full = time.perf_counter() - start
    armed = [True]

    def handler(signum, frame):  # Python's own: raises once, then stays quiet
        if armed[0]:
            armed[0] = False
            raise KeyboardInterrupt

    previous = signal.signal(signal.SIGINT, handler)
    done = threading.Event()

    def press_ctrl_c():
        # well inside the call even on a loaded machine, where the main
        # thread may take a while to enter it
        time.sleep(full / 4)
        while not done.is_set():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.01)

    thread = threading.Thread(target=press_ctrl_c)
    start = time.perf_counter()
    thread.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            mrepair.repair(V, F)
        interrupted = time.perf_counter() - start
    finally:
        armed[0] = False
        done.set()
        thread.join()
        time.sleep(0.05)  # runs the handler of a signal still pending
        signal.signal(signal.SIGINT, previous)
    assert interrupted < full


def test_the_gil_is_released():
    V, F = sphere(120, 240)
    result = {}
    worker = threading.Thread(target=lambda: result.setdefault("r", mrepair.repair(V, F)))
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    assert "r" in result and ticks > 10
