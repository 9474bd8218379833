# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""What the `mrepair` program prints and writes (issue 53), run by the CTest
test `cli_output`: the summary printed by default carries the counts of the
JSON report; `--quiet` prints nothing; `--json` and `--report` hold the same
report whatever the mode; the output keeps the input's encoding (binary or
ASCII PLY and STL), binary across formats, `--ascii` / `--binary` override,
and `batch` follows the same rule.

MREPAIR_CLI and MREPAIR_GENERATOR name the programs (CTest sets them).
MREPAIR_CLI_REFERENCE, when set, names an older `mrepair` whose JSON reports
must hold the same keys and values (times apart)."""

import json
import os
import re
import subprocess
from pathlib import Path

import pytest

CLI = os.environ.get("MREPAIR_CLI")
GEN = os.environ.get("MREPAIR_GENERATOR")
REFERENCE = os.environ.get("MREPAIR_CLI_REFERENCE")
pytestmark = pytest.mark.skipif(not (CLI and GEN and Path(CLI).exists() and Path(GEN).exists()),
                                reason="MREPAIR_CLI and MREPAIR_GENERATOR not set")

# the defect counts the summary compares, as in tools/summary.h
DEFECT_KEYS = ["invalid_polygons", "non_finite_vertices", "isolated_vertices", "duplicate_points",
               "degenerate_faces", "duplicate_faces", "non_manifold_edges", "non_manifold_vertices",
               "inconsistent_orientation_edges", "boundary_loops", "small_holes", "connected_components",
               "small_components", "near_degenerate_faces", "spiked_vertices", "t_junctions"]


def generate(path, mode, faces, seed, *extra):
    subprocess.run([GEN, mode, "--faces", str(faces), "--seed", str(seed), "--output", str(path), *extra],
                   check=True, stdout=subprocess.DEVNULL)


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    """a small scan with spikes, holes and islands, binary and ASCII, PLY, STL and OFF"""
    d = tmp_path_factory.mktemp("cli_output")
    # no NaN points: every command, remesh too, must read it as a mesh
    scan = ["--spikes", "2", "--holes", "2", "--islands", "2", "--slivers", "3", "--nan", "0", "--nan-referenced", "0"]
    generate(d / "scan.ply", "scan", 3000, 53, *scan)
    generate(d / "scan_ascii.ply", "scan", 3000, 53, *scan, "--ascii")
    generate(d / "scan.stl", "scan", 3000, 53, *scan)
    generate(d / "scan_ascii.stl", "scan", 3000, 53, *scan, "--ascii")
    generate(d / "scan.off", "scan", 3000, 53, *scan)
    generate(d / "part.ply", "cad", 2000, 54, "--flipped", "2", "--duplicates", "2", "--degenerate", "2")
    return d


def run(*args, code=0):
    r = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert r.returncode == code, r.stdout + r.stderr
    return r


def parse_summary(text):
    """('repair', 'ok', why, {label: value}) from the summary's lines"""
    lines = text.splitlines()
    m = re.match(r"mrepair ([a-z-]+): ([a-z_]+)(?:: (.*))?$", lines[0])
    assert m, text
    fields = {}
    for line in lines[1:]:
        assert line.startswith("  "), text
        label, value = re.match(r"  (\S(?:.*?\S)?)  +(\S.*)$", line).groups()
        assert label not in fields, text
        fields[label] = value
    return m.group(1), m.group(2), m.group(3), fields


def arrow(before, after):
    return f"{before} -> {after}"


def changed_defects(fields):
    """{key: value} of the summary's defect lines"""
    return {label.replace(" ", "_"): v for label, v in fields.items() if label.replace(" ", "_") in DEFECT_KEYS}


def without_times(value):
    """the report with every time (a key that ends in 'seconds') left out"""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if not k.endswith("seconds")}
    return value


def encoding(path):
    """'binary' or 'ascii' from the bytes of a PLY or STL file"""
    data = Path(path).read_bytes()
    if path.suffix == ".ply":
        header = data[: data.index(b"end_header")].decode()
        return "ascii" if "format ascii" in header else "binary"
    assert path.suffix == ".stl"
    binary_size = len(data) >= 84 and len(data) == 84 + 50 * int.from_bytes(data[80:84], "little")
    return "binary" if binary_size else "ascii"


# ---- the summary ----------------------------------------------------------------------------

