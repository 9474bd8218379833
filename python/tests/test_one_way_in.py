# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""One way in: `clean` and `repair` with default options give the same mesh
through the library (the example programs, which pass no option but the
profile), the command line and Python, for each profile. Each front end
passes only what its user gave, so the defaults are the library's alone
(a Python `clean` that always passed max_hole=100 once cancelled the cad
profile's 500)."""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import mrepair

CLI = os.environ.get("MREPAIR_CLI")
LIBRARY = {"repair": os.environ.get("MREPAIR_EXAMPLE_REPAIR"),
           "clean": os.environ.get("MREPAIR_EXAMPLE_CLEAN")}
SAMPLES = Path(os.environ.get("MREPAIR_SAMPLE_DIR", Path(__file__).resolve().parents[2] / "examples/data"))
needs_programs = pytest.mark.skipif(
    not all(p and Path(p).exists() for p in [CLI, *LIBRARY.values()]),
    reason="MREPAIR_CLI, MREPAIR_EXAMPLE_REPAIR and MREPAIR_EXAMPLE_CLEAN not set")


def library_mesh(command, src, out, profile):
    args = [LIBRARY[command], str(src), str(out)]
    args += ["profile=" + profile] if command == "repair" else [profile]
    run = subprocess.run(args, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    return mrepair.read(out)


def cli_mesh(command, src, out, profile):
    run = subprocess.run([CLI, command, str(src), str(out), "--profile", profile, "--quiet"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return mrepair.read(out)


def python_mesh(command, src, profile):
    V, F = mrepair.read(src)
    V2, F2, _ = getattr(mrepair, command)(V, F, profile=profile)
    return V2, F2


@needs_programs
@pytest.mark.parametrize("command", ["clean", "repair"])
@pytest.mark.parametrize("profile", ["auto", "scan", "cad"])
@pytest.mark.parametrize("sample", ["sample_scan.off", "sample_cad.off"])
def test_the_three_ways_in_give_one_mesh(tmp_path, command, profile, sample):
    src = SAMPLES / sample
    if command == "clean":
        # `clean` takes a manifold mesh: the sample through the soup stage
        # alone, its scan defects (spikes, islands, holes) kept
        manifold = tmp_path / "manifold.off"
        run = subprocess.run([CLI, "soup", str(src), str(manifold), "--quiet"], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        src = manifold
    V1, F1 = library_mesh(command, src, tmp_path / "library.off", profile)
    V2, F2 = cli_mesh(command, src, tmp_path / "cli.off", profile)
    V3, F3 = python_mesh(command, src, profile)
    assert len(F1) > 0
    # exact: the three ran the same code with the same settings
    assert np.array_equal(V1, V2) and np.array_equal(V1, V3)
    assert np.array_equal(np.asarray(F1), np.asarray(F2)) and np.array_equal(np.asarray(F1), np.asarray(F3))


def test_python_clean_keeps_the_cad_hole_limit():
    """a 200-vertex hole: filled by the cad profile (limit 500) unless
    max_hole says otherwise, left open by the scan profile (limit 100)."""
    n = 200
    ring = [(np.cos(2 * np.pi * i / n), np.sin(2 * np.pi * i / n), 0.0) for i in range(n)]
    outer = [(2 * x, 2 * y, 0.0) for x, y, _ in ring]
    V = np.array(ring + outer)
    F = []
    for i in range(n):
        j = (i + 1) % n
        F += [(i, n + i, n + j), (i, n + j, j)]
    F = np.array(F)
    _, _, cad = mrepair.clean(V, F, profile="cad")
    _, _, scan = mrepair.clean(V, F, profile="scan", only="fill_small_holes")
    _, _, capped = mrepair.clean(V, F, profile="cad", max_hole=100)
    assert cad["clean"]["holes"]["holes_filled"] == 1
    assert scan["clean"]["holes"]["holes_filled"] == 0
    assert capped["clean"]["holes"]["holes_filled"] == 0
