# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""The reports are those of the `mrepair` commands (same keys; the same
figures where the work is the same), and the folder example runs."""

import csv
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mrepair
from meshes import two_sheets

CLI = os.environ.get("MREPAIR_CLI")
SAMPLES = Path(os.environ.get("MREPAIR_SAMPLE_DIR", Path(__file__).resolve().parents[2] / "examples/data"))
EXAMPLES = Path(os.environ.get("MREPAIR_EXAMPLES_DIR",
                               Path(__file__).resolve().parents[2] / "examples/python"))
# the sections of each command's report that describe its files
FILE_SECTIONS = {"inspect": {"file"}, "soup": {"file"}}
OTHER_FILE_SECTIONS = {"input", "output"}
needs_cli = pytest.mark.skipif(not CLI or not Path(CLI).exists(), reason="MREPAIR_CLI not set")


def keys(tree):
    """the nested key structure of a report, without timings."""
    if not isinstance(tree, dict):
        return None
    return {k: keys(v) for k, v in tree.items() if k != "seconds"}


def command_report(tmp_path, *args):
    out = subprocess.run([CLI, *map(str, args), "--json", "--quiet"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def without_files(report, command):
    files = FILE_SECTIONS.get(command, OTHER_FILE_SECTIONS)
    return {k: v for k, v in report.items() if k not in files}


@needs_cli
def test_repair_report_is_the_commands(tmp_path):
    src = SAMPLES / "sample_scan.off"
    cli = command_report(tmp_path, "repair", src, tmp_path / "out.off")
    V, F = mrepair.read(src)
    V2, F2, report = mrepair.repair(V, F)
    assert keys(report) == keys(without_files(cli, "repair"))
    # the same job on the same data: the same figures and the same mesh
    assert report["face_accounting"] == cli["face_accounting"]
    assert report["after"]["defects"] == cli["after"]["defects"]
    V3, F3 = mrepair.read(tmp_path / "out.off")
    assert np.array_equal(V2, V3) and np.array_equal(F2, F3)


@needs_cli
def test_mesh_call_reports_are_the_commands(tmp_path):
    V, F = two_sheets(1e-3)
    src = tmp_path / "sheets.off"
    mrepair.write(src, V, F)
    out = tmp_path / "out.off"
    pairs = [
        (["inspect", src], mrepair.inspect(V, F)),
        (["soup", src, out], mrepair.soup_to_manifold(V, F)[2]),
        (["close-gaps", src, out, "--tolerance", "0.01"], mrepair.close_gaps(V, F, 0.01)[2]),
        (["clean", src, out], mrepair.clean(V, F)[2]),
        (["remesh", src, out, "--edge-length", "0.2"], mrepair.remesh(V, F, edge_length=0.2)[2]),
    ]
    for args, report in pairs:
        cli = command_report(tmp_path, *args)
        assert keys(report) == keys(without_files(cli, args[0])), args[0]
    # same input, same work: same counts
    cli = command_report(tmp_path, "inspect", src)
    assert mrepair.inspect(V, F)["defects"] == cli["defects"]


def test_repair_folder_example(tmp_path):
    inbox = tmp_path / "in"
    inbox.mkdir()
    shutil.copy(SAMPLES / "sample_scan.off", inbox / "scan.off")
    V, F = two_sheets(1e-3)
    mrepair.write(inbox / "sheets.ply", V, F, binary=True)
    (inbox / "broken.stl").write_text("solid x\nfacet normal 0 0 1\n")
    (inbox / "notes.txt").write_text("not a mesh")
    csv_path = tmp_path / "defects.csv"
    run = subprocess.run([sys.executable, str(EXAMPLES / "repair_folder.py"), str(inbox),
                          str(tmp_path / "out"), "--csv", str(csv_path)],
                         capture_output=True, text=True, env=dict(os.environ))
    assert run.returncode == 1, run.stderr  # one file could not be read
    rows = {r["mesh"]: r for r in csv.DictReader(open(csv_path))}
    assert set(rows) == {"scan.off", "sheets.ply", "broken.stl"}
    assert rows["broken.stl"]["status"].startswith("failed")
    scan = rows["scan.off"]
    assert int(scan["spiked_vertices_before"]) > int(scan["spiked_vertices_after"])
    assert (tmp_path / "out" / "scan.off").exists() and (tmp_path / "out" / "sheets.ply").exists()