def test_repair_summary_has_the_counts_of_the_report(data, tmp_path):
    out, rep = tmp_path / "out.ply", tmp_path / "r.json"
    r = run("repair", data / "scan.ply", out, "--report", rep)
    assert r.stderr == ""
    report = json.loads(rep.read_text())
    command, status, why, f = parse_summary(r.stdout)
    assert (command, status, why) == ("repair", report["clean"]["status"], None)
    assert len(r.stdout.splitlines()) <= 20
    before, after = report["before"], report["after"]
    assert f["profile"] == report["clean"]["profile"]["profile"]
    assert f["faces"] == arrow(before["input"]["faces"], after["input"]["faces"])
    assert f["vertices"] == arrow(before["input"]["vertices"], after["input"]["vertices"])
    expected = {k: arrow(before["defects"][k], after["defects"][k]) for k in DEFECT_KEYS
                if before["defects"][k] != after["defects"][k]}
    assert expected, "the generated scan has defects that repair removes"
    assert changed_defects(f) == expected
    assert f["closed"] == ("yes" if after["defects"]["closed"] else "no")
    assert f["intersection-free"] == after["defects"]["intersection_free"]
    assert re.fullmatch(r"\d+\.\d\d s", f["time"])
    assert f["output"] == f"{out} (PLY, binary)"
    assert f["report"] == str(rep)


def test_soup_summary_has_the_counts_of_the_report(data, tmp_path):
    rep = tmp_path / "r.json"
    r = run("soup", data / "part.ply", tmp_path / "out.off", "--report", rep)
    report = json.loads(rep.read_text())
    command, status, _, f = parse_summary(r.stdout)
    assert (command, status) == ("soup", report["soup"]["status"])
    before, after = report["before"], report["after"]
    assert f["faces"] == arrow(before["faces"], after["faces"])
    assert f["vertices"] == arrow(before["vertices"], after["vertices"])
    expected = {k: arrow(before[k], after[k]) for k in DEFECT_KEYS if k in before and before[k] != after[k]}
    assert expected
    assert {k: v for k, v in changed_defects(f).items() if k in before} == expected
    assert f["output"] == f"{tmp_path / 'out.off'} (OFF)"


def test_clean_close_gaps_and_remesh_summaries(data, tmp_path):
    rep = tmp_path / "r.json"
    _, status, _, f = parse_summary(run("clean", data / "scan.ply", tmp_path / "c.ply", "--report", rep).stdout)
    clean = json.loads(rep.read_text())["clean"]
    assert status == clean["status"]
    assert f["faces"] == arrow(clean["faces_before"], clean["faces_after"])
    assert f["vertices"] == arrow(clean["vertices_before"], clean["vertices_after"])
    assert f.get("holes filled", "0") == str(clean["holes"]["holes_filled"])

    _, status, _, f = parse_summary(
        run("close-gaps", data / "scan.ply", tmp_path / "g.ply", "--tolerance", "0.01", "--relative",
            "--report", rep).stdout)
    gaps = json.loads(rep.read_text())["close_gaps"]
    assert status == gaps["status"]
    for key in ("boundary_edges", "boundary_loops"):
        b, a = gaps[key + "_before"], gaps[key + "_after"]
        assert f.get(key.replace("_", " ")) == (arrow(b, a) if b != a else None)
    assert f["closed"] == ("yes" if gaps["boundary_edges_after"] == 0 else "no")

    _, status, _, f = parse_summary(
        run("remesh", tmp_path / "c.ply", tmp_path / "m.ply", "--faces", "2000", "--report", rep).stdout)
    remesh = json.loads(rep.read_text())["remesh"]
    assert status == remesh["status"]
    assert f["faces"] == arrow(remesh["faces_before"], remesh["faces_after"])
    assert f["output"].endswith("(PLY, binary)")


def test_inspect_summary_lists_each_defect_found(data):
    r = run("inspect", data / "scan.ply")
    report = json.loads(run("inspect", data / "scan.ply", "--json").stdout)
    command, status, _, f = parse_summary(r.stdout)
    assert (command, status) == ("inspect", report["status"])
    assert f["faces"] == str(report["input"]["faces"])
    assert f["vertices"] == str(report["input"]["vertices"])
    found = {k: str(report["defects"][k]) for k in DEFECT_KEYS
             if k != "connected_components" and report["defects"][k] != 0}
    assert found
    assert {k: v for k, v in changed_defects(f).items() if k != "connected_components"} == found
    pairs = report["defects"]["self_intersecting_pairs"]
    assert f.get("self intersecting pairs") == (str(pairs) if pairs else None)
    assert f["intersection-free"] == report["defects"]["intersection_free"]
    assert f["input"].startswith(f"{data / 'scan.ply'} (PLY, binary)")
    # --verbose: the full report, as before (a table of every key)
    verbose = run("inspect", data / "scan.ply", "--verbose").stdout
    assert "thresholds:" in verbose and "max_dihedral_angle" in verbose


@pytest.mark.parametrize("command", ["repair", "soup", "clean", "close-gaps", "remesh", "inspect"])
def test_quiet_prints_nothing(data, tmp_path, command):
    extra = {"close-gaps": ["--tolerance", "auto"], "remesh": ["--faces", "2000"]}.get(command, [])
    out = [] if command == "inspect" else [tmp_path / "out.ply"]
    r = run(command, data / "scan.ply", *out, *extra, "--quiet")
    assert (r.stdout, r.stderr) == ("", "")
    # errors still go to stderr, in one line, with the exit code of before
    r = run(command, tmp_path / "missing.ply", *out, *extra, "--quiet", code=1)
    assert r.stdout == "" and len(r.stderr.splitlines()) == 1 and "missing.ply" in r.stderr


