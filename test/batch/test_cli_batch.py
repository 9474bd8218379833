# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""`mrepair batch` (issue 41), run by the CTest test `cli_batch`: a folder of
generated meshes with one truncated file and one made to time out; manifest
lines and statuses; outputs byte-identical to single `mrepair repair` runs; a
batch killed in the middle and resumed; isolation limits; usage errors.

MREPAIR_CLI and MREPAIR_GENERATOR name the programs (CTest sets them)."""

import fcntl
import json
import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

CLI = os.environ.get("MREPAIR_CLI")
GEN = os.environ.get("MREPAIR_GENERATOR")
pytestmark = pytest.mark.skipif(not (CLI and GEN and Path(CLI).exists() and Path(GEN).exists()),
                                reason="MREPAIR_CLI and MREPAIR_GENERATOR not set")

KEYS = ["path", "status", "message", "seconds", "cpu_seconds", "peak_memory_mb", "exit_code", "signal",
        "faces_in", "faces_out", "defects_before", "defects_after", "face_accounting"]
TIMEOUT = "1.5"  # the 1M-face scan takes about 9 s here (8.8 s), a small file 0.05 s


def generate(path, mode, faces, seed, *extra):
    path.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run([GEN, mode, "--faces", str(faces), "--seed", str(seed), "--output", str(path), *extra],
                   check=True, stdout=subprocess.DEVNULL)


def make_dataset(root, slow=True):
    """small scans and CAD parts in nested folders, every format; a truncated
    OFF; with `slow`, a 1M-face scan that a short --timeout kills."""
    generate(root / "scan1.ply", "scan", 2000, 1)
    generate(root / "sub" / "scan2.off", "scan", 3000, 2, "--ascii")
    generate(root / "sub" / "deeper" / "part1.stl", "cad", 2000, 3)
    generate(root / "part2.obj", "cad", 3000, 4)
    generate(root / "sub" / "scan3.stl", "scan", 2500, 5)
    text = (root / "sub" / "scan2.off").read_text()
    (root / "broken.off").write_text(text[: len(text) // 2])  # truncated
    (root / "notes.txt").write_text("not a mesh\n")
    if slow:
        generate(root / "huge.ply", "scan", 1_000_000, 7)


def batch(*args, check=None):
    r = subprocess.run([CLI, "batch", *map(str, args)], capture_output=True, text=True)
    if check is not None:
        assert r.returncode == check, r.stdout + r.stderr
    return r


def command_lines():
    """the command lines of the running processes (from /proc: no `ps` needed)."""
    found = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                found.append((d / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace"))
            except OSError:
                pass
    return found


def manifest_lines(path):
    return [json.loads(l) for l in Path(path).read_text().splitlines() if l.strip()]


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    root = tmp_path_factory.mktemp("batch") / "in"
    make_dataset(root)
    return root


@pytest.fixture(scope="module")
def first_run(dataset, tmp_path_factory):
    out = tmp_path_factory.mktemp("batch_out") / "out"
    r = batch(dataset, out, "--jobs", 2, "--timeout", TIMEOUT, "--quiet")
    return out, r


def test_statuses_and_manifest(dataset, first_run):
    out, r = first_run
    assert r.returncode == 1, r.stdout + r.stderr  # two files are not repaired
    lines = manifest_lines(out / "manifest.jsonl")
    by_path = {l["path"]: l for l in lines}
    assert len(lines) == len(by_path) == 7  # one line per mesh file, notes.txt left out
    # the largest file starts first and the small ones go through the other
    # slot while it runs (a slot is refilled as soon as its child ends; a slot
    # left idle until the next child ends would let one small file through)
    assert [l["path"] for l in lines].index("huge.ply") >= 3
    for l in lines:
        assert list(l) == KEYS
    assert by_path["broken.off"]["status"] == "unreadable"
    assert by_path["broken.off"]["exit_code"] == 1 and by_path["broken.off"]["message"]
    assert by_path["huge.ply"]["status"] == "timeout"
    assert by_path["huge.ply"]["signal"] == "SIGKILL" and by_path["huge.ply"]["exit_code"] is None
    assert 1.4 < by_path["huge.ply"]["seconds"] < 30
    for p in ["scan1.ply", "sub/scan2.off", "sub/deeper/part1.stl", "part2.obj", "sub/scan3.stl"]:
        l = by_path[p]
        assert l["status"] in ("ok", "partial"), l
        assert l["exit_code"] == 0 and l["message"] == ""
        fa = l["face_accounting"]
        assert fa["reconciles"] is True and fa["faces_in"] == l["faces_in"] and fa["faces_out"] == l["faces_out"]
        assert l["faces_in"] > 1000 and l["faces_out"] > 1000
        assert isinstance(l["defects_before"], dict) and isinstance(l["defects_after"], dict)
        assert l["defects_after"]["non_manifold_edges"] == 0
        assert l["peak_memory_mb"] > 0
        assert (out / p).exists()
    # failed files leave no output, and no temporary file is left anywhere
    assert not (out / "broken.off").exists() and not (out / "huge.ply").exists()
    assert not [p for p in out.rglob("*") if "mrepair-partial" in p.name]
    assert "not repaired" in r.stdout and "huge.ply: timeout" in r.stdout


def test_outputs_are_those_of_single_repairs(dataset, first_run, tmp_path):
    out, _ = first_run
    for line in manifest_lines(out / "manifest.jsonl"):
        if line["status"] not in ("ok", "partial"):
            continue
        single = tmp_path / line["path"].replace("/", "_")
        r = subprocess.run([CLI, "repair", dataset / line["path"], single, "--quiet"], capture_output=True)
        assert r.returncode == 0
        assert (out / line["path"]).read_bytes() == single.read_bytes(), line["path"]


def test_resume_skips_what_is_done(dataset, first_run):
    out, _ = first_run
    before = manifest_lines(out / "manifest.jsonl")
    stamp = {p: (out / p).stat().st_mtime_ns for p in ("scan1.ply", "part2.obj")}
    # the timeout is retried (not done), the unreadable file is final (done)
    r = batch(dataset, out, "--jobs", 2, "--timeout", TIMEOUT, "--quiet", "--json", check=1)
    summary = json.loads(r.stdout)
    assert summary["skipped_as_done"] == 6 and summary["repaired_now"] == 1
    assert summary["statuses"]["timeout"] == 1 and summary["statuses"]["unreadable"] == 1
    after = manifest_lines(out / "manifest.jsonl")
    assert after[: len(before)] == before
    assert [l["path"] for l in after[len(before):]] == ["huge.ply"]
    assert {p: (out / p).stat().st_mtime_ns for p in stamp} == stamp
    # an output that went missing is repaired again
    (out / "scan1.ply").unlink()
    r = batch(dataset, out, "--jobs", 1, "--quiet", "--json", "--file", "scan1.ply", check=0)
    assert json.loads(r.stdout)["repaired_now"] == 1 and (out / "scan1.ply").exists()


def test_kill_in_the_middle_and_resume(tmp_path):
    src, out = tmp_path / "in", tmp_path / "out"
    for i in range(8):
        generate(src / f"m{i}.ply", "scan", 60000 + 1000 * i, 10 + i)
    manifest = out / "manifest.jsonl"
    p = subprocess.Popen([CLI, "batch", src, out, "--jobs", "1", "--quiet"], stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and p.poll() is None:
        if manifest.exists() and len(manifest.read_text().splitlines()) >= 3:
            break
        time.sleep(0.01)
    assert p.poll() is None, "the batch ended before it could be killed"
    p.send_signal(signal.SIGKILL)
    p.wait()
    first = manifest_lines(manifest)
    assert 3 <= len(first) < 8
    for l in first:  # what the manifest says is done is there, complete
        assert l["status"] in ("ok", "partial")
        assert (out / l["path"]).exists()
    # the repair in flight died with the batch (PR_SET_PDEATHSIG)
    time.sleep(0.5)
    assert not [c for c in command_lines() if str(out) in c]
    # a temporary output a killed run left (here made by hand) is removed by the next run,
    # and so is the private folder of the killed batch (by any batch that starts
    # after it: one of another test may have been first)
    (out / ".m7.mrepair-partial-elsewhere-1.ply").write_bytes(b"ply\n")
    tmp = Path(os.environ.get("TMPDIR", "/tmp"))
    r = batch(src, out, "--jobs", 2, "--quiet", "--json", check=0)
    summary = json.loads(r.stdout)
    assert summary["skipped_as_done"] == len(first) and summary["repaired_now"] == 8 - len(first)
    final = manifest_lines(manifest)
    paths = [l["path"] for l in final]
    assert sorted(paths) == sorted(f"m{i}.ply" for i in range(8))  # nothing done twice, all done
    assert final[: len(first)] == first
    assert all(l["status"] in ("ok", "partial") for l in final)
    assert not [p for p in out.rglob("*") if "mrepair-partial" in p.name]
    assert not list(tmp.glob(f"mrepair-batch.{p.pid}.*"))


def test_memory_limit(dataset, tmp_path):
    r = batch(dataset, tmp_path / "out", "--file", "huge.ply", "--memory", "150", "--timeout", "60", "--json",
              check=1)
    line = manifest_lines(tmp_path / "out" / "manifest.jsonl")[0]
    assert line["status"] == "out_of_memory", line
    assert json.loads(r.stdout)["statuses"]["out_of_memory"] == 1


def test_usage_errors_fail_at_once(dataset, tmp_path):
    out = tmp_path / "out"
    for args in (["--profil", "cad"], ["--profile", "bogus"], ["--max-hole", "x"], ["--jobs", "0"],
                 ["--timeout", "-1"]):
        r = batch(dataset, out, *args)
        assert r.returncode == 2 and "mrepair batch:" in r.stderr, (args, r.stderr)
        assert not (out / "manifest.jsonl").exists() or not (out / "manifest.jsonl").read_text()
    assert batch(dataset, dataset).returncode == 2  # the outputs would replace the inputs
    assert batch(tmp_path / "missing", out).returncode == 2


def test_options_reach_the_repair(dataset, tmp_path):
    """a repair option is passed through: the output is that of `repair` with it."""
    out = tmp_path / "out"
    batch(dataset, out, "--file", "part2.obj", "--profile", "scan", "--max-hole", "20", "--quiet", check=0)
    single = tmp_path / "single.obj"
    subprocess.run([CLI, "repair", dataset / "part2.obj", single, "--profile", "scan", "--max-hole", "20", "--quiet"],
                   check=True, capture_output=True)
    assert (out / "part2.obj").read_bytes() == single.read_bytes()


def test_one_manifest_one_batch(dataset, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    with open(out / "manifest.jsonl", "a") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        r = batch(dataset, out, "--quiet")
    assert r.returncode == 2 and "in use" in r.stderr


def test_manifest_to_stdout(dataset, tmp_path):
    r = batch(dataset, tmp_path / "out", "--file", "sub/scan2.off", "--manifest", "-", check=0)
    lines = [json.loads(l) for l in r.stdout.splitlines()]
    assert len(lines) == 1 and lines[0]["path"] == "sub/scan2.off" and list(lines[0]) == KEYS


def test_sigterm_stops_cleanly(tmp_path):
    """SIGTERM (or Ctrl-C) kills the repairs in flight, removes their temporary
    outputs, records nothing for them and exits 128 + 15."""
    src, out = tmp_path / "in", tmp_path / "out"
    for i in range(6):
        generate(src / f"m{i}.ply", "scan", 60000 + 1000 * i, 30 + i)
    p = subprocess.Popen([CLI, "batch", src, out, "--jobs", "2"], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and p.poll() is None:
        if (out / "manifest.jsonl").exists() and (out / "manifest.jsonl").read_text().strip():
            break
        time.sleep(0.01)
    p.send_signal(signal.SIGTERM)
    stdout, _ = p.communicate(timeout=30)
    assert p.returncode == 128 + signal.SIGTERM, stdout
    assert "interrupted by SIGTERM" in stdout and "left to do" in stdout
    lines = manifest_lines(out / "manifest.jsonl")
    assert 1 <= len(lines) < 6 and all(l["status"] in ("ok", "partial") for l in lines)
    assert sorted(p.name for p in out.glob("*.ply")) == sorted(l["path"] for l in lines)
    assert not [p for p in out.rglob("*") if "mrepair-partial" in p.name]
    assert not [c for c in command_lines() if str(out) in c]