@pytest.mark.parametrize("command", ["repair", "soup", "clean", "close-gaps", "remesh", "inspect"])
def test_json_report_is_the_same_in_every_mode(data, tmp_path, command):
    extra = {"close-gaps": ["--tolerance", "auto"], "remesh": ["--faces", "2000"]}.get(command, [])
    out = [] if command == "inspect" else [tmp_path / "out.ply"]
    printed = json.loads(run(command, data / "scan.ply", *out, *extra, "--json").stdout)
    reports = []
    for mode in ([], ["--verbose"], ["--quiet"], ["--json", "--quiet"]):
        rep = tmp_path / "r.json"
        run(command, data / "scan.ply", *out, *extra, *mode, "--report", rep)
        reports.append(json.loads(rep.read_text()))
    for r in reports:
        assert without_times(r) == without_times(printed)
    if REFERENCE:  # the program before issue 53: the same report (OFF out: ASCII in both)
        text_out = [] if command == "inspect" else [tmp_path / "out.off"]
        old = subprocess.run([REFERENCE, command, data / "scan.ply", *text_out, *extra, "--json", "--quiet"],
                             capture_output=True, text=True)
        assert old.returncode == 0, old.stderr
        new = json.loads(run(command, data / "scan.ply", *text_out, *extra, "--json").stdout)
        assert without_times(json.loads(old.stdout)) == without_times(new)


# ---- the encoding ---------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["scan.ply", "scan_ascii.ply", "scan.stl", "scan_ascii.stl"])
def test_repair_keeps_the_encoding(data, tmp_path, name):
    src = data / name
    out = tmp_path / ("out" + src.suffix)
    r = run("repair", src, out)
    assert encoding(src) == ("ascii" if "ascii" in name else "binary")
    assert encoding(out) == encoding(src)
    word = {"binary": "binary", "ascii": "ASCII"}[encoding(src)]
    assert parse_summary(r.stdout)[3]["output"] == f"{out} ({src.suffix[1:].upper()}, {word})"


@pytest.mark.parametrize("command", ["soup", "clean", "close-gaps", "remesh"])
def test_every_command_keeps_the_encoding(data, tmp_path, command):
    extra = {"close-gaps": ["--tolerance", "auto"], "remesh": ["--faces", "2000"]}.get(command, [])
    for name in ("scan_ascii.ply", "scan.stl"):
        out = tmp_path / ("out" + Path(name).suffix)
        run(command, data / name, out, *extra, "--quiet")
        assert encoding(out) == encoding(data / name), (command, name)


def test_across_formats_binary_where_the_format_has_it(data, tmp_path):
    for out in (tmp_path / "a.ply", tmp_path / "a.stl"):
        run("repair", data / "scan.off", out, "--quiet")
        assert encoding(out) == "binary"
    run("repair", data / "scan_ascii.ply", tmp_path / "b.stl", "--quiet")
    assert encoding(tmp_path / "b.stl") == "binary"
    run("repair", data / "scan.ply", tmp_path / "c.off", "--quiet")  # OFF has text only
    assert (tmp_path / "c.off").read_text().startswith("OFF")


def test_ascii_and_binary_override(data, tmp_path):
    out = tmp_path / "out.ply"
    run("repair", data / "scan.ply", out, "--ascii", "--quiet")
    assert encoding(out) == "ascii"
    run("repair", data / "scan_ascii.ply", out, "--binary", "--quiet")
    assert encoding(out) == "binary"
    run("repair", data / "scan.off", tmp_path / "out.stl", "--ascii", "--quiet")
    assert encoding(tmp_path / "out.stl") == "ascii"
    run("soup", data / "scan.stl", tmp_path / "s.stl", "--ascii", "--quiet")
    assert encoding(tmp_path / "s.stl") == "ascii"
    r = run("repair", data / "scan.ply", out, "--ascii", "--binary", code=2)
    assert "exclude each other" in r.stderr


def test_batch_keeps_the_encoding(data, tmp_path):
    src = tmp_path / "in"
    src.mkdir()
    for name in ("scan.ply", "scan_ascii.ply", "scan.stl", "scan_ascii.stl"):
        (src / name).write_bytes((data / name).read_bytes())
    run("batch", src, tmp_path / "kept", "--jobs", "2", "--quiet")
    for name in ("scan.ply", "scan_ascii.ply", "scan.stl", "scan_ascii.stl"):
        assert encoding(tmp_path / "kept" / name) == encoding(src / name), name
    run("batch", src, tmp_path / "ascii", "--jobs", "2", "--quiet", "--ascii")
    for name in ("scan.ply", "scan.stl"):
        assert encoding(tmp_path / "ascii" / name) == "ascii", name
